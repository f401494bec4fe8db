"""Closed form against SPEC.md check values and invariants."""
import math

import numpy as np
import pytest

from reservoirs import reservoir

from asperity.errors import InputError
from asperity.friction.diagnostics import (
    ADMISSIBILITY_TOL,
    check_admissibility,
    check_associativity,
    closed_form_dT_dpsi,
)
from asperity.friction.faces import compute_axis_coefficients, compute_reservoir
from asperity.friction.reservoir import Reservoir, directions
from asperity.texture.closed_form import compute_H, compute_wedge_axis_closed_form
from asperity.texture.wedges import GaussianWedgeTexture, WedgeTexture


#: SPEC.md gives its check values to 6 decimals: they hold to half a unit of the last one
SPEC_ROUNDING = 5e-7


def spec_axes(a_deg, b_deg, ma, mb):
    """SPEC.md section 2 written out by hand: mu_a+, mu_a-, mu_b."""
    a, b = math.radians(a_deg), math.radians(b_deg)
    ta, tb = math.tan(a), math.tan(b)

    def H(x, y):
        return (x + math.tan(y)) / (1 - x * math.tan(y))
    return ((H(ma, a) * tb + H(mb, -b) * ta) / (ta + tb),
            (H(mb, b) * ta + H(ma, -a) * tb) / (ta + tb),
            (ma * tb / math.cos(a) + mb * ta / math.cos(b)) / (ta + tb))


def test_spec_check_values_asymmetric_wedge():
    ax = compute_axis_coefficients(WedgeTexture(30, 10, 0.1, 0.2))
    assert ax["mu_a_plus"] == pytest.approx(0.185697, abs=SPEC_ROUNDING)
    assert ax["mu_a_minus"] == pytest.approx(0.193238, abs=SPEC_ROUNDING)
    assert ax["mu_b_plus"] == pytest.approx(0.182587, abs=SPEC_ROUNDING)
    assert ax["mu_b_minus"] == pytest.approx(0.182587, abs=SPEC_ROUNDING)


def test_spec_check_values_shallow_wedge():
    ax = compute_axis_coefficients(WedgeTexture(5, 5, 0.1, 0.1))
    assert ax["mu_a_plus"] == pytest.approx(0.100773, abs=SPEC_ROUNDING)
    assert ax["mu_a_minus"] == pytest.approx(0.100773, abs=SPEC_ROUNDING)


@pytest.mark.parametrize("a,b,ma,mb", [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (60, 15, 0.3, 0.1),
                                       (20, 40, 0.15, 0.25)])
def test_axis_coefficients_are_the_spec_formulas(a, b, ma, mb):
    """The facet homogenisation on the axes against SPEC.md's formulas typed in by hand
    (not the library's H): agreement to rounding (measured 2e-16)."""
    ax = compute_axis_coefficients(WedgeTexture(a, b, ma, mb))
    plus, minus, mu_b = spec_axes(a, b, ma, mb)
    got = [ax["mu_a_plus"], ax["mu_a_minus"], ax["mu_b_plus"], ax["mu_b_minus"]]
    np.testing.assert_allclose(got, [plus, minus, mu_b, mu_b], rtol=1e-14, atol=0)


@pytest.mark.parametrize("a,b,ma,mb", [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (60, 15, 0.3, 0.1),
                                       (45, 20, 0.0, 0.5)])
def test_oblique_formula_reduces_to_H_formulas_on_axes(a, b, ma, mb):
    t = WedgeTexture(a, b, ma, mb)
    ref = compute_wedge_axis_closed_form(t.alpha, t.beta, ma, mb)
    got = compute_axis_coefficients(t)
    for k in ref:
        assert got[k] == pytest.approx(ref[k], rel=1e-14), k      # measured 4e-16


def test_H_self_locking_is_inf_not_nan():
    assert compute_H(0.3, math.radians(80)) == math.inf
    assert compute_H(0.1, 0.0) == 0.1
    assert compute_H(0.2, math.radians(30)) == pytest.approx(
        (0.2 + math.tan(math.radians(30))) / (1 - 0.2 * math.tan(math.radians(30))), rel=1e-15)


def one_face_point(gradient, mu, psi):
    """SPEC.md section 2 for one face, typed in: the tip velocity is s lifted onto the face,
    v = (s, g.s); the force on the tip is along m - mu v/|v| (m the upward unit normal);
    p = -(horizontal part) / (vertical part)."""
    g = np.array(gradient, float)
    s = np.array([math.cos(psi), math.sin(psi)])
    m = np.array([-g[0], -g[1], 1.0]) / math.sqrt(1 + g @ g)
    v = np.array([s[0], s[1], g @ s])
    F = m - mu * v / np.linalg.norm(v)
    return -F[:2] / F[2]


