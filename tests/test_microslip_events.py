"""The exact march of the slider chain (issue 18 item 7): nearly symmetric friction resolved
for every pair, the one-increment path identical to the event-by-event path, the least
motion of a chain that may translate, and the dynamic mode with nearly equal coefficients."""
from __future__ import annotations

import numpy as np
import pytest

from asperity.microslip.chains import (
    MicroslipTolerances,
    elastic_limit,
    strip_chain,
    two_node_chain,
)
from asperity.microslip.closed_forms import two_node_drift_per_cycle, two_node_dT_c
from asperity.microslip.dynamic import simulate_dynamic
from asperity.microslip.loading import Loading
from asperity.microslip.quasi_static import simulate

EVENTS = MicroslipTolerances(events_only=True)
K, KT, N, AT, L0, MU = 1e6, 5e5, 100.0, 1.2e-5, 0.1, 0.1
# the shipped bushing's strip (lam l = 7.6)
BUSHING = dict(h=2.5e-3, E=1.1e11, p=5e6, l=0.04, k_t=1e13, alpha_T=6e-6)
RELATIVE = [0.0, 1e-12, 3e-12, 1e-10, 1e-8, 1e-6, 1e-5, 1e-4, 1e-3]


@pytest.mark.parametrize("r", RELATIVE + [-x for x in RELATIVE[1:]])
@pytest.mark.parametrize("margin", [0.7, 1.5, 40.0])
def test_two_node_nearly_symmetric_pairs_match_the_closed_form(r, margin):
    """The two-node drift is -alpha_T l0 (dT range - 2 dT_c) per cycle for every mu+ > mu-
    however close (the weaker slider caps the bar force: the other never slips), towards
    the smaller coefficient; equal coefficients (r = 0) do not drift.  To 1e-12 of
    alpha_T l0 dT range, both marches."""
    mup, mum = MU * (1 + max(r, 0.0)), MU * (1 + max(-r, 0.0))
    dTc = two_node_dT_c(K, KT, N, mup, mum, AT, L0)
    rng = 2 * margin * dTc
    want = two_node_drift_per_cycle(K, KT, N, mup, mum, AT, L0, 0.0, rng)
    for tol in (None, EVENTS):
        res = simulate(two_node_chain(K, L0, AT, KT, N, mup, mum),
                       Loading.cycles_between(0.0, rng), 6, **({"tol": tol} if tol else {}))
        assert abs(res.drift_per_cycle - want) <= 1e-12 * AT * L0 * rng, (r, margin, tol)
        if r == 0.0 or margin < 1:
            assert res.drift_per_cycle == 0.0
        else:
            assert np.sign(res.drift_per_cycle) == -np.sign(r)


def strip_drift(r, n, rng, tol=None, **over):
    par = {**BUSHING, **over}
    c = strip_chain(n=n, mu_plus=0.15 * (1 + max(r, 0.0)), mu_minus=0.15 * (1 + max(-r, 0.0)),
                    **par)
    res = simulate(c, Loading.cycles_between(0.0, rng), 30, **({"tol": tol} if tol else {}))
    return res.drift_per_cycle / (par["alpha_T"] * par["l"] * rng), res


@pytest.mark.parametrize("lam_l", [0.5, 7.6])
def test_strip_drift_tends_to_zero_with_the_asymmetry(lam_l):
    """Unlike the two-node model, a strip's drift shrinks with mu+ - mu- (the neutral region
    moves continuously): at a range that slips the whole strip, drift / (alpha_T l dT) goes
    to zero with r, has the sign of -r, never exceeds (the continuum's) r / 2 by more than
    one element's share, and is zero for equal coefficients."""
    kt = (lam_l / BUSHING["l"]) ** 2 * BUSHING["E"] * BUSHING["h"]
    n = 101
    c0 = strip_chain(n=n, mu_plus=0.15, mu_minus=0.15, **{**BUSHING, "k_t": kt})
    rng = min(5000.0, 400 * elastic_limit(c0))
    prev = None
    for r in (1e-1, 3e-2, 1e-2, 1e-3, 1e-4, 1e-6, 0.0):
        d, res = strip_drift(r, n, rng, k_t=kt)
        assert d <= 0.0 and abs(d) <= r / 2 + 1.0 / (n - 1), (r, d)
        if prev is not None:
            assert abs(d) <= abs(prev) + 1e-12, "drift grows as the asymmetry shrinks"
        prev = d
    assert prev == 0.0


