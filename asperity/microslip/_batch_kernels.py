"""Numba kernel of :func:`asperity.microslip.batch.assess_batch`: a whole block of cases of
one model in one call, each case the per-case path (:func:`~.risk.assess_assembly` ->
:func:`~.verdict.assess` -> :func:`~.quasi_static.long_life` -> ``simulate``) step for
step: the chain built as ``two_node_chain``/``strip_chain`` and ``Assembly.chain`` build
it, ``elastic_limit``, the checks of ``simulate`` (margin, capacity, cost), the lead-in and
the cycles marched by the same :func:`._march_kernels.march` with the same arguments (a
budget that never splits a cycle), the stabilisation test, the drift and its
extrapolation.  Sums over nodes are numpy's (pairwise, :func:`np_sum`) and the weighted
mean ``np.dot`` (BLAS, as ``weight @ u``), so the numbers are the per-case path's.

A case the per-case path would refuse or fail (resolvability of the chain, margin, cost,
a solver status other than OK or slide-off, an overflowing count) gets CODE_OTHER: the
caller runs it through the per-case path, which gives the message.  No validation here.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ._chain_kernels import STATUS_OK, STATUS_SLIDE_OFF, solve_chain
from ._march_kernels import march

refresh(__file__)     # drop cached kernels compiled against older callees

CODE_OK = 0
CODE_SLIDES_OFF = 1
CODE_OTHER = 2        # not handled here: run the case through the per-case path
#: verdict indices (verdict.VERDICTS)
SHAKEDOWN, ALTERNATING, RATCHET, SLIDES_OFF = 0, 1, 2, 3
#: float outputs (rows of ``fout``) and integer outputs (rows of ``iout``)
F_DT_C, F_MARGIN, F_DRIFT, F_AFTER, F_CYCLES_TO, F_MU_PLUS, F_MU_MINUS = range(7)
I_CODE, I_VERDICT, I_STABILISED, I_EXTRAPOLATED, I_MARCHED = range(5)
#: the constants of the per-case path (chains.TOL, limits, quasi_static), as numbers
STABILISED, NO_DRIFT, EVENTS_PER_NODE = 1e-9, 1e-8, 50
STIFFNESS_RATIO, ASYMMETRY, MARGIN, SAME_FRICTION = 1e9, 1e3, 1e4, 1e-12
MAX_NODE_UPDATES = 3e10
BUDGET = 1 << 60      # node-passes of one march call: a cycle is never split


@njit(cache=True)
def _block_sum(a, lo, n):
    """numpy's sum of a block of at most 128 values: eight running sums, then the rest."""
    if n < 8:
        res = 0.0
        for i in range(lo, lo + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    while i < n - (n % 8):
        b = lo + i
        r0, r1, r2, r3 = r0 + a[b], r1 + a[b + 1], r2 + a[b + 2], r3 + a[b + 3]
        r4, r5, r6, r7 = r4 + a[b + 4], r5 + a[b + 5], r6 + a[b + 6], r7 + a[b + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@njit(cache=True)
def np_sum(a, lo, n):
    """numpy's sum of a[lo:lo + n] (float64, contiguous): its pairwise summation (halves
    cut at a multiple of 8 down to blocks of 128), the same additions in the same order.
    Without recursion (numba's cache of a recursive kernel crashes when loaded): a stack
    of tasks (lo, n, 0: sum the part, 1: add the last two partial sums)."""
    if n <= 128:
        return _block_sum(a, lo, n)
    t_lo, t_n, t_op = np.empty(256, np.int64), np.empty(256, np.int64), np.empty(256, np.int64)
    vals = np.empty(128)
    t_lo[0], t_n[0], t_op[0] = lo, n, 0
    nt, nv = 1, 0
    while nt:
        nt -= 1
        if t_op[nt] == 1:
            nv -= 1
            vals[nv - 1] = vals[nv - 1] + vals[nv]
        elif t_n[nt] <= 128:
            vals[nv] = _block_sum(a, t_lo[nt], t_n[nt])
            nv += 1
        else:
            b, m = t_lo[nt], t_n[nt]
            m2 = m // 2
            m2 -= m2 % 8
            t_op[nt] = 1
            t_lo[nt + 1], t_n[nt + 1], t_op[nt + 1] = b + m2, m - m2, 0
            t_lo[nt + 2], t_n[nt + 2], t_op[nt + 2] = b, m2, 0
            nt += 3
    return vals[0]


@njit(cache=True)
def same_friction(mp, mm):
    """limits.same_friction."""
    if mp == mm:
        return True
    if not (math.isfinite(mp) and math.isfinite(mm)):
        return False
    return abs(mp - mm) <= SAME_FRICTION * max(abs(mp), abs(mm))


@njit(cache=True)
def build_chain(strip, par, j, n, mp, mm, force_at, kb, le, kt, cp, cm, fw, weight):
    """The chain arrays of case j (chains.two_node_chain / strip_chain, then
    Assembly.chain's force placement: 0 uniform, 1 start, 2 end); returns (mu+, mu-) as
    the chain holds them, or mu+ = NaN if ``_check_resolvable`` refuses the chain.
    par (6, m): two-node k, l0, alpha_T, k_t, N; strip h, E, p, l, k_t, alpha_T."""
    if same_friction(mp, mm):
        mm = mp
    if strip:
        h, E, p, ll, k_t = par[0, j], par[1, j], par[2, j], par[3, j], par[4, j]
        dx = ll / (n - 1)
        ke = E * h / dx
        for e in range(n - 1):
            kb[e] = ke
            le[e] = dx
        for i in range(n):
            t = 0.5 * dx if i == 0 or i == n - 1 else dx
            N = p * t
            kt[i] = k_t * t
            cp[i] = mp * N
            cm[i] = mm * N
            fw[i] = t / ll
            weight[i] = t / ll
    else:
        k, l0, k_t, N = par[0, j], par[1, j], par[3, j], par[4, j]
        kb[0] = k
        le[0] = l0
        for i in range(2):
            kt[i] = k_t
            cp[i] = mp * N
            cm[i] = mm * N
            fw[i] = 0.5
            weight[i] = 0.5
    if force_at != 0:
        for i in range(n):
            fw[i] = 0.0
        fw[0 if force_at == 1 else n - 1] = 1.0
    if kb.max() / kt.min() > STIFFNESS_RATIO or kt.max() / kb.min() > STIFFNESS_RATIO:
        return np.nan, mm
    if math.isfinite(mp) and math.isfinite(mm) and max(mp, mm) > ASYMMETRY * min(mp, mm):
        return np.nan, mm
    return mp, mm


@njit(cache=True)
def elastic_limit(kb, le, kt, cp, cm, alpha_T, th, f, st, G, P, u):
    """chains.elastic_limit (heating): dT_c of the chain (inf if no slider ever slips)."""
    n = kt.size
    for e in range(n - 1):
        th[e] = alpha_T * le[e] * 1.0
    for i in range(n):
        f[i] = 0.0
        st[i] = 0
    solve_chain(kb, kt, th, f, st, G, P, u)
    lim = np.inf
    for i in range(n):
        q = kt[i] * u[i]
        x = cp[i] / q if q > 0 else (cm[i] / -q if q < 0 else np.inf)
        lim = min(lim, x)
    return lim


@njit(cache=True)
def refine(a, b, s, out):
    """Loading._refine of one segment: s points from a (excluded) to b (included)."""
    for jj in range(s):
        out[jj] = a + (b - a) * float(jj + 1) / s


@njit(cache=True)
def march_cost(n, dT, F, s, cycles):
    """quasi_static.march_cost (bytes, node-passes) of a uniform chain, recording 2 nodes."""
    P = dT.size
    m = (P - 1) * s
    points = cycles * m + s
    mem = 24.0 * n * 8 + float(m) * n * 8 + cycles * (n * 8.0 + 300) + 2.0 * points * 40
    nz = 0
    for i in range(P - 1):
        nz += F[i + 1] - F[i] != 0.0
    moving = float(s * nz)
    lead = s * (n / 10 if F[0] != 0.0 else 1.0)
    work = cycles * (10.0 * (m - moving) * n + moving * n * n + 2000) + 10 * lead * n
    return mem, work


@njit(cache=True)
def assess_block(strip, par, n, mu_p, mu_m, dT, F, s, force_at, cycles, tolerance,
                 max_marched, free_bytes, max_work, fout, iout):
    """Every case of the block (see the module's docstring); fout (7, m), iout (5, m) out."""
    m_cases, P = dT.shape
    mp_ = (P - 1) * s
    kb, le, th = np.empty(n - 1), np.empty(n - 1), np.empty(n - 1)
    kt, cp, cm, fw, weight = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    u, q, q_prev, acc, f = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    G, Pw = np.empty(n), np.empty(n)
    st = np.empty(n, np.int64)
    state = np.empty(2)
    rec = np.array([0, n - 1], np.int64)
    dTc, Fc, slip = np.empty(mp_), np.empty(mp_), np.empty(mp_)
    held = np.empty(mp_, np.int64)
    guess = np.empty((mp_, n), np.int64)
    ru = np.empty((mp_, 2))
    dT0, F0, slip0 = np.empty(s), np.empty(s), np.empty(s)
    held0 = np.empty(s, np.int64)
    guess0 = np.empty((s, n), np.int64)
    ru0 = np.empty((s, 2))
    mean_u = np.empty(max_marched + 1)
    max_events = EVENTS_PER_NODE * n + 1000
    for j in range(m_cases):
        fout[:, j] = np.nan
        iout[:, j] = -1
        iout[I_CODE, j] = CODE_OTHER
        mp, mm = build_chain(strip, par, j, n, mu_p[j], mu_m[j], force_at, kb, le, kt, cp,
                             cm, fw, weight)
        if math.isnan(mp):
            continue                                   # _check_resolvable refuses it
        alpha_T = par[5, j] if strip else par[2, j]
        dTj, Fj = dT[j], F[j]
        dT_c = elastic_limit(kb, le, kt, cp, cm, alpha_T, th, f, st, G, Pw, u)
        rng = dTj.max() - dTj.min()
        fin = math.isfinite(dT_c)
        if fin and rng / (2.0 * dT_c) > MARGIN:
            continue                                   # quasi_static.check_margin
        fout[F_DT_C, j] = dT_c
        fout[F_MARGIN, j] = rng / (2.0 * dT_c) if fin and dT_c > 0 else 0.0
        fout[F_MU_PLUS, j] = mp
        fout[F_MU_MINUS, j] = mm
        tol = tolerance[j]
        c = cycles[j]
        ncyc = int(min(max_marched, math.ceil(c)))
        # quasi_static.check_capacity
        hi = max(0.0, Fj.max())
        lo = min(0.0, Fj.min())
        if hi >= np_sum(cp, 0, n) or -lo >= np_sum(cm, 0, n):
            _slides_off(j, tol, fout, iout)
            continue
        mem, work = march_cost(n, dTj, Fj, s, ncyc)
        if mem > free_bytes or work > MAX_NODE_UPDATES or work > max_work:
            continue                                   # quasi_static.check_march
        # load_scale and the stabilisation's force scale
        big = max(rng, max(abs(dTj.max()), abs(dTj.min())))
        scale = abs(alpha_T) * np_sum(le, 0, n - 1) * big
        el = 0.0
        cap = -np.inf
        for i in range(n):
            if math.isfinite(cp[i]) and math.isfinite(cm[i]):
                el = max(el, max(cp[i], cm[i]) / kt[i])
            for x in (cp[i], cm[i]):
                if math.isfinite(x):
                    cap = max(cap, x)
        scale = max(scale, el, 1e-300)
        cap = cap if cap > 0 else 1.0
        u[:] = 0.0
        q[:] = 0.0
        state[:] = 0.0
        acc[:] = 0.0
        a_dT, a_F = 0.0, 0.0
        code = STATUS_OK
        if dTj[0] != 0.0 or Fj[0] != 0.0:              # the lead-in
            refine(0.0, dTj[0], s, dT0)
            refine(0.0, Fj[0], s, F0)
            guess0[:] = 0
            code = march(kb, le, kt, cp, cm, fw, alpha_T, a_dT, a_F, dT0, F0, u, q, guess0,
                         state, acc, slip0, held0, rec, ru0, max_events, False, BUDGET)[0]
            a_dT, a_F = dT0[s - 1], F0[s - 1]
        for i in range(P - 1):
            refine(dTj[i], dTj[i + 1], s, dTc[i * s:(i + 1) * s])
            refine(Fj[i], Fj[i + 1], s, Fc[i * s:(i + 1) * s])
        guess[:] = 0
        mean_u[0] = np.dot(weight, u)
        q_prev[:] = q
        stab = -1
        slipped = False
        k = 0
        while code == STATUS_OK and k < ncyc:
            k += 1
            code = march(kb, le, kt, cp, cm, fw, alpha_T, a_dT, a_F, dTc, Fc, u, q, guess,
                         state, acc, slip, held, rec, ru, max_events, False, BUDGET)[0]
            if code != STATUS_OK:
                break
            a_dT, a_F = dTc[mp_ - 1], Fc[mp_ - 1]
            mean_u[k] = np.dot(weight, u)
            slipped = slip.max() > NO_DRIFT * scale
            dq = 0.0
            for i in range(n):
                dq = max(dq, abs(q[i] - q_prev[i]))
            if dq <= STABILISED * cap:
                stab = k if stab < 0 else stab
                if k >= 2:
                    break
            else:
                stab = -1
            q_prev[:] = q
        if code == STATUS_SLIDE_OFF:
            _slides_off(j, tol, fout, iout)
            continue
        if code != STATUS_OK:
            continue                                   # quasi_static.SolverError
        d = mean_u[k] - mean_u[k - 1]
        if abs(d) <= NO_DRIFT * scale:
            d = 0.0
        if not _life(j, mean_u, k, d, c, tol, fout):
            continue                                   # cycles_to overflows (math.ceil)
        fout[F_DRIFT, j] = d
        iout[I_VERDICT, j] = RATCHET if d != 0.0 else (ALTERNATING if slipped else SHAKEDOWN)
        iout[I_STABILISED, j] = stab
        iout[I_EXTRAPOLATED, j] = c > k
        iout[I_MARCHED, j] = k
        iout[I_CODE, j] = CODE_OK


@njit(cache=True)
def _slides_off(j, tol, fout, iout):
    """verdict.assess's fields of a case that slides off."""
    iout[I_CODE, j] = CODE_SLIDES_OFF
    iout[I_VERDICT, j] = SLIDES_OFF
    iout[I_MARCHED, j] = 0
    fout[F_CYCLES_TO, j] = np.nan if math.isnan(tol) else 0.0


@njit(cache=True)
def _life(j, mean_u, k, d, c, tol, fout):
    """MicroslipResult.drift_after(c) and cycles_to(tol) (NaN: None) into fout; False if
    the per-case path's math.ceil would overflow."""
    if c <= k and c == np.floor(c):
        fout[F_AFTER, j] = mean_u[int(c)]
    else:
        fout[F_AFTER, j] = mean_u[k] + (c - k) * d
    if math.isnan(tol):
        return True
    for i in range(k + 1):
        if abs(mean_u[i]) >= tol:
            fout[F_CYCLES_TO, j] = i
            return True
    if d == 0.0:
        return True
    last = mean_u[k]
    if np.sign(last) == 0.0 or np.sign(last) == np.sign(d):
        x = (tol - abs(last)) / abs(d)
    else:
        x = (tol + abs(last)) / abs(d)
    if not math.isfinite(x):
        return False
    fout[F_CYCLES_TO, j] = k + max(np.ceil(x), 1.0)
    return True
