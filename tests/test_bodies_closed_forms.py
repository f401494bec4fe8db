"""Closed forms of a sliding and spinning disc and ring (SPEC.md 8), the spin drift on a
direction-dependent law, and the reference ODE to rest (asperity.bodies.closed_forms).

The closed forms are checked against our own quadrature of their definition (the
velocity field of the body, point by point), not against themselves."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from asperity.bodies import closed_forms as cf
from asperity.errors import InputError
from asperity.laws.planar import coulomb_law, ellipse_law, truncated_ellipse_law

EPS = [0.0, 1e-3, 0.1, 0.3, 0.5, 0.653, 0.9, 0.99, 1.0, 1.01, 1.5, 2.0, 3.0, 10.0, 100.0]


def ring_by_quadrature(eps: float, rho: float = 1.0):
    """(f, m) of a ring of radius rho (R = 1) sliding at v = eps along x and spinning at
    omega = 1: the mean unit velocity of its points along x, and their mean moment."""
    def unit(p):
        ux, uy = eps - rho * math.sin(p), rho * math.cos(p)
        n = math.hypot(ux, uy)
        return (ux / n, uy / n) if n > 0 else (0.0, 0.0)

    def fx(p):
        return unit(p)[0]

    def mz(p):
        ux, uy = unit(p)
        return rho * math.cos(p) * uy - rho * math.sin(p) * ux
    kw = dict(points=[math.pi / 2], epsabs=1e-14, epsrel=1e-12, limit=400)
    with warnings.catch_warnings():        # quad's "roundoff" notes where the value is ~0
        warnings.simplefilter("ignore")
        f = quad(fx, -math.pi / 2, 1.5 * math.pi, **kw)[0] / (2 * math.pi)
        m = quad(mz, -math.pi / 2, 1.5 * math.pi, **kw)[0] / (2 * math.pi)
    return f, m


def disc_by_quadrature(eps: float):
    """(f, m) of the uniformly loaded unit disc: the rings' integrals over the radius
    (load 2 rho drho), split at the instantaneous centre rho = eps."""
    pts = [eps] if 0 < eps < 1 else None
    kw = dict(points=pts, epsabs=1e-13, epsrel=1e-12, limit=200)
    with warnings.catch_warnings():        # quad's "roundoff" notes at 1e-14 on tiny parts
        warnings.simplefilter("ignore")
        f = quad(lambda r: 2 * r * ring_by_quadrature(eps, r)[0], 0, 1, **kw)[0]
        m = quad(lambda r: 2 * r * ring_by_quadrature(eps, r)[1], 0, 1, **kw)[0]
    return f, m


@pytest.mark.parametrize("eps", EPS)
def test_disc_closed_forms_match_quadrature(eps):
    f, m = cf.disc_f_m(eps)
    fq, mq = disc_by_quadrature(eps)
    assert abs(f - fq) < 1e-10 and abs(m - mq) < 1e-10, (eps, f - fq, m - mq)


@pytest.mark.parametrize("eps", EPS)
def test_ring_closed_forms_match_quadrature(eps):
    f, m = cf.ring_f_m(eps)
    fq, mq = ring_by_quadrature(eps)
    assert abs(f - fq) < 1e-10 and abs(m - mq) < 1e-10, (eps, f - fq, m - mq)


def test_special_values_and_limits():
    f, m = cf.disc_f_m(np.array([0.0, 1.0, np.inf]))
    assert f[0] == 0.0 and m[0] == pytest.approx(2 / 3, abs=1e-15)
    assert f[1] == pytest.approx(8 / (3 * math.pi), rel=1e-14)
    assert m[1] == pytest.approx(8 / (9 * math.pi), rel=1e-14)
    assert f[2] == pytest.approx(1.0, rel=1e-15) and m[2] == 0.0
    f, m = cf.ring_f_m(np.array([0.0, 1.0, np.inf]))
    assert f[0] == 0.0 and m[0] == pytest.approx(1.0, abs=1e-15)
    assert f[1] == pytest.approx(2 / math.pi, rel=1e-14) == m[1]
    assert f[2] == pytest.approx(1.0, rel=1e-15) and m[2] == 0.0


def test_asymptotes_without_cancellation():
    """Slow slide and slow spin: the leading terms, to near rounding (the series branch)."""
    e = np.array([1e-9, 1e-6, 1e-4])
    f, m = cf.disc_f_m(e)
    np.testing.assert_allclose(f, e - e**3 / 8, rtol=1e-13)     # f = eps - eps^3/8 + ...
    f, m = cf.disc_f_m(1 / e)
    np.testing.assert_allclose(m, e / 4, rtol=1e-7)              # m ~ 1/(4 eps)
    f, m = cf.ring_f_m(e)
    np.testing.assert_allclose(f, e / 2, rtol=1e-7)              # f ~ eps/2
    f, m = cf.ring_f_m(1 / e)
    np.testing.assert_allclose(m, e / 2, rtol=1e-7)              # m ~ 1/(2 eps)


def test_branches_join_and_ring_symmetry():
    """Continuous across eps = 1 and across the series threshold (eps = 1/2 and 2; the
    ring's f has an (eps - 1) log|eps - 1| term at 1: 3e-11 over 1e-12); the ring's
    f(eps) = m(1/eps)."""
    for x in (0.5, 1.0, 2.0):
        e = np.array([x * (1 - 1e-12), x, x * (1 + 1e-12)])
        for fn in (cf.disc_f_m, cf.ring_f_m):
            f, m = fn(e)
            assert np.ptp(f) < 1e-10 and np.ptp(m) < 1e-10, (fn.__name__, x, f, m)
    e = np.geomspace(1e-3, 1e3, 61)
    f, _ = cf.ring_f_m(e)
    _, m = cf.ring_f_m(1 / e)
    np.testing.assert_allclose(f, m, rtol=1e-13)


def test_vectorised_like_scalar():
    e = np.array([[0.0, 0.2], [1.0, 7.0]])
    f, m = cf.disc_f_m(e)
    assert f.shape == m.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            assert (f[i, j], m[i, j]) == cf.disc_f_m(float(e[i, j]))
    assert isinstance(cf.disc_f_m(0.3)[0], float)


@pytest.mark.parametrize("bad", [-1e-3, math.nan, "x", None, [0.1, -2.0]])
def test_bad_eps_refused(bad):
    with pytest.raises(InputError, match="eps"):
        cf.disc_f_m(bad)


def test_fixed_points():
    """f(eps0) = eps0 m(eps0)/k_I: 0.653002 for the disc (SPEC.md 8), 1 for the ring;
    attracting (d eps/d lambda = eps - k_I f/m changes sign from + to - across it as the
    spin decays, lambda = -ln omega)."""
    e0 = cf.terminal_ratio("disc")
    assert e0 == pytest.approx(0.653002, abs=5e-7)
    assert cf.terminal_ratio("ring") == pytest.approx(1.0, abs=1e-12)
    for kind, fixed in (("disc", e0), ("ring", 1.0)):
        k = cf.INERTIA_FACTOR[kind]
        e = np.array([0.5 * fixed, 2 * fixed])
        f, m = cf.footprint_f_m(kind, e)
        d_eps = e - k * f / m                      # d eps / d lambda, lambda = ln(omega0/omega)
        assert d_eps[0] > 0 > d_eps[1], (kind, d_eps)   # towards the fixed point from both sides


def direct_stop(v0, omega0, mu, g, R, kind):
    """The ODE in time, stopped by events: stop time and distance (independent path)."""
    k = cf.INERTIA_FACTOR[kind]
    a = mu * g

    def rhs(_t, y):
        v, w = max(y[0], 0.0), max(y[1], 0.0)
        f, m = cf.footprint_f_m(kind, v / w if w > 0 else math.inf)
        return [-a * f, -a * m / k, v]

    def end(_t, y):
        return min(y[0], y[1])
    end.terminal, end.direction = True, -1
    sol = solve_ivp(rhs, (0, 100.0), [v0, R * omega0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-15, events=end)
    return sol.t[-1], sol.y[2, -1]


@pytest.mark.parametrize("kind", ["disc", "ring"])
@pytest.mark.parametrize("omega0", [2.0, 40.0, 2000.0])
def test_reference_terminal_ratio_and_together(kind, omega0):
    """From a slow spin (eps = 10) and fast ones (eps = 0.5, 0.01), v/(R omega) tends to
    eps0 (0.653002 disc, 1 ring), and slide and spin stop together at the time the direct
    integration in t finds."""
    R, v0, mu, g = 0.05, 1.0, 0.3, 9.81
    ref = cf.disc_reference(v0, omega0, mu, g, R, kind)
    assert ref.together and ref.slide_stop_time == ref.spin_stop_time == ref.stop_time
    assert ref.terminal_ratio == pytest.approx(cf.TERMINAL_RATIO[kind], abs=2e-6)
    t, s = direct_stop(v0, omega0, mu, g, R, kind)
    assert ref.stop_time == pytest.approx(t, rel=1e-6)
    assert ref.distance == pytest.approx(s, rel=1e-6)
    # the spin carries the disc further than a pure slide, and makes it last longer
    assert ref.distance > v0 * v0 / (2 * mu * g) and ref.stop_time > v0 / (mu * g)
    assert np.all(np.diff(ref.t) >= 0) and np.all(np.diff(ref.v) <= 1e-15)


@pytest.mark.parametrize("kind,k,m0", [("disc", 0.5, 2 / 3), ("ring", 1.0, 1.0)])
def test_reference_pure_slide_and_pure_spin(kind, k, m0):
    mu, g, R = 0.4, 9.81, 0.02
    ref = cf.disc_reference(2.0, 0.0, mu, g, R, kind)            # the point mass
    assert ref.stop_time == pytest.approx(2.0 / (mu * g), rel=1e-14)
    assert ref.distance == pytest.approx(4.0 / (2 * mu * g), rel=1e-14)
    assert ref.turned == 0.0 and ref.terminal_ratio is None
    ref = cf.disc_reference(0.0, 30.0, mu, g, R, kind)           # I domega/dt = -mu m g R m0
    assert ref.stop_time == pytest.approx(k * R * 30.0 / (mu * g * m0), rel=1e-14)
    assert ref.turned == pytest.approx(30.0 * ref.stop_time / 2, rel=1e-14)
    assert ref.distance == 0.0


@pytest.mark.parametrize("field,value", [("v0", -1.0), ("omega0", math.nan), ("mu", 0.0),
                                         ("R", 0.0), ("g", math.inf), ("kind", "square")])
def test_reference_refuses_bad_input(field, value):
    args = dict(v0=1.0, omega0=1.0, mu=0.3, g=9.81, R=0.05, kind="disc")
    args[field] = value
    with pytest.raises(InputError, match=field):
        cf.disc_reference(**args)


# ----------------------------------------------------------------------------- spin drift

def half_ellipse_integral(A: float, B: float) -> float:
    """int over the half circle of directions of the force's component along the half's
    axis, for the associated ellipse of semi-axes A (along it) and B: with u = sin psi,
    int_-1^1 A^2 / sqrt(A^2 + (B^2 - A^2) u^2) du."""
    if B > A:
        c = math.sqrt(B * B - A * A)
        return 2 * A * A / c * math.asinh(c / A)
    if B < A:
        c = math.sqrt(A * A - B * B)
        return 2 * A * A / c * math.asin(c / A)
    return 2 * A


def test_spin_drift_zero_for_symmetric_laws():
    for law in (coulomb_law(0.3), ellipse_law(0.4, 0.15)):
        assert np.all(np.abs(cf.spin_drift_force(law)) < 1e-14)


@pytest.mark.parametrize("ap,am,b", [(0.3, 0.1, 0.2), (0.1, 0.35, 0.2), (0.2, 0.2, 0.2)])
def test_spin_drift_of_truncated_ellipse(ap, am, b):
    """-1/(2 pi) int p dpsi of a truncated ellipse with mu_b+ = mu_b- = b: along t_a,
    -(I(mu_a+) - I(mu_a-)) / (2 pi) (towards the side of the smaller coefficient), none
    along t_b."""
    law = truncated_ellipse_law(ap, am, b, b)
    d = cf.spin_drift_force(law, n=20000)
    want = -(half_ellipse_integral(ap, b) - half_ellipse_integral(am, b)) / (2 * math.pi)
    assert d[0] == pytest.approx(want, abs=1e-7)
    assert abs(d[1]) < 1e-12
    if ap != am:
        assert abs(d[0]) > 0.01 and np.sign(d[0]) == np.sign(am - ap)
