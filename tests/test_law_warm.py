"""The warm-started law kernels of the Moreau solver (issue 20, speed of the star law)
agree with the plain ones: the projection onto a support set D started from the last one
(searches skipped, Taylor series near a kept point), the star polygon's radial function
from the last edge, the law's point and alpha with the kept radial functions, and a whole
point-mass slide against a reference stepping written here with the plain kernels.

Tolerances: a warm projection is the same point as the plain search's to 1e-13 of |y| (both
are iterations converged to rounding; the Taylor series' errors are ~1e-16); a slide's
states agree to 1e-9 m, m/s (each step's fixed point is converged to 1e-12 of the normal
impulse by both) and the stop step exactly.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.dynamics import moreau as M
from asperity.laws import planar as L
from asperity.laws._law_kernels import (
    WARM_P1,
    law_alpha,
    law_alpha_warm,
    law_point,
    law_point_warm,
    new_warm,
)
from asperity.laws._set_kernels import SET_STAR, SET_SUPPORT, star_radial, support_project
from asperity.laws._warm_kernels import PW_H, PW_K, star_radial_dir, support_project_warm


def gauge_star_law():
    """The star law of a gauge file fitted to a windward wedge texture (30/10 deg)."""
    from asperity.friction.derive import derive
    from asperity.laws.fitting import fit_derivation
    from asperity.texture.wedges import WedgeTexture
    d = derive(WedgeTexture(30, 10, 0.1, 0.2), "windward", "closed-form", 180)
    return L.from_gauge(fit_derivation(d, "star", holdout=False))


LAWS = {"star 0.6/0.3": lambda: L.star_law(0.6, 0.3),
        "star 0.2/0.5, 90 directions": lambda: L.star_law(0.2, 0.5, directions=90),
        "windward star": L.windward_star_law,
        "gauge-file star": gauge_star_law}


@pytest.fixture(scope="module", params=list(LAWS))
def law(request):
    return LAWS[request.param]()


def _paths(rng, rho_max, n=3000):
    """Prox arguments as a solver makes them: slow turns (1e-7 to 1e-3 rad a call) with
    slowly changing length, jumps to anywhere, points inside and far outside."""
    phi = rng.uniform(0, 2 * math.pi)
    r = 1.5 * rho_max
    out = []
    for _ in range(n):
        u = rng.uniform()
        if u < 0.03:
            phi = rng.uniform(-10, 10)
            r = rho_max * rng.uniform(0.05, 4.0)
        else:
            phi += rng.choice([1e-7, 1e-5, 3e-5, 1e-4, 1e-3]) * rng.choice([-1, 1])
            r *= 1.0 + 1e-4 * rng.standard_normal()
        out.append((r * math.cos(phi), r * math.sin(phi)))
    return np.array(out)


def test_warm_projection_is_the_plain_projection(law):
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    assert dk == SET_SUPPORT and ck == SET_STAR
    rng = np.random.default_rng(1)
    wk = new_warm(1)[0]
    n = dt.shape[0]
    rho = float(np.max(dt[:, 3]))
    worst, outside, skipped = 0.0, 0, 0
    for x0, x1 in _paths(rng, rho):
        y0, y1, ins = support_project(dt, 0, n, x0, x1)
        k_before = wk[PW_K]
        w0, w1, wins, rr, ux, uy = support_project_warm(dt, 0, n, x0, x1, wk)
        assert wins == ins
        scale = math.hypot(y0, y1)
        worst = max(worst, math.hypot(w0 - y0, w1 - y1) / scale)
        assert rr == pytest.approx(scale, rel=1e-12) if not ins else True
        assert math.hypot(ux, uy) == pytest.approx(1.0, abs=1e-15)
        outside += not ins
        skipped += (not ins) and k_before == wk[PW_K] and wk[PW_H] > 0.0   # warm path
    assert worst < 1e-13, worst
    assert outside > 2000 and skipped > 1000      # both paths were exercised


def test_star_radial_from_the_last_edge(law):
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    rng = np.random.default_rng(2)
    n = ct.shape[0]
    k = -1
    for phi in np.concatenate([rng.uniform(-7, 7, 500), np.cumsum(rng.normal(0, 0.01, 500)),
                               ct[:, 2], ct[:, 2] + 1e-15]):
        rho, k = star_radial_dir(ct, 0, n, math.cos(phi), math.sin(phi), k)
        assert rho == pytest.approx(star_radial(ct, 0, n, phi), rel=1e-12)
        assert 0 <= k < n
    for phi in rng.uniform(-7, 7, 200):                # from a far edge: the search
        rho, _ = star_radial_dir(ct, 0, n, math.cos(phi), math.sin(phi), int(rng.integers(n)))
        assert rho == pytest.approx(star_radial(ct, 0, n, phi), rel=1e-12)


def test_warm_law_point_and_alpha_are_the_plain_ones(law):
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    nc, nd = ct.shape[0], dt.shape[0]
    rng = np.random.default_rng(3)
    wk = new_warm(1)[0]
    rho = float(np.max(dt[:, 3]))
    for x0, x1 in _paths(rng, rho, 1500):
        a, b, ins = law_point(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, x0, x1)
        wa, wb, wins = law_point_warm(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, x0, x1, wk)
        assert wins == ins
        assert math.hypot(wa - a, wb - b) <= 1e-13 * math.hypot(a, b)
        al = law_alpha(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, wa, wb)
        wal = law_alpha_warm(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, wa, wb, wk)
        assert wal == pytest.approx(al, rel=1e-12)


def reference_slide(law, u0, dt, n_steps, tol=1e-12, max_iter=2000):
    """The point mass stepped with the plain kernels (no warm start, no extrapolated alpha):
    midpoint Moreau, r = m = 1, the fixed-point iteration of moreau.py written out."""
    assoc, ck, cp, ct, dk, dp, dtab = law.kernel_sets
    nc, nd = ct.shape[0], dtab.shape[0]
    ln = 9.81 * dt
    q = np.zeros(2)
    u = np.array(u0, float)
    P = np.zeros(2)
    qs, us, stop = [q.copy()], [u.copy()], None
    for step in range(n_steps):
        qm = q + 0.5 * dt * u
        ins = False
        for _ in range(max_iter):
            p = P / ln
            al = law_alpha(assoc, ck, cp, ct, 0, nc, dk, dp, dtab, 0, nd, p[0], p[1])
            z = al * (p + (u - P) / ln)
            a, b, ins = law_point(assoc, ck, cp, ct, 0, nc, dk, dp, dtab, 0, nd, z[0], z[1])
            res = math.hypot(a - p[0], b - p[1])
            P = np.array([a, b]) * ln
            if res <= tol:
                break
        ue = np.zeros(2) if ins else u - P
        q = qm + 0.5 * dt * ue
        if not ue.any() and u.any():
            stop = step + 1
        u = ue
        qs.append(q.copy())
        us.append(u.copy())
    return np.array(qs), np.array(us), stop


@pytest.mark.parametrize("angle,dt", [(40.0, 1e-3), (100.0, 1e-4), (-75.0, 3e-4)])
def test_slide_agrees_with_the_plain_kernels(law, angle, dt):
    u0 = 1.5 * np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    t_end = 1.5 * 1.5 / (9.81 * law.min_tangential())
    n = int(round(t_end / dt))
    if n > 4000:
        n = 4000
    r = M.simulate(M.point_mass(law), u0, dt=dt, t_end=n * dt)
    qs, us, stop = reference_slide(law, u0, dt, n)
    assert r.ok
    np.testing.assert_allclose(r.q, qs, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.u, us, rtol=0, atol=1e-9)
    assert r.stop_step == stop


def test_alpha_near_the_last_point_is_the_plain_alpha(law):
    """law_alpha_near (D's radial function by Newton from the last projection's root, the
    star polygon's from the last edge) at points turned and stretched a little from the last
    law point, and far away (the searches), against law_alpha."""
    from asperity.laws._law_kernels import law_alpha_near
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    nc, nd = ct.shape[0], dt.shape[0]
    rng = np.random.default_rng(4)
    wk = new_warm(1)[0]
    rho = float(np.max(dt[:, 3]))
    worst = 0.0
    for x0, x1 in _paths(rng, rho, 1500):
        a, b, ins = law_point_warm(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, x0, x1, wk)
        wk[WARM_P1], wk[WARM_P1 + 1] = a, b      # the solver keeps its last force
        turn = rng.choice([1e-7, 1e-5, 1e-4, 1e-2, 1.0]) * rng.choice([-1, 1])
        c, s = math.cos(turn), math.sin(turn)
        f = 1.0 + 1e-3 * rng.standard_normal()
        q0, q1 = f * (c * a - s * b), f * (s * a + c * b)
        kept = wk.copy()
        got = law_alpha_near(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, q0, q1, wk)
        want = law_alpha(assoc, ck, cp, ct, 0, nc, dk, dp, dt, 0, nd, q0, q1)
        worst = max(worst, abs(got - want) / want)
        np.testing.assert_array_equal(wk, kept)          # the kept values are left alone
    assert worst < 1e-13, worst


def test_point_mass_converges_in_one_iteration_when_it_extrapolates():
    """With the force extrapolated from the last three steps, a steady slide needs one
    iteration a step (the residual of the first is already below tol) and gives the same
    path as the plain stepping (test above); a slide to rest restarts the history."""
    law = L.star_law(0.6, 0.3)
    u0 = 10 * np.array([math.cos(0.5), math.sin(0.5)])
    r = M.simulate(M.point_mass(law), u0, dt=1e-4, t_end=0.5, record_every=5000)
    assert r.ok and r.max_iterations_used <= 3 and r.mean_iterations < 1.01
