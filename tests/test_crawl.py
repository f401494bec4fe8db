"""The crawl solver (issue 26) against closed forms and invariants: the tube limit, the sign
and order of the speed with the coefficients, the quasi-static limit of the dynamics, the
power balance, mirror and frame invariances, and the orders of convergence."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import j0

from asperity.crawling.gait import CurvatureWave
from asperity.crawling.solver import coefficient_law, crawl

F, B = 0.1, 0.15        # forward, backward coefficients (Hu et al.'s ratios 1 : 1.5 : 2)


def qs(law, **kw):
    kw.setdefault("points", 60)
    kw.setdefault("steps_per_period", 200)
    return crawl(law, quasi_static=True, **kw)


def U(res):
    assert res.ok, res.message
    return res.speed_body_lengths_per_period


@pytest.mark.parametrize("A,k", [(7.0, 1.0), (5.0, 2.0)])
def test_tube_limit_is_the_bessel_speed(A, k):
    """mu_t >> mu_f: the body slides along its own track, U -> J0(A / (2 pi k)) / k body
    lengths per period (0.7130 for A = 7, k = 1)."""
    tube = j0(A / (2 * math.pi * k)) / k
    gait = CurvatureWave(amplitude=A, waves=k)
    assoc = U(qs(coefficient_law(F, F, 1000 * F, "associated"), gait=gait))
    comp = [U(qs(coefficient_law(F, F, r * F, "componentwise"), gait=gait))
            for r in (1e1, 1e2, 1e3)]
    assert assoc == pytest.approx(tube, rel=2e-3)
    err = [tube - c for c in comp]                 # the componentwise rule comes slower
    assert 0 < err[2] < err[1] / 3 < err[0] / 9
    assert comp[2] == pytest.approx(tube, rel=2e-2)


def test_speed_rises_with_the_transverse_ratio_and_reverses_below_one():
    speeds = [U(qs(coefficient_law(F, F, r * F))) for r in (0.5, 1.5, 2.0, 5.0, 50.0)]
    assert speeds[0] < 0 < speeds[1]                         # mu_t < mu_f: tail-ward
    assert all(a < b for a, b in zip(speeds[1:], speeds[2:]))
    tube = j0(7 / (2 * math.pi))
    assert speeds[-1] < tube


def test_isotropic_friction_barely_propels():
    """Isotropic Coulomb friction: no propulsion from anisotropy; what is left is far below
    any anisotropic law's speed (a small drift of the nonlinear law, |U| < 0.01)."""
    iso = U(qs(coefficient_law(F, F, F, "associated")))
    assert abs(iso) < 0.01
    assert abs(iso) < 0.05 * U(qs(coefficient_law(F, F, 2 * F, "associated")))


def test_the_three_rules_are_the_same_law_for_isotropic_coefficients():
    speeds = [U(qs(coefficient_law(F, F, F, rule)))
              for rule in ("componentwise", "associated", "colinear")]
    assert speeds[1] == pytest.approx(speeds[0], abs=1e-9)
    assert speeds[2] == pytest.approx(speeds[0], abs=1e-6)


def test_backward_coefficient_matters_only_where_points_slide_backwards():
    """Crawling head-wards (mu_t > mu_f) no point of this gait slides backwards: mu_b does
    not change the speed at all; crawling tail-wards (mu_t < mu_f) points do, and a larger
    mu_b holds the body back."""
    for rule in ("componentwise", "associated"):
        fwd = [U(qs(coefficient_law(F, b, 2 * F, rule))) for b in (F, 3 * F)]
        assert fwd[1] == pytest.approx(fwd[0], rel=1e-9)
        back = [U(qs(coefficient_law(F, b, 0.5 * F, rule))) for b in (F, 3 * F)]
        assert back[0] < 0 and back[1] > back[0] + 0.01 * abs(back[0])


def test_quasi_static_speed_depends_on_the_gait_and_law_only():
    law = coefficient_law(F, B, 2 * F)
    ref = qs(law)
    for kw in ({"g": 1.0}, {"mass": 7.0}, {"gait": CurvatureWave(period=3.0)}):
        assert U(qs(law, **kw)) == pytest.approx(U(ref), rel=1e-9)
    # lengths scale: the same speed in body lengths
    big = qs(law, gait=CurvatureWave(length=1000.0, period=2.0))
    assert U(big) == pytest.approx(U(ref), rel=1e-9)
    assert big.q[-1, 0] == pytest.approx(1000 * ref.q[-1, 0], rel=1e-9)


def test_power_of_the_gait_is_the_dissipation_quasi_statically():
    for rule in ("componentwise", "associated", "colinear"):
        res = qs(coefficient_law(F, B, 2 * F, rule))
        assert res.work[-1] > 0
        assert res.work[-1] == pytest.approx(res.dissipated[-1], rel=1e-8)
        assert np.all(np.diff(res.dissipated) >= -1e-15)


