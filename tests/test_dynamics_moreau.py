"""Moreau time-stepping (asperity.dynamics) and the planar laws (asperity.laws.planar): closed forms,
invariants (exact stick, energy), convergence towards a tight ODE reference, deflection,
ratcheting, and the kernels against slow NumPy versions."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.dynamics import moreau as M
from asperity.dynamics import references as R
from asperity.errors import InputError
from asperity.laws import planar as L
from asperity.laws.geometry import unit

G = 9.81


# ----------------------------------------------------------------------------- kernels vs NumPy

def test_ellipse_projection_is_the_nearest_boundary_point():
    law = L.truncated_ellipse_law(0.2, 0.08, 0.12, 0.15, theta=0.3)
    rng = np.random.default_rng(1)
    x = rng.normal(size=(300, 2)) * 0.4
    y, inside = L.prox_set(law, x)
    C = law.law.C
    k = C.gauge(x)
    np.testing.assert_array_equal(inside, k <= 1)
    np.testing.assert_array_equal(y[inside], x[inside])
    phi = np.linspace(0, 2 * np.pi, 400001)
    B = C.radial(phi)[:, None] * unit(phi)
    for i in np.flatnonzero(~inside)[:60]:
        dmin = np.hypot(*(B - x[i]).T).min()
        assert np.hypot(*(y[i] - x[i])) <= dmin + 1e-12, "projection is not the nearest point"
        assert abs(C.gauge(y[i:i + 1])[0] - 1) < 1e-13


def test_support_set_projection_matches_normal_points():
    law = L.windward_star_law()
    D = L.solver_D(law)
    psi = np.linspace(0, 2 * np.pi, 997, endpoint=False) + 1e-3
    y, _, _ = D.normal_point(psi)
    for t in (1e-3, 0.3, 5.0):
        P, inside = L.prox_set(law, y + t * unit(psi))
        assert not inside.any()
        np.testing.assert_allclose(P, y, atol=2e-14, err_msg="prox onto D: the boundary point "
                                   "whose normal is the offset direction")
    # points beyond the flat edge (sliding along the ridges) project onto the edge itself
    x = np.array([[0.1, 2.0], [-0.3, 1.0]])
    P, _ = L.prox_set(law, x)
    h = D.support(np.array([0.5 * np.pi]))[0]
    np.testing.assert_allclose(P, [[0.1, h], [-0.3, h]], atol=1e-15)
    # points on a flat edge, or off it by rounding, are their own projection (they used to
    # jump to the edge's end when x.s - h rounded to <= 0 at the edge's normal)
    for e in D.edges:
        _, ym, yp = D.normal_point(np.array([e]))
        on = ym + np.linspace(0.0, 1.0, 2001)[:, None] * (yp - ym)
        for f in (1.0, 1.0 - 1e-15, 1.0 + 1e-15, 1.0 + 3e-15):
            P, _ = L.prox_set(law, f * on)
            np.testing.assert_allclose(P, f * on, rtol=0, atol=1e-14)


def test_kernel_radial_and_law_point_match_the_gauge_module():
    law = L.windward_star_law()
    phi = np.linspace(-7, 7, 2001)
    np.testing.assert_allclose(L.kernel_radial(law, phi), law.law.C.radial(phi), rtol=1e-14)
    psi = np.linspace(0, 2 * np.pi, 500, endpoint=False) + 1e-4
    y, _, _ = L.solver_D(law).normal_point(psi)
    P, inside = L.law_point(law, y + 0.2 * unit(psi))
    np.testing.assert_allclose(P, law.force(psi), atol=1e-14,
                               err_msg="Walker-Leine map: C point on the ray of D's normal point")
    # inside: alpha maps C onto D, the inverse maps y back into C with k_C(P) <= 1
    P, inside = L.law_point(law, 0.5 * y)
    assert inside.all() and np.all(law.law.C.gauge(P) < 1)


@pytest.mark.parametrize("make", [L.windward_star_law, lambda: L.star_law(0.5, 0.2)],
                         ids=["windward-star", "stretched-star"])
def test_sticking_map_undoes_alpha(make):
    """Sticking (SPEC.md 3): alpha maps C into D, y = alpha(P) P with
    alpha = 1/(k_D(P) - k_C(P) + 1).  The Walker-Leine map must give P back from y for every
    P inside C, scale with the normal impulse, and on the boundary of C (sliding) give the
    boundary point.  alpha from the solver's D (scaled into C: alpha <= 1) through the
    kernels' radial functions (the gauge module's D is an inscribed polygon, 2e-6 off)."""
    law = make()
    rng = np.random.default_rng(7)
    phi = rng.uniform(0, 2 * np.pi, 500)
    rho_c, rho_d = L.kernel_radial(law, phi, "C"), L.kernel_radial(law, phi, "D")

    def alpha(r):
        return 1.0 / (r / rho_d - r / rho_c + 1.0)
    for t in (rng.uniform(0.02, 0.98, 500), np.ones(500)):
        r = t * rho_c
        P = r[:, None] * unit(phi)
        a = alpha(r)
        assert np.all(a <= 1.0) and a.min() < 0.9, "a non-associated law: alpha < 1"
        Q, inside = L.law_point(law, a[:, None] * P)
        assert t[0] == 1.0 or inside.all(), "alpha(P) P lies in D"
        np.testing.assert_allclose(Q, P, rtol=1e-13, atol=1e-16,
                                   err_msg="law_point(alpha(P) P) = P (measured 3e-16)")
        Q, _ = L.law_point(law, 250.0 * a[:, None] * P, normal=250.0)
        np.testing.assert_allclose(Q, 250.0 * P, rtol=1e-13, atol=1e-14)


def test_prox_interval():
    np.testing.assert_array_equal(L.prox_interval([-3, -0.1, 0.2, 5], 0.5, 1.0, 2.0),
                                  [-1.0, -0.1, 0.2, 2.0])


# ----------------------------------------------------------------------------- closed forms

@pytest.mark.parametrize("dt", [1e-3, 1e-4])
@pytest.mark.parametrize("angle", [0.0, 37.0, 200.0])
def test_isotropic_stop_time_and_distance(dt, angle):
    u0, mu = 2.0, 0.3
    r = M.slide(L.coulomb_law(mu), u0, angle, dt=dt)
    assert r.ok
    T, S = R.coulomb_stop_time(u0, mu), R.coulomb_stop_distance(u0, mu)
    assert 0 <= r.stop_time - T < dt, "stop time u0/(mu g) within one step"
    assert abs(np.hypot(*r.q_final) - S) < u0 * dt, "stop distance u0^2/(2 mu g) within O(dt)"
    assert abs(M.deflection_deg(angle, r.q_final)) < 1e-9, "isotropic: no deflection"


@pytest.mark.parametrize("law,axes", [
    (L.ellipse_law(0.6, 0.25), (0.6, 0.6, 0.25, 0.25)),
    (L.truncated_ellipse_law(0.2, 0.08, 0.12, 0.15), (0.2, 0.08, 0.12, 0.15)),
    (L.star_law(0.5, 0.2), (0.5, 0.5, 0.2, 0.2)),
])
def test_principal_axes_stop_like_coulomb(law, axes):
    u0, dt = 1.5, 1e-4
    for angle, mu in zip((0.0, 180.0, 90.0, 270.0), axes):
        r = M.slide(law, u0, angle, dt=dt)
        T, S = R.coulomb_stop_time(u0, mu), R.coulomb_stop_distance(u0, mu)
        assert abs(r.stop_time - T) < dt * 1.0001, f"stop time along {angle} deg with mu {mu}"
        d = r.q_final
        along = d @ unit(math.radians(angle))[0]
        assert abs(along - S) < u0 * dt, f"distance along {angle} deg with mu {mu}"
        assert abs(M.deflection_deg(angle, d)) < 1e-12, "no deflection along a principal axis"


# ----------------------------------------------------------------------------- invariants

@pytest.mark.parametrize("law", [L.ellipse_law(0.6, 0.3), L.windward_star_law()],
                         ids=["ellipse", "star"])
def test_exact_stick_for_1e5_steps(law):
    dt = 1e-3
    r = M.slide(law, 1.0, 35.0, dt=dt, t_end=0.6)
    assert r.stop_step is not None
    r = M.simulate(M.point_mass(law), [math.cos(0.6), math.sin(0.6)], dt=dt,
                   t_end=(r.stop_step + 100_000) * dt)
    k = r.stop_step
    assert r.steps - k >= 100_000
    after = r.q[k:]
    assert np.all(after == after[0]), "zero drift after the stop, bit for bit"
    assert np.all(r.u[k:] == 0.0)


def test_stick_under_a_constant_force_below_the_threshold():
    law = L.truncated_ellipse_law(0.3, 0.15, 0.2, 0.2)
    body = M.point_mass(law, 2.0)
    f = M.Force(constant=(0.14 * 2.0 * G, 0.1 * 2.0 * G))          # inside the reservoir
    r = M.simulate(body, [0.0, 0.0], dt=1e-3, t_end=100.0, force=f, record_every=1000)
    assert np.all(r.q == 0.0) and np.all(r.u == 0.0) and r.steps == 100_000


def test_constant_force_above_the_threshold_accelerates_exactly():
    mu, m, F = 0.2, 3.0, 10.0
    r = M.simulate(M.point_mass(L.coulomb_law(mu), m), [0.0, 0.0], dt=1e-3, t_end=2.0,
                   force=M.Force(constant=(F, 0.0)))
    a = F / m - mu * G
    np.testing.assert_allclose(r.q[:, 0], 0.5 * a * r.t ** 2, rtol=1e-12, atol=1e-15)
    assert np.all(r.q[:, 1] == 0)


@pytest.mark.parametrize("law", [L.ellipse_law(0.6, 0.3), L.collinear_law(mu1=0.6, mu2=0.3),
                                 L.star_law(0.6, 0.3), L.windward_star_law()],
                         ids=["ellipse", "collinear", "star", "windward"])
def test_energy_never_increases(law):
    r = M.slide(law, 2.0, 23.0, dt=2e-4)
    E = r.energy
    assert r.ok and E[-1] == 0.0
    assert np.all(np.diff(E) <= 1e-12 * E[0]), "kinetic energy must not increase"


def test_rigid_body_spin_down_closed_form():
    """A square body on four contacts at radius R spinning at w0 with no translation: the
    friction torque is mu m g R, so it stops after w0 J / (mu m g R) without translating."""
    mu, m, J, R, w0 = 0.4, 2.0, 0.05, 0.2, 8.0
    pts = R * np.array([[1, 0], [0, 1], [-1, 0], [0, -1]], float)
    body = M.Body(mass=m, inertia=J, contacts=pts, laws=L.coulomb_law(mu))
    dt = 1e-5
    r = M.simulate(body, [0.0, 0.0, w0], dt=dt, t_end=0.3)
    T = w0 * J / (mu * m * G * R)
    assert r.ok and abs(r.stop_time - T) < 2 * dt
    theta = 0.5 * w0 * T
    assert abs(r.q_final[2] - theta) < w0 * dt
    assert np.abs(r.q[:, :2]).max() < 1e-12, "a symmetric spin does not translate"
    assert np.all(np.diff(r.energy) <= 1e-12 * r.energy[0])


def test_rigid_body_with_mixed_laws_sticks_exactly_and_loses_energy():
    pts = np.array([[0.3, 0.1], [-0.2, 0.25], [-0.1, -0.3]])
    laws = (L.ellipse_law(0.5, 0.2), L.windward_star_law(), L.coulomb_law(0.3))
    body = M.Body(mass=1.5, inertia=0.04, contacts=pts, laws=laws, share=[0.5, 0.3, 0.2])
    r = M.simulate(body, [1.0, 0.4, 6.0], dt=1e-4, t_end=1.0)
    assert r.ok and r.stop_step is not None
    assert np.all(np.diff(r.energy) <= 1e-12 * r.energy[0])
    assert np.all(r.q[r.stop_step:] == r.q[r.stop_step])


# ----------------------------------------------------------------------------- convergence

@pytest.fixture(scope="module")
def references():
    out = {}
    for name, law, angle in (("ellipse", L.ellipse_law(0.6, 0.3), 30.0),
                             ("windward star", L.windward_star_law(), 45.0)):
        out[name] = (law, angle, R.reference_path(law, 2.0, angle, rtol=1e-11))
    return out


@pytest.mark.parametrize("name", ["ellipse", "windward star"])
def test_first_order_convergence_to_the_ode_reference(references, name):
    law, angle, (t_stop, rest, dense) = references[name]
    dts = [2e-3, 1e-3, 5e-4, 2.5e-4]
    err = [R.path_error(M.slide(law, 2.0, angle, dt=dt), dense) for dt in dts]
    order = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all((order > 0.85) & (order < 1.15)), f"{name}: orders {order}, errors {err}"
    assert err[-1] < 0.25 * dts[-1] * 2.0, "error O(u0 dt)"


def test_sliding_along_the_ridges_is_a_sliding_mode(references):
    """Windward: the path turns towards t_b and then slides exactly along the ridges."""
    law, angle, _ = references["windward star"]
    r = M.slide(law, 2.0, angle, dt=1e-4)
    tail = r.u[(r.u[:, 1] > 0) & (np.abs(r.u[:, 0]) < 1e-9)]
    assert tail.shape[0] > 100 and np.all(np.abs(tail[:, 0]) < 1e-10)


# ----------------------------------------------------------------------------- deflection

@pytest.mark.parametrize("law", [L.ellipse_law(0.6, 0.3), L.star_law(0.6, 0.3)],
                         ids=["ellipse", "star"])
def test_off_axis_sliding_deflects_towards_the_low_friction_axis(law):
    for angle, sign in ((30.0, 1), (60.0, 1), (-45.0, -1), (135.0, -1), (210.0, 1)):
        d = M.deflection_deg(angle, M.slide(law, 2.0, angle, dt=1e-4).q_final)
        assert sign * d > 1.0, f"launched at {angle} deg: deflection {d} deg towards t_b"


def test_collinear_law_goes_straight():
    law = L.collinear_law(mu1=0.6, mu2=0.3)
    for angle in (20.0, 45.0, 110.0):
        r = M.slide(law, 2.0, angle, dt=1e-4)
        assert abs(M.deflection_deg(angle, r.q_final)) < 1e-11          # 1.6e-12 reached
        mu = law.radial(math.radians(angle))[0]
        assert abs(r.stop_time - R.coulomb_stop_time(2.0, mu)) < 1e-4


# ----------------------------------------------------------------------------- ratcheting

@pytest.mark.parametrize("mu_p,mu_m,F0", [(0.3, 0.15, 0.2), (0.12, 0.25, 0.18),
                                          (0.3, 0.15, 0.29)])
def test_ratchet_drift_per_cycle_matches_the_closed_form(mu_p, mu_m, F0):
    m, T, dt = 2.0, 0.4, 1e-4
    law = L.truncated_ellipse_law(mu_p, mu_m, 0.2, 0.2)
    F = F0 * m * G
    r = M.simulate(M.point_mass(law, m), [0.0, 0.0], dt=dt, t_end=10 * T,
                   force=M.Force(amplitude=(F, 0.0), period=T, waveform="square"),
                   record_every=int(round(T / dt)))
    drift = np.diff(r.q[:, 0])[1:]          # cycle 1 lacks the stop of its slip (in cycle 2)
    ref = R.ratchet_drift_square(F, m, T, mu_p, mu_m)
    assert ref != 0 and np.sign(ref) == (-1 if mu_m < mu_p else 1), "towards low friction"
    np.testing.assert_allclose(drift, ref, rtol=1e-6, err_msg="drift per cycle")  # 3e-7 reached
    assert np.all(r.q[:, 1] == 0)


def test_ratchet_converges_at_first_order():
    m, T, mu_p, mu_m, F = 1.0, 0.4, 0.3, 0.15, 0.2 * G
    law = L.truncated_ellipse_law(mu_p, mu_m, 0.2, 0.2)
    ref = R.ratchet_drift_square(F, m, T, mu_p, mu_m)
    errs = []
    for dt in (4e-3, 2e-3, 1e-3, 5e-4):
        # from rest at T/2 (sticking) to 3.5 T: three whole slip-and-stop cycles
        r = M.simulate(M.point_mass(law, m), [0.0, 0.0], dt=dt, t_end=3.5 * T,
                       force=M.Force(amplitude=(F, 0.0), period=T, waveform="square"))
        errs.append(abs(r.q_final[0] / 3 - ref))
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(order > 0.8) and errs[-1] < 0.01 * abs(ref), f"errors {errs}"


def test_no_drift_without_asymmetry():
    m, T, mu = 1.0, 0.4, 0.2
    law = L.truncated_ellipse_law(mu, mu, 0.2, 0.2)
    # below the threshold: no motion at all
    r = M.simulate(M.point_mass(law, m), [0.0, 0.0], dt=1e-4, t_end=4 * T,
                   force=M.Force(amplitude=(0.19 * G, 0.0), period=T, waveform="square"))
    assert np.all(r.q == 0)
    # above it (slip both ways): the drift per cycle dies out
    for wave in ("square", "sine"):
        r = M.simulate(M.point_mass(law, m), [0.0, 0.0], dt=1e-4, t_end=40 * T,
                       force=M.Force(amplitude=(0.5 * G, 0.0), period=T, waveform=wave),
                       record_every=int(round(T / 1e-4)))
        drift = np.diff(r.q[:, 0])
        slip = abs(r.q[:, 0]).max()
        assert np.abs(drift[-10:]).max() < 1e-6 * slip, f"{wave}: drift {drift[-10:]}"
    with pytest.raises(InputError, match="both"):
        R.ratchet_drift_square(0.5 * G, m, T, mu, mu)


# ----------------------------------------------------------------------------- status, input

def test_non_convergence_is_reported():
    r = M.slide(L.windward_star_law(), 2.0, 45.0, dt=1e-3,
                settings=M.Settings(max_iterations=1))
    assert r.status == "not-converged" and r.fail_step is not None
    assert r.fail_residual > 1e-12
    assert f"step {r.fail_step}" in r.status_message()


def test_bad_input_names_the_field():
    with pytest.raises(InputError, match="mu1"):
        L.ellipse_law(-1, 0.3)
    with pytest.raises(InputError, match="dt"):
        M.slide(L.coulomb_law(0.3), 1.0, 0.0, dt=0.0)
    with pytest.raises(InputError, match="share"):
        M.Body(mass=1, inertia=1, contacts=[[0, 0], [1, 0]], laws=L.coulomb_law(0.3),
               share=[0.5, 0.6])
    with pytest.raises(InputError, match="relax"):
        M.Settings(relax=2.0)


def test_gauge_file_laws(tmp_path):
    from asperity.friction.derive import derive
    from asperity.laws.fitting import fit_derivation
    from asperity.laws.gauge_file import write_gauge
    from asperity.texture.wedges import WedgeTexture
    d = derive(WedgeTexture(30, 10, 0.1, 0.2), "windward", "closed-form", 180)
    for kind, name in (("star", "star"), ("truncated-ellipse", "truncated-ellipse")):
        gl = fit_derivation(d, kind, holdout=False)
        path = tmp_path / f"{kind}.json"
        write_gauge(path, gl)
        law = L.from_gauge(path)
        assert law.name == name
        a = M.slide(law, 1.0, 40.0, dt=1e-3)
        b = M.slide(L.from_gauge(gl), 1.0, 40.0, dt=1e-3)
        np.testing.assert_array_equal(a.q, b.q)
        c = L.from_gauge(path, "collinear")
        assert abs(M.deflection_deg(40.0, M.slide(c, 1.0, 40.0, dt=1e-3).q_final)) < 1e-9
    with pytest.raises(InputError, match="kind must be one of ellipse, collinear, got 'star'"):
        L.from_gauge(path, "star")
