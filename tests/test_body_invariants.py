"""What any correct body solver keeps: the rest horizon (the time by which a body with no
external force is surely at rest) bounds the exact stopping times of a uniformly loaded
disc's pure slide (v0 / (mu g)) and pure spin (3 R omega0 / (4 mu g)), for mu below and
above 1; the reported stop times match the recorded motion; a disc, or points in mirror
pairs about the y axis, launched exactly along an axis slide the point mass's distance; a
force across t_a moves a body at rest only beyond the limit set; a force and a torque move a
pair of points only beyond its limit surface (a closed form on Coulomb friction and
ellipses), every step checked against its optimality conditions; a warm start
extrapolated to exactly zero on a body that sticks ends the step at rest; a run until rest
at the smallest time steps is sized by the rest horizon, not refused."""
from __future__ import annotations

import math

import pytest

from asperity import coulomb_law
from asperity.bodies import footprint as fpm
from asperity.dynamics.body_horizon import rest_horizon

G = 9.81


@pytest.mark.parametrize("mu", [0.3, 1.0, 3.0])
@pytest.mark.parametrize("g", [G, 1.62])
def test_rest_horizon_bounds_the_closed_form_stopping_times(mu, g):
    R, m = 0.05, 2.0
    fp = fpm.disc(R, contact_points=256)
    inertia = m * fp.inertia_per_mass
    law = coulomb_law(mu)
    v0, w0 = 1.3, 40.0
    slide = rest_horizon(fp.points, fp.weights, law, m, inertia, (v0, 0.0, 0.0), g)
    spin = rest_horizon(fp.points, fp.weights, law, m, inertia, (0.0, 0.0, w0), g)
    t_slide, t_spin = v0 / (mu * g), 3 * R * w0 / (4 * mu * g)
    assert t_slide <= slide < 20 * t_slide
    assert t_spin <= spin < 20 * t_spin
    # both at once stop no later than the bound of the combined speed
    both = rest_horizon(fp.points, fp.weights, law, m, inertia, (v0, 0.0, w0), g)
    assert both == pytest.approx(math.hypot(slide, spin), rel=1e-12)


@pytest.mark.parametrize("u0", [(0.03, 0.0, 2.0), (0.004, -0.002, 0.05), (0.5, 0.2, 1.0)])
def test_slide_and_spin_stop_times_are_where_the_motion_stays_below_the_threshold(u0):
    """BodyResult's slide (spin) stop time: from then on |v| (rho |omega|, rho = sqrt(I/m))
    stays below STOP_FRACTION of |v0| + rho |omega0| + g dt, and the step before was above
    -- read off the recorded states (every step), a body of 4 kg (m != 1), slow starts
    (a velocity scale below 1) included."""
    import numpy as np

    from asperity.dynamics.body import STOP_FRACTION, simulate_body
    fp = fpm.disc(0.05, contact_points=64)
    m, dt = 4.0, 2e-4
    inertia = m * fp.inertia_per_mass
    res = simulate_body(fp.points, fp.weights, coulomb_law(0.4), mass=m, inertia=inertia,
                        u0=u0, dt=dt)
    assert res.ok and res.rest
    rho = math.sqrt(inertia / m)
    thr = STOP_FRACTION * (math.hypot(u0[0], u0[1]) + rho * abs(u0[2]) + G * dt)
    for stop, speed in ((res.slide_stop_time, np.hypot(res.u[:, 0], res.u[:, 1])),
                        (res.spin_stop_time, rho * np.abs(res.u[:, 2]))):
        assert stop is not None and 0 < stop <= res.stop_time + 1e-12
        after = res.t >= stop - 1e-12
        assert np.all(speed[after] <= thr) and speed[~after][-1] > thr


@pytest.mark.parametrize("u0", [(0.0, 0.8, 0.0), (-0.8, 0.0, 0.0), (0.0, -0.5, 0.0)])
def test_disc_launched_along_an_axis_slides_the_point_mass_distance(u0):
    """No spin, launched exactly along x or y (the other components exactly 0): the disc
    slides v0^2 / (2 mu g) and stops at v0 / (mu g), as a point mass on Coulomb friction."""
    from asperity.dynamics.body import simulate_body
    fp = fpm.disc(0.05, contact_points=64)
    mu, dt = 0.4, 1e-4
    res = simulate_body(fp.points, fp.weights, coulomb_law(mu), mass=1.0,
                        inertia=fp.inertia_per_mass, u0=u0, dt=dt)
    v0 = math.hypot(u0[0], u0[1])
    assert res.ok and res.rest
    assert res.stop_time == pytest.approx(v0 / (mu * G), abs=2 * dt)
    travel = math.hypot(res.q_final[0], res.q_final[1])
    assert travel == pytest.approx(v0 ** 2 / (2 * mu * G), rel=2e-3)
    assert abs(res.q_final[2]) < 1e-9                  # no spin appears