def test_symmetric_gait_keeps_its_heading_and_mirror_gait_mirrors_the_path():
    law = coefficient_law(F, B, 2 * F)
    a = qs(law, periods=2)
    assert abs(a.heading_drift_rad_per_period) < 1e-9
    from asperity.crawling.gait import FourierGait
    b = qs(law, periods=2, gait=FourierGait([(1, 1, -7.0, 0.0)]))      # kappa L = -7 cos ...
    np.testing.assert_allclose(b.q[:, 0], a.q[:, 0], atol=1e-10)
    np.testing.assert_allclose(b.q[:, 1:], -a.q[:, 1:], atol=1e-10)


def test_a_law_symmetric_under_a_half_turn_crawls_the_same_turned_by_180_deg():
    law = coefficient_law(F, F, 2 * F, "associated")
    assert U(qs(law, texture_angle_deg=180.0)) == pytest.approx(U(qs(law)), rel=1e-9)
    assert U(qs(law, texture_angle_deg=-180.0)) == pytest.approx(U(qs(law)), rel=1e-9)
    ground = [U(qs(law, texture_on="ground", texture_angle_deg=a)) for a in (0.0, 180.0)]
    assert ground[1] == pytest.approx(ground[0], rel=1e-9)


def test_ground_texture_with_the_grain_against_it_and_across():
    """An asymmetric ground texture (mu+ = 0.1 along +x, mu- = 0.3): the body crawls
    differently with the grain and against it; across it (transverse coefficient smaller
    than both along), the texture's anisotropy points the wrong way and the body barely
    moves or moves back."""
    from asperity.laws.planar import truncated_ellipse_law
    law = truncated_ellipse_law(0.1, 0.3, 0.4, 0.4)
    w = U(qs(law, texture_on="ground", texture_angle_deg=0.0))
    a = U(qs(law, texture_on="ground", texture_angle_deg=180.0))
    x = U(qs(law, texture_on="ground", texture_angle_deg=90.0))
    assert w > 0.25 and a < -0.2                  # the ground's easy way wins either way
    assert abs(x) < 0.03 * min(w, -a)


def test_dynamics_tends_to_the_quasi_static_speed_as_the_froude_number_vanishes():
    law = coefficient_law(F, B, 2 * F)
    q = U(qs(law, points=40, steps_per_period=200))
    d = crawl(law, points=40, steps_per_period=200, periods=6, g=1e4)
    assert d.froude <= 1e-3
    assert U(d) == pytest.approx(q, rel=2e-3)
    slow = crawl(law, points=40, steps_per_period=200, periods=6)      # Fr ~ 1: differs
    assert abs(U(slow) - q) > 1e-3


def test_dynamic_run_from_rest_reaches_a_periodic_motion():
    res = crawl(coefficient_law(F, B, 2 * F), points=40, steps_per_period=200, periods=8)
    assert res.transient_periods == 4
    s = res.speed_per_period
    assert abs(s[-1] - s[-2]) < 1e-3 * abs(s[-1])
    assert abs(s[0] - s[-1]) > 1e-2 * abs(s[-1])                 # the transient is real
    assert res.u[0].tolist() == [0.0, 0.0, 0.0]                  # from rest


def test_convergence_in_dt_is_second_order_quasi_statically():
    law = coefficient_law(F, B, 2 * F)
    u = [U(qs(law, steps_per_period=p)) for p in (50, 100, 200)]
    r = (u[0] - u[1]) / (u[1] - u[2])
    assert 3.0 < r < 5.5, u


def test_convergence_in_points():
    law = coefficient_law(F, B, 2 * F, "associated")
    u = [U(qs(law, points=n)) for n in (25, 50, 100, 200)]
    d = np.abs(np.diff(u))
    assert d[1] < 0.7 * d[0] and d[2] < 0.7 * d[1], u
    assert d[2] < 1e-3 * abs(u[-1])


def test_json_numbers_and_cost_of_transport():
    from asperity.crawling.output import summary
    law = coefficient_law(F, B, 2 * F)
    res = qs(law)
    obj = summary(res, law)
    assert obj["rule"] == "componentwise" and obj["quasi_static"] is True
    assert obj["froude"] == pytest.approx(1.0 / (9.81 * F), rel=1e-12)
    d = math.hypot(*(res.q[-1, :2] - res.q[0, :2]))
    assert obj["cost_of_transport"] == pytest.approx(res.work[-1] / (9.81 * d), rel=1e-12)
    assert obj["speed_per_period"] == [pytest.approx(U(res))]


