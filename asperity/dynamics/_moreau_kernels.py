"""Numba kernels of the Moreau time-stepping solver (physics in
:mod:`asperity.dynamics.moreau`; sets and laws in :mod:`asperity.laws._set_kernels` and
:mod:`asperity.laws._law_kernels`).

Array-in/array-out loops, no Python objects, no validation (the wrappers validate and coerce).
Kernels cannot raise: failures come back in the ``info`` array (see ``INFO_*`` and
``STATUS_*``), which :mod:`~asperity.dynamics.moreau` turns into a status and a message.
The step's helpers are compiled with ``_nrt=False`` (they allocate nothing): a call with
array arguments then costs no reference counts (atomic operations, ~3 ns each, that took
two thirds of a point mass's step); the point mass's end velocity is computed on scalars
and a force that does not depend on time is evaluated once.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ..laws._law_kernels import (WARM_A1, WARM_A2, WARM_NA, WARM_NP, WARM_P1, WARM_P2, WARM_P3,
                                 law_alpha_near, law_alpha_warm, law_point_warm)
from ..laws._set_kernels import TWO_PI

refresh(__file__)     # drop cached kernels compiled against older callees

STATUS_OK = 0
STATUS_NOT_CONVERGED = 1   # the fixed-point iteration hit its limit above the tolerance
STATUS_NON_FINITE = 2      # a velocity became NaN/inf (integration stopped)
INFO_STEPS = 0             # steps integrated
INFO_STOP_STEP = 1         # steps done when the body last came to rest (-1: moving at the end)
INFO_MAX_ITER = 2          # largest number of fixed-point iterations in one step
INFO_STATUS = 3
INFO_FAIL_STEP = 4         # first step (0-based) that did not converge (-1: none)
INFO_FAIL_RESIDUAL = 5     # its residual
INFO_MAX_RESIDUAL = 6      # largest final residual over all steps
INFO_RECORDS = 7           # rows written to the record arrays
INFO_ITER_TOTAL = 8        # fixed-point iterations summed over the steps
INFO_HALTED = 9            # 1: stopped before n_steps (at rest with halt_at_rest, or non-finite)
INFO_SIZE = 10
FORCE_NONE = 0
FORCE_SQUARE = 1
FORCE_SINE = 2


@njit(cache=True, _nrt=False)
def _force(fpar, ftab, step, t, ndof, out):
    """External force at the midpoint time t: table row if given, else
    constant + amplitude * w(t) with w the square wave (+1 on the first half period) or
    sin(2 pi t / T)."""
    if ftab.shape[0] > 0:
        for j in range(ndof):
            out[j] = ftab[step, j]
        return
    kind = int(fpar[0])
    T = fpar[1]
    w = 0.0
    if kind == FORCE_SQUARE:
        ph = (t / T) % 1.0
        w = 1.0 if ph < 0.5 else -1.0
    elif kind == FORCE_SINE:
        w = math.sin(TWO_PI * t / T)
    for j in range(ndof):
        out[j] = fpar[2 + j] + fpar[5 + j] * w


@njit(cache=True, _nrt=False, error_model="numpy")
def _end_velocity(ue, uf, minv, P, ow, nc, ndof):
    """u_E = u_free - M^-1 W P (contact impulses Lambda_i = -P_i; ``ow`` the contact
    offsets turned to the current angle, used when ndof == 3)."""
    for j in range(ndof):
        ue[j] = uf[j]
    for i in range(nc):
        ue[0] -= minv[0] * P[i, 0]
        ue[1] -= minv[1] * P[i, 1]
        if ndof == 3:
            ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] - ow[i, 1] * P[i, 0])


@njit(cache=True, _nrt=False)
def _jacobi_iterate(uf, ue, minv, P, Pn, ow, stick, warm, lam_n, assoc, kinds, pars, tabs,
                    offs, ns, r, tol, max_iter, nc, ndof):
    """The Jacobi fixed-point iteration of one step over all contacts (see
    :func:`integrate`); updates P, stick and the warm rows; returns (iterations, residual)."""
    res = 0.0
    it = 0
    for it in range(1, max_iter + 1):
        _end_velocity(ue, uf, minv, P, ow, nc, ndof)   # u_E for Lambda_i = -P_i
        res = 0.0
        for i in range(nc):
            g0 = ue[0]
            g1 = ue[1]
            if ndof == 3:
                g0 -= ue[2] * ow[i, 1]
                g1 += ue[2] * ow[i, 0]
            ln = lam_n[i]
            p0 = P[i, 0] / ln
            p1 = P[i, 1] / ln
            wk = warm[i]
            al = -1.0
            if it == 1 and wk[WARM_NA] >= 2.0:
                # first guess of alpha: extrapolated from the last two steps' (the
                # fixed point is the same; the guess saves an iteration as it turns)
                al = 2.0 * wk[WARM_A1] - wk[WARM_A2]
            if not 0.0 < al <= 1.0:
                al = law_alpha_warm(assoc[i], kinds[i, 0], pars[i, 0], tabs, offs[i, 0],
                                    ns[i, 0], kinds[i, 1], pars[i, 1], tabs, offs[i, 1],
                                    ns[i, 1], p0, p1, wk)
            z0 = al * (p0 + r * g0 / ln)
            z1 = al * (p1 + r * g1 / ln)
            a, b, ins = law_point_warm(assoc[i], kinds[i, 0], pars[i, 0], tabs,
                                       offs[i, 0], ns[i, 0], kinds[i, 1], pars[i, 1],
                                       tabs, offs[i, 1], ns[i, 1], z0, z1, wk)
            stick[i] = ins
            e = math.hypot(a - p0, b - p1)
            if e > res:
                res = e
            Pn[i, 0] = a * ln
            Pn[i, 1] = b * ln
        for i in range(nc):
            P[i, 0] = Pn[i, 0]
            P[i, 1] = Pn[i, 1]
        if res <= tol:
            break
    for i in range(nc):
        wk = warm[i]
        ln = lam_n[i]
        wk[WARM_A2] = wk[WARM_A1]
        wk[WARM_A1] = law_alpha_warm(assoc[i], kinds[i, 0], pars[i, 0], tabs, offs[i, 0],
                                     ns[i, 0], kinds[i, 1], pars[i, 1], tabs, offs[i, 1],
                                     ns[i, 1], P[i, 0] / ln, P[i, 1] / ln, wk)
        if wk[WARM_NA] < 2.0:
            wk[WARM_NA] += 1.0
    return it, res


@njit(cache=True, _nrt=False, error_model="numpy")
def _point_iterate(uf, minv, P, wk, ln, assoc, ck, cp, dk, dp, tabs, coff, cn, doff, dn, r,
                   tol, max_iter):
    """The fixed-point iteration of one step of a point mass (one contact, W = identity):
    the same iteration as the general one in :func:`integrate`, on scalars, started from the
    force extrapolated (quadratically) from the last three steps when they slid, with its
    alpha (so the first iteration converges when the extrapolation is within tol: ~1e-14
    at dt = 1e-4 s); else from the last step's force with alpha extrapolated from the last
    two steps.  Updates P and the warm row wk; returns (iterations, residual, stick)."""
    res = 0.0
    it = 0
    ins = False
    iln = 1.0 / ln
    rl = r * iln
    al = -1.0
    if wk[WARM_NP] >= 3.0:
        e0 = 3.0 * (wk[WARM_P1] - wk[WARM_P2]) + wk[WARM_P3]
        e1 = 3.0 * (wk[WARM_P1 + 1] - wk[WARM_P2 + 1]) + wk[WARM_P3 + 1]
        P[0, 0] = e0 * ln
        P[0, 1] = e1 * ln
        al = 1.0 if assoc else law_alpha_near(assoc, ck, cp, tabs, coff, cn, dk, dp, tabs,
                                              doff, dn, P[0, 0] * iln, P[0, 1] * iln, wk)
    elif wk[WARM_NA] >= 2.0:
        al = 2.0 * wk[WARM_A1] - wk[WARM_A2]
    for it in range(1, max_iter + 1):
        p0 = P[0, 0] * iln
        p1 = P[0, 1] * iln
        g0 = uf[0] - minv[0] * P[0, 0]
        g1 = uf[1] - minv[1] * P[0, 1]
        if it > 1 or not 0.0 < al <= 1.0:
            al = law_alpha_warm(assoc, ck, cp, tabs, coff, cn, dk, dp, tabs, doff, dn, p0, p1,
                                wk)
        z0 = al * (p0 + rl * g0)
        z1 = al * (p1 + rl * g1)
        a, b, ins = law_point_warm(assoc, ck, cp, tabs, coff, cn, dk, dp, tabs, doff, dn,
                                   z0, z1, wk)
        res = math.hypot(a - p0, b - p1)
        P[0, 0] = a * ln
        P[0, 1] = b * ln
        if res <= tol:
            break
    wk[WARM_A2] = wk[WARM_A1]
    wk[WARM_A1] = law_alpha_warm(assoc, ck, cp, tabs, coff, cn, dk, dp, tabs, doff, dn,
                                 P[0, 0] * iln, P[0, 1] * iln, wk)
    if wk[WARM_NA] < 2.0:
        wk[WARM_NA] += 1.0
    for j in range(2):
        wk[WARM_P3 + j] = wk[WARM_P2 + j]
        wk[WARM_P2 + j] = wk[WARM_P1 + j]
    wk[WARM_P1] = P[0, 0] * iln
    wk[WARM_P1 + 1] = P[0, 1] * iln
    if ins or res > tol:                  # a stick (or a failed step): start the history anew
        wk[WARM_NP] = 0.0
    elif wk[WARM_NP] < 3.0:
        wk[WARM_NP] += 1.0
    return it, res, ins


@njit(cache=True, error_model="numpy")
def integrate(q, u, P, warm, minv, offsets, lam_n, assoc, kinds, pars, tabs, offs, ns,
              fpar, ftab, t0, dt, n_steps, step0, n_chunk, r, tol, max_iter, full_rank,
              halt_at_rest, record_every, rec_t, rec_q, rec_u, info):
    """Moreau midpoint time-stepping of a body on a plane (SPEC.md section 4), steps
    ``step0`` to ``step0 + n_chunk`` of ``n_steps``: the state (q, u, the impulses P that
    start each step's iteration, info, the records) is carried in the arguments, so that a
    run split into pieces gives the same result as one piece, bit for bit.

    q, u   : (ndof,) state, updated in place; ndof = 2 (point mass x, y) or 3 (rigid body)
    P      : (nc, 2) contact impulses of the last step (zeros before the first), in place
    warm   : (nc, WARM_SIZE) each contact's warm start of the law's kernels
             (laws._law_kernels.new_warm before the first step), carried like P
    minv   : (ndof,) inverse mass matrix diagonal
    offsets: (nc, 2) contact points in the body frame (rotated by theta at q_M)
    lam_n  : (nc,) normal impulse per step of each contact (share * m g dt)
    assoc  : (nc,) C is D (alpha = 1)
    kinds  : (nc, 2) set kinds of C and D; pars (nc, 2, 8); tabs (rows, 8) all tables,
             offs/ns (nc, 2) their first row and length
    fpar, ftab : external force (see _force)
    r      : prox parameter (0 < r < 2 / max eig(W^T M^-1 W)); the iteration uses r alpha_i
             at contact i (the normal cone is a cone, any positive multiple is valid)
    tol    : fixed-point tolerance on max_i |P_i^{k+1} - P_i^k| / lam_n_i
    full_rank : W^T has full column rank: all contacts sticking means u_E = 0 exactly
    halt_at_rest : stop integrating once at rest under no external force (nothing can move)
    Records every ``record_every`` steps (and the initial state) into rec_*; info as INFO_*.
    """
    ndof = q.shape[0]
    nc = offsets.shape[0]
    f = np.zeros(ndof)
    qm = np.zeros(ndof)
    uf = np.zeros(ndof)
    ue = np.zeros(ndof)
    Pn = np.zeros((nc, 2))
    ow = np.zeros((nc, 2))
    stick = np.zeros(nc, np.bool_)
    unforced = ftab.shape[0] == 0 and int(fpar[0]) == FORCE_NONE
    if unforced:
        for j in range(ndof):
            if fpar[2 + j] != 0.0:
                unforced = False
    if step0 == 0:
        for j in range(INFO_SIZE):
            info[j] = 0.0
        info[INFO_STOP_STEP] = -1.0
        info[INFO_FAIL_STEP] = -1.0
        moving0 = False
        for j in range(ndof):
            if u[j] != 0.0:
                moving0 = True
        if not moving0:
            info[INFO_STOP_STEP] = 0.0
        rec_t[0] = t0
        for j in range(ndof):
            rec_q[0, j] = q[j]
            rec_u[0, j] = u[j]
        info[INFO_RECORDS] = 1
    nrec = int(info[INFO_RECORDS])
    max_it = int(info[INFO_MAX_ITER])
    it_total = int(info[INFO_ITER_TOTAL])
    status = int(info[INFO_STATUS])
    stop_at = min(n_steps, step0 + n_chunk)
    # a point mass (one contact at the centre): the iteration on scalars
    point = ndof == 2 and nc == 1
    cp0 = pars[0, 0]
    dp0 = pars[0, 1]
    wk0 = warm[0]
    halted = False
    step = step0
    # a force that does not depend on time (w = 0): evaluated once, not per step (a call
    # with array arguments costs their reference counts, atomic operations: ~30 ns)
    const_force = ftab.shape[0] == 0 and int(fpar[0]) == FORCE_NONE
    if const_force:
        _force(fpar, ftab, 0, t0, ndof, f)
    for step in range(step0, stop_at):
        tm = t0 + (step + 0.5) * dt
        if not const_force:
            _force(fpar, ftab, step, tm, ndof, f)
        for j in range(ndof):
            qm[j] = q[j] + 0.5 * dt * u[j]
            uf[j] = u[j] + dt * minv[j] * f[j]
        if ndof == 3:
            c = math.cos(qm[2])
            s = math.sin(qm[2])
            for i in range(nc):
                ow[i, 0] = c * offsets[i, 0] - s * offsets[i, 1]
                ow[i, 1] = s * offsets[i, 0] + c * offsets[i, 1]
        if point:
            it, res, stick[0] = _point_iterate(uf, minv, P, wk0, lam_n[0], assoc[0],
                                               kinds[0, 0], cp0, kinds[0, 1], dp0, tabs,
                                               offs[0, 0], ns[0, 0], offs[0, 1], ns[0, 1], r,
                                               tol, max_iter)
        else:
            it, res = _jacobi_iterate(uf, ue, minv, P, Pn, ow, stick, warm, lam_n, assoc,
                                      kinds, pars, tabs, offs, ns, r, tol, max_iter, nc,
                                      ndof)
        it_total += it
        if it > max_it:
            max_it = it
        if res > info[INFO_MAX_RESIDUAL]:
            info[INFO_MAX_RESIDUAL] = res
        if res > tol and status == STATUS_OK:
            status = STATUS_NOT_CONVERGED
            info[INFO_FAIL_STEP] = step
            info[INFO_FAIL_RESIDUAL] = res
        if point:                         # _end_velocity on scalars (no array call)
            ue[0] = uf[0] - minv[0] * P[0, 0]
            ue[1] = uf[1] - minv[1] * P[0, 1]
        else:
            _end_velocity(ue, uf, minv, P, ow, nc, ndof)
        all_stick = full_rank
        for i in range(nc):
            if not stick[i]:
                all_stick = False
        if all_stick and res <= tol:
            for j in range(ndof):
                ue[j] = 0.0
        finite = True
        moving = False
        for j in range(ndof):
            if not math.isfinite(ue[j]):
                finite = False
            if ue[j] != 0.0:
                moving = True
        if not finite:
            status = STATUS_NON_FINITE
            if info[INFO_FAIL_STEP] < 0:
                info[INFO_FAIL_STEP] = step
            halted = True
            break
        was_moving = False
        for j in range(ndof):
            if u[j] != 0.0:
                was_moving = True
            q[j] = qm[j] + 0.5 * dt * ue[j]
            u[j] = ue[j]
        if not moving:
            if was_moving:
                info[INFO_STOP_STEP] = step + 1
        else:
            info[INFO_STOP_STEP] = -1.0
        done = step + 1
        last = done == n_steps or (halt_at_rest and unforced and not moving)
        if (done % record_every == 0 or last) and nrec < rec_t.shape[0]:
            rec_t[nrec] = t0 + done * dt
            for j in range(ndof):
                rec_q[nrec, j] = q[j]
                rec_u[nrec, j] = u[j]
            nrec += 1
        if halt_at_rest and unforced and not moving:
            halted = True
            break
    if stop_at > step0:
        info[INFO_STEPS] = step + 1
        if status == STATUS_NON_FINITE:
            info[INFO_STEPS] = step
    info[INFO_HALTED] = 1.0 if halted else 0.0
    info[INFO_MAX_ITER] = max_it
    info[INFO_STATUS] = status
    info[INFO_RECORDS] = nrec
    info[INFO_ITER_TOTAL] = it_total
