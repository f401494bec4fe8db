"""Numba kernel of :mod:`asperity.microslip.friction_batch`: the tangential friction
T = p . s of a periodic wedge texture for two sliding directions, case by case over a
block of textures.

Per case, the arithmetic of :func:`asperity.friction.faces.compute_face_reservoir` on the
texture's two faces (:meth:`asperity.texture.wedges.WedgeTexture.faces`), operation for
operation and in the same order, and ``tan`` from the C library as ``math.tan`` (NumPy's
vectorised ``tan`` may differ from it in the last bit): the result is that of the per-case
path bit for bit.  The faces of a wedge of angles a, b (rad) and local frictions mu_a,
mu_b:

    gradient (tan a, 0) and (-tan b, 0), horizontal-area weights
    tan b / (tan a + tan b) and tan a / (tan a + tan b).

For each direction s = (cos psi, sin psi) and face (gradient g, friction mu):

    nrm = sqrt(1 + g.g), slope = g.s, |v| = sqrt(1 + slope^2),
    F_z = 1/nrm - mu slope/|v|,  F_h = g/nrm + mu s/|v|,

the reservoir point is the weighted mean of F_h/F_z over the loaded faces (all faces, or
the climbed ones in the windward regime, the level ones when none is climbed), and the
direction self-locks (T = +inf) when a loaded face has F_z <= lock_tol.

Array-in/array-out, no validation (the wrapper validates); a case the kernel cannot do
comes back with a status code, never raises.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

STATUS_OK = 0
#: windward regime: no face climbed or level in a direction (compute_face_reservoir raises)
STATUS_NO_WINDWARD = 1
#: the case was skipped (marked bad on entry)
STATUS_SKIPPED = 2


@njit(cache=True)
def wedge_tangential(alpha_rad, beta_rad, mu_a, mu_b, cs, sn, windward, level_tol,
                     lock_tol, todo, T, tan_a, tan_b, status):
    """T (m, 2) of m wedge textures for the directions ``cs``, ``sn`` (m, 2) (cos psi and
    sin psi of each case's two directions, computed by the caller as the per-case path
    does); ``tan_a``, ``tan_b`` (m,) receive tan alpha and tan beta; ``status`` (m,) a
    STATUS_* code.  Cases with ``todo`` False are skipped (T = NaN)."""
    m = alpha_rad.shape[0]
    gx = np.empty(2)
    mu = np.empty(2)
    w = np.empty(2)
    hx = np.empty(2)
    hy = np.empty(2)
    fz = np.empty(2)
    sl = np.empty(2)
    for i in range(m):
        if not todo[i]:
            T[i, 0] = np.nan
            T[i, 1] = np.nan
            status[i] = STATUS_SKIPPED
            continue
        ta = math.tan(alpha_rad[i])
        tb = math.tan(beta_rad[i])
        tan_a[i] = ta
        tan_b[i] = tb
        gx[0] = ta
        gx[1] = -tb
        mu[0] = mu_a[i]
        mu[1] = mu_b[i]
        w[0] = tb / (ta + tb)
        w[1] = ta / (ta + tb)
        status[i] = STATUS_OK
        for d in range(2):
            sx = cs[i, d]
            sy = sn[i, d]
            for f in range(2):
                g = gx[f]
                nrm = math.sqrt(1.0 + g * g + 0.0 * 0.0)
                slope = g * sx + 0.0 * sy
                vlen = math.sqrt(1.0 + slope * slope)
                fz[f] = 1.0 / nrm - mu[f] * slope / vlen
                hx[f] = g / nrm + mu[f] * sx / vlen
                hy[f] = 0.0 / nrm + mu[f] * sy / vlen
                sl[f] = slope
            locked = False
            ww0 = 0.0
            ww1 = 0.0
            climbed = False
            if windward:
                level = False
                for f in range(2):
                    if sl[f] > level_tol and w[f] > 0:
                        climbed = True
                    if abs(sl[f]) <= level_tol and w[f] > 0:
                        level = True
                if not climbed and not level:
                    status[i] = STATUS_NO_WINDWARD
            for f in range(2):
                if not windward:
                    loaded = w[f] > 0
                elif climbed:
                    loaded = sl[f] > level_tol and w[f] > 0
                else:
                    loaded = abs(sl[f]) <= level_tol and w[f] > 0
                if loaded:
                    if f == 0:
                        ww0 = w[0]
                    else:
                        ww1 = w[1]
                    if fz[f] <= lock_tol:
                        locked = True
            if locked:
                T[i, d] = np.inf
                continue
            s0 = fz[0] if fz[0] > lock_tol else 1.0
            s1 = fz[1] if fz[1] > lock_tol else 1.0
            wsum = ww0 + ww1
            pa = (ww0 * hx[0] / s0 + ww1 * hx[1] / s1) / wsum
            pb = (ww0 * hy[0] / s0 + ww1 * hy[1] / s1) / wsum
            T[i, d] = pa * sx + pb * sy
        if status[i] != STATUS_OK:
            T[i, 0] = np.nan
            T[i, 1] = np.nan
    return T
