"""The independent quasi-static crawl reference (tests/crawl_reference.py) against closed forms,
exact symmetries and invariants of the model of Hu et al. (2009), issue 26 item 1.

These check the reference itself; the comparison with the package's crawl solver sits beside
the solver's own tests.  Figures quoted are for A = 7, k = 1 unless stated.

A finding the issue's list states otherwise, checked below: isotropic Coulomb friction does
propel this gait, slowly: U = +0.00575 L per period (converged in points and steps to 1e-5),
not 0; only an odd law with a time-symmetric gait (a standing wave) gives exactly 0.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from crawl_reference import Instant, reference_speed, solve_instant
from scipy.special import j0

P, S = 201, 100               # points and steps of the quick runs
STANDING = [[1.0, 1.0, 3.5, 0.0], [1.0, -1.0, 3.5, 0.0]]   # 7 cos 2 pi s cos 2 pi t


def run(mu, rule="componentwise", A=7.0, k=1.0, points=P, steps=S, terms=None):
    return reference_speed(A, k, *mu, rule, points=points, steps=steps, terms=terms)


@pytest.mark.parametrize("k", [1.0, 2.0])
@pytest.mark.parametrize("rule, ratios, order", [("componentwise", (1e3, 1e4), 1),
                                                 ("associated", (1e1, 1e2), 2)])
def test_tube_limit(rule, ratios, order, k):
    """mu_t / mu_f -> infinity: the body slides along its own track, U -> J0(A / 2 pi k) / k,
    and every point slides forward at L / (k T): dissipation -> mu_f rho g L^2 / (k T).
    U approaches as (mu_f / mu_t)^order (componentwise 1, associated 2): the extrapolation
    from two ratios lands on the tube speed to 1e-4 (the quadrature's floor at 401 points;
    it falls as h^2)."""
    tube = j0(7.0 / (2 * np.pi * k)) / k
    lo, hi = (run((1.0, 1.0, ratio), rule, k=k, points=401) for ratio in ratios)
    gain = (ratios[1] / ratios[0]) ** order
    assert tube - lo["U"] > tube - hi["U"] > 0, "U must rise towards the tube speed"
    assert 0.5 * gain < (tube - lo["U"]) / (tube - hi["U"]) < 1.5 * gain
    extrapolated = hi["U"] + (hi["U"] - lo["U"]) / (gain - 1)
    assert extrapolated == pytest.approx(tube, rel=2e-4), f"{rule}, k = {k}"
    assert hi["dissipation"] == pytest.approx(1.0 / k, rel=1e-3)


def test_tube_speed_for_the_issue_figure():
    assert j0(7.0 / (2 * np.pi)) == pytest.approx(0.7130, abs=5e-5)
    assert run((1.0, 1.0, 1e3), "associated")["U"] == pytest.approx(0.7130, rel=1e-3)


@pytest.mark.parametrize("rule", ["componentwise", "associated", "colinear"])
def test_power_of_the_gait_is_the_dissipation(rule):
    """Zero net force and torque: the rigid motion does no work, so the gait's power
    (-int f . dX/dt) equals the friction dissipation (-int f . u) at every instant."""
    r = run((1.0, 1.5, 2.0), rule)
    assert r["dissipation"] > 0
    assert r["power_gait"] == pytest.approx(r["dissipation"], rel=1e-9)
    assert r["residual"] < 1e-10


def test_power_balance_holds_through_sticking_nodes():
    """Colinear on a coarse body pivots about a node at rest at some instants (its friction a
    point of its set): the balance must hold there too."""
    r = run((1.0, 1.5, 2.0), "colinear", points=51)
    assert r["stick_instants"] > 0, "this case was chosen to exercise the sticking node"
    assert r["power_gait"] == pytest.approx(r["dissipation"], rel=1e-9)
    fine = run((1.0, 1.5, 2.0), "colinear", points=1601)
    assert r["U"] == pytest.approx(fine["U"], rel=2e-2)


def test_all_rules_coincide_for_isotropic_friction():
    us = [run((1.0, 1.0, 1.0), rule)["U"] for rule in ("componentwise", "associated", "colinear")]
    assert np.ptp(us) < 1e-12


def test_isotropic_friction_barely_propels_and_converges():
    """Not zero (see the module docstring): U = 0.00575 +- 1e-5, small beside the anisotropic
    cases (0.159 at mu_t / mu_f = 2), the same at twice the points and steps."""
    coarse, fine = run((1, 1, 1), points=401, steps=200)["U"], run((1, 1, 1), points=801, steps=400)["U"]
    assert abs(coarse - fine) < 2e-5
    assert 0.0055 < fine < 0.0060
    assert fine < 0.05 * run((1.0, 1.0, 2.0))["U"]


@pytest.mark.parametrize("mu", [(1.0, 1.0, 1.0), (1.0, 1.0, 10.0), (2.0, 2.0, 0.5)])
def test_an_odd_law_reverses_with_the_wave(mu):
    """mu_f = mu_b: the law is odd and rate-independent, so the wave run tail-ward
    (n = -1) retraces the motion backwards: U -> -U exactly."""
    forward = run(mu)
    backward = run(mu, terms=[[1.0, -1.0, 7.0, 0.0]])
    assert backward["U"] == pytest.approx(-forward["U"], rel=1e-9, abs=1e-14)


@pytest.mark.parametrize("mu", [(1.0, 1.0, 1.0), (1.0, 1.0, 10.0)])
def test_standing_wave_on_an_odd_law_goes_nowhere(mu):
    """A time-symmetric gait on an odd rate-independent law: the shape path is retraced, no
    net motion (the scallop theorem of dry friction)."""
    r = run(mu, terms=STANDING)
    assert abs(r["U"]) < 1e-12 and abs(r["lateral"]) < 1e-12 and abs(r["heading_drift"]) < 1e-12


def test_standing_wave_ratchets_when_backward_friction_is_larger():
    """mu_b > mu_f breaks the oddness: the standing wave ratchets head-ward."""
    assert run((1.0, 3.0, 10.0), terms=STANDING)["U"] > 0.05


def test_speed_rises_with_lateral_friction_and_turns_tailward_below_forward():
    ratios = (0.3, 0.5, 0.9, 1.2, 2.0, 10.0, 100.0)
    us = [run((1.0, 1.0, q))["U"] for q in ratios]
    assert all(b > a for a, b in itertools.pairwise(us)), f"U must rise with mu_t / mu_f: {us}"
    assert us[0] < 0 and us[1] < 0 and us[2] < 0, "mu_t < mu_f moves the body tail-ward"


def min_tangential_slip(mu, points=P, steps=S):
    """Smallest u.t over the body and the period (negative: some point slides tail-ward)."""
    x, low = np.zeros(3), np.inf
    for tau in np.arange(steps) / steps:
        inst = Instant([[1.0, 1.0, 7.0, 0.0]], tau, points, mu, "componentwise")
        x, _ = solve_instant(inst, x)
        low = min(low, float(np.min(np.einsum("ij,ij->i", inst.velocity(x), inst.t))))
    return low


def test_backward_friction_matters_only_where_points_slide_backwards():
    assert min_tangential_slip((1.0, 1.0, 2.0)) > 0.05
    assert np.ptp([run((1.0, b, 2.0))["U"] for b in (0.5, 1.0, 5.0)]) == 0.0
    assert min_tangential_slip((1.0, 1.0, 1.0)) < -0.01
    slow, fast = run((1.0, 1.0, 1.0))["U"], run((1.0, 5.0, 1.0))["U"]
    assert fast - slow > 5e-3, "with points sliding backwards a larger mu_b pushes head-ward"


def test_symmetric_gait_keeps_its_heading_and_mirror_mirrors_the_path():
    assert abs(run((1.0, 1.5, 2.0))["heading_drift"]) < 1e-12
    turning = np.array([[1.0, 1.0, 7.0, 0.0], [0.0, 0.0, 2.0, 0.0]])   # a constant bend added
    r = run((1.0, 1.5, 5.0), terms=turning)
    m = run((1.0, 1.5, 5.0), terms=turning * [1, 1, -1, -1])
    assert abs(r["heading_drift"]) > 0.5 and abs(r["lateral"]) > 1e-3
    assert m["U"] == pytest.approx(r["U"], rel=1e-10)
    assert m["lateral"] == pytest.approx(-r["lateral"], rel=1e-8)
    assert m["heading_drift"] == pytest.approx(-r["heading_drift"], rel=1e-10)


@pytest.mark.parametrize("rule", ["componentwise", "associated"])
def test_second_order_in_points_and_steps(rule):
    """The trapezoid rule on integrands with kinks only (u never vanishes in these cases):
    halving the spacing divides the change by 4 (observed 3.9 to 4.2)."""
    mu = (1.0, 1.5, 2.0)
    up = [run(mu, rule, points=p, steps=50)["U"] for p in (101, 201, 401)]
    assert 3.5 < (up[0] - up[1]) / (up[1] - up[2]) < 4.5
    us = [run(mu, rule, points=101, steps=s)["U"] for s in (50, 100, 200)]
    assert 3.5 < (us[0] - us[1]) / (us[1] - us[2]) < 4.5


def test_the_three_rules_differ_sixfold_on_the_same_coefficients():
    """The issue's warning: the rule must be explicit; at (1, 1.5, 2) U is 0.313 (associated),
    0.159 (componentwise) and 0.049 (colinear)."""
    u = {rule: run((1.0, 1.5, 2.0), rule)["U"] for rule in ("associated", "componentwise", "colinear")}
    assert u["associated"] > u["componentwise"] > u["colinear"] > 0
    assert u["associated"] / u["colinear"] > 5


def test_a_body_that_does_not_change_shape_does_not_move():
    """A = 0: every point is at rest, the force is set-valued everywhere; the reference
    takes f = 0 there (no NaN) and the body stays."""
    r = run((1.0, 1.5, 2.0), "associated", A=0.0, points=51, steps=8)
    assert r["U"] == 0.0 and r["dissipation"] == 0.0 and np.isfinite(r["residual"])


@pytest.mark.parametrize("field, value", [
    ("rule", "sideways"), ("mu", (0.0, 1.0, 1.0)), ("mu", (1.0, np.nan, 1.0)),
    ("points", 2), ("steps", 3), ("A", np.inf)])
def test_bad_arguments_are_refused(field, value):
    kw = {"mu": (1.0, 1.0, 2.0), "rule": "componentwise", "A": 7.0, "points": P, "steps": S}
    kw[field] = value
    with pytest.raises(ValueError):
        run(kw["mu"], kw["rule"], A=kw["A"], points=kw["points"], steps=kw["steps"])