@pytest.mark.parametrize("mu_t_b,moves", [(0.2, True), (0.4, False)])
def test_force_across_t_a_moves_the_body_only_beyond_mu_t_b(mu_t_b, moves):
    """An ellipse law, mu 0.6 along t_a (x) and mu_t_b along t_b (y); a body at rest pushed
    along y by 0.3 m g: beyond the limit set when mu_t_b = 0.2 (then it accelerates at
    (0.3 - 0.2) g along y), inside it when mu_t_b = 0.4 (then it never moves)."""
    from asperity.dynamics.body import simulate_body
    from asperity.dynamics.moreau import Force
    from asperity.laws.planar import ellipse_law
    fp = fpm.disc(0.05, contact_points=64)
    m, t = 2.0, 0.2
    res = simulate_body(fp.points, fp.weights, ellipse_law(0.6, mu_t_b), mass=m,
                        inertia=m * fp.inertia_per_mass, dt=1e-3, t_end=t,
                        force=Force(constant=(0.0, 0.3 * m * G, 0.0)))
    assert res.ok
    if moves:
        assert res.u_final[1] == pytest.approx(0.1 * G * t, rel=1e-3)
        assert abs(res.u_final[0]) < 1e-9 and abs(res.u_final[2]) < 1e-9
    else:
        assert not res.u_final.any() and not res.q_final.any()


@pytest.mark.parametrize("u0", [(0.0, 0.8, 0.0), (0.0, -0.5, 0.0)])
@pytest.mark.parametrize("shape", ["pair", "square"])
def test_a_footprint_symmetric_about_y_launched_along_y_slides_the_point_mass_distance(u0,
                                                                                      shape):
    """Points in mirror pairs about the y axis, launched exactly along y: every point slips
    alike, so vx and omega stay exactly 0 and the body is a point mass on Coulomb friction
    (a rest flag read from vx and omega alone took this motion for rest)."""
    from asperity.dynamics.body import simulate_body
    a, b = 0.04, 0.02
    pts = [(-a, 0.0), (a, 0.0)] if shape == "pair" else \
        [(-a, -b), (a, -b), (-a, b), (a, b)]
    w = [1.0 / len(pts)] * len(pts)
    inertia = a * a + (0.0 if shape == "pair" else b * b)
    mu, dt = 0.4, 1e-4
    res = simulate_body(pts, w, coulomb_law(mu), mass=1.0, inertia=inertia, u0=u0, dt=dt)
    v0 = abs(u0[1])
    assert res.ok and res.rest
    assert res.stop_time == pytest.approx(v0 / (mu * G), abs=2 * dt)
    assert math.copysign(1.0, res.q_final[1]) == math.copysign(1.0, u0[1])
    assert abs(res.q_final[1]) == pytest.approx(v0 ** 2 / (2 * mu * G), rel=2e-3)
    assert res.q_final[0] == 0.0 and res.q_final[2] == 0.0


def pair_holds(fx, fy, torque, a):
    """Whether two points at (+-a, 0), each carrying half the load and so a reaction of at
    most 1/2 (per unit of mu m g: a disc), hold the load (fx, fy, torque): f_1 + f_2 =
    (fx, fy) and a (f_2y - f_1y) = torque fix f_1y = fy / 2 - torque / (2 a) and f_2y =
    fy / 2 + torque / (2 a); the x components share fx, which fits iff
    sqrt(1/4 - f_1y^2) + sqrt(1/4 - f_2y^2) >= |fx|."""
    y1, y2 = fy / 2 - torque / (2 * a), fy / 2 + torque / (2 * a)
    return abs(y1) <= 0.5 and abs(y2) <= 0.5 and \
        math.sqrt(0.25 - y1 * y1) + math.sqrt(0.25 - y2 * y2) >= abs(fx)


def pair_limit(direction, a):
    """The scale s at which the load s * direction leaves what the pair holds (bisection)."""
    lo, hi = 0.0, 10.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if pair_holds(*(mid * x for x in direction), a) else (lo, mid)
    return lo