@pytest.mark.parametrize("rule,coeffs,A,k", [
    ("componentwise", (0.1, 0.15, 0.2), 7.0, 1.0),
    ("componentwise", (0.2, 0.3, 0.1), 7.0, 1.0),
    ("associated", (0.1, 0.1, 0.5), 5.0, 1.5),
    ("associated", (0.2, 0.3, 0.1), 7.0, 1.0),
    ("colinear", (0.1, 0.15, 0.2), 7.0, 1.0),
    ("colinear", (0.2, 0.3, 0.1), 5.0, 1.5),
])
def test_agrees_with_the_independent_quasi_static_reference(rule, coeffs, A, k):
    """tests/crawl_reference.py (root finding on net force and torque at each instant,
    written without reading the solver): within 0.5 % (measured: 1e-5 to 1e-3)."""
    from crawl_reference import reference_speed
    ref = reference_speed(A, k, *coeffs, rule, points=201, steps=200)
    res = crawl(coefficient_law(*coeffs, rule), gait=CurvatureWave(amplitude=A, waves=k),
                quasi_static=True, points=200, steps_per_period=400)
    assert U(res) == pytest.approx(ref["U"], rel=5e-3)
    assert res.heading_drift_rad_per_period == pytest.approx(ref["heading_drift"], abs=1e-3)


def test_pyelastica_continuum_snake_side_by_side():
    """PyElastica's continuum snake (its speed recorded by benchmarks/crawl_pyelastica.py in
    benchmarks/crawl_pyelastica_results.json): its gait's main curvature term (A = 7,
    k = 1), its Froude number and coefficients (1 : 1.5 : 2, componentwise), dynamic:
    within 2 % (measured 0.08 %)."""
    import json
    from pathlib import Path
    pe = json.loads((Path(__file__).resolve().parents[1] / "benchmarks" /
                     "crawl_pyelastica_results.json").read_text())
    prm = pe["parameters"]
    mu = prm["mu_forward"]
    gait = CurvatureWave(amplitude=7.0, waves=1.0, period=prm["period_s"],
                         length=prm["length_m"])
    res = crawl(coefficient_law(mu, 1.5 * mu, 2 * mu), gait=gait, points=51, periods=11,
                g=prm["gravity_m_s2"])
    assert res.froude == pytest.approx(prm["froude"], rel=1e-6)
    assert U(res) == pytest.approx(pe["pyelastica"]["speed_body_lengths_per_period"], rel=0.02)


def test_python_api_summary_is_the_commands_json():
    import asperity
    res = asperity.crawl(mu_f=F, mu_b=B, mu_t=2 * F, rule="associated", quasi_static=True,
                         points=40)
    obj = res.summary()
    assert obj["rule"] == "associated" and obj["law"] == res.law_description
    assert obj["speed_body_lengths_per_period"] == res.speed_body_lengths_per_period
    with pytest.raises(asperity.InputError, match="amplitude applies"):
        asperity.crawl(mu_f=F, mu_b=B, mu_t=2 * F, gait=CurvatureWave(), amplitude=3.0)
    with pytest.raises(asperity.InputError, match="mu_t"):
        asperity.crawl(mu_f=F, mu_b=B)
    with pytest.raises(asperity.InputError, match="law and mu_f"):
        asperity.crawl(coefficient_law(F, B, F), mu_f=F)


def test_gait_tables_are_kept_only_for_gaits_their_parameters_define():
    """A second crawl on an equal gait reuses its tables and gives the same numbers bit for
    bit; a different gait (or weights) is tabulated anew."""
    from asperity.crawling import solver
    law = coefficient_law(F, B, 2 * F)
    a = qs(law, gait=CurvatureWave(amplitude=6.0))
    n = len(solver._TABLES)
    b = qs(law, gait=CurvatureWave(amplitude=6.0))
    assert len(solver._TABLES) == n and b.q.tobytes() == a.q.tobytes()
    c = qs(law, gait=CurvatureWave(amplitude=6.5))
    assert U(c) != U(a)
    w = np.linspace(1.0, 2.0, 60)
    d = qs(law, gait=CurvatureWave(amplitude=6.0), weights=w)
    assert U(d) != pytest.approx(U(a), rel=1e-6)
    with pytest.raises(Exception, match="crosses itself"):
        qs(law, gait=CurvatureWave(amplitude=20.0))


@pytest.mark.parametrize("side", ["body", "ground"])
@pytest.mark.parametrize("angle", [90.0, 30.0, -135.0])
def test_texture_angle_is_the_law_turned_by_it(side, angle):
    """A texture at ``angle`` is the same law with its axes turned by that angle (a
    truncated ellipse of theta = angle) at angle 0: on the body and on the ground."""
    from asperity.laws.planar import truncated_ellipse_law
    a = qs(truncated_ellipse_law(0.1, 0.3, 0.25, 0.4), texture_on=side,
           texture_angle_deg=angle, points=40, steps_per_period=100)
    b = qs(truncated_ellipse_law(0.1, 0.3, 0.25, 0.4, theta=math.radians(angle)),
           texture_on=side, points=40, steps_per_period=100)
    assert U(a) == pytest.approx(U(b), rel=1e-6, abs=1e-9)
    np.testing.assert_allclose(a.q, b.q, rtol=0, atol=1e-9)


