"""Friction sets and the Walker-Leine law: closed forms and invariants."""
import math
from pathlib import Path

import numpy as np
import pytest
from reservoirs import grid, reservoir

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.laws.convex_set import ConvexSet
from asperity.laws.fitting import fit_derivation, fit_star, prepare_reservoir
from asperity.laws.geometry import angle_between, unit
from asperity.laws.sets import StarSet, TruncatedEllipse
from asperity.laws.walker_leine import associated, coulomb
from asperity.texture.wedges import load_texture

SURF = Path(__file__).resolve().parents[1] / "surfaces"
RNG = np.random.default_rng(1234)


# ----------------------------------------------------------------------------- closed forms

def test_coulomb_is_collinear_with_radius_mu():
    psi = RNG.uniform(-10, 10, 500)
    f = coulomb(0.3).force(psi)
    np.testing.assert_allclose(f.p, 0.3 * unit(psi), rtol=0, atol=1e-15,
                               err_msg="Coulomb: p = mu s")
    np.testing.assert_allclose(f.alpha, 1.0, rtol=0, atol=1e-15)
    np.testing.assert_allclose(f.lateral, 0.0, atol=1e-15)
    assert not f.set_valued.any()


def test_truncated_ellipse_axes_radial_and_gauge():
    e = TruncatedEllipse(0.2, 0.08, 0.12, 0.15)
    f = associated(e).force(np.array([0, np.pi, np.pi / 2, 3 * np.pi / 2]))
    np.testing.assert_allclose(f.p, [[0.2, 0], [-0.08, 0], [0, 0.12], [0, -0.15]], atol=1e-15,
                               err_msg="sliding along an axis gives that axis' coefficient")
    # radial function of a quarter ellipse at 30 deg (quadrant +a, -b)
    A, B = 0.2, 0.15
    phi = -math.radians(30)
    rho = 1 / math.sqrt((math.cos(phi) / A) ** 2 + (math.sin(phi) / B) ** 2)
    assert e.radial(phi)[0] == pytest.approx(rho, rel=1e-14)
    x = RNG.normal(size=(200, 2))
    t = RNG.uniform(0.1, 5, 200)
    np.testing.assert_allclose(e.gauge(t[:, None] * x), t * e.gauge(x), rtol=1e-13,
                               err_msg="gauge is positively homogeneous")
    assert e.criterion([[0.2, 0]], 1.0)[0] == pytest.approx(0.0, abs=1e-15)


def test_truncated_ellipse_criterion_scales_with_the_normal_stress():
    """Antoni et al. eq. 18, g = k(tau) - sigma_n, at stresses in Pa (sigma_n != 1): zero on
    sigma_n times the boundary in each quadrant, -sigma_n/2 at half of it, > 0 outside;
    one sigma_n per row too."""
    e = TruncatedEllipse(0.2, 0.08, 0.12, 0.15, theta=0.3)
    phi = np.radians([20.0, 110.0, 200.0, 290.0, 0.0, 90.0])      # all four quarter ellipses
    edge = e.radial(phi)[:, None] * unit(phi)                       # k(edge) = 1
    for sn in (2.5e6, 40.0, 0.3):
        np.testing.assert_allclose(e.criterion(sn * edge, sn), 0.0, rtol=0, atol=4e-16 * sn,
                                   err_msg="g = 0 on sigma_n C")
        np.testing.assert_allclose(e.criterion(0.5 * sn * edge, sn), -0.5 * sn, rtol=4e-15)
        np.testing.assert_allclose(e.criterion(1.5 * sn * edge, sn), 0.5 * sn, rtol=4e-15)
    sn = np.array([1e5, 2e5, 3e5, 4e5, 5e5, 6e5])
    np.testing.assert_allclose(e.criterion(0.25 * sn[:, None] * edge, sn), -0.75 * sn,
                               rtol=4e-15)
    # by hand, Antoni's figure 7 values on the axes of the unrotated ellipse
    f = TruncatedEllipse(0.2, 0.08, 0.12, 0.15)
    np.testing.assert_allclose(f.criterion([[0.1e6, 0], [-0.1e6, 0], [0, 0.1e6], [0, -0.1e6]],
                                           1e6), [-0.5e6, 0.25e6, -1e6 / 6, -1e6 / 3], rtol=1e-14)


def test_associated_ellipse_force_is_normal_to_the_boundary():
    for theta in (0.0, 0.4):
        e = TruncatedEllipse(0.2, 0.08, 0.12, 0.15, theta=theta)
        psi = RNG.uniform(0, 2 * np.pi, 2000)
        f = associated(e).force(psi)
        np.testing.assert_allclose(e.gauge(f.p), 1.0, rtol=1e-13, err_msg="force on the boundary")
        # outward normal of the boundary at p: gradient of the gauge, by central differences
        h = 1e-7
        grad = np.column_stack([(e.gauge(f.p + [h, 0]) - e.gauge(f.p - [h, 0])) / (2 * h),
                                (e.gauge(f.p + [0, h]) - e.gauge(f.p - [0, h])) / (2 * h)])
        ang = angle_between(grad, unit(psi))
        # central differences of step 1e-7: the angle is 2e-8 deg (measured)
        assert np.degrees(ang.max()) < 1e-7, "associated law: s is the normal at p"
        np.testing.assert_allclose(f.alpha, 1.0, rtol=0, atol=1e-15)     # C is D: exactly 1
        np.testing.assert_allclose(e.support(psi), np.einsum("ij,ij->i", f.p, unit(psi)),
                                   rtol=4e-15, err_msg="h(s) = p . s on the boundary")