def test_windward_spec_values_and_jump():
    t = WedgeTexture(30, 30, 0.3, 0.3)
    r = compute_reservoir(t, np.radians([0.0, 89.0, 90.0, 91.0]), "windward")
    assert np.hypot(*r.p[0]) == pytest.approx(1.061, abs=5e-4)      # SPEC.md, 3 decimals
    np.testing.assert_allclose(r.p[1], [0.585, 0.348], atol=5e-4)
    np.testing.assert_allclose(r.p[3], [-0.585, 0.348], atol=5e-4)
    assert r.set_valued.tolist() == [False, False, True, False]
    # the same from the one face that is climbed, computed by hand (measured 1e-16)
    ta = math.tan(math.radians(30))
    np.testing.assert_allclose(r.p[0], [(0.3 + ta) / (1 - 0.3 * ta), 0.0], rtol=1e-14, atol=1e-15,
                               err_msg="psi = 0: the alpha face alone, H(mu, alpha)")
    np.testing.assert_allclose(r.p[1], one_face_point([ta, 0.0], 0.3, math.radians(89.0)),
                               rtol=1e-14, err_msg="psi = 89 deg: the alpha face alone")
    np.testing.assert_allclose(r.p[3], one_face_point([-ta, 0.0], 0.3, math.radians(91.0)),
                               rtol=1e-14, err_msg="psi = 91 deg: the beta face alone")


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
    np.testing.assert_allclose(p1, p2, rtol=1e-14)      # measured: equal bit for bit
    np.testing.assert_allclose(p1, p3, rtol=1e-14)


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


def test_inadmissible_reservoir_is_refused_at_its_worst_direction():
    """check_admissibility must say no where p.s < 0 (the force pushes the body along):
    T(psi) = 0.2 + 0.25 cos(psi - 57 deg) dips to -0.05 at 237 deg (on the 1-deg grid)."""
    psi = directions(360)
    T = 0.2 + 0.25 * np.cos(psi - math.radians(57))
    s = np.column_stack([np.cos(psi), np.sin(psi)])
    lateral = 0.03 * np.column_stack([-np.sin(psi), np.cos(psi)])
    a = check_admissibility(reservoir(psi, T[:, None] * s + lateral))
    assert not a.admissible
    assert a.min_dissipation == pytest.approx(-0.05, abs=1e-15)
    assert a.psi_min_deg == pytest.approx(237.0, abs=1e-12)
    # one bad direction among good ones is enough, and the flip side: all good passes
    p = 0.3 * s
    p[200] = -0.01 * s[200]
    a = check_admissibility(reservoir(psi, p))
    assert not a.admissible and a.psi_min_deg == pytest.approx(200.0, abs=1e-12)
    assert a.min_dissipation == pytest.approx(-0.01, rel=1e-14)
    assert check_admissibility(reservoir(psi, 0.3 * s)).admissible


def test_admissibility_tolerance_and_self_locking_directions():
    """-1e-13 is rounding (ADMISSIBILITY_TOL = 1e-12), -1e-11 is not; a self-locking
    direction dissipates without bound and passes, but does not hide a bad one."""
    assert ADMISSIBILITY_TOL == 1e-12
    psi = directions(8)
    s = np.column_stack([np.cos(psi), np.sin(psi)])
    for T3, ok in ((-1e-13, True), (-1e-11, False), (0.0, True)):
        p = 0.2 * s
        p[3] = T3 * s[3]
        assert check_admissibility(reservoir(psi, p)).admissible is ok, T3
    locked = np.zeros(8, bool)
    locked[[1, 2]] = True
    p = 0.2 * s
    p[locked] = np.inf

    def res(p):
        return Reservoir(psi=psi, p=p, locked=locked, locked_face=np.where(locked, 0, -1),
                         set_valued=np.zeros(8, bool), contact="all-faces")
    a = check_admissibility(res(p))
    assert a.admissible and a.min_dissipation == pytest.approx(0.2, rel=1e-15)
    p[5] = -0.1 * s[5]
    a = check_admissibility(res(p))
    assert not a.admissible and a.psi_min_deg == pytest.approx(225.0, abs=1e-12)


@pytest.mark.parametrize("kw,field", [
    (dict(alpha_deg=0, beta_deg=10, mu_alpha=0.1, mu_beta=0.1), "alpha_deg"),
    (dict(alpha_deg=10, beta_deg=90, mu_alpha=0.1, mu_beta=0.1), "beta_deg"),
    (dict(alpha_deg=10, beta_deg=10, mu_alpha=-0.1, mu_beta=0.1), "mu_alpha"),
    (dict(alpha_deg=10, beta_deg=10, mu_alpha=0.1, mu_beta=float("nan")), "mu_beta"),
])
def test_bad_texture_input(kw, field):
    with pytest.raises(InputError, match=field):
        WedgeTexture(**kw)
