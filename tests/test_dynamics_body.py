"""The rigid-body solver (asperity.dynamics.body): a footprint of N contact points that slides,
spins and sticks as one body (issue 20; SPEC.md sections 4 and 8)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipe, ellipk

from asperity.dynamics.body import TABLE_SIZE, law_tables, simulate_body
from asperity.dynamics.moreau import Body, Force, simulate, slide
from asperity.dynamics.references import ratchet_drift_square
from asperity.errors import InputError
from asperity.laws.planar import (coulomb_law, ellipse_law, star_law, truncated_ellipse_law,
                                  collinear_law)

G = 9.81
MU = 0.3


def disc_points(R, rings=8, sectors=32):
    """Midpoint polar rings of a uniformly loaded disc: weights = cell areas / disc area
    (centrally symmetric for an even number of sectors)."""
    r = (np.arange(rings) + 0.5) / rings * R
    th = (np.arange(sectors) + 0.5) / sectors * 2 * math.pi
    rr, tt = np.meshgrid(r, th, indexing="ij")
    pts = np.column_stack([(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel()])
    w = rr.ravel()
    return pts, w / w.sum()


def ring_points(R, n=256):
    th = (np.arange(n) + 0.5) / n * 2 * math.pi
    return np.column_stack([R * np.cos(th), R * np.sin(th)]), np.full(n, 1.0 / n)


def f_m(eps):
    """SPEC.md 8: force f(eps) and torque m(eps) factors of a uniformly loaded Coulomb disc."""
    if eps <= 1.0:
        k2 = eps * eps
        E = ellipe(k2)
        K1 = (1 - k2) * ellipk(k2) if k2 < 1 else 0.0      # (1 - k^2) K -> 0 at k = 1
        return (4 / (3 * math.pi * eps) * ((1 + k2) * E - K1),
                4 / (9 * math.pi) * ((4 - 2 * k2) * E - K1))
    k2 = 1.0 / (eps * eps)
    E, K = ellipe(k2), ellipk(k2)
    e2 = eps * eps
    return (4 / (3 * math.pi) * ((1 + e2) * E - (e2 - 1) * K),
            4 / (9 * math.pi * eps) * ((4 * e2 - 2 * e2 * e2) * E
                                        + (2 * e2 * e2 - 5 * e2 + 3) * K))


def run(pts, w, law, u0, dt=1e-4, R=None, **kw):
    """A disc of radius R (default: the farthest point) and of mass 1 unless told."""
    kw.setdefault("mass", 1.0)
    R = np.hypot(pts[:, 0], pts[:, 1]).max() if R is None else R
    kw.setdefault("inertia", 0.5 * kw["mass"] * R * R)
    return simulate_body(pts, w, law, u0=u0, dt=dt, **kw)


# ----------------------------------------------------------------------------- closed forms

def test_closed_forms_of_the_disc_match_their_quadrature():
    """f(eps), m(eps) of the test (SPEC.md 8) against a direct polar quadrature."""
    assert f_m(1.0)[0] == pytest.approx(8 / (3 * math.pi), rel=1e-12)
    assert f_m(1.0 - 1e-9)[1] == pytest.approx(8 / (9 * math.pi), rel=1e-8)
    pts, w = disc_points(1.0, 400, 800)
    for eps in (0.2, 0.653, 1.7, 5.0):
        gx = eps - pts[:, 1]                         # v = eps along x, omega = 1, R = 1
        gy = pts[:, 0]
        n = np.hypot(gx, gy)
        f = w @ (gx / n)
        m = w @ ((pts[:, 0] * gy - pts[:, 1] * gx) / n)
        assert f == pytest.approx(f_m(eps)[0], rel=2e-4)
        assert m == pytest.approx(f_m(eps)[1], rel=2e-4)


@pytest.mark.parametrize("eps", [0.3, 1.0, 3.0])
def test_first_step_decelerations_of_a_disc_follow_f_and_m(eps):
    R, dt = 0.1, 1e-7
    pts, w = disc_points(R, 128, 256)
    w0 = 10.0
    r = run(pts, w, coulomb_law(MU), (eps * R * w0, 0.0, w0), dt=dt, t_end=dt, R=R)
    v1 = r.u[-1]
    a = (v1[0] - eps * R * w0) / dt
    alpha = (v1[2] - w0) / dt
    f, m = f_m(eps)
    assert a == pytest.approx(-MU * G * f, rel=2e-3)
    assert alpha == pytest.approx(-2 * MU * G / R * m, rel=2e-3)
    assert abs(v1[1]) < 1e-6 * eps * R * w0


# ----------------------------------------------------------------------------- point-mass limit

@pytest.mark.parametrize("law", [ellipse_law(0.3, 0.15),
                                 truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)])
@pytest.mark.parametrize("angle", [0.0, 37.0, 200.0])
def test_without_spin_a_symmetric_footprint_follows_the_point_mass(law, angle):
    pts, w = disc_points(0.05, 4, 16)
    u0 = 1.2
    ref = slide(law, u0, angle, dt=1e-4)
    a = math.radians(angle)
    r = run(pts, w, law, (u0 * math.cos(a), u0 * math.sin(a), 0.0), dt=1e-4)
    assert r.ok and ref.ok
    assert r.steps == ref.steps
    assert r.stop_time == pytest.approx(ref.stop_time, abs=1e-12)
    np.testing.assert_allclose(r.q[:, :2], ref.q, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.u[:, :2], ref.u, rtol=0, atol=1e-9)
    assert np.abs(r.q[:, 2]).max() < 1e-9


def test_texture_angle_turns_the_law_with_the_support():
    law = truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)
    pts, w = disc_points(0.05, 4, 16)
    u0, angle, tex = 1.0, 50.0, 30.0
    ref = slide(law, u0, angle - tex, dt=1e-4)
    a = math.radians(angle)
    r = run(pts, w, law, (u0 * math.cos(a), u0 * math.sin(a), 0.0), texture_angle_deg=tex)
    c, s = math.cos(math.radians(tex)), math.sin(math.radians(tex))
    rest = np.array([c * ref.q[-1, 0] - s * ref.q[-1, 1], s * ref.q[-1, 0] + c * ref.q[-1, 1]])
    np.testing.assert_allclose(r.q_final[:2], rest, atol=1e-9)
    assert r.final_angle_rad == pytest.approx(0.0, abs=1e-9)


def test_star_law_tables_follow_the_law():
    """Tables of c(psi): linear interpolation on TABLE_SIZE directions; against the law at
    random directions (away from D's flat edges, where c jumps) the error is below
    dpsi^2/8 max|c''|."""
    law = star_law(0.3, 0.2)
    kind, par, tab, assoc, mu = law_tables(law)
    psi = np.random.default_rng(3).uniform(0, 2 * math.pi, 4000)
    dpsi = 2 * math.pi / TABLE_SIZE
    k = np.minimum((psi / dpsi).astype(int), TABLE_SIZE - 1)
    t = psi / dpsi - k
    c = tab[k, :2] + t[:, None] * (tab[k + 1, :2] - tab[k, :2])
    exact = law.force(psi)
    jump = np.hypot(*(tab[k + 1, :2] - tab[k, :2]).T) > 1e-2 * mu       # a flat edge inside
    err = np.hypot(*(c - exact).T)[~jump]
    assert jump.sum() < 0.01 * psi.size
    assert err.max() < 1e-5 * mu


def test_without_spin_the_star_law_follows_the_point_mass_to_the_table_error():
    law = star_law(0.3, 0.2)
    pts, w = disc_points(0.05, 4, 16)
    ref = slide(law, 1.0, 20.0, dt=1e-4)
    a = math.radians(20.0)
    r = run(pts, w, law, (math.cos(a), math.sin(a), 0.0))
    assert r.ok
    np.testing.assert_allclose(r.q_final[:2], ref.q[-1], atol=2e-5)
    assert abs(r.stop_time - ref.stop_time) <= 2e-4


# ----------------------------------------------------------------------------- stick

def test_constant_wrench_inside_limit_set_sticks_bit_for_bit():
    pts, w = disc_points(0.1, 4, 16)
    f = Force(constant=(0.5, -0.3, 0.01))                   # |F| = 0.58 N < mu m g = 2.9 N
    r = simulate_body(pts, w, coulomb_law(MU), mass=1.0, inertia=0.005, q0=(0.2, 0.1, 0.3),
                      dt=1e-3, t_end=0.2, force=f)
    assert r.ok
    assert np.all(r.u == 0.0)
    assert np.all(r.q == np.array([0.2, 0.1, 0.3]))
    assert r.stop_time == 0.0


@pytest.mark.parametrize("law", [coulomb_law(MU), ellipse_law(0.3, 0.2), star_law(0.3, 0.2)])
def test_stick_is_decided_by_the_limit_set(law):
    """A pure torque just inside the footprint's limit torque sum_i w_i m g h_C-limit holds the
    body for good; just outside, it turns at once."""
    pts, w = disc_points(0.1, 4, 16)
    # limit torque of a pure spin: each point resists with rho(psi) along its slip
    kind, par, tab, assoc, mu = law_tables(law)
    psi = np.arctan2(pts[:, 0], -pts[:, 1])          # slip direction of a point at spin > 0
    if law.name == "star":
        c = law.force(psi)
    else:
        c = law.force(psi)
    limit = G * (w @ (pts[:, 0] * c[:, 1] - pts[:, 1] * c[:, 0]))
    for factor, still in ((1 - 1e-6, True), (1 + 1e-3, False)):
        r = simulate_body(pts, w, law, mass=1.0, inertia=0.005, dt=1e-3, t_end=0.05,
                          force=Force(constant=(0.0, 0.0, factor * limit)))
        assert r.ok
        assert np.all(r.u == 0.0) == still, (factor, r.u[-1])
        if not still:
            assert r.u[-1, 2] > 0


def test_force_outside_the_limit_set_moves_the_body_though_not_along_the_force():
    """On the ellipse 0.3/0.1 a force at 45 deg between the limit radius rho and the support
    h of that direction: the ray of the free motion shows no sliding (h > |F|/mg), the body
    slides all the same (|F|/mg > rho, along the normal of the ellipse) -- found by the least
    margin over the sphere -- and moves exactly as the point mass does."""
    law = ellipse_law(0.3, 0.1)
    pts, w = disc_points(0.05, 4, 16)
    rho = 1.0 / math.sqrt(0.5 / 0.09 + 0.5 / 0.01)
    h = math.sqrt(0.5 * 0.09 + 0.5 * 0.01)
    F = 1.02 * rho * G                                     # 2 % outside
    assert rho * G < F < h * G
    fx = fy = F / math.sqrt(2.0)
    r = simulate_body(pts, w, law, mass=1.0, inertia=1e-3, dt=1e-4, t_end=0.05,
                      force=Force(constant=(fx, fy, 0.0)))
    ref = simulate(Body(mass=1.0, laws=(law,)), (0.0, 0.0), dt=1e-4, t_end=0.05,
                   force=Force(constant=(fx, fy)))
    assert r.ok and ref.ok
    assert np.hypot(*r.u[1, :2]) > 0.0                    # moving from the first step on
    np.testing.assert_allclose(r.u[:, :2], ref.u, atol=1e-12)
    np.testing.assert_allclose(r.q[:, :2], ref.q, atol=1e-12)


def test_few_point_footprints_match_the_multi_contact_jacobi_solver():
    """Random 4- to 6-point footprints sliding and spinning (points stick one by one: F's kinks)
    against asperity.dynamics.moreau.simulate, an independent solver over the 2N contact
    impulses (which converges for few points)."""
    rng = np.random.default_rng(5)
    compared = 0
    for k in range(8):
        n = 4 + k % 3
        pts = rng.normal(scale=0.05, size=(n, 2))
        w = rng.uniform(0.2, 1.0, n)
        w /= w.sum()
        pts -= w @ pts
        law = (coulomb_law(0.3), ellipse_law(0.3, 0.15))[k % 2]
        u0 = np.array([rng.normal(), rng.normal(), rng.normal(scale=20)])
        r = simulate_body(pts, w, law, mass=1.0, inertia=2e-3, u0=u0, dt=1e-4)
        ref = simulate(Body(mass=1.0, laws=law, inertia=2e-3, contacts=pts, share=w), u0,
                       dt=1e-4, t_end=r.steps * 1e-4)
        assert r.ok and r.rest
        if not ref.ok:                     # the Jacobi iteration's limit, not ours
            continue
        compared += 1
        # (the Jacobi solver declares rest only when every contact sticks: it may end one
        # step later with a velocity at its tolerance; the paths are compared)
        np.testing.assert_allclose(r.u, ref.u, atol=1e-9)
        np.testing.assert_allclose(r.q, ref.q, atol=1e-11)
    assert compared >= 5


def test_square_wave_at_rest_below_threshold_never_moves():
    pts, w = disc_points(0.1, 4, 16)
    f = Force(amplitude=(0.2, 0.1, 0.005), period=0.1, waveform="square")
    r = simulate_body(pts, w, ellipse_law(0.3, 0.2), mass=1.0, inertia=0.005, dt=1e-3,
                      t_end=0.5, force=f)
    assert r.ok and np.all(r.u == 0.0) and np.all(r.q == 0.0)


# ----------------------------------------------------------------------------- energy

def test_energy_never_increases_from_random_starts():
    rng = np.random.default_rng(11)
    laws = [coulomb_law(0.3), ellipse_law(0.3, 0.1), truncated_ellipse_law(0.2, 0.08, 0.12, 0.15),
            star_law(0.3, 0.2), collinear_law(mu1=0.3, mu2=0.15)]
    for k in range(10):
        n = int(rng.integers(3, 40))
        pts = rng.normal(scale=0.05, size=(n, 2))
        w = rng.uniform(0.1, 1.0, n)
        w /= w.sum()
        pts -= w @ pts                               # any footprint, centre of pressure at 0
        u0 = (rng.normal(), rng.normal(), rng.normal(scale=30.0))
        law = laws[k % len(laws)]
        r = simulate_body(pts, w, law, mass=rng.uniform(0.5, 2), inertia=rng.uniform(1e-4, 1e-2),
                          u0=u0, dt=2e-4, texture_angle_deg=float(rng.uniform(-90, 90)))
        assert r.ok, r.message
        e = r.energy
        assert np.all(np.diff(e) <= 1e-13 * e[0]), (law.name, np.diff(e).max())
        assert r.rest and e[-1] == 0.0


# ----------------------------------------------------------------------------- terminal ratio

@pytest.mark.parametrize("eps0", [0.5, 5.0])
def test_disc_stops_sliding_and_spinning_together_at_ratio_0653(eps0):
    """From eps0 far below 0.653 the approach is slow (0.1 -> 0.55 at dt = 1e-4 over a
    thousandfold fall of the speed): the starts are 0.5 and 5."""
    R = 0.1
    pts, w = disc_points(R, 16, 64)
    w0 = 15.0 / (1.0 + eps0)                          # slow spin for a large eps0
    r = run(pts, w, coulomb_law(MU), (eps0 * R * w0, 0.0, w0), dt=1e-4, R=R)
    assert r.ok and r.rest
    assert r.slide_stop_time == r.stop_time == r.spin_stop_time
    assert r.terminal_ratio(R) == pytest.approx(0.653002, rel=1e-2)


@pytest.mark.parametrize("eps0", [0.2, 4.0])
def test_ring_stops_at_ratio_one(eps0):
    R = 0.1
    pts, w = ring_points(R, 512)
    w0 = 20.0 / (1.0 + eps0)
    r = run(pts, w, coulomb_law(MU), (eps0 * R * w0, 0.0, w0), inertia=R * R)
    assert r.ok and r.rest
    assert r.slide_stop_time == r.stop_time == r.spin_stop_time
    assert r.terminal_ratio(R) == pytest.approx(1.0, rel=5e-3)


# ----------------------------------------------------------------------------- drift

def test_pure_spin_on_an_asymmetric_law_drifts_and_an_ellipse_does_not():
    """From rest, a spinning disc feels -m g / (2 pi) integral of p(psi) dpsi."""
    R, dt = 0.1, 1e-7
    pts, w = disc_points(R, 16, 512)
    law = truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)
    psi = 2 * math.pi * (np.arange(20000) + 0.5) / 20000
    mean_p = law.force(psi).mean(axis=0)
    r = run(pts, w, law, (0.0, 0.0, 20.0), dt=dt, t_end=dt)
    a = r.u[-1, :2] / dt
    np.testing.assert_allclose(a, -G * mean_p, rtol=0, atol=2e-4 * G * 0.1)
    assert np.hypot(*mean_p) > 0.02                  # the drift is real
    r = run(pts, w, ellipse_law(0.3, 0.1), (0.0, 0.0, 20.0), dt=dt, t_end=dt)
    assert np.abs(r.u[-1, :2]).max() < 1e-12


def test_spinning_disc_on_the_asymmetric_law_drifts_along_the_mean_force():
    R = 0.1
    pts, w = disc_points(R, 8, 64)
    law = truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)
    r = run(pts, w, law, (0.0, 0.0, 40.0), dt=1e-4)
    assert r.ok and r.rest
    psi = 2 * math.pi * (np.arange(4000) + 0.5) / 4000
    mean_p = law.force(psi).mean(axis=0)
    d = r.q_final[:2]
    cosang = -(d @ mean_p) / (np.hypot(*d) * np.hypot(*mean_p))
    assert np.hypot(*d) > 1e-4 and cosang > 0.9


# ----------------------------------------------------------------------------- convergence

def _disc_ode(pts, w, v0, w0, R):
    """Reference: the ODE of the same footprint (dv/dt = -g sum w_i c_i, I domega/dt = ...)
    by solve_ivp at tight tolerances until the speed falls to 1e-7 of the start."""
    rho2 = 0.5 * R * R

    def rhs(t, y):
        c, s = math.cos(y[2]), math.sin(y[2])
        ox = c * pts[:, 0] - s * pts[:, 1]              # the footprint turns with the body
        oy = s * pts[:, 0] + c * pts[:, 1]
        gx = y[3] - y[5] * oy
        gy = y[4] + y[5] * ox
        n = np.hypot(gx, gy)
        fx, fy = MU * gx / n, MU * gy / n
        tq = w @ (ox * fy - oy * fx)
        return [y[3], y[4], y[5], -G * (w @ fx), -G * (w @ fy), -G * tq / rho2]

    def slow(t, y):
        return math.hypot(y[3], y[4]) + R * abs(y[5]) - 1e-7 * (v0 + R * w0)
    slow.terminal = True
    sol = solve_ivp(rhs, (0, 10.0), [0, 0, 0, v0, 0, w0], method="DOP853", rtol=1e-11,
                    atol=1e-13, events=slow)
    return sol.t_events[0][0], sol.y_events[0][0][0]


def test_stop_time_and_distance_converge_in_dt():
    R = 0.1
    pts, w = disc_points(R, 8, 32)
    v0, w0 = 1.0, 20.0
    T, X = _disc_ode(pts, w, v0, w0, R)
    errs = []
    for dt in (4e-3, 2e-3, 1e-3, 5e-4):
        r = run(pts, w, coulomb_law(MU), (v0, 0.0, w0), dt=dt, R=R)
        assert r.ok and r.rest
        errs.append((abs(r.stop_time - T), abs(r.q_final[0] - X)))
    errs = np.array(errs)
    order = np.log2(errs[:-1] / errs[1:])
    assert np.all(errs[1:] < errs[:-1])
    assert np.all(order.mean(axis=0) > 0.8)
    assert errs[-1, 0] < 2e-3 and errs[-1, 1] < 1e-4


# ----------------------------------------------------------------------------- external loads

def test_shaken_body_walks_as_the_point_mass_in_one_dimension():
    """Square-wave push along t_a on an asymmetric law: no spin, the body ratchets by the
    two-node closed form per cycle, as the point mass does."""
    law = truncated_ellipse_law(0.2, 0.1, 0.15, 0.15)
    pts, w = disc_points(0.05, 4, 16)
    F0, T = 1.5, 0.2                                 # mu- m g = 0.98 < F0 < mu+ m g = 1.96
    f = Force(amplitude=(F0, 0.0, 0.0), period=T, waveform="square")
    cycles = 5
    t_end = (cycles + 0.5) * T
    r = simulate_body(pts, w, law, mass=1.0, inertia=1e-3, dt=1e-4, t_end=t_end, force=f)
    ref = simulate(Body(mass=1.0, laws=(law,)), (0.0, 0.0), dt=1e-4, t_end=t_end,
                   force=Force(amplitude=(F0, 0.0), period=T, waveform="square"))
    assert r.ok and ref.ok
    np.testing.assert_allclose(r.q[:, :2], ref.q, atol=1e-9)
    drift = ratchet_drift_square(F0, 1.0, T, 0.2, 0.1)
    # at rest in the middle of every pushing half period: x there, cycle after cycle
    k = np.rint(((np.arange(cycles + 1) + 0.5) * T) / 1e-4).astype(int)
    per_cycle = np.diff(r.q[k, 0])
    np.testing.assert_allclose(per_cycle, drift, rtol=5e-3)
    assert abs(r.q_final[2]) < 1e-9


def test_oscillating_torque_on_an_asymmetric_law_moves_the_body_sideways():
    """A disc twisted back and forth on the truncated ellipse: every spin drifts it along
    -mean p for both signs of the spin (the mean force does not depend on the sense)."""
    law = truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)
    R = 0.1
    pts, w = disc_points(R, 8, 64)
    tq = 3.0 * (w @ np.hypot(*pts.T)) * 0.2 * G       # well above the limit torque
    f = Force(amplitude=(0.0, 0.0, tq), period=0.1, waveform="sine")
    r = simulate_body(pts, w, law, mass=1.0, inertia=0.5 * R * R, dt=1e-4, t_end=1.0,
                      force=f)
    assert r.ok
    psi = 2 * math.pi * (np.arange(4000) + 0.5) / 4000
    mean_p = law.force(psi).mean(axis=0)
    d = r.q_final[:2]
    assert np.hypot(*d) > 1e-4
    assert -(d @ mean_p) / (np.hypot(*d) * np.hypot(*mean_p)) > 0.9


# ----------------------------------------------------------------------------- bad input

def test_bad_input_is_one_line():
    pts, w = disc_points(0.1, 2, 8)
    law = coulomb_law(MU)
    kw = dict(mass=1.0, inertia=0.005, u0=(1.0, 0.0, 0.0), dt=1e-3)
    for bad in (dict(points=pts[:, :1]), dict(weights=w[:-1]), dict(weights=-w),
                dict(weights=2 * w), dict(u0=(math.nan, 0, 0)), dict(u0=(0, 0, math.inf)),
                dict(inertia=0.0), dict(dt=0.0), dict(dt=2.0), dict(t_end=-1.0),
                dict(points=np.zeros((2_000_000, 2)), weights=np.full(2_000_000, 5e-7)),
                dict(force=Force(constant=(1.0, 0, 0))), dict(texture_angle_deg=math.nan)):
        args = dict(points=pts, weights=w, law=law, **kw)
        args.update(bad)
        with pytest.raises(InputError) as e:
            simulate_body(args.pop("points"), args.pop("weights"), args.pop("law"), **args)
        assert "\n" not in str(e.value)