def test_world_shapes_text_and_final_state():
    """The plot's snapshots: the body's points in the world, their mean the recorded centre
    and their mean tangent the recorded heading; the text names the gait's parameters; the
    JSON's final state is the last recorded one."""
    from asperity.crawling.output import summary, text, world_shapes
    res = crawl(coefficient_law(F, B, 2 * F), points=50, periods=2, steps_per_period=100)
    idx = np.array([0, 37, 100, len(res.t) - 1])
    sh = world_shapes(res, CurvatureWave(), idx)
    np.testing.assert_allclose(sh.mean(axis=1), res.q[idx, :2], atol=1e-12)
    # turned back by the recorded heading about the centre: the gait's body-frame shape
    rel = (sh[..., 0] - res.q[idx, 0][:, None]) + 1j * (sh[..., 1] - res.q[idx, 1][:, None])
    body = rel * np.exp(-1j * res.q[idx, 2])[:, None]
    kin = CurvatureWave().kinematics(res.t[idx], 50)
    np.testing.assert_allclose(body.real, kin.r[..., 0], atol=1e-12)
    np.testing.assert_allclose(body.imag, kin.r[..., 1], atol=1e-12)
    obj = summary(res)
    fs = obj["final_state"]
    assert [fs["x_m"], fs["y_m"], fs["theta_rad"]] == res.q[-1].tolist()
    words = text(obj)
    assert "amplitude 7" in words and "waves 1" in words and "kind" not in words


def test_plot_draws_the_snapshots_and_each_periods_speed(tmp_path, monkeypatch):
    """The figure's data: the snapshot lines are world_shapes at the last period's times, the
    step line the speed of each period at the period's edges."""
    import asperity.io as aio
    from asperity.crawling import output
    got = {}
    monkeypatch.setattr(aio, "save_figure_atomic",
                        lambda fig, path, **kw: got.setdefault("fig", fig))
    res = crawl(coefficient_law(F, B, 2 * F), points=30, periods=3, steps_per_period=40)
    output.plot(tmp_path / "c.png", res, CurvatureWave(), output.summary(res))
    ax, bx = got["fig"].axes
    k = len(res.t)
    snaps = np.linspace(k - 1 - (k - 1) // 3, k - 1, 9).round().astype(int)
    shapes = output.world_shapes(res, CurvatureWave(), snaps)
    np.testing.assert_allclose(ax.lines[0].get_xydata(), shapes[0], atol=1e-12)
    step = [ln for ln in bx.lines if ln.get_label() == "speed of each period"][0]
    x, y = step.get_data()
    np.testing.assert_allclose(x, [0.0, 1.0, 2.0, 3.0])
    np.testing.assert_allclose(y[:3], res.speed_per_period)


def test_without_friction_the_gait_turns_the_body_keeping_its_angular_momentum():
    """g -> 0 (friction 1e-7 of the inertial forces): the centre stays where it is and the
    angular momentum I omega + S (S the gait's own spin, per unit mass) keeps its value at
    rest, S(0), so the body turns against its gait's swing."""
    gait = CurvatureWave()
    res = crawl(coefficient_law(F, B, 2 * F), gait=gait, points=60, periods=1,
                steps_per_period=100, g=1e-6)
    kin = gait.kinematics(res.t, 60)
    L = kin.inertia * res.u[:, 2] + kin.spin
    assert np.abs(kin.spin).max() > 0.05                    # the gait does swing
    np.testing.assert_allclose(L[1:], kin.spin[0], atol=1e-5 * np.abs(kin.spin).max())
    assert np.abs(res.q[:, :2]).max() < 1e-6
    assert np.abs(res.q[:, 2]).max() > 0.01                  # and the body turns


@pytest.mark.parametrize("rule", ["componentwise", "associated", "colinear"])
@pytest.mark.parametrize("which", [0, 1, 2])
@pytest.mark.parametrize("bad, says", [(-1.0, "must be in [1e-06, 100], got -1"),
                                       (math.nan, "must be in [1e-06, 100], got NaN")])
def test_a_bad_coefficient_is_named_as_given_whatever_the_rule(rule, which, bad, says):
    """mu_f, mu_b, mu_t by their own names, not by the ellipse's axes they become."""
    from asperity.errors import InputError
    mus = [0.1, 0.15, 0.2]
    mus[which] = bad
    with pytest.raises(InputError) as exc:
        coefficient_law(*mus, rule=rule)
    assert str(exc.value) == f"{('mu_f', 'mu_b', 'mu_t')[which]} {says}"
