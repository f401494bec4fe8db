"""The generated Abaqus/Standard FRIC, compiled with gfortran and called through ctypes as
Abaqus calls it, against ``asperity law --psi`` (``GaugeLaw.force``) and against itself:

* steady sliding along 360 local directions stays on TAU = PRESS R(th) p(phi - th) (texture
  on the main surface) or -PRESS R(th) p(phi + 180 - th) (secondary), for an asymmetric
  ellipse, a star law, the windward star law with set-valued directions and the
  componentwise law, at several angles PROPS(2);
* sliding from rest reaches that force (laws without flat edges);
* elastic stick, reversal (mu_a+ one way, mu_a- the other), NFDIR = 1;
* DDTDDG and DDTDDP against central differences of the routine itself;
* invariances: turning DGAM, TAU and PROPS(2) together turns the answer; scaling
  PRESS, PROPS(1) and TAU together scales it; the side flip equals a half turn.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from fe_builds import needs_gfortran
from fe_laws import fric_library, law, rot, steady_tau

from asperity.fe.fortran_harness import call_fric

pytestmark = needs_gfortran
K, P = 1e10, 2e6                      # elastic slip stiffness (Pa/m), pressure (Pa)
LAWS = ("ellipse", "star", "windward", "componentwise")


def fric(name, tau, dgam, props=(K, 0.0, 1.0), press=P, nfdir=2, statev=(0.0, 0.0, 0.0)):
    return call_fric(fric_library(name), lm=0, tau=np.atleast_1d(np.asarray(tau, float)),
                     statev=np.asarray(statev, float), dgam=np.atleast_1d(dgam), press=press,
                     props=np.asarray(props, float), nfdir=nfdir)


@pytest.mark.parametrize("name", LAWS)
@pytest.mark.parametrize("th_deg, side", [(0.0, 1), (30.0, 1), (-70.0, -1), (0.0, -1)])
def test_steady_sliding_keeps_the_laws_force_in_360_directions(name, th_deg, side):
    gl = law(name)
    th = math.radians(th_deg)
    worst = 0.0
    for phi in np.radians(np.arange(360.0) + 0.5):
        ref = steady_tau(gl, phi, th, side, P)
        u = np.array([math.cos(phi), math.sin(phi)])
        for dg in (1e-7, 1e-4):                       # 0.02 and 20 elastic slips
            out = fric(name, ref, dg * u, (K, th_deg, side))
            assert out.lm == 0
            worst = max(worst, float(np.abs(out.tau - ref).max()) / P)
            plastic = out.dslip
            assert plastic @ u > 0.0                  # the plastic slip goes along the slip
    assert worst < 1e-4


@pytest.mark.parametrize("name", ["ellipse", "star", "componentwise"])
def test_sliding_from_rest_reaches_the_laws_force(name):
    gl = law(name)
    for phi in np.radians([0.0, 37.0, 90.0, 181.0, 250.0, 333.0]):
        u = np.array([math.cos(phi), math.sin(phi)])
        tau = np.zeros(2)
        for _ in range(40):
            tau = fric(name, tau, 5e-5 * u).tau
        assert np.abs(tau - steady_tau(gl, phi, 0.0, 1, P)).max() < 1e-4 * P


@pytest.mark.parametrize("name", LAWS)
def test_elastic_stick_is_the_predictor(name):
    rng = np.random.default_rng(3)
    for _ in range(20):
        tau0 = 0.3 * P * 0.1 * rng.normal(size=2)
        dg = 1e-6 * P / K * rng.normal(size=2)
        out = fric(name, tau0, dg)
        assert np.allclose(out.tau, tau0 + K * dg, rtol=0, atol=1e-12 * P)
        assert np.allclose(out.ddtddg, K * np.eye(2), rtol=1e-15)
        assert np.all(out.ddtddp == 0.0) and np.all(np.abs(out.dslip) < 1e-20)


@pytest.mark.parametrize("name", LAWS)
def test_reversal_keeps_mu_plus_and_mu_minus(name):
    gl = law(name)
    mu_plus = gl.force(np.array([0.0])).p[0, 0]
    mu_minus = -gl.force(np.array([math.pi])).p[0, 0]
    for nfdir in (1, 2):
        tau = np.zeros(nfdir)
        e1 = np.eye(nfdir)[0]
        for sign, mu in ((1.0, mu_plus), (-1.0, -mu_minus), (1.0, mu_plus)):
            for _ in range(30):
                tau = fric(name, tau, sign * 3e-5 * e1, nfdir=nfdir).tau
            assert abs(tau[0] - mu * P) < 1e-4 * P, (nfdir, sign)


@pytest.mark.parametrize("name", LAWS)
def test_nfdir_1_limits_along_the_turned_law(name):
    gl = law(name)
    for th_deg, side in ((0.0, 1), (25.0, 1), (25.0, -1), (200.0, 1)):
        th = math.radians(th_deg) + (math.pi if side < 0 else 0.0)
        up = fric(name, [0.0], [1e-3], (K, th_deg, side), nfdir=1)
        down = fric(name, [0.0], [-1e-3], (K, th_deg, side), nfdir=1)
        s = np.array([math.cos(-th), math.sin(-th)])            # direction 1 in the law frame
        mu_up = gl.force(np.array([-th])).p[0] @ s                # > 0
        mu_down = -gl.force(np.array([math.pi - th])).p[0] @ s    # > 0
        assert up.tau[0] == pytest.approx(mu_up * P, abs=1e-4 * P)
        assert down.tau[0] == pytest.approx(-mu_down * P, abs=1e-4 * P)
        assert up.ddtddg[0, 0] == 0.0 and up.ddtddp[0] == pytest.approx(up.tau[0] / P)


def _numeric(name, tau0, dg, props, press, nfdir):
    out = fric(name, tau0, dg, props, press, nfdir)
    h = 1e-6 * np.abs(dg).max() + 1e-12
    num = np.zeros((nfdir, nfdir))
    for b in range(nfdir):
        e = np.zeros(nfdir)
        e[b] = h
        num[:, b] = (fric(name, tau0, dg + e, props, press, nfdir).tau
                     - fric(name, tau0, dg - e, props, press, nfdir).tau) / (2 * h)
    hp = 1e-6 * press
    nump = (fric(name, tau0, dg, props, press + hp, nfdir).tau
            - fric(name, tau0, dg, props, press - hp, nfdir).tau) / (2 * hp)
    return out, num, nump


@pytest.mark.parametrize("name", LAWS)
def test_tangents_match_central_differences(name):
    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(30):
        nfdir = 2 if rng.random() < 0.8 else 1
        th_deg, side = rng.uniform(-180, 180), rng.choice([-1.0, 1.0])
        tau0 = 0.05 * P * rng.normal(size=nfdir)
        dg = 4e-5 * rng.normal(size=nfdir)
        out, num, nump = _numeric(name, tau0, dg, (K, th_deg, side), P, nfdir)
        scale = K * max(1e-3, float(np.abs(num).max()) / K)
        assert np.abs(out.ddtddg - num).max() < 2e-5 * scale, (out.ddtddg, num)
        assert np.abs(out.ddtddp - nump).max() < 2e-5, (out.ddtddp, nump)
        checked += 1
    assert checked == 30


@pytest.mark.parametrize("name", ["star", "windward"])
def test_turning_everything_turns_the_answer(name):
    rng = np.random.default_rng(5)
    for _ in range(10):
        a = rng.uniform(-math.pi, math.pi)
        th_deg = rng.uniform(-90, 90)
        tau0 = 0.1 * P * rng.normal(size=2)
        dg = 5e-5 * rng.normal(size=2)
        base = fric(name, tau0, dg, (K, th_deg, 1.0))
        R = rot(a)
        turned = fric(name, R @ tau0, R @ dg, (K, th_deg + math.degrees(a), 1.0))
        assert np.abs(turned.tau - R @ base.tau).max() < 1e-9 * P
        assert np.abs(turned.ddtddg - R @ base.ddtddg @ R.T).max() < 1e-7 * K


@pytest.mark.parametrize("name", ["ellipse", "windward"])
def test_units_and_the_side_flip(name):
    rng = np.random.default_rng(9)
    for _ in range(10):
        th_deg = rng.uniform(-180, 180)
        tau0 = 0.1 * P * rng.normal(size=2)
        dg = 5e-5 * rng.normal(size=2)
        base = fric(name, tau0, dg, (K, th_deg, 1.0))
        c = 7.5                             # PRESS, PROPS(1), TAU in other units of stress
        scaled = fric(name, c * tau0, dg, (c * K, th_deg, 1.0), press=c * P)
        assert np.abs(scaled.tau - c * base.tau).max() < 1e-9 * c * P
        flipped = fric(name, tau0, dg, (K, th_deg + 180.0, -1.0))
        assert np.abs(flipped.tau - base.tau).max() < 1e-9 * P


@pytest.mark.parametrize("name", ["windward", "componentwise"])
def test_energies_slip_flag_and_no_pressure(name):
    rng = np.random.default_rng(8)
    for _ in range(20):
        tau0 = 0.1 * P * rng.normal(size=2)
        dg = 5e-5 * rng.normal(size=2) * rng.choice([1e-3, 1.0])
        out = fric(name, tau0, dg, statev=(0.25, 3.0, 7.0))
        assert out.sfd == pytest.approx(out.tau @ out.dslip, rel=1e-12, abs=1e-30)
        assert out.sfd >= -1e-9 * P * np.abs(out.dslip).sum()   # friction dissipates
        assert out.sed == pytest.approx(out.tau @ out.tau / (2 * K), rel=1e-12)
        slipped = bool(np.abs(out.dslip).max() > 0)
        assert out.statev[2] == (1.0 if slipped else 0.0)
        assert out.statev[0] == pytest.approx(0.25 + np.hypot(*out.dslip), rel=1e-12)
        assert out.statev[1] == 3.0
    none = fric(name, [3e4, -2e4], [1e-6, 2e-6], press=0.0)
    assert none.lm == 0 and np.all(none.tau == 0.0) and none.sed == 0.0 and none.sfd == 0.0
    assert np.allclose(none.dslip, [3e4 / K + 1e-6, -2e4 / K + 2e-6], rtol=1e-12)


def test_no_elastic_stiffness_asks_for_rigid_stick():
    out = fric("star", [1e4, 0.0], [1e-6, 0.0], (0.0, 0.0, 1.0))
    assert out.lm == 1


@pytest.mark.parametrize("name", ["windward", "star", "ellipse"])
def test_a_small_slip_moves_the_stress_a_little_from_anywhere_on_the_boundary(name):
    """Continuity of the return map: from any stress on PRESS C (the arcs of C that slide
    along one direction included), a slip increment of size d moves the stress by O(K d),
    never to another root of a non-associated law far along the boundary."""
    gl = law(name)
    rng = np.random.default_rng(17)
    worst = 0.0
    for _ in range(400):
        phi = rng.uniform(-math.pi, math.pi)
        th_deg, side = rng.uniform(-180, 180), rng.choice([-1.0, 1.0])
        th = math.radians(th_deg) + (math.pi if side < 0 else 0.0)
        c = (1 + 1e-6) * gl.law.C.radial(np.array([phi]))[0]    # on the boundary
        tau0 = P * rot(th) @ (c * np.array([math.cos(phi), math.sin(phi)]))
        a = rng.uniform(-math.pi, math.pi)
        dg = 1e-4 * P / K * np.array([math.cos(a), math.sin(a)])
        out = fric(name, tau0, dg, (K, th_deg, side))
        worst = max(worst, float(np.linalg.norm(out.tau - tau0)) / (1e-4 * P))
    assert worst < 30.0


def _returns(tab, q):
    """Every return of the trial q (per unit pressure) on the table: points P(psi) of the
    nodes' polygon with q - P(psi) = lam (cos psi, sin psi), lam >= 0 (bisection in each
    interval where the cross product changes sign)."""
    psi = np.append(tab.psi, tab.psi[0] + 2 * math.pi)
    p = np.vstack([tab.p, tab.p[:1]])

    def g(j, t):
        s = psi[j] + t * (psi[j + 1] - psi[j])
        x = p[j] + t * (p[j + 1] - p[j])
        return (math.cos(s) * (q[1] - x[1]) - math.sin(s) * (q[0] - x[0]),
                math.cos(s) * (q[0] - x[0]) + math.sin(s) * (q[1] - x[1]), x)
    out = []
    gn = np.cos(psi) * (q[1] - p[:, 1]) - np.sin(psi) * (q[0] - p[:, 0])
    for j in np.flatnonzero(gn[:-1] * gn[1:] <= 0):
        a = gn[j]
        lo, hi = 0.0, 1.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if (g(j, mid)[0] > 0) == (a > 0):
                lo = mid
            else:
                hi = mid
        _, lam, x = g(j, 0.5 * (lo + hi))
        if lam >= 0:
            out.append(x)
    return np.array(out)


@pytest.mark.parametrize("name", ["skewed", "skewed-mirrored"])
def test_of_several_returns_the_one_nearest_where_the_path_leaves_c(name):
    """A strongly non-associated law (D turned against C) has trial stresses with several
    returns far apart: FRIC takes the one nearest the point where the elastic path from
    the start stress leaves C (the start itself on the boundary), whichever it meets
    first (the law and its mirror image meet them in opposite orders)."""
    from asperity.fe.table import law_table
    gl = law(name)
    tab = law_table(gl)
    rng = np.random.default_rng(4)
    seen = 0
    for _ in range(12000):
        phi = rng.uniform(-math.pi, math.pi)
        on = rng.random() < 0.5
        r = float(tab.radial([phi])[0])
        start = (1.0 if on else rng.uniform(0.0, 0.9)) * r * np.array([math.cos(phi),
                                                                         math.sin(phi)])
        q = r * (1 + rng.uniform(0.0, 0.3)) * np.array([math.cos(phi + rng.normal(0, 0.3)),
                                                        math.sin(phi + rng.normal(0, 0.3))])
        if np.hypot(*q) <= tab.radial([math.atan2(q[1], q[0])])[0]:
            continue
        roots = _returns(tab, q)
        if len(roots) < 2 or np.ptp(np.linalg.norm(roots - roots[0], axis=1)) < 0.05:
            continue
        if on:
            x = start
        else:                                   # where the path start -> q leaves C
            lo, hi = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                v = start + mid * (q - start)
                inside = np.hypot(*v) <= tab.radial([math.atan2(v[1], v[0])])[0]
                lo, hi = (mid, hi) if inside else (lo, mid)
            x = start + hi * (q - start)
        want = roots[np.argmin(np.linalg.norm(roots - x, axis=1))]
        th_deg, side = rng.uniform(-180, 180), rng.choice([-1.0, 1.0])
        R = rot(math.radians(th_deg) + (math.pi if side < 0 else 0.0))   # law -> local
        out = fric(name, P * R @ start, R @ (q - start) * P / K, (K, th_deg, side))
        assert np.abs(out.tau / P - R @ want).max() < 1e-6, (start, q, roots)
        seen += 1
    assert seen >= 12


@pytest.mark.parametrize("name", ["windward", "ellipse"])
def test_the_routines_law_is_exactly_its_table(name):
    """ASPFRC (force for a sliding direction) and ASPRAD (the boundary of C along a ray),
    which the explicit routines and the 1D return call, against the table's own
    interpolation to rounding: every interval, the last one (back to 360 deg) included."""
    import ctypes as C

    from asperity.fe.table import law_table
    tab = law_table(law(name))
    lib = fric_library(name)
    rng = np.random.default_rng(6)
    last = np.linspace(tab.psi[-1], tab.psi[0] + 2 * math.pi, 7)[1:-1]
    psi = np.concatenate([rng.uniform(-20, 20, 2000), last, last - 2 * math.pi])
    r, n, px, py = C.c_double(), C.c_int(), C.c_double(), C.c_double()
    for x in psi:
        lib.aspfrc_(C.byref(C.c_double(P)), C.byref(C.c_double(x)), C.byref(px),
                    C.byref(py), C.byref(n))
        assert np.abs([px.value, py.value] - tab.force([x])[0]).max() < 1e-12, x
    for phi in rng.uniform(-20, 20, 2000):
        lib.asprad_(C.byref(C.c_double(P)), C.byref(C.c_double(phi)), C.byref(r), C.byref(n))
        assert abs(r.value - tab.radial([phi])[0]) < 1e-12, phi


@pytest.mark.parametrize("name", ["windward", "componentwise"])
def test_nfdir_1_energies_and_every_angle(name):
    """NFDIR = 1 along every law angle PROPS(2) in steps of 0.5 deg: the limits are the
    law's tangential forces along +-direction 1; SFD = TAU DSLIP >= 0, SED = TAU^2/2K."""
    gl = law(name)
    for th_deg in np.arange(-180.0, 180.0, 0.5) + 0.25:
        th = math.radians(th_deg)
        s = np.array([math.cos(-th), math.sin(-th)])
        for sign, psi in ((1.0, -th), (-1.0, math.pi - th)):
            out = fric(name, [0.3 * sign * P * 0.1], [sign * 1e-3], (K, th_deg, 1.0), nfdir=1)
            assert out.tau[0] == pytest.approx(P * gl.force(np.array([psi])).p[0] @ s,
                                               abs=1e-4 * P)
            assert out.sfd == pytest.approx(out.tau[0] * out.dslip[0], rel=1e-12)
            assert out.sfd > 0 and out.sed == pytest.approx(out.tau[0] ** 2 / (2 * K), rel=1e-12)


def test_no_or_negative_pressure_frees_the_point():
    for press in (0.0, -5e5):
        out = fric("star", [3e4, -2e4], [1e-6, 2e-6], press=press)
        assert out.lm == 0 and np.all(out.tau == 0.0) and out.sed == 0.0 and out.sfd == 0.0
        one = fric("star", [3e4], [1e-6], press=press, nfdir=1)
        assert np.all(one.tau == 0.0) and one.dslip[0] == pytest.approx(3e4 / K + 1e-6)
