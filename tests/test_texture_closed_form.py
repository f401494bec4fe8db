"""Closed form against SPEC.md check values and invariants."""
import math

import numpy as np
import pytest

from asperity.errors import InputError
from asperity.friction.diagnostics import (
    check_admissibility,
    check_associativity,
    closed_form_dT_dpsi,
)
from asperity.friction.faces import compute_axis_coefficients, compute_reservoir
from asperity.friction.reservoir import directions
from asperity.texture.closed_form import compute_H, compute_wedge_axis_closed_form
from asperity.texture.wedges import GaussianWedgeTexture, WedgeTexture


def test_spec_check_values_asymmetric_wedge():
    ax = compute_axis_coefficients(WedgeTexture(30, 10, 0.1, 0.2))
    assert ax["mu_a_plus"] == pytest.approx(0.185697, abs=1e-6)
    assert ax["mu_a_minus"] == pytest.approx(0.193238, abs=1e-6)
    assert ax["mu_b_plus"] == pytest.approx(0.182587, abs=1e-6)
    assert ax["mu_b_minus"] == pytest.approx(0.182587, abs=1e-6)


def test_spec_check_values_shallow_wedge():
    ax = compute_axis_coefficients(WedgeTexture(5, 5, 0.1, 0.1))
    assert ax["mu_a_plus"] == pytest.approx(0.100773, abs=1e-6)
    assert ax["mu_a_minus"] == pytest.approx(0.100773, abs=1e-6)


@pytest.mark.parametrize("a,b,ma,mb", [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (60, 15, 0.3, 0.1),
                                       (45, 20, 0.0, 0.5)])
def test_oblique_formula_reduces_to_H_formulas_on_axes(a, b, ma, mb):
    t = WedgeTexture(a, b, ma, mb)
    ref = compute_wedge_axis_closed_form(t.alpha, t.beta, ma, mb)
    got = compute_axis_coefficients(t)
    for k in ref:
        assert got[k] == pytest.approx(ref[k], rel=1e-12), k


def test_H_self_locking_is_inf_not_nan():
    assert compute_H(0.3, math.radians(80)) == math.inf
    assert compute_H(0.1, 0.0) == pytest.approx(0.1)


def test_windward_spec_values_and_jump():
    t = WedgeTexture(30, 30, 0.3, 0.3)
    r = compute_reservoir(t, np.radians([0.0, 89.0, 90.0, 91.0]), "windward")
    assert np.hypot(*r.p[0]) == pytest.approx(1.061, abs=5e-4)
    np.testing.assert_allclose(r.p[1], [0.585, 0.348], atol=5e-4)
    np.testing.assert_allclose(r.p[3], [-0.585, 0.348], atol=5e-4)
    assert r.set_valued.tolist() == [False, False, True, False]


def test_all_faces_non_associated_spec_figures():
    t = WedgeTexture(30, 30, 0.3, 0.3)
    psi = directions(3600)
    r = compute_reservoir(t, psi)
    dT, ok = closed_form_dT_dpsi(lambda q: compute_reservoir(t, q), psi)
    a = check_associativity(r, dT, ok)
    assert a.max_deviation == pytest.approx(0.012, abs=5e-4)
    assert a.max_lateral == pytest.approx(0.055, abs=6e-4)  # SPEC rounds 0.0545
    assert not a.associated


def test_flat_isotropic_faces_are_coulomb_and_associated():
    from asperity.friction.faces import compute_face_reservoir
    psi = directions(72)
    r = compute_face_reservoir([[0.0, 0.0]], [0.4], [1.0], psi)
    np.testing.assert_allclose(r.tangential, 0.4, rtol=1e-12)
    np.testing.assert_allclose(r.lateral, 0.0, atol=1e-12)
    dT, ok = closed_form_dT_dpsi(lambda q: compute_face_reservoir([[0.0, 0.0]], [0.4], [1.0], q), psi)
    assert check_associativity(r, dT, ok).associated


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_height_independence_and_gaussian_same_faces(contact):
    psi = directions(36)
    p1 = compute_reservoir(WedgeTexture(30, 10, 0.1, 0.2, height=1e-6), psi, contact).p
    p2 = compute_reservoir(WedgeTexture(30, 10, 0.1, 0.2, height=1e-3), psi, contact).p
    p3 = compute_reservoir(GaussianWedgeTexture(30, 10, 0.1, 0.2, 5e-6, 1e-6), psi, contact).p
    np.testing.assert_allclose(p1, p2, rtol=1e-12)
    np.testing.assert_allclose(p1, p3, rtol=1e-12)


def test_rotating_mirror_symmetry():
    # a symmetric wedge is mirror-symmetric about t_a: p_b(-psi) = -p_b(psi)
    t = WedgeTexture(25, 25, 0.2, 0.2)
    psi = np.radians(np.arange(1, 89, 7.0))
    r1, r2 = compute_reservoir(t, psi), compute_reservoir(t, -psi)
    np.testing.assert_allclose(r1.p[:, 0], r2.p[:, 0], rtol=1e-12)
    np.testing.assert_allclose(r1.p[:, 1], -r2.p[:, 1], rtol=1e-12)


def test_self_locking_flagged_with_face():
    r = compute_reservoir(WedgeTexture(80, 10, 0.3, 0.2), np.array([0.0, np.pi]))
    assert r.locked.tolist() == [True, False]
    assert r.locked_face[0] == 0
    assert not np.isnan(r.p).any()


@pytest.mark.parametrize("a,b,ma,mb", [(30, 10, 0.1, 0.2), (70, 5, 0.5, 0.0), (10, 60, 0.9, 0.05)])
@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_admissible(a, b, ma, mb, contact):
    r = compute_reservoir(WedgeTexture(a, b, ma, mb), directions(720), contact)
    assert check_admissibility(r).admissible


@pytest.mark.parametrize("kw,field", [
    (dict(alpha_deg=0, beta_deg=10, mu_alpha=0.1, mu_beta=0.1), "alpha_deg"),
    (dict(alpha_deg=10, beta_deg=90, mu_alpha=0.1, mu_beta=0.1), "beta_deg"),
    (dict(alpha_deg=10, beta_deg=10, mu_alpha=-0.1, mu_beta=0.1), "mu_alpha"),
    (dict(alpha_deg=10, beta_deg=10, mu_alpha=0.1, mu_beta=float("nan")), "mu_beta"),
])
def test_bad_texture_input(kw, field):
    with pytest.raises(InputError, match=field):
        WedgeTexture(**kw)
