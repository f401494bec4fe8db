"""The fast default march of the slider chain (issue 28 item 3) against the march it speeds
up: simulate remembers each segment's start statuses from the cycle before (the pivoting's
start of its rate problem), solves the next segment's increment ahead in the same pass as
this one's rate problems and keeps its work arrays from one call of the kernel to the next.
None of it may change a result: on fuzzed chains (two nodes, strips, random non-uniform
chains) and histories, simulate gives bit for bit what the public kernel ``march`` gives
point by point with nothing remembered and nothing solved ahead, in pieces of one load
point as in one piece, and agrees with the event-by-event march (an independent path: no
increment, every slider's start and stop located one by one)."""
from __future__ import annotations

import numpy as np
import pytest

from asperity.microslip import pacing, quasi_static
from asperity.microslip.chains import (
    TOL,
    Chain,
    MicroslipTolerances,
    elastic_limit,
    is_uniform,
    strip_chain,
    two_node_chain,
)
from asperity.microslip.loading import Loading
from asperity.microslip.quasi_static import simulate

EVENTS = MicroslipTolerances(events_only=True)


def fuzzed(rng, case):
    """A chain (uniform: two nodes or a strip; every third a random non-uniform chain,
    marched event by event) and a history of 2-5 points, no force, a constant one or one
    that changes (marched event by event), 1-3 load points per segment."""
    kind = case % 3
    n = int(rng.integers(2, 50))
    r = 10 ** rng.uniform(-12, 0.5) * rng.choice([-1, 1]) * (rng.random() < 0.85)
    mup, mum = 0.15 * (1 + max(r, 0)), 0.15 * (1 + max(-r, 0))
    sign = rng.choice([-1.0, 1.0])
    if kind == 2 and n > 2:
        le = rng.uniform(0.5, 2, n - 1) * 1e-3
        trib = np.zeros(n)
        trib[:-1] += le / 2
        trib[1:] += le / 2
        normal = 5e6 * trib * rng.uniform(0.5, 2, n)
        fw = rng.uniform(0.1, 1, n)
        c = Chain("random", np.r_[0.0, np.cumsum(le)],
                  2.75e8 / le * rng.uniform(0.5, 2, n - 1), le,
                  trib * 10 ** rng.uniform(12, 14) * rng.uniform(0.5, 2, n), mup * normal,
                  mum * normal, fw / fw.sum(), trib / trib.sum(), 6e-6 * sign, mup, mum,
                  {"normal_loads": normal})
    elif n == 2:
        c = two_node_chain(1e6, 0.1, 1.2e-5 * sign, 10 ** rng.uniform(3, 8), 100.0, mup, mum)
    else:
        kt = (10 ** rng.uniform(-1, 1.5) / 0.04) ** 2 * 1.1e11 * 2.5e-3
        c = strip_chain(2.5e-3, 1.1e11, 5e6, 0.04, kt, 6e-6 * sign, n, mup, mum)
    cap = min(c.cp.sum(), c.cm.sum())
    m = int(rng.integers(2, 6))
    dT = np.clip(rng.uniform(-1, 1, m) * elastic_limit(c) * 10 ** rng.uniform(-0.5, 1.5),
                 -4000, 4000)
    force = int(rng.integers(0, 4))
    F = (np.zeros(m) if force <= 1 else np.full(m, rng.uniform(-0.9, 0.9) * cap)
         if force == 2 else rng.uniform(-0.9, 0.9, m) * cap)
    return c, Loading(np.r_[dT, dT[0]], np.r_[F, F[0]], int(rng.integers(1, 4)))


