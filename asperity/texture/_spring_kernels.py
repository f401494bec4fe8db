"""Numba kernels of the spring-on-wedge simulation (physics in :mod:`asperity.texture.springs`).

Array-in/array-out loops, no Python objects, no validation (the wrapper in :mod:`~asperity.texture.springs`
validates and coerces).  Kernels cannot raise: failures come back as integer status codes
per spring (see the ``STATUS_*`` constants), which springs.py turns into flags/messages.

Profile arrays (one period of the texture, see texture.Profile):
    xs (k+1,), zs (k+1,)  nodes, xs[0] = 0, xs[k] = L
    seg_mu (k,)           local friction of segment j
    seg_loaded (k,) int8  1 if tips on segment j can carry load (contact regime)
The tip x coordinate is stored unwrapped; segment ``J`` (any integer) is segment
``J mod k`` shifted by ``(J div k) L``.  Node ``J`` is the left end of segment ``J``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ._tip_kernels import FACE, FREE, height, locate, seg_geom, update_tip

STATUS_OK = 0
STATUS_LOCKED = 1          # a tip cannot climb its face: force grows without bound
STATUS_NO_CONVERGENCE = 2  # the return mapping did not converge
STATUS_TOO_MANY_CROSSINGS = 3  # more face changes in one step than allowed


@njit(cache=True, parallel=True)
def run_rigid(xs, zs, seg_px, seg_py, seg_lock, seg_loaded, X0, ux, kn, z_rest):
    """k_f = inf: every tip stays under its base and slides with it.

    seg_px, seg_py : (k,) force ratio -R_h/R_z of a tip sliding in s on segment j
                     (closed-form per-face reservoir point)
    seg_lock       : (k,) int8, 1 if segment j self-locks for this direction
    X0 (n,)        : spring base x positions at rest; ux (m,) base x displacements of
                     the averaging steps
    Returns sums (n, 5) = [R_x, R_y, R_z, tips in contact, tips sliding] over the steps,
    status (n,), locked_seg (n,) (segment index in 0..k-1, -1 none).
    """
    n = X0.size
    m = ux.size
    out = np.zeros((n, 5))
    status = np.zeros(n, np.int64)
    lock_seg = np.full(n, -1, np.int64)
    for i in prange(n):
        for s in range(m):
            x = X0[i] + ux[s]
            J = locate(x, xs)
            j, xl, xr, zl, zr, g = seg_geom(J, xs, zs)
            if seg_loaded[j] == 0:
                continue
            z = zl + g * (x - xl)
            if z <= z_rest:
                continue
            if seg_lock[j] != 0:
                if status[i] == 0:
                    status[i] = STATUS_LOCKED
                    lock_seg[i] = j
                continue
            Rz = kn * (z - z_rest)
            out[i, 0] -= seg_px[j] * Rz
            out[i, 1] -= seg_py[j] * Rz
            out[i, 2] += Rz
            out[i, 3] += 1.0
            out[i, 4] += 1.0
    return out, status, lock_seg


@njit(cache=True, parallel=True)
def run_elastic(xs, zs, seg_mu, seg_loaded, X0, ux, uy, kn, kf, z_rest, cx, n_window,
                record, lock_force):
    """Finite k_f: quasi-static steps of every spring tip (stick / slide / corner).

    X0 (n,)       : spring base x at rest
    ux, uy (m,)   : base displacement (t_a, t_b) at each step; step 0 should be the rest
                    position (tips land under their bases and relax: the rest state)
    cx            : t_a component of the sliding direction (lock test)
    n_window      : the last n_window steps are summed into ``sums``
    record        : if True, per-step per-spring values are returned in ``steps``
                    (n, m, 5), else steps has shape (1, 1, 5)
    lock_force    : a tip whose horizontal force exceeds this is reported locked
    Returns sums (n, 5) = [R_x, R_y, R_z, in contact, sliding], steps, status (n,),
    lock_seg (n,) (segment 0..k-1 or -1), and the final tip state (mode, xt, dy) (n, 3).
    """
    n = X0.size
    m = ux.size
    k = xs.size - 1
    out = np.zeros((n, 5))
    if record:
        steps = np.zeros((n, m, 5))
    else:
        steps = np.zeros((1, 1, 5))
    status = np.zeros(n, np.int64)
    lock_seg = np.full(n, -1, np.int64)
    final = np.zeros((n, 3))
    for i in prange(n):
        mode = FREE
        J = locate(X0[i], xs)
        xt = X0[i]
        dy = 0.0
        prev_uy = 0.0
        for s in range(m):
            bx = X0[i] + ux[s]
            dy_tr = dy - (uy[s] - prev_uy)
            prev_uy = uy[s]
            code, mode, J, xt, dy, sl = update_tip(mode, J, xt, dy_tr, bx, xs, zs, seg_mu,
                                                    seg_loaded, kn, kf, z_rest)
            if code != 0:
                status[i] = code
                break
            if mode == FREE:
                continue
            z = height(xt, xs, zs) if mode == FACE else seg_geom(J, xs, zs)[3]
            Rx = kf * (xt - bx)
            Ry = kf * dy
            Rz = kn * (z - z_rest)
            j = J % k
            if j < 0:
                j += k
            if mode == FACE and not sl:
                g = seg_geom(J, xs, zs)[5]
                mu = seg_mu[j]
                # stuck on a face the base climbs, with the limiting force direction
                # (-s, 0) inside the cone: the tip never slides again
                if g * cx > 0.0 and (1.0 + g * g) <= (1.0 + mu * mu) * g * g * cx * cx:
                    status[i] = STATUS_LOCKED
                    lock_seg[i] = j
                    break
            if math.sqrt(Rx * Rx + Ry * Ry) > lock_force:
                status[i] = STATUS_LOCKED
                lock_seg[i] = j
                break
            if record:
                steps[i, s, 0] = Rx
                steps[i, s, 1] = Ry
                steps[i, s, 2] = Rz
                steps[i, s, 3] = 1.0
                steps[i, s, 4] = 1.0 if sl else 0.0
            if s >= m - n_window:
                out[i, 0] += Rx
                out[i, 1] += Ry
                out[i, 2] += Rz
                out[i, 3] += 1.0
                if sl:
                    out[i, 4] += 1.0
        final[i, 0] = mode
        final[i, 1] = xt
        final[i, 2] = dy
    return out, steps, status, lock_seg, final