def test_one_increment_and_event_by_event_give_the_same_march():
    """Fuzzed chains (two nodes and strips, lam l 0.1 to 30), coefficients from equal to 3x
    apart, temperature histories of 2-5 points, no force, a constant force or a force that
    changes (marched event by event), 1-2 load points per segment: the default march (one
    certain increment per segment) and the event-by-event march agree to 1e-9 of the
    thermal displacement (measured: 2e-13)."""
    rng = np.random.default_rng(18)
    for case in range(60):
        n = int(rng.integers(2, 40))
        r = 10 ** rng.uniform(-12, 0.5) * rng.choice([-1, 1]) * (rng.random() < 0.85)
        mup, mum = 0.15 * (1 + max(r, 0)), 0.15 * (1 + max(-r, 0))
        sign = rng.choice([-1.0, 1.0])
        if n == 2:
            c = two_node_chain(K, L0, AT * sign, 10 ** rng.uniform(3, 8), N, mup, mum)
        else:
            kt = (10 ** rng.uniform(-1, 1.5) / 0.04) ** 2 * 1.1e11 * 2.5e-3
            c = strip_chain(2.5e-3, 1.1e11, 5e6, 0.04, kt, 6e-6 * sign, n, mup, mum)
        cap = min(c.cp.sum(), c.cm.sum())
        m = int(rng.integers(2, 6))
        dT = np.append(x := rng.uniform(-1, 1, m) * 10 ** rng.uniform(0.5, 3), x[0])
        kind = case % 3
        F = (np.zeros(m + 1) if kind == 0 else np.full(m + 1, rng.uniform(-0.9, 0.9) * cap)
             if kind == 1 else rng.uniform(-0.9, 0.9, m + 1) * cap)
        F[-1] = F[0]
        L = Loading(dT, F, int(rng.integers(1, 3)))
        a = simulate(c, L, 6, until_stable=False)
        b = simulate(c, L, 6, until_stable=False, tol=EVENTS)
        scale = abs(c.alpha_T) * c.length * max(L.dT_range, np.abs(L.dT).max())
        assert np.isfinite(a.u_end).all() and np.isfinite(b.u_end).all()
        np.testing.assert_allclose(a.u_end, b.u_end, rtol=0, atol=1e-9 * scale,
                                   err_msg=f"case {case}: one increment vs events")
        np.testing.assert_allclose(a.q_end, b.q_end, rtol=0, atol=1e-9 * c.cp.max())


@pytest.mark.parametrize("n", [2, 3, 4, 51, 52])
@pytest.mark.parametrize("tol", [None, EVENTS], ids=["default", "events"])
def test_equal_coefficients_never_drift_even_when_the_whole_chain_slides(n, tol):
    """mu+ = mu- exactly and a range that slides every slider at once (an even chain: no
    node in the middle holds it): the chain may translate as a whole; the least motion (the
    limit of a small viscosity) keeps it centred, so no drift, over a history of several
    points (seen: 0.065 of alpha_T l dT per cycle before the least motion was chosen among
    the degenerate solutions)."""
    c = (two_node_chain(K, L0, -AT, KT, N, 0.15, 0.15) if n == 2 else
         strip_chain(2.5e-3, 1.1e11, 5e6, 0.04, (10.7 / 0.04) ** 2 * 1.1e11 * 2.5e-3, -6e-6, n,
                     0.15, 0.15))
    dTc = elastic_limit(c)
    L = Loading(np.array([0.5, 20.0, -8.0, 40.0, 0.5]) * dTc, np.zeros(5), 2)
    res = simulate(c, L, 6, until_stable=False, **({"tol": tol} if tol else {}))
    scale = AT * c.length * 48 * dTc
    assert np.isfinite(res.mean_u).all()
    assert np.abs(res.mean_u).max() <= 1e-12 * scale
    assert res.drift_per_cycle == 0.0 and res.slip_in_cycle


def test_dynamic_mode_takes_nearly_equal_coefficients():
    """The Moreau solution accepts every pair: equal coefficients give no drift; mu+ and mu-
    1e-3 apart give the two-node closed form once the loading is slow enough (its rate
    effects, about 1/steps, below the asymmetry: 2e5 steps per segment)."""
    dTc = two_node_dT_c(K, KT, N, MU * 1.001, MU, AT, L0)
    L = Loading.cycles_between(0.0, 3 * dTc)
    same = simulate_dynamic(two_node_chain(K, L0, AT, KT, N, MU, MU), L, 3,
                            steps_per_segment=20_000)
    assert same.drift_per_cycle == 0.0
    near = simulate_dynamic(two_node_chain(K, L0, AT, KT, N, MU * 1.001, MU), L, 3,
                            steps_per_segment=200_000)
    want = two_node_drift_per_cycle(K, KT, N, MU * 1.001, MU, AT, L0, 0.0, 3 * dTc)
    assert near.drift_per_cycle == pytest.approx(want, rel=2e-3)