def march_point_by_point(c, loading, cycles):
    """The march as simulate did it before issue 28: the public kernel ``march`` once a
    cycle (fresh work arrays, no start statuses remembered, nothing solved ahead; a
    chain outside the uniform class event by event, as simulate does).
    Returns (u at the cycle ends, q at the end, events one by one, displacements of the end
    nodes at every load point)."""
    from asperity.microslip._march_kernels import march
    n = c.n
    u, q, state, acc = np.zeros(n), np.zeros(n), np.zeros(2), np.zeros(n)
    rec = np.array([0, n - 1], np.int64)
    load, events, trace = [0.0, 0.0], 0, [np.zeros((1, 2))]

    def run(dT, F, guess):
        m = dT.size
        ru = np.empty((m, 2))
        code, done, ev, _ = march(c.kb, c.le, c.kt, c.cp, c.cm, c.fw, float(c.alpha_T),
                                  load[0], load[1], dT, F, u, q, guess, state, acc,
                                  np.zeros(m), np.zeros(m, np.int64), rec, ru,
                                  TOL.max_events_per_node * n + 1000, not is_uniform(c),
                                  1 << 62)
        assert code == 0 and done == m
        load[:] = float(dT[-1]), float(F[-1])
        trace.append(ru)
        return ev

    dT0, F0 = loading.lead_in()
    if dT0.size:
        events += run(dT0, F0, np.zeros((dT0.size, n), np.int64))
    dTc, Fc = loading.cycle_points()
    guess = np.zeros((dTc.size, n), np.int64)
    ends = [u.copy()]
    for _ in range(cycles):
        events += run(dTc, Fc, guess)
        ends.append(u.copy())
    return np.array(ends), q.copy(), events, np.concatenate(trace)


class OnePoint(pacing.Pacer):
    """Pieces of one node-pass: the kernel returns after every load point (and every event
    of a segment marched event by event)."""

    def size(self, left=None):
        return 1


@pytest.mark.parametrize("seed", range(4))
def test_the_fast_march_is_the_march_point_by_point_bit_for_bit(seed, monkeypatch):
    rng = np.random.default_rng(2028 + seed)
    for case in range(12):
        c, L = fuzzed(rng, case)
        cycles = int(rng.integers(3, 9))
        ends, q, events, trace = march_point_by_point(c, L, cycles)
        res = simulate(c, L, cycles, until_stable=False)
        what = f"seed {seed} case {case}: {c.kind}, {c.n} nodes"
        np.testing.assert_array_equal(res.u_end, ends, err_msg=what)
        np.testing.assert_array_equal(res.q_end, q, err_msg=what)
        np.testing.assert_array_equal(res.trace["u"], trace, err_msg=what)
        assert res.solver["events_one_by_one"] == events, what
        if case % 4 == 0:
            with monkeypatch.context() as mp:
                mp.setattr(quasi_static, "Pacer", OnePoint)
                pieces = simulate(c, L, cycles, until_stable=False)
            np.testing.assert_array_equal(pieces.u_end, ends, err_msg=what + ", in pieces")
            np.testing.assert_array_equal(pieces.q_end, q, err_msg=what + ", in pieces")


def test_the_fast_march_agrees_with_the_march_event_by_event():
    """Uniform chains without a change of force are marched one increment a segment:
    equal to every slider's start and stop located one by one, to 1e-11 of the thermal
    displacement and of the largest threshold (measured: 7e-15 and 1.2e-13)."""
    rng = np.random.default_rng(28)
    taken = 0
    for case in range(30):
        c, L = fuzzed(rng, 3 * case + (case % 2))          # uniform chains only
        a = simulate(c, L, 5, until_stable=False)
        b = simulate(c, L, 5, until_stable=False, tol=EVENTS)
        scale = abs(c.alpha_T) * c.length * max(L.dT_range, np.abs(L.dT).max())
        np.testing.assert_allclose(a.u_end, b.u_end, rtol=0, atol=1e-11 * scale)
        np.testing.assert_allclose(a.q_end, b.q_end, rtol=0, atol=1e-11 * c.cp.max())
        taken += a.solver["events_one_by_one"] < b.solver["events_one_by_one"]
    assert taken >= 15, taken
