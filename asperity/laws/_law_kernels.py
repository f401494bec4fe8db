"""Numba kernels of the Walker-Leine map of a law (sets in
:mod:`asperity.laws._set_kernels`): the force on ``C`` for a prox argument, the factor
``alpha``, and their vectorised forms for the Python wrappers in :mod:`asperity.laws.planar`.

Kernels that allocate nothing are compiled with ``_nrt=False`` (no reference counts:
numba increfs and decrefs every array argument of a call with atomic operations, which
cost a Moreau step of a point mass ~200 ns of its ~300;
:mod:`asperity.dynamics._moreau_kernels`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ._set_kernels import SET_STAR, SET_SUPPORT, set_project, set_radial, support_radial
from ._warm_kernels import (PW_K, PW_SIZE, star_radial_dir, support_project_warm,
                            support_radial_warm)

refresh(__file__)     # drop cached kernels compiled against older callees

#: columns of a contact's warm-start row (see :func:`law_point_warm`): the projection's
#: (PW_*), rho_C and rho_D on the ray of the last point, whether they are valid, the star
#: polygon's edge last hit
WARM_RC, WARM_RD, WARM_VALID, WARM_EDGE = PW_SIZE, PW_SIZE + 1, PW_SIZE + 2, PW_SIZE + 3
#: a solver's own columns: alpha at the end of the last two steps and how many are kept
WARM_A1, WARM_A2, WARM_NA = PW_SIZE + 4, PW_SIZE + 5, PW_SIZE + 6
#: and the force per unit normal impulse of the last three steps (x, y each) and how many
WARM_P1, WARM_P2, WARM_P3, WARM_NP = PW_SIZE + 7, PW_SIZE + 9, PW_SIZE + 11, PW_SIZE + 13
WARM_SIZE = PW_SIZE + 14


@njit(cache=True, _nrt=False, inline="always")
def reservoir_radius(r, rc, rd):
    """|P| of the reservoir point on the ray of y = alpha(P) P, |y| = r, with the radial
    functions rc of C and rd of D on that ray: k = k_D(y) (at most 1),
    |P| = k rho_D / (1 - k + k rho_D / rho_C)."""
    k = r / rd
    if k > 1.0:
        k = 1.0
    return k * rd / (1.0 - k + k * rd / rc)


@njit(cache=True, _nrt=False)
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
    t = reservoir_radius(r, rc, rd)
    return t * y0 / r, t * y1 / r, inside


@njit(cache=True, _nrt=False)
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
def new_warm(nc):
    """(nc, WARM_SIZE) warm-start rows of nc contacts before their first step."""
    wk = np.zeros((nc, WARM_SIZE))
    for i in range(nc):
        wk[i, PW_K] = -1.0
        wk[i, WARM_EDGE] = -1.0
    return wk


@njit(cache=True, _nrt=False, inline="always", error_model="numpy")
def law_point_warm(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, x0, x1, wk):
    """:func:`law_point` for a solver that calls it again and again with nearby arguments
    (a fixed-point iteration, time steps).  ``wk`` (WARM_SIZE,) is the contact's row: the
    warm start of the projection onto a support set D (:func:`support_project_warm`) and of
    the star polygon's edge (:func:`star_radial_dir`), and rho_C, rho_D on the ray of the
    returned point, so that :func:`law_alpha_warm` of it needs no search.  Same result as
    :func:`law_point` to ~1e-15."""
    if assoc:
        wk[WARM_VALID] = 0.0
        return set_project(dk, dp, dtab, doff, dn, x0, x1)
    if dk == SET_SUPPORT:
        y0, y1, inside, rd, ux, uy = support_project_warm(dtab, doff, dn, x0, x1, wk)
        r = rd if not inside else math.hypot(y0, y1)      # outside: y on D's boundary
        if r == 0.0:
            wk[WARM_VALID] = 0.0
            return 0.0, 0.0, inside
    else:
        y0, y1, inside = set_project(dk, dp, dtab, doff, dn, x0, x1)
        r = math.hypot(y0, y1)
        if r == 0.0:
            wk[WARM_VALID] = 0.0
            return 0.0, 0.0, inside
        ux = y0 / r
        uy = y1 / r
        rd = set_radial(dk, dp, dtab, doff, dn, math.atan2(y1, y0))
    if ck == SET_STAR:
        rc, edge = star_radial_dir(ctab, coff, cn, ux, uy, int(wk[WARM_EDGE]))
        wk[WARM_EDGE] = edge
    else:
        rc = set_radial(ck, cp, ctab, coff, cn, math.atan2(uy, ux))
    t = reservoir_radius(r, rc, rd) if inside or r != rd else rc     # on D: P on C
    wk[WARM_RC] = rc
    wk[WARM_RD] = rd
    wk[WARM_VALID] = 1.0
    return t * ux, t * uy, inside


@njit(cache=True, _nrt=False, error_model="numpy")
def law_alpha_near(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, P0, P1, wk):
    """:func:`law_alpha` of a point P near the last one of :func:`law_point_warm` with the row
    ``wk``: the radial functions from its warm starts (D's by :func:`support_radial_warm`,
    the star polygon's from its last edge), else by the searches; wk's kept values of the
    last point are left as they are."""
    if assoc:
        return 1.0
    r = math.hypot(P0, P1)
    if r == 0.0:
        return 1.0
    ux = P0 / r
    uy = P1 / r
    ok = False
    rd = 0.0
    if dk == SET_SUPPORT:
        dphi = 0.0                                # from the ray of the last point
        if wk[WARM_VALID] != 0.0:
            q0 = wk[WARM_P1]
            q1 = wk[WARM_P1 + 1]
            rq = math.hypot(q0, q1)
            if rq > 0.0:
                dphi = (q0 * uy - q1 * ux) / rq
        rd, ok = support_radial_warm(dtab, doff, dn, ux, uy, wk, dphi)
        if not ok:
            rd = support_radial(dtab, doff, dn, math.atan2(uy, ux))[0]
    else:
        rd = set_radial(dk, dp, dtab, doff, dn, math.atan2(uy, ux))
    if ck == SET_STAR:
        rc, edge = star_radial_dir(ctab, coff, cn, ux, uy, int(wk[WARM_EDGE]))
    else:
        rc = set_radial(ck, cp, ctab, coff, cn, math.atan2(uy, ux))
    return 1.0 / (r / rd - r / rc + 1.0)


@njit(cache=True, _nrt=False, inline="always", error_model="numpy")
def law_alpha_warm(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, P0, P1, wk):
    """:func:`law_alpha` of the point last returned by :func:`law_point_warm` with the same
    row ``wk`` (its radial functions kept there), else of any P."""
    if assoc:
        return 1.0
    if wk[WARM_VALID] == 0.0:
        return law_alpha(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, P0, P1)
    r = math.hypot(P0, P1)
    return 1.0 / (r / wk[WARM_RD] - r / wk[WARM_RC] + 1.0)


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
