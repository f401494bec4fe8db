"""Numba kernels of the Walker-Leine map of a law (sets in
:mod:`asperity.laws._set_kernels`): the force on ``C`` for a prox argument, the factor
``alpha``, and their vectorised forms for the Python wrappers in :mod:`asperity.laws.planar`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._set_kernels import set_project, set_radial


@njit(cache=True)
def law_point(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, x0, x1):
    """The Walker-Leine law at the prox argument x (per unit normal impulse, already scaled
    by alpha): y = prox_D(x), then the reservoir point P on the ray of y with
    k_C(P) chosen so that alpha(P) P = y, i.e. |P| = k rho_D / (1 - k + k rho_D / rho_C) with
    k = k_D(y).  Returns (P0, P1, inside)."""
    y0, y1, inside = set_project(dk, dp, dtab, doff, dn, x0, x1)
    if assoc:
        return y0, y1, inside
    r = math.hypot(y0, y1)
    if r == 0.0:
        return 0.0, 0.0, inside
    phi = math.atan2(y1, y0)
    rc = set_radial(ck, cp, ctab, coff, cn, phi)
    rd = set_radial(dk, dp, dtab, doff, dn, phi)
    k = r / rd
    if k > 1.0:
        k = 1.0
    t = k * rd / (1.0 - k + k * rd / rc)
    return t * y0 / r, t * y1 / r, inside


@njit(cache=True)
def law_alpha(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, P0, P1):
    """alpha(P) = 1 / (k_D(P) - k_C(P) + 1)."""
    if assoc:
        return 1.0
    r = math.hypot(P0, P1)
    if r == 0.0:
        return 1.0
    phi = math.atan2(P1, P0)
    rc = set_radial(ck, cp, ctab, coff, cn, phi)
    rd = set_radial(dk, dp, dtab, doff, dn, phi)
    return 1.0 / (r / rd - r / rc + 1.0)


@njit(cache=True)
def law_point_many(assoc, ck, cp, ctab, dk, dp, dtab, x):
    m = x.shape[0]
    out = np.empty((m, 2))
    ins = np.empty(m, np.bool_)
    for i in range(m):
        a, b, c = law_point(assoc, ck, cp, ctab, 0, ctab.shape[0], dk, dp, dtab, 0,
                            dtab.shape[0], x[i, 0], x[i, 1])
        out[i, 0] = a
        out[i, 1] = b
        ins[i] = c
    return out, ins