# ------------------------------------------------------- against the exact rational reference

def _chain_of(model, r):
    """The chain of ``model`` with mu+ = 0.15 (1 + r) (r < 0: mu- larger), as built by the
    package (pairs 1e-12 apart become equal); lam l = 3.5 for the strips."""
    mup, mum = 0.15 * (1 + max(r, 0.0)), 0.15 * (1 + max(-r, 0.0))
    if model == "two-node":
        return two_node_chain(K, L0, AT, KT, N, mup, mum)
    n = int(model.split("=")[1])
    return strip_chain(2e-3, 2e11, 1e6, 0.1, (3.5 / 0.1) ** 2 * 2e11 * 2e-3, 1.2e-5, n, mup,
                       mum)


@pytest.mark.parametrize("model", ["two-node", "strip n=9", "strip n=10", "strip n=11"])
@pytest.mark.parametrize("r", [0.0, 2e-12, 1e-9, 1e-6, 1e-5, 1e-4, 1e-3, -1e-9, -1e-5, -1e-3])
@pytest.mark.parametrize("load", ["margin 1.5", "margin 40", "history", "force"])
def test_nearly_symmetric_pairs_against_the_exact_reference(model, r, load):
    """Issue 18 item 7: mu+ and mu- from equal to 1e-3 apart, both ways, two-node and strips
    (odd and even nodes), simple cycles at two margins, a 4-point temperature history and a
    force in phase (marched event by event): the drift per cycle and every end state of the
    default march and of the event-by-event march agree with the exact rational march
    (tests/chain_reference.py, written independently of the package) to 1e-6 of
    alpha_T l dT range (measured: about 1e-15)."""
    from chain_reference import march as exact
    c = _chain_of(model, r)
    dTc = elastic_limit(c)
    if load == "history":
        L = Loading(np.array([0.0, 30.0, -6.0, 12.0, 0.0]) * dTc, np.zeros(5))
    elif load == "force":
        L = Loading.cycles_between(0.0, 6 * dTc, 0.0, 0.3 * min(c.cp.sum(), c.cm.sum()))
    else:
        L = Loading.cycles_between(0.0, 2 * float(load.split()[1]) * dTc)
    ref = exact(c, L, 4)
    scale = abs(c.alpha_T) * c.length * max(L.dT_range, np.abs(L.dT).max())
    for tol in (None, EVENTS):
        got = simulate(c, L, 4, until_stable=False, **({"tol": tol} if tol else {}))
        assert abs(got.drift_per_cycle - ref.drift_f) <= 1e-6 * scale, (tol, got.drift_per_cycle,
                                                                        ref.drift_f)
        np.testing.assert_allclose(got.u_end, ref.u_f, rtol=0, atol=1e-6 * scale)
        np.testing.assert_allclose(got.q_end, ref.q_f[-1], rtol=0, atol=1e-9 * c.cp.max())


@pytest.mark.parametrize("n", [201, 200])
def test_a_whole_sliding_strip_says_when_its_nodes_decide_the_drift(n):
    """The bushing's strip at 1000 K slides whole; mu+ 1e-4 above mu- is below the 2/(n-1)
    its nodes resolve: an odd strip shows no drift, an even one about an element's thermal
    expansion per cycle (the artefact of the nodes); ``resolution`` says so, with the bound
    alpha_T l dT_range (mu+ - mu-)/(mu+ + mu-) of the continuum and the node count that
    resolves it; 1e-1 apart, or two nodes, it says nothing."""
    from asperity.microslip.risk_text import near_symmetric_notes
    from asperity.microslip.verdict import assess
    c = strip_chain(n=n, mu_plus=0.15 * 1.0001, mu_minus=0.15, **BUSHING)
    L = Loading.cycles_between(0.0, 1000.0)
    out = assess(c, L, 1e6, 1e-4)
    res = out["resolution"]
    scale = BUSHING["alpha_T"] * BUSHING["l"] * 1000.0
    assert res["nodes"] == n and res["asymmetry_resolved"] == pytest.approx(2 / (n - 1))
    assert res["continuum_drift_bound_m"] == pytest.approx(scale * 1e-4 / 2.0001, rel=1e-6)
    need = res["nodes_to_resolve"]
    assert 2 / out["asymmetry"] < need - 1 <= 2 / out["asymmetry"] + 2
    d = out["drift_per_cycle_m"] / (scale / (n - 1))
    assert (d == 0.0) if n % 2 else (-1.0 < d < -0.5), d
    note = near_symmetric_notes(out)
    assert len(note) == 1 and f"{n} nodes" in note[0] and f">= {need} " in note[0]
    assert ("none" in note[0]) == bool(n % 2)
    far = assess(c.with_friction(0.15 * 1.1, 0.15), L, 1e6, 1e-4)
    assert far["resolution"] is None and near_symmetric_notes(far) == []
    two = assess(two_node_chain(K, L0, AT, KT, N, MU * 1.0001, MU),
                 Loading.cycles_between(0.0, 3 * two_node_dT_c(K, KT, N, MU * 1.0001, MU, AT,
                                                               L0)), 1e6, 1e-4)
    assert two["resolution"] is None and two["asymmetry"] == pytest.approx(1e-4 / 1.0001)
    two["assembly"] = {"model": "two-node"}
    assert "ratchets by the full amount" in near_symmetric_notes(two)[0]


