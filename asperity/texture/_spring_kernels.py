"""Numba kernels of the spring-on-wedge simulation (physics in :mod:`asperity.texture.springs`).

Array-in/array-out loops, no Python objects, no validation (the wrapper in :mod:`~asperity.texture.springs`
validates and coerces).  Kernels cannot raise: failures come back as integer status codes
per spring (see the ``STATUS_*`` constants), which springs.py turns into flags/messages.

Profile arrays (one period of the texture, see texture.Profile):
    xs (k+1,), zs (k+1,)  nodes, xs[0] = 0, xs[k] = L
    seg_mu (k,)           local friction of segment j
    seg_loaded (k,) int8  1 if tips on segment j can carry load (contact regime)
The tip x coordinate is stored unwrapped; segment ``J`` (any integer) is segment
``J mod k`` shifted by ``(J div k) L``.  Node ``J`` is the left end of segment ``J``
(and, to the last bit, the right end of segment ``J - 1``: _tip_kernels.seg_geom).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..kernel_cache import refresh
from ._tip_kernels import FACE, FREE, height, locate, seg_geom, update_tip

refresh(__file__)     # drop cached kernels compiled against older callees

STATUS_OK = 0
STATUS_LOCKED = 1          # a tip cannot climb its face: force grows without bound
STATUS_NO_CONVERGENCE = 2  # the return mapping did not converge
STATUS_TOO_MANY_CROSSINGS = 3  # more face changes in one step than allowed


@njit(cache=True, parallel=True)
def rigid_piece(xs, zs, seg_px, seg_py, seg_lock, seg_loaded, X0, ux, kn, z_rest, out, status,
                lock_seg):
    """k_f = inf, one piece: every tip stays under its base and slides with it.

    seg_px, seg_py : (k,) force ratio -R_h/R_z of a tip sliding in s on segment j
                     (closed-form per-face reservoir point)
    seg_lock       : (k,) int8, 1 if segment j self-locks for this direction
    X0 (n,)        : spring base x positions at rest; ux (q,) base x displacements of
                     the averaging steps of this piece
    Adds to out (n, 5) = [R_x, R_y, R_z, tips in contact, tips sliding] over the steps and
    sets status (n,), lock_seg (n,) (segment index in 0..k-1, -1 none) at the first lock.
    The pieces of a run (steps split anywhere) give the sums of one call bit for bit.
    """
    n = X0.size
    m = ux.size
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


@njit(cache=True)
def run_rigid(xs, zs, seg_px, seg_py, seg_lock, seg_loaded, X0, ux, kn, z_rest):
    """:func:`rigid_piece` over all steps at once: (sums (n, 5), status (n,), lock_seg (n,))."""
    n = X0.size
    out = np.zeros((n, 5))
    status = np.zeros(n, np.int64)
    lock_seg = np.full(n, -1, np.int64)
    rigid_piece(xs, zs, seg_px, seg_py, seg_lock, seg_loaded, X0, ux, kn, z_rest, out, status,
                lock_seg)
    return out, status, lock_seg


@njit(cache=True, parallel=True)
def elastic_piece(xs, zs, seg_mu, seg_loaded, X0, ux, uy, kn, kf, z_rest, cx, s0, window,
                  record, lock_force, tip, tip_at, out, rec, status, lock_seg):
    """Finite k_f, one piece: quasi-static steps s0 .. s0 + q - 1 of every spring tip
    (stick / slide / corner), continuing from the tip state of the previous piece.

    X0 (n,)       : spring base x at rest
    ux, uy (q,)   : base displacement (t_a, t_b) at the steps of this piece; step 0 should
                    be the rest position (tips land under their bases and relax)
    cx            : t_a component of the sliding direction (lock test)
    window        : steps s >= window are summed into ``out``
    record        : if True, per-spring values of each step of the piece go to rec (n, q, 5)
    lock_force    : a tip whose horizontal force exceeds this is reported locked
    tip (n, 3)    : tip state (x_t, dy, previous u_y), tip_at (n, 2) int: (mode, J); set
                    here at step 0, read and written by every piece
    Adds to out (n, 5) = [R_x, R_y, R_z, in contact, sliding]; status (n,) and lock_seg
    (n,) (segment 0..k-1 or -1): a spring with a non-zero status is not moved again.
    The pieces of a run (steps split anywhere) give the result of one call bit for bit.
    """
    n = X0.size
    q = ux.size
    k = xs.size - 1
    for i in prange(n):
        if status[i] != 0:
            continue
        if s0 == 0:
            mode = FREE
            J = locate(X0[i], xs)
            xt = X0[i]
            dy = 0.0
            prev_uy = 0.0
        else:
            mode = tip_at[i, 0]
            J = tip_at[i, 1]
            xt = tip[i, 0]
            dy = tip[i, 1]
            prev_uy = tip[i, 2]
        for t in range(q):
            s = s0 + t
            bx = X0[i] + ux[t]
            dy_tr = dy - (uy[t] - prev_uy)
            prev_uy = uy[t]
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
                rec[i, t, 0] = Rx
                rec[i, t, 1] = Ry
                rec[i, t, 2] = Rz
                rec[i, t, 3] = 1.0
                rec[i, t, 4] = 1.0 if sl else 0.0
            if s >= window:
                out[i, 0] += Rx
                out[i, 1] += Ry
                out[i, 2] += Rz
                out[i, 3] += 1.0
                if sl:
                    out[i, 4] += 1.0
        tip_at[i, 0] = mode
        tip_at[i, 1] = J
        tip[i, 0] = xt
        tip[i, 1] = dy
        tip[i, 2] = prev_uy


@njit(cache=True)
def add_rows(total, rows):
    """total (c,) += rows (n, c), row after row (the same sum however the rows are split)."""
    for i in range(rows.shape[0]):
        for c in range(rows.shape[1]):
            total[c] += rows[i, c]


@njit(cache=True)
def add_records(total, rec, s0):
    """total (m, 5)[s0 + t] += rec (n, q, 5)[i, t], spring after spring (as add_rows)."""
    for i in range(rec.shape[0]):
        for t in range(rec.shape[1]):
            for c in range(rec.shape[2]):
                total[s0 + t, c] += rec[i, t, c]
