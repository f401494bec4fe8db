"""Numba kernels of the slider chain: its equations, the complementarity problem of its
rates and increments (physics in :mod:`asperity.microslip.quasi_static`; the march in
:mod:`asperity.microslip._march_kernels`, the Moreau kernel of
:mod:`asperity.microslip.dynamic` in :mod:`asperity.microslip._dynamic_kernels`).

Array-in/array-out loops, no Python objects, no validation (the wrappers validate and
coerce).  Kernels cannot raise: failures come back as integer status codes (``STATUS_*``),
which the wrappers turn into messages or physical outcomes.

The chain (SPEC.md section 5), n nodes on a line:
    kb (n-1,)  axial stiffness of the element between nodes e and e+1 (N/m)
    le (n-1,)  its length (m); its free thermal elongation is alpha_T le dT
    kt (n,)    tangential contact stiffness of node i (N/m), in series with a slider
    cp, cm (n,) slider thresholds mu+ N_i (slides towards +x) and mu- N_i (towards -x), N,
               positive, possibly +inf (self-locking)
    fw (n,)    share of the external tangential force F acting on node i (sums to 1)
State: u (n,) node displacements and q (n,) contact forces q = kt (u - s) (s: slider
positions), admissible in [-cm, cp].  Equilibrium of node i (element forces
N_e = kb_e (u_{e+1} - u_e - alpha_T le_e dT)):  N_i - N_{i-1} - q_i + F fw_i = 0.

The rate-independent chain is piecewise linear: along a linear load segment the state moves
linearly between *events* (a sticking slider reaching a threshold, a sliding slider whose
slip would reverse); :mod:`._march_kernels` marches it, event by event or in one increment
where that is certain to be exact.

Both are linear complementarity problems of the same form, solved by principal pivoting
(:func:`solve_lcp`) on a condensation of the chain from its left end in springs in series
(no difference of large stiffnesses).  A sliding slider's force is its threshold exactly
(never recomputed from u - s), so which of two nearly equal thresholds is reached first is
decided by the thresholds, not by rounding: mu+ and mu- that differ by 1e-12 of their value
are told apart; forces within AT_THRESHOLD of a threshold are at it (ties).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

STATUS_OK = 0
STATUS_SLIDE_OFF = 1       # no equilibrium: the external load exceeds the sliders' capacity
STATUS_NO_CONVERGENCE = 2  # the pivoting did not settle, or too many events in a segment
STATUS_NON_FINITE = 3      # a displacement overflowed (never passed on as a number)

#: a sticking slider whose force is within this fraction of a threshold is at it, and a
#: force may overshoot a threshold by this fraction before the slider must slide (ties of
#: equal thresholds reached together; mu+ and mu- closer than limits.SAME_FRICTION = 1e-12
#: are made equal, so every distinct pair stands out of it)
AT_THRESHOLD = 1e-13
#: a sliding slider sticks when its slip points back by more than this x the largest
#: displacement (rate or increment): the sign of a rounding is no reversal
SLIP_BACK = 1e-12
#: nodal loads that sum to this x their magnitudes balance (a floating chain may translate)
BALANCED = 1e-12
#: principal pivoting: flip every violation for this many rounds, then one at a time (least
#: index first: finite for the positive definite problems of a chain that sticks somewhere)
_BLOCK_ROUNDS = 8
#: a round of the pivoting that settled nothing (:func:`lcp_settle`)
_GO_ON = -1


@njit(cache=True)
def in_series(k1, k2):
    """The stiffness of two springs in series (the condensation of :func:`solve_chain`)."""
    return k1 * k2 / (k1 + k2)


@njit(cache=True)
def solve_chain(kb, kt, th, f, st, G, P, v):
    """Displacements ``v`` (out) of the chain under element elongations ``th`` (n-1,) and
    nodal loads ``f`` (n,), with the contact springs of sliders ``st == 0`` (the others
    carry no stiffness: their force is in ``f``).

    Condensation from the left: the part 0..i of the chain pulls node i with P_i - G_i v_i
    (G_i: its stiffness to the support, springs in series; P_i: its load), then back
    substitution from the right end.  G, P: work arrays (n,).
    Returns 0; 1 if no spring holds the chain and its loads do not balance; 2 if no spring
    holds it and they balance (v holds the solution with v[n-1] = 0: the rigid
    translation is the caller's)."""
    n = v.size
    G[0] = kt[0] if st[0] == 0 else 0.0
    P[0] = f[0]
    fabs = abs(f[0])
    for i in range(1, n):
        e = i - 1
        if G[e] > 0.0:
            sr = in_series(kb[e], G[e])
            p = sr * (P[e] / G[e] + th[e])
        else:
            sr = 0.0
            p = P[e]
        G[i] = sr + (kt[i] if st[i] == 0 else 0.0)
        P[i] = p + f[i]
        fabs += abs(f[i])
    code = 0
    if G[n - 1] > 0.0:
        v[n - 1] = P[n - 1] / G[n - 1]
    else:
        if abs(P[n - 1]) > BALANCED * fabs:
            return 1
        v[n - 1] = 0.0
        code = 2
    for i in range(n - 2, -1, -1):
        if G[i] > 0.0:
            sr = in_series(kb[i], G[i])
            v[i] = (P[i] + sr * (v[i + 1] - th[i] - P[i] / G[i])) / G[i]
        else:
            v[i] = v[i + 1] - th[i] + P[i] / kb[i]
    return code


@njit(cache=True)
def _translate(kt, st, lo, hi, v):
    """No spring holds the chain and its loads balance: add the translation t of least
    motion (minimising sum kt (v + t)^2, the limit of a small viscosity) that keeps every
    slider's direction (v + t >= hi sliding towards +x, <= lo towards -x).  Returns the
    index of a slider that cannot keep its direction whatever t (it must stick) or -1."""
    n = v.size
    tlo = -np.inf
    thi = np.inf
    ilo = -1
    ihi = -1
    num = 0.0
    den = 0.0
    for i in range(n):
        if st[i] > 0 and hi[i] - v[i] > tlo:
            tlo = hi[i] - v[i]
            ilo = i
        elif st[i] < 0 and lo[i] - v[i] < thi:
            thi = lo[i] - v[i]
            ihi = i
        num -= kt[i] * v[i]
        den += kt[i]
    t = num / den
    if tlo > thi:
        return ilo if tlo - t > t - thi else ihi
    t = min(max(t, tlo), thi)
    for i in range(n):
        v[i] += t
    return -1


@njit(cache=True)
def _all_at_bounds(kt, cp, cm, lo, hi, st, v):
    """Every slider slides, or sticks with its force at a threshold (within AT_THRESHOLD),
    and at least one sticks."""
    one = False
    for i in range(v.size):
        if st[i] == 0:
            if not (_at_hi(kt[i], cp[i], hi[i], v[i]) or _at_lo(kt[i], cm[i], lo[i], v[i])):
                return False
            one = True
    return one


@njit(cache=True)
def _at_hi(kt, cp, hi, v):
    """A sticking slider's force kt v at its (finite) threshold towards +x."""
    return math.isfinite(hi) and abs(kt * (v - hi)) <= AT_THRESHOLD * cp


@njit(cache=True)
def _at_lo(kt, cm, lo, v):
    """A sticking slider's force kt v at its (finite) threshold towards -x."""
    return math.isfinite(lo) and abs(kt * (v - lo)) <= AT_THRESHOLD * cm


@njit(cache=True)
def solve_lcp(kb, kt, cp, cm, th, base, lo, hi, st, f, G, P, v, max_rounds):
    """The complementarity problem of the chain: displacements (rates or increments) ``v``
    under elongations ``th`` and nodal loads ``base``, where a sticking slider i keeps
    lo_i <= v_i <= hi_i (its force kt v within its thresholds) and a sliding one has its
    force at the bound (load base_i - kt_i hi_i, slip v_i - hi_i >= 0 towards +x; likewise
    lo_i towards -x).  ``st`` (in: the guess, out: the solution): +1/-1 sliding towards
    +x/-x, 0 sticking.  f, G, P: work arrays.  Returns STATUS_OK, STATUS_SLIDE_OFF,
    STATUS_NO_CONVERGENCE or STATUS_NON_FINITE."""
    for rnd in range(max_rounds):
        lcp_loads(kt, base, lo, hi, st, f)
        code = lcp_settle(kt, cp, cm, lo, hi, st, f, v, solve_chain(kb, kt, th, f, st, G, P, v),
                          rnd)
        if code != _GO_ON:
            return code
    return STATUS_NO_CONVERGENCE


@njit(cache=True)
def lcp_loads(kt, base, lo, hi, st, f):
    """The nodal loads ``f`` of a round of :func:`solve_lcp`: a sliding slider's force at
    its bound."""
    for i in range(f.size):
        if st[i] > 0:
            f[i] = base[i] - kt[i] * hi[i]
        elif st[i] < 0:
            f[i] = base[i] - kt[i] * lo[i]
        else:
            f[i] = base[i]


@njit(cache=True)
def lcp_settle(kt, cp, cm, lo, hi, st, f, v, code, rnd):
    """The end of round ``rnd`` of :func:`solve_lcp` (``code``: of the chain's solve
    ``v`` under the loads ``f``): a status (STATUS_OK: ``st`` solves it), or _GO_ON with
    ``st`` pivoted for the next round."""
    n = v.size
    if code == 1:
        # the sliders cannot hold the load: one pushing along it stops
        tot = 0.0
        for i in range(n):
            tot += f[i]
        flip = -1
        for i in range(n):
            if st[i] != 0 and st[i] * tot < 0.0:
                flip = i
                break
        if flip < 0:
            return STATUS_SLIDE_OFF
        st[flip] = 0
        return _GO_ON
    if code == 2:
        flip = _translate(kt, st, lo, hi, v)
        if flip >= 0:
            st[flip] = 0
            return _GO_ON
    scale = 0.0
    for i in range(n):
        scale = max(scale, abs(v[i]))
    if not math.isfinite(scale):
        return STATUS_NON_FINITE
    back = SLIP_BACK * scale
    nviol = 0
    first = -1
    for i in range(n):
        to = 0
        if st[i] > 0:
            to = -1 if v[i] - hi[i] < -back else 1
        elif st[i] < 0:
            to = 1 if v[i] - lo[i] > back else -1
        elif kt[i] * (v[i] - hi[i]) > AT_THRESHOLD * cp[i]:
            to = 2
        elif kt[i] * (lo[i] - v[i]) > AT_THRESHOLD * cm[i]:
            to = -2
        if to == 2 or to == -2 or (st[i] != 0 and to == -st[i]):
            nviol += 1
            if first < 0:
                first = i
            if rnd < _BLOCK_ROUNDS:
                st[i] = 0 if st[i] != 0 else to // 2
    if nviol == 0:
        if code == 0 and _all_at_bounds(kt, cp, cm, lo, hi, st, v):
            # a degenerate solution: every slider slides or sticks exactly at a bound, a
            # whole family of solutions (the chain may translate); the one of least
            # motion lets them all slide (solve again so, if that keeps directions)
            for i in range(n):
                if st[i] == 0:
                    st[i] = 1 if _at_hi(kt[i], cp[i], hi[i], v[i]) else -1
            return _GO_ON
        return STATUS_OK
    if rnd >= _BLOCK_ROUNDS:
        st[first] = 0 if st[first] != 0 else (1 if v[first] > hi[first] else -1)
    return _GO_ON


@njit(cache=True)
def solve_lcps(kb, kt, cp, cm, TH, W, ST, codes, max_rounds):
    """:func:`solve_lcp` for several independent problems at once, round by round (each
    round's chain solves in one pass over the nodes: their recurrences, each bound by the
    latency of its divisions, overlap in the processor): problem k under the elongations
    TH[k], W[k] = (lo, hi, base, f, G, P, v), statuses ST[k], for each k with codes[k]
    == _GO_ON on entry; codes[k] (out): its status.  Each problem takes exactly the rounds
    it takes alone: the results are those of :func:`solve_lcp`, bit for bit."""
    K = codes.size
    chain = np.zeros(K, np.int64)
    for rnd in range(max_rounds):
        more = False
        for k in range(K):
            if codes[k] == _GO_ON:
                lcp_loads(kt, W[k, 2], W[k, 0], W[k, 1], ST[k], W[k, 3])
                more = True
        if not more:
            return
        solve_chains(kb, kt, TH, W, ST, codes, chain)
        for k in range(K):
            if codes[k] == _GO_ON:
                codes[k] = lcp_settle(kt, cp, cm, W[k, 0], W[k, 1], ST[k], W[k, 3], W[k, 6],
                                      chain[k], rnd)
    for k in range(K):
        if codes[k] == _GO_ON:
            codes[k] = STATUS_NO_CONVERGENCE


@njit(cache=True)
def solve_chains(kb, kt, TH, W, ST, codes, chain):
    """:func:`solve_chain` of the problems k with codes[k] == _GO_ON (see
    :func:`solve_lcps`), the same operations in one pass over the nodes; chain[k] (out):
    each one's code."""
    K = codes.size
    n = kt.size
    fabs = np.zeros(K)
    for k in range(K):
        if codes[k] == _GO_ON:
            W[k, 4, 0] = kt[0] if ST[k, 0] == 0 else 0.0
            W[k, 5, 0] = W[k, 3, 0]
            fabs[k] = abs(W[k, 3, 0])
    for i in range(1, n):
        e = i - 1
        for k in range(K):
            if codes[k] != _GO_ON:
                continue
            g = W[k, 4, e]
            if g > 0.0:
                sr = in_series(kb[e], g)
                p = sr * (W[k, 5, e] / g + TH[k, e])
            else:
                sr = 0.0
                p = W[k, 5, e]
            W[k, 4, i] = sr + (kt[i] if ST[k, i] == 0 else 0.0)
            W[k, 5, i] = p + W[k, 3, i]
            fabs[k] += abs(W[k, 3, i])
    for k in range(K):
        if codes[k] != _GO_ON:
            continue
        chain[k] = 0
        if W[k, 4, n - 1] > 0.0:
            W[k, 6, n - 1] = W[k, 5, n - 1] / W[k, 4, n - 1]
        elif abs(W[k, 5, n - 1]) > BALANCED * fabs[k]:
            chain[k] = 1
        else:
            W[k, 6, n - 1] = 0.0
            chain[k] = 2
    for i in range(n - 2, -1, -1):
        for k in range(K):
            if codes[k] != _GO_ON or chain[k] == 1:
                continue
            g = W[k, 4, i]
            P = W[k, 5, i]
            if g > 0.0:
                sr = in_series(kb[i], g)
                W[k, 6, i] = (P + sr * (W[k, 6, i + 1] - TH[k, i] - P / g)) / g
            else:
                W[k, 6, i] = W[k, 6, i + 1] - TH[k, i] + P / kb[i]


@njit(cache=True)
def rate_bounds(cp, cm, q, lo, hi):
    """Bounds of the rate problem at the state q: a slider at a threshold (within
    AT_THRESHOLD) may not move out of it (bound 0), the others are free (+-inf)."""
    for i in range(q.size):
        hi[i] = 0.0 if q[i] >= cp[i] * (1.0 - AT_THRESHOLD) else np.inf
        lo[i] = 0.0 if q[i] <= -cm[i] * (1.0 - AT_THRESHOLD) else -np.inf


@njit(cache=True)
def rate_statuses(kb, kt, cp, cm, fw, th, dF, q, st, w, keep=True):
    """The sliders' statuses ``st`` (out) of the rate problem at the state q under the load
    rates (th, dF); w: (7, n) work array (w[6] holds the rates on return).  The pivoting
    starts from the sliders at a threshold sliding on (``keep``: the load goes on as
    before) or from every slider sticking (the load turns back: they all stop).  Returns
    the status code."""
    n = q.size
    lo, hi, base, f, G, P, v = w[0], w[1], w[2], w[3], w[4], w[5], w[6]
    rate_bounds(cp, cm, q, lo, hi)
    for i in range(n):
        base[i] = dF * fw[i]
        if keep:
            st[i] = 1 if q[i] == cp[i] else (-1 if q[i] == -cm[i] else 0)
        else:
            st[i] = 0
    return solve_lcp(kb, kt, cp, cm, th, base, lo, hi, st, f, G, P, v, 4 * n + 2 * _BLOCK_ROUNDS)