def test_truncated_ellipse_is_convex_and_C1():
    e = TruncatedEllipse(0.2, 0.08, 0.12, 0.15)
    phi = np.linspace(0, 2 * np.pi, 4000, endpoint=False)
    poly = StarSet(e.radial(phi)[:, None] * unit(phi))
    assert poly.is_convex()
    # C1: the force (normal rule) is continuous across the axes
    for ax in (0, np.pi / 2, np.pi, 1.5 * np.pi):
        f = associated(e).force(np.array([ax - 1e-9, ax + 1e-9]))
        assert np.hypot(*(f.p[0] - f.p[1])) < 1e-9         # |dp/dpsi| 2e-9 (measured 5e-10)


def test_star_set_radial_gauge_and_convexity():
    diamond = StarSet([[1, 0], [0, 1], [-1, 0], [0, -1]])
    assert diamond.radial(np.pi / 4)[0] == pytest.approx(math.sqrt(0.5), rel=1e-15)
    assert diamond.gauge([[0.25, 0.25]])[0] == pytest.approx(0.5, rel=1e-15)
    assert diamond.gauge([[0.0, 0.0]])[0] == 0.0
    assert diamond.is_convex()
    phi = np.linspace(0, 2 * np.pi, 10, endpoint=False)
    star = StarSet((1 + 0.5 * (np.arange(10) % 2))[:, None] * unit(phi))
    assert not star.is_convex()
    assert np.degrees(star.turning_angles().min()) < -10
    with pytest.raises(InputError, match="increasing polar angle"):
        StarSet([[1, 0], [-1, 0.1], [0, 1], [0, -1]])
    with pytest.raises(InputError, match="finite"):
        StarSet([[1, 0], [0, np.nan], [-1, 0]])


# ----------------------------------------------------------------------------- D and the law

def test_convex_set_of_a_disc_and_consistency_check():
    psi = grid(36)
    D = ConvexSet(psi, np.full(36, 0.5), np.zeros(36))
    y, ym, yp = D.normal_point(psi + 0.05)
    np.testing.assert_allclose(y, 0.5 * unit(psi + 0.05), atol=1e-15)
    assert D.is_convex() and D.min_turn_rate() == pytest.approx(1.0)
    np.testing.assert_allclose(D.gauge(0.25 * unit(psi)), 0.5, rtol=1e-15)   # measured 2e-16
    with pytest.raises(InputError, match="not a consistent support function"):
        ConvexSet(psi, 0.5 + 0.01 * np.arange(36), np.zeros(36))


def test_fit_star_of_associated_data_gives_D_equal_C():
    e = TruncatedEllipse(0.3, 0.2, 0.15, 0.25)
    psi = grid(720)
    law, rep = fit_star(prepare_reservoir(reservoir(psi, associated(e).force(psi).p)))
    q = RNG.uniform(0, 2 * np.pi, 400)
    f, ref = law.force(q), associated(e).force(q)
    rel = np.hypot(*(f.p - ref.p).T) / np.hypot(*ref.p.T)
    assert rel.max() < 3e-4          # 1.2e-4 reached, where the flat ellipse turns fastest
    np.testing.assert_allclose(f.alpha, 1.0, atol=1e-4,               # 5.0e-5 reached
                               err_msg="associated data: D = C, alpha = 1 while sliding")
    assert rep.C_convex and rep.D_convex
    # ln h closes in the continuum; the linear-delta model leaves a discretisation residue
    # (1.2e-5, closed by turning the forces 1.0e-4 deg)
    assert abs(rep.closure_residual) < 3e-5 and rep.closure_max_angle_deg < 3e-4


def test_closure_residual_of_a_turned_sliding_rule():
    """Forces of an associated ellipse all turned by 3 deg: ln h does not close; the fit
    closes it by turning them back by 3 deg and says so."""
    e = TruncatedEllipse(0.3, 0.3, 0.15, 0.15)
    psi = grid(720)
    y = associated(e).force(psi).p
    c, s = math.cos(math.radians(3)), math.sin(math.radians(3))
    p = y @ np.array([[c, s], [-s, c]])
    law, rep = fit_star(prepare_reservoir(reservoir(psi, p)))
    assert abs(rep.closure_residual) > 0.05
    assert rep.closure_max_angle_deg == pytest.approx(3.0, abs=1e-12)   # 9e-16 reached
    f = law.force(psi[::7])
    assert np.degrees(angle_between(f.p, y[::7])).max() < 1e-12         # 5e-14 reached


def test_not_star_shaped_data_is_rejected():
    psi = grid(360)
    delta = 0.8 * np.sin(3 * psi)          # polar angle psi + delta goes back where 2.4 cos 3psi < -1
    p = 0.3 * unit(psi + delta)
    with pytest.raises(InputError, match="not star-shaped"):
        fit_star(prepare_reservoir(reservoir(psi, p)))


def test_inadmissible_and_self_locking_data_are_rejected():
    psi = grid(72)
    with pytest.raises(InputError, match="not admissible"):
        prepare_reservoir(reservoir(psi, 0.3 * unit(psi + 2.0)))
    d = derive(load_texture(SURF / "self-locking.toml"), "all-faces", "closed-form", 72)
    with pytest.raises(InputError, match="self-locks"):
        fit_derivation(d, "star")