@pytest.mark.parametrize("k", [0.95, 1.05])
@pytest.mark.parametrize("direction", [(1.0, 0.0, 0.03), (1.0, 0.4, 0.024), (-0.3, 1.0, -0.02)])
@pytest.mark.parametrize("law", ["coulomb", "ellipse", "windward-star"])
def test_a_load_moves_a_pair_of_points_only_beyond_its_limit_surface(law, direction, k):
    """Two points at (+-a, 0), half the weight each, at rest under a force and a torque
    (direction: (fx, fy, torque) per unit of mu m g, the force turned into C's axes).  On
    Coulomb friction and on an ellipse (a linear map of Coulomb's disc) the pair holds
    exactly the loads of :func:`pair_holds`: k = 0.95 of the limit stays at rest, 1.05
    moves, though each component alone is within its limit.  On every law, every step is
    checked against its optimality conditions (tests/body_kkt.py): a rest only where no
    motion releases energy, a motion solving its equations.  The free motion is not the
    direction of least margin here: the stick test's search has to find it."""
    from body_kkt import check_run

    from asperity.dynamics.moreau import Force
    from asperity.laws.planar import ellipse_law, windward_star_law
    a, m = 0.03, 1.0
    mu_x, mu_y = {"coulomb": (0.3, 0.3), "ellipse": (0.3, 0.15),
                  "windward-star": (0.3, 0.2)}[law]
    lw = {"coulomb": coulomb_law(mu_x), "ellipse": ellipse_law(mu_x, mu_y),
          "windward-star": windward_star_law(30.0, 15.0, mu_x, mu_y)}[law]
    s = k * pair_limit(direction, a)
    fx, fy, torque = (s * x for x in direction)
    load = Force(constant=(fx * mu_x * m * G, fy * mu_y * m * G, torque * mu_y * m * G))
    res, rep = check_run([(-a, 0.0), (a, 0.0)], [0.5, 0.5], lw, mass=m, inertia=m * a * a,
                         u0=(0.0, 0.0, 0.0), dt=1e-4, t_end=0.01, force=load)
    what = f"{law}, {direction}, k = {k}: {res.message}, {rep}"
    assert res.ok, what
    assert rep["worst_residual"] < 1e-8 and rep["worst_gauge"] <= 1 + 1e-9, what
    assert rep["min_margin"] >= -1e-9, what
    if law != "windward-star":
        assert bool(res.u_final.any()) == (k > 1), what


@pytest.mark.parametrize("law", ["collinear", "coulomb"])
def test_a_warm_start_extrapolated_to_zero_on_a_body_that_sticks_ends_at_rest(law):
    """The step's Newton iteration starts from 2 u_A - u_P, the extrapolation of the last two
    velocities: exactly 0 when the velocity halved in one step.  If the body then sticks (its
    free velocity well inside the limit set), the iteration cannot leave 0 (on a
    non-associated law no step lowers the residual), and the step must fall back on the
    stick test along u_A: at rest, status OK.  The step runs compiled and as plain Python
    (py_func: there an index past an array's end raises, which compiled numba code does not
    check), with the same result."""
    import numpy as np

    from asperity.dynamics import _body_kernels as K
    from asperity.dynamics.body import law_tables
    from asperity.laws.planar import collinear_law
    a, m, dt = 0.03, 1.0, 1e-3
    lw = collinear_law(mu1=0.3, mu2=0.1) if law == "collinear" else coulomb_law(0.3)
    kind, par, tab, assoc, mu_max = law_tables(lw)
    ox, oy = np.array([-a, a]), np.zeros(2)
    ext = np.zeros((0, 4))          # a rigid footprint: no slip offsets, one law orientation
    md = np.array([m, m, m * a * a])
    lam = np.full(2, 0.5 * m * G * dt)
    uA = np.array([0.02 * G * dt, 0.0, 0.0])        # a fifth of what mu = 0.1 stops
    got = []
    for step in (K.step_velocity, K.step_velocity.py_func):
        out = np.full(3, np.nan)
        its, status, _ = step(uA, 2 * uA, True, uA.copy(), md, ox, oy, ext, lam, kind, par, tab,
                              assoc, 1e-12, 100, m * G * dt * mu_max / math.sqrt(m), out,
                              np.empty(3), np.empty((3, 3)), np.empty(16), np.empty(3))
        assert status == K.STATUS_OK and not out.any(), (status, out)
        got.append(its)
    assert got[0] == got[1]


@pytest.mark.parametrize("dt", [1e-8, 1e-9])
def test_a_run_until_rest_at_tiny_steps_is_sized_by_its_horizon(dt):
    """A disc launched at 10 um/s stops after v0 / (mu g) = 3.4 us: a run until rest
    (t_end None) with dt of 1e-8 or 1e-9 s needs some thousand steps, and its end time is
    the rest horizon's multiple plus a few steps -- a budget in seconds (a run of 10 s is
    1e9-1e10 steps, beyond any run's limit) would refuse it.  It runs, and stops at the
    closed form within a step."""
    from asperity.dynamics.body import simulate_body
    from asperity.dynamics.body_horizon import HORIZON_FACTOR, rest_time
    fp = fpm.disc(0.05, contact_points=16)
    m, mu, v0 = 1.0, 0.3, 1e-5
    inertia = m * fp.inertia_per_mass
    law = coulomb_law(mu)
    h = rest_horizon(fp.points, fp.weights, law, m, inertia, (v0, 0.0, 0.0), G)
    t = rest_time(fp.points, fp.weights, law, m, inertia, (v0, 0.0, 0.0), G, dt)
    assert HORIZON_FACTOR * h < t <= HORIZON_FACTOR * h + 100 * dt
    res = simulate_body(fp.points, fp.weights, law, mass=m, inertia=inertia,
                        u0=(v0, 0.0, 0.0), dt=dt)
    assert res.ok and res.rest
    assert res.slide_stop_time == pytest.approx(v0 / (mu * G), abs=1.01 * dt)
