"""Numba kernels of the quasi-static march of the slider chain (the chain, its arrays and
the complementarity solver in :mod:`asperity.microslip._chain_kernels`; physics in
:mod:`asperity.microslip.quasi_static`).

Along a linear load segment the state moves linearly between *events*; two exact ways
along a segment:

* event by event (:func:`segment_events`): at the current state solve the rate problem
  (which sliders at a threshold slide, which stick), advance to the next event, repeat;
* in one increment (:func:`segment_increment`): the backward-Euler increment to the
  segment's end is the exact end state when no slider stops sliding inside the segment (the
  set of sliding sliders only grows).  The wrapper takes it only where that holds: a
  uniform chain (:func:`asperity.microslip.chains.is_uniform`: the two-node model, the
  strip) under a segment whose external force does not change -- a theorem for the sliders
  of the end zones, and no stop in 453 364 events of fuzzed uniform chains and histories
  (random chains do stop: 8 081 stops in 8 255 segments) -- and after a check: the
  sliders sliding at the start all slip in the increment, some slider sticks (else the
  chain's translation is a rate's least motion), and all that slipped still slide at its
  end (the rate problem there); else the segment is marched event by event.

Cost (issue 28): each pivoting round is a chain solve bound by the latency of its
divisions, so independent problems are solved together (:func:`._chain_kernels.solve_lcps`,
one pass over the nodes): the rate problems at a segment's start and end with the next
segment's increment (solved ahead from this one's end state, used if this one is taken).
:func:`march_memo` (simulate's) also starts the rate problem at a segment's start from its
solution one cycle earlier (four rounds from every slider sticking, one once the cycle is
stabilised) and keeps its work arrays, with the increment solved ahead, from one call to
the next.  A pivoting's start changes its solution only where two solutions tie within
AT_THRESHOLD and SLIP_BACK: on fuzzed chains and histories the results are those of
:func:`march`, which remembers nothing, bit for bit (tests/test_chain_march.py).

Array-in/array-out loops, no Python objects, no validation; failures come back as the
status codes of :mod:`._chain_kernels`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ._chain_kernels import (
    _BLOCK_ROUNDS,
    _GO_ON,
    STATUS_NO_CONVERGENCE,
    STATUS_OK,
    rate_bounds,
    rate_statuses,
    solve_lcp,
    solve_lcps,
)

refresh(__file__)     # drop cached kernels compiled against older callees


@njit(cache=True)
def segment_events(kb, kt, cp, cm, fw, th, dF, u, q, acc, st, w, max_events, state, budget,
                   keep=True):
    """March the state (u, q) along one linear load segment (elongations ``th``, force
    change ``dF`` over it) event by event, from the fraction ``state[0]`` of the segment
    already done (``state[1]``: events so far in it) until it ends or about ``budget``
    node-passes are spent (one per node and event); ``acc`` (n,) accumulates each slider's
    |slip|; st (n,), w (7, n): work arrays.  ``state`` is updated (state[0] = 1: the
    segment is done); ``keep``: the segment goes on in the direction of the one before (the
    sliders' statuses the guess of its first rate problem).  Returns (code, node-passes
    spent)."""
    n = u.size
    lam = state[0]
    events = int(state[1])
    work = 0
    while True:
        code = rate_statuses(kb, kt, cp, cm, fw, th, dF, q, st, w, keep or lam > 0.0)
        work += n
        if code != STATUS_OK:
            return code, work
        lo, hi, du = w[0], w[1], w[6]
        # the next event: a sticking slider reaching a threshold it is not at (a rate out
        # of the one it is at is within AT_THRESHOLD of zero)
        dl = 1.0 - lam
        hit = False
        for i in range(n):
            if st[i] > 0:
                q[i] = cp[i]
            elif st[i] < 0:
                q[i] = -cm[i]
            else:
                dq = kt[i] * du[i]
                t = np.inf
                if dq > 0.0 and hi[i] != 0.0 and math.isfinite(cp[i]):
                    t = (cp[i] - q[i]) / dq
                elif dq < 0.0 and lo[i] != 0.0 and math.isfinite(cm[i]):
                    t = (-cm[i] - q[i]) / dq
                if t < dl:
                    dl = max(t, 0.0)
                    hit = True
        for i in range(n):
            d = dl * du[i]
            u[i] += d
            if st[i] == 0:
                q[i] += kt[i] * d
            else:
                acc[i] += abs(d)
        if not hit:
            state[0] = 1.0
            state[1] = events
            return STATUS_OK, work
        lam += dl
        events += 1
        state[0] = lam
        state[1] = events
        if events > max_events:
            return STATUS_NO_CONVERGENCE, work
        if work >= budget:
            return STATUS_OK, work


@njit(cache=True)
def segment_increment(kb, kt, cp, cm, fw, TH, dF, u, q, acc, guess, memo, W, S, X, keep, b,
                      codes, g_next):
    """The backward-Euler increment of one linear load segment, taken if certain to be the
    exact end state (see the module's docstring): returns True and updates (u, q, acc), or
    returns False and leaves them as they were.  ``guess`` (n,) int64: the statuses to
    start the pivoting from (in), the increment's statuses (out; left as they were if the
    rate problem at the start does not settle).  ``memo`` (n,) int64 or (0,): see
    :func:`march_memo`.  W (4, 7, n), S (4, n) int64, X (3, n), codes (4,) int64: work
    arrays (:func:`increment_work`); TH (4, n-1): the segment's elongations in rows 0 and 1.

    The increment is solved in slot ``b`` (2 or 3) unless it was already (codes[b] !=
    _GO_ON: its status, its statuses in S[b]); then, in one pass, the rate problems at its
    start (slot 0) and end (slot 1) and, if ``g_next`` (the next segment's guess) is given,
    the next segment's increment from this one's end state in the other slot (under the
    elongations TH[5 - b]): its status in codes[5 - b], good if this one is taken."""
    n = u.size
    if dF != 0.0:
        return False
    th = TH[0]
    nb = 5 - b
    rounds = 4 * n + 2 * _BLOCK_ROUNDS
    if codes[b] == _GO_ON:
        increment_problem(kt, cp, cm, q, guess, W[b], S[b])
        codes[b] = solve_lcp(kb, kt, cp, cm, th, W[b, 2], W[b, 0], W[b, 1], S[b], W[b, 3],
                             W[b, 4], W[b, 5], W[b, 6], rounds)
    gb, lo, hi, v = S[b], W[b, 0], W[b, 1], W[b, 6]
    if codes[b] != STATUS_OK:
        if rate_statuses(kb, kt, cp, cm, fw, th, 0.0, q, S[0], W[0], keep) == STATUS_OK:
            guess[:] = gb
        return False
    sticks = False
    for i in range(n):
        sticks = sticks or gb[i] == 0
    # the end state, kept aside in X: u, q, slip
    ue, qe, se = X[0], X[1], X[2]
    for i in range(n):
        ue[i] = u[i] + v[i]
        if gb[i] > 0:
            qe[i] = cp[i]
            se[i] = v[i] - hi[i]
        elif gb[i] < 0:
            qe[i] = -cm[i]
            se[i] = lo[i] - v[i]
        else:
            qe[i] = q[i] + kt[i] * v[i]
            se[i] = 0.0
    # the rate problems at the start (0) and, if some slider sticks, at the end (1)
    codes[0] = codes[1] = codes[nb] = _GO_ON
    rate_problem(cp, cm, fw, q, memo, S[0], W[0], (_ON if keep else _STUCK) if memo.size == 0
                 or memo[0] == _UNSET else _MEMO)
    if sticks:
        rate_problem(cp, cm, fw, qe, memo, S[1], W[1], _ON)
    else:
        codes[1] = STATUS_OK
    if g_next.size:
        increment_problem(kt, cp, cm, qe, g_next, W[nb], S[nb])
    else:
        codes[nb] = STATUS_OK
    solve_lcps(kb, kt, cp, cm, TH, W, S, codes, rounds)
    if codes[0] != STATUS_OK:
        if memo.size:
            memo[0] = _UNSET
        return False
    guess[:] = gb
    st = S[0]
    if memo.size:
        memo[:] = st
    for i in range(n):
        if st[i] != 0 and guess[i] != st[i]:
            return False            # a slider sliding at the start stopped in the increment
    if not sticks:
        return False                # the chain translates: its least motion is a rate's
    # every slider that slipped still slides at the end
    if codes[1] != STATUS_OK:
        return False
    st = S[1]
    for i in range(n):
        if guess[i] != 0 and se[i] > 0.0 and st[i] != guess[i]:
            return False
    for i in range(n):
        u[i] = ue[i]
        q[i] = qe[i]
        acc[i] += se[i]
    return True


@njit(cache=True)
def increment_problem(kt, cp, cm, q, guess, w, st):
    """Set up the increment from the state q without a change of force in w (lo, hi, base)
    and its pivoting's start ``guess`` in st."""
    for i in range(q.size):
        w[1, i] = (cp[i] - q[i]) / kt[i]
        w[0, i] = (-cm[i] - q[i]) / kt[i]
        w[2, i] = 0.0
        st[i] = guess[i]


#: rate_problem's starts: every slider sticking, the sliders at a threshold sliding on, the
#: statuses remembered from the cycle before; memo[0] == _UNSET: nothing remembered
_STUCK, _ON, _MEMO, _UNSET = 0, 1, 2, 2


@njit(cache=True)
def rate_problem(cp, cm, fw, q, memo, st, w, start):
    """Set up the rate problem at the state q without a change of force in w (lo, hi,
    base) and its pivoting's start in st (``start``: _STUCK, _ON as in
    :func:`rate_statuses`, or _MEMO: the statuses ``memo``)."""
    rate_bounds(cp, cm, q, w[0], w[1])
    base = w[2]
    for i in range(q.size):
        base[i] = 0.0 * fw[i]
        if start == _MEMO:        # those of them at their threshold still
            st[i] = memo[i] if (memo[i] > 0 and w[1, i] == 0.0) or (
                memo[i] < 0 and w[0, i] == 0.0) else 0
        elif start == _ON:
            st[i] = 1 if q[i] == cp[i] else (-1 if q[i] == -cm[i] else 0)
        else:
            st[i] = 0


@njit(cache=True)
def increment_work(n):
    """The work arrays of :func:`segment_increment` for a chain of n nodes: TH, W, S, X,
    codes, and ctl (2,) int64 (see :func:`march_memo`)."""
    ctl = np.zeros(2, np.int64)
    ctl[1] = 2
    return (np.empty((4, max(n - 1, 0))), np.empty((4, 7, n)), np.empty((4, n), np.int64),
            np.empty((3, n)), np.full(4, _GO_ON), ctl)


@njit(cache=True)
def march(kb, le, kt, cp, cm, fw, alpha_T, dT0, F0, dT_seq, F_seq, u, q, guess, state, acc,
          slip_seq, held_seq, rec_nodes, rec_u, max_events, events_only, budget):
    """March the load points (dT_seq[j], F_seq[j]) from the state (u, q) (updated in place),
    the first point's segment starting at the load (dT0, F0) and done up to the fraction
    ``state[0]`` (``state[1]``: its events so far, ``acc``: its sliders' |slip| so far),
    each linear segment in one certain increment or event by event (always, if
    ``events_only``), until every point is done or about ``budget`` node-passes are spent.
    The state (u, q, state, acc) carries everything: the points marched in pieces give
    exactly the result of one call.

    guess (m, n) int64: the sliders' statuses of each point's increment one cycle earlier,
    the pivoting's start (exact once the cycle is stabilised); overwritten.
    slip_seq (m,): the largest |slip| of a slider over each segment (out).
    held_seq (m,) int64: sliders below their thresholds at each point (out; 0 or 1 when the
    whole chain slides about a node).
    rec_u (m, len(rec_nodes)): node displacements recorded at each point.
    Returns (code, points completed, events marched one by one, node-passes spent); on
    return with points completed < m and code STATUS_OK, ``state`` holds the progress of
    the next point's segment."""
    none = np.empty(0, np.int64)
    return march_memo(kb, le, kt, cp, cm, fw, alpha_T, dT0, F0, dT_seq, F_seq, u, q, guess,
                      np.empty((dT_seq.size, 0), np.int64), increment_work(u.size), 0.0, 0.0,
                      none, state, acc, slip_seq, held_seq, rec_nodes, rec_u, max_events,
                      events_only, budget)


@njit(cache=True)
def march_memo(kb, le, kt, cp, cm, fw, alpha_T, dT0, F0, dT_seq, F_seq, u, q, guess, memo,
               ws, dT_next, F_next, g_next, state, acc, slip_seq, held_seq, rec_nodes, rec_u,
               max_events, events_only, budget):
    """:func:`march`, and

    memo (m, n) int64 (or (m, 0): nothing kept): the statuses of the rate problem at the
    start of each point's segment one cycle earlier (memo[j, 0] == _UNSET: not known), its
    pivoting's start; overwritten.  Once the cycle is stabilised it is that problem's
    solution (one round, not several from every slider sticking);
    ws: the work arrays (:func:`increment_work`), kept from one call to the next: the
    increment of the point after the last one marched, solved ahead, is taken from them by
    the next call, which must go on from where this one stopped (the same state, guesses
    and points);
    (dT_next, F_next): the point after dT_seq[-1], g_next (n,) int64 its guess (or (0,):
    none)."""
    n = u.size
    m = dT_seq.size
    TH, W, S, X, codes, ctl = ws
    none = g_next[:0]
    # the slot of the next increment, solved ahead for point ``ahead`` (ctl: of the call
    # before: solved ahead for the first point, its slot)
    b = ctl[1]
    ahead = 0 if ctl[0] == 1 and state[0] == 0.0 else -1
    ctl[0] = 0
    done = 0
    th = TH[0]
    st = S[0]
    w = W[0]
    events = 0
    work = 0
    a_dT = dT0
    a_F = F0
    p_dT = 0.0
    p_F = 0.0
    for j in range(m):
        ddT = dT_seq[j] - a_dT
        dF = F_seq[j] - a_F
        # the load goes on as in the segment before (not known for the first of a call)
        keep = j > 0 and ddT * p_dT >= 0.0 and dF * p_F >= 0.0 and (ddT != 0.0) == (
            p_dT != 0.0)
        for e in range(n - 1):
            th[e] = alpha_T * le[e] * ddT
            TH[1, e] = th[e]
        if state[0] == 0.0:
            for i in range(n):
                acc[i] = 0.0
            state[1] = 0.0
            if not events_only:
                if ahead != j:
                    codes[b] = _GO_ON
                # the next segment's increment solved ahead if it may be taken
                last = j + 1 == m
                g1 = g_next if last else guess[j + 1]
                nxt = g1.size > 0 and (F_next if last else F_seq[j + 1]) - F_seq[j] == 0.0
                if nxt:
                    dd = (dT_next if last else dT_seq[j + 1]) - dT_seq[j]
                    for e in range(n - 1):
                        TH[5 - b, e] = alpha_T * le[e] * dd
                ahead = -1
                if segment_increment(kb, kt, cp, cm, fw, TH, dF, u, q, acc, guess[j],
                                     memo[j], W, S, X, keep, b, codes, g1 if nxt else none):
                    state[0] = 1.0
                    work += 10 * n
                    if nxt:
                        ahead = j + 1
                        b = 5 - b
        if state[0] < 1.0:
            ev0 = int(state[1])
            code, wk = segment_events(kb, kt, cp, cm, fw, th, dF, u, q, acc, st, w,
                                      max_events, state, budget - work, keep)
            work += wk
            events += int(state[1]) - ev0
            if code != STATUS_OK:
                return code, j, events, work
            if state[0] < 1.0:
                return STATUS_OK, j, events, work
        smax = 0.0
        held = 0
        for i in range(n):
            if acc[i] > smax:
                smax = acc[i]
            if q[i] != cp[i] and q[i] != -cm[i]:
                held += 1
        slip_seq[j] = smax
        held_seq[j] = held
        for k in range(rec_nodes.size):
            rec_u[j, k] = u[rec_nodes[k]]
        a_dT = dT_seq[j]
        a_F = F_seq[j]
        p_dT = ddT
        p_F = dF
        state[0] = 0.0
        done = j + 1
        if work >= budget:
            break
    ctl[0] = 1 if ahead == done else 0
    ctl[1] = b
    return STATUS_OK, done, events, work
