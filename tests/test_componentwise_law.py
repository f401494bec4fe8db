"""The componentwise law (issue 26, item 3; Hu, Nirody, Scott and Shelley, PNAS 2009): for the
unit slip u = (cos psi, sin psi) in the law's frame the force per unit normal load on the
body is -(mu_{f|b} u_x, mu_t u_y), mu_f where u_x >= 0.

Checked against that closed form (written here, not read from the package) for the law's
own evaluation, the solver's proximal map and ``asperity law --psi --json``; the three
coefficients recovered on the axes; Coulomb and the x-symmetric law as special cases;
mirror invariance; the gauge file round trip; a point mass on the axes (stop distance and
time of Coulomb with the axis's mu) and launched obliquely (every recorded step's
deceleration is (mu_{f|b} g cos psi, mu_t g sin psi) at the step's slip direction, the
kinetic energy lost equals the work of that force, each velocity component keeps its sign
and decays, the path bends towards the axis of the smaller coefficient); a disc body on it
(every step passes tests/body_kkt.py); the refusals.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run, run_json

from asperity import componentwise_law, coulomb_law, law_from_gauge, read_gauge, write_gauge
from asperity.dynamics.moreau import point_mass, simulate
from asperity.errors import InputError
from asperity.laws.componentwise import componentwise_gauge
from asperity.laws.planar import law_point, solver_D

G = 9.81
CASES = [(0.3, 0.6, 0.9), (1.1, 0.11, 2.0), (0.2, 0.4, 0.1), (0.05, 0.05, 0.5)]
PSI = 2 * math.pi * np.arange(360) / 360


def closed_form(psi, mu_f, mu_b, mu_t):
    """(m, 2) p = -force / N of the componentwise rule."""
    ux, uy = np.cos(psi), np.sin(psi)
    return np.column_stack([np.where(ux >= 0, mu_f, mu_b) * ux, mu_t * uy])


@pytest.mark.parametrize("mu", CASES)
def test_the_force_is_the_componentwise_closed_form_in_360_directions(mu):
    law = componentwise_law(*mu)
    want = closed_form(PSI, *mu)
    f = law.law.force(PSI)
    np.testing.assert_allclose(f.p, want, rtol=0, atol=1e-13,
                               err_msg="the law's sliding force is the componentwise rule")
    assert not f.set_valued.any()
    # the solver's map: a prox argument on the sliding side of D's point of normal u gives p
    u = np.column_stack([np.cos(PSI), np.sin(PSI)])
    y = solver_D(law).normal_point(PSI)[0]
    P, stick = law_point(law, y + 0.37 * u)
    assert not stick.any()
    np.testing.assert_allclose(P, want, rtol=0, atol=1e-12,
                               err_msg="the solver's proximal map slides with the rule's force")
    # a prox argument inside D sticks, with a force on its ray inside C
    x = 0.5 * y
    P, stick = law_point(law, x)
    assert stick.all()
    assert np.all(np.abs(P[:, 0] * x[:, 1] - P[:, 1] * x[:, 0]) < 1e-13)
    assert np.all(law.law.C.gauge(P) <= 1 + 1e-12)
    # dissipation p.u = mu_{f|b} cos^2 + mu_t sin^2 > 0
    assert np.all(np.einsum("ij,ij->i", want, u) >= min(mu) - 1e-15)


def test_law_psi_json_gives_the_closed_form_in_360_directions(capsys, tmp_path):
    mu = (0.3, 0.6, 0.9)
    path = tmp_path / "cw.json"
    code, _, err = run(capsys, "law", "--mu-f", mu[0], "--mu-b", mu[1], "--mu-t", mu[2],
                       "--output", path)
    assert code == 0, err
    for k in range(360):
        obj = run_json(capsys, "law", path, "--psi", k)
        want = closed_form(np.array([math.radians(k)]), *mu)[0]
        assert np.allclose(obj["p"], want, rtol=0, atol=1e-12), (k, obj, want)
        u = np.array([math.cos(math.radians(k)), math.sin(math.radians(k))])
        assert obj["tangential"] == pytest.approx(want @ u, abs=1e-12)
        assert obj["set_valued"] is False and 0 < obj["alpha"] <= 1 + 1e-12
    # without a file: the same law from the flags
    obj = run_json(capsys, "law", "--mu-f", mu[0], "--mu-b", mu[1], "--mu-t", mu[2],
                   "--psi", 200)
    assert np.allclose(obj["p"], closed_form(np.array([math.radians(200)]), *mu)[0],
                       atol=1e-12)


@pytest.mark.parametrize("mu", CASES)
def test_the_three_coefficients_are_recovered_on_the_axes(mu, capsys):
    mu_f, mu_b, mu_t = mu
    ax = componentwise_law(*mu).axes()
    assert ax["mu_a_plus"] == pytest.approx(mu_f, rel=1e-14)
    assert ax["mu_a_minus"] == pytest.approx(mu_b, rel=1e-14)
    assert ax["mu_b_plus"] == pytest.approx(mu_t, rel=1e-14)
    assert ax["mu_b_minus"] == pytest.approx(mu_t, rel=1e-14)
    for deg, m in ((0, mu_f), (180, mu_b), (90, mu_t), (270, mu_t)):
        obj = run_json(capsys, "law", "--mu-f", mu_f, "--mu-b", mu_b, "--mu-t", mu_t,
                       "--psi", deg)
        assert obj["tangential"] == pytest.approx(m, rel=1e-12), (deg, obj)
        assert obj["lateral"] == pytest.approx(0.0, abs=1e-12), (deg, obj)


def test_equal_coefficients_are_coulomb_and_equal_f_b_is_symmetric_in_x():
    for mu in (1e-6, 0.3, 1.0, 100.0):
        np.testing.assert_allclose(componentwise_law(mu, mu, mu).force(PSI),
                                   coulomb_law(mu).force(PSI), rtol=1e-13, atol=1e-19,
                                   err_msg=f"mu_f = mu_b = mu_t = {mu}: Coulomb")
    mirror = np.array([-1.0, 1.0])
    sym = componentwise_law(0.4, 0.4, 0.1)
    np.testing.assert_allclose(sym.force(math.pi - PSI), sym.force(PSI) * mirror, atol=1e-14,
                               err_msg="mu_f = mu_b: the law is its own mirror in x")
    np.testing.assert_allclose(sym.force(PSI), np.column_stack(
        [0.4 * np.cos(PSI), 0.1 * np.sin(PSI)]), atol=1e-14)
    asym = componentwise_law(0.4, 0.2, 0.1)              # the check can fail
    assert np.abs(asym.force(math.pi - PSI) - asym.force(PSI) * mirror).max() > 0.1


@pytest.mark.parametrize("mu", CASES)
def test_swapping_f_and_b_mirrors_the_law_in_x_and_the_n_mirror_keeps_it(mu):
    mu_f, mu_b, mu_t = mu
    law, swapped = componentwise_law(mu_f, mu_b, mu_t), componentwise_law(mu_b, mu_f, mu_t)
    # psi = 90 and 270 deg sit on both halves: leave the exact axis out of the x-mirror
    psi = PSI + 1e-3
    np.testing.assert_allclose(swapped.force(math.pi - psi),
                               law.force(psi) * np.array([-1.0, 1.0]), rtol=0, atol=1e-13)
    np.testing.assert_allclose(law.force(-psi), law.force(psi) * np.array([1.0, -1.0]),
                               rtol=0, atol=1e-13)


def test_a_gauge_file_round_trip_keeps_the_rule_and_the_coefficients(tmp_path, capsys):
    mu = (0.3, 0.6, 0.9)
    path = tmp_path / "cw.json"
    write_gauge(path, componentwise_gauge(*mu))
    obj = json.loads(path.read_text())
    assert obj["law"] == "componentwise"
    assert obj["parameters"] == {"rule": "componentwise", "mu_f": 0.3, "mu_b": 0.6, "mu_t": 0.9}
    try:
        import jsonschema
    except ImportError:                                  # pragma: no cover
        jsonschema = None
    if jsonschema is not None:
        from asperity.laws.gauge_schema import schema
        jsonschema.validate(obj, schema(1))
    gl = read_gauge(path)
    assert gl.kind == "componentwise"
    np.testing.assert_array_equal(gl.force(PSI).p, componentwise_law(*mu).law.force(PSI).p)
    law = law_from_gauge(path)
    assert law.name == "componentwise" and not law.associated
    np.testing.assert_allclose(law.force(PSI), closed_form(PSI, *mu), atol=1e-13)
    assert law_from_gauge(path, "collinear").name == "collinear"
    # the CLI writes the same file, and its summary names the rule and the coefficients
    cli = tmp_path / "cli.json"
    assert run(capsys, "law", "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0.9, "--output", cli)[0] == 0
    assert json.loads(cli.read_text())["parameters"] == obj["parameters"]
    s = run_json(capsys, "law", cli)
    assert s["law"] == "componentwise" and s["parameters"] == obj["parameters"]
    # an edited coefficient no longer agrees with the recorded data and fit: one line
    bad = dict(obj, parameters={**obj["parameters"], "mu_f": 0.31})
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(bad))
    code, _, err = run(capsys, "law", edited)
    assert code == 1 and len(err.strip().splitlines()) == 1 and "fit." in err, err
    for key, value, words in (("mu_t", 0, "parameters.mu_t"), ("mu_b", -0.2, "parameters.mu_b"),
                              ("rule", "associated", "parameters.rule")):
        edited.write_text(json.dumps(dict(obj, parameters={**obj["parameters"], key: value})))
        code, _, err = run(capsys, "law", edited)
        assert code == 1 and words in err and len(err.strip().splitlines()) == 1, err


def test_a_plot_of_the_law_is_written(tmp_path, capsys):
    png = tmp_path / "cw.png"
    code, _, err = run(capsys, "law", "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0.9,
                         "--psi", 30, "--plot", png)
    assert code == 0 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", err


def _slide(law, u0, angle_deg, dt=1e-4):
    a = math.radians(angle_deg)
    t_end = 1.5 * u0 / (G * law.min_tangential()) + 10 * dt
    return simulate(point_mass(law), [u0 * math.cos(a), u0 * math.sin(a)], dt=dt,
                    t_end=t_end, g=G, halt_at_rest=True)


@pytest.mark.parametrize("angle, which", [(0, 0), (180, 1), (90, 2), (-90, 2)])
def test_a_point_mass_on_an_axis_stops_as_coulomb_with_that_axis_coefficient(angle, which):
    mu = (0.3, 0.6, 0.9)
    u0, dt = 1.2, 1e-4
    res = _slide(componentwise_law(*mu), u0, angle, dt)
    m = mu[which]
    assert res.status == "ok" and res.stop_step is not None
    assert np.all(res.u[-1] == 0.0)
    d = float(np.hypot(*res.q[-1]))
    assert d == pytest.approx(u0 * u0 / (2 * m * G), rel=2 * m * G * dt / u0), (angle, d)
    assert res.stop_step * dt == pytest.approx(u0 / (m * G), abs=1.5 * dt)
    a = math.radians(angle)
    assert abs(res.q[-1] @ [-math.sin(a), math.cos(a)]) < 1e-12, "no deflection on an axis"


@pytest.mark.parametrize("mu, angle", [((0.3, 0.6, 0.9), 30.0), ((0.3, 0.6, 0.9), 150.0),
                                       ((0.8, 0.2, 0.25), -40.0), ((0.1, 0.4, 0.05), 200.0)])
def test_every_step_of_an_oblique_slide_decelerates_by_the_componentwise_rule(mu, angle):
    """Implicit Moreau step of a point mass: u_E - u_A = -g dt p(psi_E), psi_E the direction
    of u_E, p = (mu_{f|b} cos, mu_t sin) -- each component obeys
    u_E,i (1 + g dt mu_i / |u_E|) = u_A,i, so it keeps its sign and shrinks, the one with
    the larger coefficient faster: the velocity (and the path) turns towards the axis of
    the smaller coefficient; the last step sticks with -u_A / (g dt) inside C."""
    law = componentwise_law(*mu)
    u0, dt = 1.0, 1e-4
    res = _slide(law, u0, angle, dt)
    assert res.status == "ok" and res.stop_step is not None
    U, Q = res.u, res.q
    assert U.shape[0] == res.stop_step + 1, "every step recorded"
    UA, UE = U[:-1], U[1:]
    moving = np.hypot(UE[:, 0], UE[:, 1]) > 0
    assert moving[:-1].all() and not moving[-1], "slides until one sticking step"
    psi = np.arctan2(UE[moving, 1], UE[moving, 0])
    decel = -(UE[moving] - UA[moving]) / dt
    np.testing.assert_allclose(decel, G * closed_form(psi, *mu), rtol=0, atol=1e-8 * G,
                               err_msg="deceleration (mu_{f|b} g cos psi, mu_t g sin psi)")
    # the sticking step: the reaction that stops the mass lies in C
    r = UA[-1] / (G * dt)
    mx = mu[0] if r[0] >= 0 else mu[1]
    assert math.hypot(r[0] / mx, r[1] / mu[2]) <= 1 + 1e-9
    # each component keeps its sign and decays monotonically
    for i in (0, 1):
        s = np.sign(U[0, i])
        assert np.all(s * U[:-1, i] > 0) and np.all(np.diff(s * U[:, i]) <= 0)
    # energy: kinetic energy lost = work of the friction force over each step's
    # displacement (midpoint scheme: dq = dt (u_A + u_E) / 2) = the dissipation
    dq = np.diff(Q, axis=0)
    np.testing.assert_allclose(dq, 0.5 * dt * (UA + UE), atol=1e-15)
    F = np.zeros_like(UA)
    F[moving] = -G * closed_form(psi, *mu)
    F[~moving] = -UA[~moving] / dt
    dE = 0.5 * (np.sum(UE ** 2, axis=1) - np.sum(UA ** 2, axis=1))
    work = np.einsum("ij,ij->i", F * dt, 0.5 * (UA + UE))
    np.testing.assert_allclose(dE, work, rtol=0, atol=1e-12)
    dissipated = -work.sum()
    assert dissipated == pytest.approx(0.5 * u0 * u0, rel=1e-9)
    assert np.all(work <= 1e-15), "friction never feeds energy"
    # the path bends towards the axis of the smaller coefficient
    mx0 = mu[0] if U[0, 0] > 0 else mu[1]
    turn = np.diff(np.unwrap(np.arctan2(U[:-1, 1], U[:-1, 0])))
    a = np.arctan2(U[:-1, 1], U[:-1, 0])
    towards_x = np.sign(np.sin(2 * a[:-1])) * turn < 0     # |tan| shrinks
    assert towards_x.all() if mu[2] > mx0 else (~towards_x).all()
    # the continuous invariant |v_y| |v_x|^(-mu_t/mu_x) holds to O(dt) while |v| >> g dt
    fast = np.hypot(U[:, 0], U[:, 1]) > 0.3 * u0
    inv = np.log(np.abs(U[fast, 1])) - mu[2] / mx0 * np.log(np.abs(U[fast, 0]))
    assert np.ptp(inv) < 5e-3, np.ptp(inv)
    # rest point and stop time against the ODE dv/dt = -g p(angle v), integrated here
    t_ref, rest_ref = _ode_rest(mu, u0, angle)
    assert np.hypot(*(Q[-1] - rest_ref)) < u0 * dt, (Q[-1], rest_ref)
    assert res.stop_step * dt == pytest.approx(t_ref, abs=1.5 * dt)


def _ode_rest(mu, u0, angle_deg):
    """(stop time, rest point) of dx/dt = v, dv/dt = -g p(angle v) (DOP853), stopped at
    |v| = 1e-10 u0 (the remaining path, < 1e-20 u0^2 / g, is left out)."""
    from scipy.integrate import solve_ivp
    a = math.radians(angle_deg)

    def rhs(_, y):
        p = closed_form(np.array([math.atan2(y[3], y[2])]), *mu)[0]
        return [y[2], y[3], -G * p[0], -G * p[1]]

    def slow(_, y):
        return math.hypot(y[2], y[3]) - 1e-10 * u0
    slow.terminal = True
    sol = solve_ivp(rhs, (0.0, 10 * u0 / (G * min(mu))), [0.0, 0.0, u0 * math.cos(a),
                    u0 * math.sin(a)], method="DOP853", rtol=1e-11, atol=1e-14, events=slow)
    assert sol.status == 1
    return float(sol.t[-1]), sol.y[:2, -1]


def test_a_disc_on_the_law_comes_to_rest_and_every_step_passes_the_kkt_check():
    from body_kkt import check_run

    from asperity.bodies.footprint import disc
    law = componentwise_law(0.3, 0.6, 0.9)
    fp = disc(0.05, contact_points=64)
    res, rep = check_run(fp.points, fp.weights, law, mass=1.0, inertia=fp.inertia_per_mass,
                         u0=(0.4, 0.25, 15.0), dt=1e-3)
    assert res.ok, res.message
    assert not res.u_final.any(), "at rest"
    assert rep["worst_residual"] < 1e-8 and rep["worst_gauge"] <= 1 + 1e-9, rep
    assert rep["min_margin"] >= -1e-9, rep
    assert rep["steps"] > 20


def test_slide_body_without_spin_along_t_slides_the_point_mass_distance():
    """A uniformly loaded disc launched along +t_a or -t_a without spin: the law is its own
    mirror in n, so no torque; every point slides as the centre, Coulomb with mu_f or mu_b."""
    from asperity.bodies.footprint import disc
    from asperity.dynamics.body_api import slide_body
    law = componentwise_law(0.3, 0.6, 0.9)
    for angle, m in ((0.0, 0.3), (180.0, 0.6)):
        run = slide_body(law, disc(0.05, contact_points=64), 0.8, angle, dt=1e-4)
        q = run.result.q_final
        assert abs(q[2]) < 1e-12 and abs(q[1]) < 1e-12
        assert math.hypot(q[0], q[1]) == pytest.approx(0.8 ** 2 / (2 * m * G), rel=2e-3)


def test_slide_takes_the_three_flags_for_a_point_mass_and_a_body(capsys, tmp_path):
    obj = run_json(capsys, "slide", "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0.9, "--u0", 0.5,
                   "--angle", 30)
    assert obj["law"] == "componentwise" and "mu_t = 0.9" in obj["description"]
    res = _slide(componentwise_law(0.3, 0.6, 0.9), 0.5, 30.0)
    assert obj["rest"] == pytest.approx(res.q[-1].tolist(), abs=1e-12)
    assert obj["deflection_deg"] < 0, "mu_t > mu_f: the path turns towards +t_a"
    path = tmp_path / "cw.json"
    write_gauge(path, componentwise_gauge(0.3, 0.6, 0.9))
    again = run_json(capsys, "slide", path, "--u0", 0.5, "--angle", 30)
    assert again["law"] == "componentwise" and again["rest"] == obj["rest"]
    assert run_json(capsys, "slide", path, "--law", "componentwise", "--u0", 0.5,
                    "--angle", 30)["rest"] == obj["rest"]
    body = run_json(capsys, "slide", "--law", "componentwise", "--mu-f", 0.3, "--mu-b", 0.6,
                    "--mu-t", 0.9, "--u0", 0.3, "--angle", 120, "--body", "disc",
                    "--radius", 0.02, "--contact-points", 32, "--omega0", 5, "--dt", 1e-3)
    assert body["law"] == "componentwise" and body["final_velocity"] == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("argv, words", [
    (["--mu-f", -0.3, "--mu-b", 0.6, "--mu-t", 0.9], "--mu-f must be in [1e-06, 100]"),
    (["--mu-f", 0.3, "--mu-b", "nan", "--mu-t", 0.9], "--mu-b must be in [1e-06, 100]"),
    (["--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0], "--mu-t must be in [1e-06, 100]"),
    (["--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", "inf"],
     "--mu-t must be a finite number in [1e-06, 100]"),
    (["--mu-f", 0.3, "--mu-t", 0.9], "needs --mu-b"),
    (["--law", "componentwise", "--mu-f", 0.3, "--mu-b", 0.6], "needs --mu-t"),
    (["--law", "ellipse", "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0.9], "--law ellipse"),
    (["--mu1", 0.3, "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", 0.9], "--mu1/--mu2"),
])
def test_slide_refuses_bad_coefficients_in_one_line(capsys, argv, words):
    code, out, err = run(capsys, "slide", *argv, "--u0", 0.5, "--angle", 30)
    assert code == 1 and out == "" and len(err.strip().splitlines()) == 1, err
    assert words in err and "Traceback" not in err and "nan" not in err.lower().replace(
        "got nan", ""), err


def test_law_refuses_flags_with_a_gauge_file_and_no_law_at_all(capsys, tmp_path):
    path = tmp_path / "cw.json"
    write_gauge(path, componentwise_gauge(0.3, 0.6, 0.9))
    for argv, words in ((["law", path, "--mu-f", 0.3], "do not apply with a gauge file"),
                        (["law"], "give a gauge file"),
                        (["law", "--mu-f", 0.3, "--mu-b", 0.6, "--mu-t", -1], "--mu-t must be"),
                        (["slide", path, "--mu-f", 0.3, "--u0", 1, "--angle", 0],
                         "do not apply with a gauge file")):
        code, _, err = run(capsys, *argv)
        assert code == 1 and words in err and len(err.strip().splitlines()) == 1, (argv, err)
    assert not (tmp_path / "nothing.json").exists()


@pytest.mark.parametrize("bad", [0.0, -0.1, float("nan"), float("inf"), 101.0, "0.3", None])
def test_the_api_refuses_a_coefficient_outside_the_laws_range(bad):
    for k in range(3):
        mu = [0.3, 0.6, 0.9]
        mu[k] = bad
        with pytest.raises(InputError, match=("mu_f", "mu_b", "mu_t")[k]) as e:
            componentwise_law(*mu)
        assert "\n" not in str(e.value)


def test_the_motion_page_builds_the_law_from_its_three_fields():
    pytest.importorskip("fastapi")
    from asperity.web.tasks_motion import _law_words, build_law
    spec = {"kind": "builtin", "law": "componentwise", "mu_f": 0.3, "mu_b": 0.6, "mu_t": 0.9}
    law = build_law(spec, {})
    assert law.name == "componentwise"
    np.testing.assert_allclose(law.force(PSI), closed_form(PSI, 0.3, 0.6, 0.9), atol=1e-13)
    text, stem = _law_words(spec, law, {}, {})
    assert "mu_t = 0.9" in text and stem.startswith("componentwise")


def test_the_motion_form_slides_on_the_componentwise_law(tmp_path):
    """The Motion page's form (in-process app, 127.0.0.1): the three fields give the
    library's path; a bad coefficient is one line at its field (422, as mu1/mu2)."""
    pytest.importorskip("fastapi")
    import re
    import time
    import warnings
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*httpx2.*")
        from fastapi.testclient import TestClient

    from asperity.web.app import create_app
    from asperity.web.settings import make_settings, prepare_data_dir
    settings = make_settings(data_dir=tmp_path / "data", workers=1)
    prepare_data_dir(settings.data_dir)
    form = {"law": "componentwise", "mu_f": "0.3", "mu_b": "0.6", "mu_t": "0.9", "u0": "0.5",
            "angle_deg": "30"}
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                    follow_redirects=False) as client:
        page = client.get("/motion").text
        assert 'value="componentwise"' in page and 'name="mu_t"' in page
        r = client.post("/motion/slide", data=form)
        assert r.status_code == 303, r.text[:500]
        jid = r.headers["location"].rsplit("/", 1)[-1]
        t0 = time.monotonic()
        while client.get(f"/api/jobs/{jid}").json()["status"] in ("queued", "running"):
            assert time.monotonic() - t0 < 120, "job did not finish"
            time.sleep(0.1)
        assert client.get(f"/api/jobs/{jid}").json()["status"] == "done"
        page = client.get(f"/jobs/{jid}").text
        assert "componentwise" in page and 'id="deflection"' in page
        rows = client.get(f"/jobs/{jid}/files/path.csv").text.strip().splitlines()
        last = [float(v) for v in rows[-1].split(",")]
        res = _slide(componentwise_law(0.3, 0.6, 0.9), 0.5, 30.0)
        assert last[1:3] == pytest.approx(res.q[-1].tolist(), abs=1e-9)
        r = client.post("/motion/slide", data={**form, "mu_t": "-1"})
        assert r.status_code == 422 and "Traceback" not in r.text
        msg = re.findall(r'class="field-error">([^<]*)<', r.text)
        assert len(msg) == 1 and "mu_t" in msg[0] and "\n" not in msg[0], msg