def test_the_increment_is_refused_when_a_sliding_slider_stops_in_it():
    """Guards of the one-increment path, on chains outside the uniform class (random
    element, contact and threshold values, where sliders do stop inside segments): where a
    slider sliding as the segment starts is not sliding in the backward-Euler increment,
    segment_increment refuses it and leaves the state untouched (the increment would be
    wrong: the event-by-event march ends elsewhere); and such chains are marched event by
    event by simulate, equal to events_only."""
    from asperity.microslip._chain_kernels import rate_statuses, solve_lcp
    from asperity.microslip._march_kernels import increment_work, segment_events, segment_increment
    from asperity.microslip.chains import Chain, is_uniform
    rng = np.random.default_rng(7)
    refused = wrong = 0
    for attempt in range(40):
        n = int(rng.integers(3, 10))
        kb, le = 10 ** rng.uniform(4, 8, n - 1), rng.uniform(0.5, 2, n - 1) * 0.01
        kt, cp, cm = 10 ** rng.uniform(4, 8, n), rng.uniform(1, 20, n), rng.uniform(1, 20, n)
        fw, aT = np.full(n, 1 / n), 1e-5
        u, q = np.zeros(n), np.zeros(n)
        st, w, acc = np.zeros(n, np.int64), np.empty((7, n)), np.zeros(n)
        for seg in range(8):
            th = aT * le * rng.uniform(-1, 1) * 10 ** rng.uniform(1, 3.5)
            st0 = np.zeros(n, np.int64)
            rate_statuses(kb, kt, cp, cm, fw, th, 0.0, q, st0, w)
            hi, lo = (cp - q) / kt, (-cm - q) / kt
            g, v = np.zeros(n, np.int64), np.empty(n)
            solve_lcp(kb, kt, cp, cm, th, np.zeros(n), lo, hi, g, np.empty(n), np.empty(n),
                      np.empty(n), v, 4 * n + 20)
            stops = any(st0[i] != 0 and g[i] != st0[i] for i in range(n))
            u0, q0 = u.copy(), q.copy()
            if stops:
                TH, W, S, X, codes, _ = increment_work(n)
                TH[:] = th
                none = np.empty(0, np.int64)
                took = segment_increment(kb, kt, cp, cm, fw, TH, 0.0, u, q, acc,
                                         np.zeros(n, np.int64), none, W, S, X, True, 2, codes,
                                         none)
                assert not took and np.array_equal(u, u0) and np.array_equal(q, q0)
                refused += 1
            segment_events(kb, kt, cp, cm, fw, th, 0.0, u, q, acc, st, w, 10_000, np.zeros(2),
                           1e18)
            if stops and np.abs(u - (u0 + v)).max() > 1e-9 * np.abs(u).max():
                wrong += 1
        if attempt < 5:
            c = Chain("random", np.r_[0.0, np.cumsum(le)], kb, le, kt, cp, cm, fw, fw, aT,
                      1.0, 1.0, {})
            assert not is_uniform(c)
            L = Loading(np.array([0.0, 800.0, -300.0, 0.0]), np.zeros(4))
            a, b = simulate(c, L, 3, until_stable=False), simulate(c, L, 3, tol=EVENTS,
                                                                   until_stable=False)
            np.testing.assert_array_equal(a.u_end, b.u_end)
    assert refused >= 5 and wrong >= 1, (refused, wrong)
