"""Gaits of a crawling body (issue 26, item 2; asperity.crawling.gait*): the body frame's
invariants, closed forms (a straight body, an arc, the wave's tangent angle), accuracy
against independent quadrature, velocities against differences in time, symmetries, the
chain -> wave limit, convergence in N, gait files, self-crossing and one-line refusals."""
from __future__ import annotations

import itertools
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar

from asperity.crawling.gait import CurvatureWave, FourierGait
from asperity.crawling.gait_chain import JointTable, SerpenoidChain
from asperity.crawling.gait_crossing import check_self_crossing
from asperity.crawling.gait_file import read_gait
from asperity.errors import InputError

GAITS = Path(__file__).resolve().parents[1] / "surfaces" / "gaits"
RNG = np.random.default_rng(26)


def wave_angle(A, k, t, L=1.0, T=1.0):
    """The curvature wave's zero-mean tangent angle and its rate as functions of s,
    written out from kappa L = A cos 2 pi (k s / L + t / T) (independent of the module):
    psi = integral_0^s kappa, minus its arc-length mean (by quad)."""
    def psi(x):
        return A / (2 * math.pi * k) * (math.sin(2 * math.pi * (k * x / L + t / T))
                                        - math.sin(2 * math.pi * t / T))

    def psi_t(x):
        return A / (k * T) * (math.cos(2 * math.pi * (k * x / L + t / T))
                              - math.cos(2 * math.pi * t / T))
    m0 = quad(psi, 0, L, epsabs=1e-13, epsrel=1e-13, limit=400)[0] / L
    m1 = quad(psi_t, 0, L, epsabs=1e-13, epsrel=1e-13, limit=400)[0] / L
    return (lambda x: psi(x) - m0), (lambda x: psi_t(x) - m1)


def mirror(a):
    return a * np.array([1.0, -1.0])


def all_gaits():
    return [CurvatureWave(7, 1), CurvatureWave(4, 2.5, period=0.7, length=0.3),
            FourierGait([(1, 1, 5, 1), (2, -1, 0, 2), (0, 0, 1.5, 0), (0, 1, 0.5, 0.5)]),
            SerpenoidChain(12, 0.4, -0.5, 0.1, period=1.3),
            JointTable(RNG.uniform(-0.5, 0.5, (8, 5)), period=2.0, length=0.5)]


# ----------------------------------------------------------------- closed forms and exactness

def test_straight_body():
    L, N = 2.0, 7
    k = CurvatureWave(0, 1, length=L).kinematics([0.0, 0.3], N)
    s = (np.arange(N) + 0.5) * L / N
    np.testing.assert_allclose(k.r[..., 0], np.broadcast_to(s - L / 2, (2, N)), atol=1e-15)
    assert np.all(k.r[..., 1] == 0) and np.all(k.v == 0) and np.all(k.tangent == 0)
    # sum of (s_i - L/2)^2 / N = L^2 (N^2 - 1) / (12 N^2)
    np.testing.assert_allclose(k.inertia, L * L * (N * N - 1) / (12 * N * N), rtol=1e-14)
    assert np.all(k.spin == 0)


@pytest.mark.parametrize("kL", [1.0, 5.0, -3.0])
def test_constant_curvature_is_an_arc_of_radius_L_over_kappaL(kL):
    L, N = 0.5, 9
    k = FourierGait([(0, 0, kL, 0)], length=L).kinematics([0.2], N)
    z = k.r[0, :, 0] + 1j * k.r[0, :, 1]
    # the circle through three points, then every point's distance to its centre
    a, b, c = z[0], z[4], z[8]
    w = (c - a) / (b - a)
    centre = a + (b - a) * (w - abs(w) ** 2) / (w - w.conjugate())
    np.testing.assert_allclose(np.abs(z - centre), L / abs(kL), rtol=1e-12,
                               err_msg="an arc of constant curvature: radius L / kappa L")
    # chords: |x_i - x_j| = 2 R sin(kappa |s_i - s_j| / 2)
    chord = 2 * L / abs(kL) * np.sin(abs(kL) / L * np.abs(k.s - k.s[0]) / 2)
    np.testing.assert_allclose(np.abs(z - z[0]), chord, atol=1e-14)
    np.testing.assert_allclose(k.tangent[0], kL * (k.s / L - 0.5), atol=1e-14)
    assert np.all(k.v == 0)


@pytest.mark.parametrize("A,k,N", [(7, 1, 201), (7, 1, 3), (100, 20, 3), (60, 0.37, 5),
                                   (30, 7.5, 11)])
def test_positions_and_velocities_against_independent_quadrature(A, k, N):
    """Positions to 1e-10 L whatever N, velocities as accurate, against quad (between
    consecutive points) on the tangent angle and its rate written out here."""
    t = 0.37
    kin = CurvatureWave(A, k).kinematics([t], N)
    phi, rate = wave_angle(A, k, t)
    edges = np.concatenate(([0.0], kin.s))
    parts = []
    for f in (lambda u: math.cos(phi(u)), lambda u: math.sin(phi(u)),
              lambda u: -math.sin(phi(u)) * rate(u), lambda u: math.cos(phi(u)) * rate(u)):
        steps = [quad(f, a, b, epsabs=1e-13, epsrel=1e-13, limit=200)[0]
                 for a, b in itertools.pairwise(edges)]
        parts.append(np.cumsum(steps))
    r, v = np.column_stack(parts[:2]), np.column_stack(parts[2:])
    r -= kin.weights @ r
    v -= kin.weights @ v
    np.testing.assert_allclose(kin.r[0], r, rtol=0, atol=1e-10)
    np.testing.assert_allclose(kin.v[0], v, rtol=0, atol=1e-10 * max(1.0, A))
    np.testing.assert_allclose(kin.tangent[0], [phi(s) for s in kin.s], rtol=0, atol=1e-12)


def test_two_link_chain_closed_form():
    """One joint of angle c: the links at -c/2 and +c/2 about the body's axis."""
    c, L = 0.8, 2.0
    kin = SerpenoidChain(2, 0.0, 0.0, c, length=L).kinematics([0.0], 4)
    s = kin.s
    ang = np.where(s < L / 2, -c / 2, c / 2)
    x = np.where(s < L / 2, -(L / 2 - s) * np.cos(c / 2), (s - L / 2) * np.cos(c / 2))
    y = np.where(s < L / 2, (L / 2 - s) * np.sin(c / 2), (s - L / 2) * np.sin(c / 2))
    xy = np.column_stack([x, y]) - np.column_stack([x, y]).mean(axis=0)
    np.testing.assert_allclose(kin.r[0], xy, atol=1e-15)
    np.testing.assert_allclose(kin.tangent[0], ang, atol=1e-15)
    assert np.all(kin.v == 0)


# --------------------------------------------------------------------------- the body frame

def _weights(kind, n):
    if kind == "uniform":
        return None
    if kind == "array":
        return RNG.uniform(0.2, 3.0, n)
    return lambda s: 1.0 + 0.8 * np.sin(5 * s)          # a profile of s (m)


@pytest.mark.parametrize("weights", ["uniform", "array", "callable"])
@pytest.mark.parametrize("gi", range(5))
def test_body_frame_invariants(gi, weights):
    gait = all_gaits()[gi]
    N = 23
    t = RNG.uniform(0, 3 * gait.period, 6)
    kin = gait.kinematics(t, N, _weights(weights, N))
    w = kin.weights
    assert abs(w.sum() - 1) < 1e-15 and np.all(w > 0)
    np.testing.assert_allclose(np.einsum("n,tnk->tk", w, kin.r), 0, atol=1e-15)
    np.testing.assert_allclose(np.einsum("n,tnk->tk", w, kin.v), 0, atol=1e-13)
    np.testing.assert_allclose(kin.inertia, np.einsum("n,tnk,tnk->t", w, kin.r, kin.r),
                               rtol=1e-13)
    # the arc-length mean of the tangent angle and of its rate: 0 (Gauss-Legendre on the
    # tangent at 200 points: exact for these smooth angles)
    if isinstance(gait, (SerpenoidChain, JointTable)):
        theta, omega = gait.link_angles(t)
        assert np.abs(theta.mean(axis=1)).max() < 1e-15
        assert np.abs(omega.mean(axis=1)).max() < 1e-13
    else:
        x, wq = np.polynomial.legendre.leggauss(200)
        phi, rate = gait.tangent_angle(t, (x + 1) / 2 * gait.length)
        assert np.abs(phi @ wq / 2).max() < 1e-13
        assert np.abs(rate @ wq / 2).max() < 1e-12
    # d I / dt = 2 sum w r . v (a difference in t): the inertia and the velocities agree
    h = 1e-5 * gait.period
    ip, im = (gait.kinematics(t + d, N, _weights(weights, N)).inertia for d in (h, -h))
    # (the random weights are drawn again: only the uniform and callable ones repeat)
    if weights != "array":
        np.testing.assert_allclose((ip - im) / (2 * h),
                                   2 * np.einsum("n,tnk,tnk->t", w, kin.r, kin.v),
                                   atol=1e-7 * gait.length ** 2 / gait.period)


@pytest.mark.parametrize("gi", range(5))
def test_periodic_in_time(gi):
    gait = all_gaits()[gi]
    t = np.array([0.1, 0.45]) * gait.period
    a, b = gait.kinematics(t, 17), gait.kinematics(t + 3 * gait.period, 17)
    np.testing.assert_allclose(b.r, a.r, atol=1e-12 * gait.length)
    np.testing.assert_allclose(b.v, a.v, atol=1e-11 * gait.length / gait.period)


@pytest.mark.parametrize("gi", [0, 2, 3])
def test_velocity_is_the_time_derivative_to_second_order(gi):
    gait = all_gaits()[gi]
    t = np.array([0.13, 0.61]) * gait.period
    kin = gait.kinematics(t, 31)
    errors, spin = [], []
    for h in (2e-3, 1e-3):
        d = h * gait.period
        fd = (gait.kinematics(t + d, 31).r - gait.kinematics(t - d, 31).r) / (2 * d)
        errors.append(np.abs(fd - kin.v).max())
        # the internal angular momentum sum w r x v, with v by the difference
        h_fd = (kin.r[..., 0] * fd[..., 1] - kin.r[..., 1] * fd[..., 0]) @ kin.weights
        spin.append(np.abs(h_fd - kin.spin).max())
    for e in (errors, spin):
        order = math.log2(e[0] / e[1])
        assert 1.9 < order < 2.1, (e, order)


def test_joint_table_velocity_against_differences():
    """The periodic spline: the velocity is its derivative, also across t = T."""
    gait = all_gaits()[4]
    t = np.array([0.3, 1.1, 0.0, 2.0])
    kin = gait.kinematics(t, 20)
    d = 1e-6
    fd = (gait.kinematics(t + d, 20).r - gait.kinematics(t - d, 20).r) / (2 * d)
    np.testing.assert_allclose(fd, kin.v, atol=1e-7)


# ----------------------------------------------------------------------------- symmetries

@pytest.mark.parametrize("k", [1, 2.5])
def test_half_period_later_the_shape_is_mirrored(k):
    """kappa(s, t + T/2) = -kappa(s, t) for every k: the mirror image, r_y -> -r_y."""
    gait, t = CurvatureWave(7, k), np.array([0.05, 0.3])
    a, b = gait.kinematics(t, 15), gait.kinematics(t + 0.5, 15)
    np.testing.assert_allclose(b.r, mirror(a.r), atol=1e-14)
    np.testing.assert_allclose(b.v, mirror(a.v), atol=1e-13)
    np.testing.assert_allclose(b.tangent, -a.tangent, atol=1e-14)
    assert np.abs(b.r[..., 1] - a.r[..., 1]).max() > 0.05       # not symmetric already


def test_negative_amplitude_is_the_mirror_image():
    t = np.array([0.2, 0.7])
    a = CurvatureWave(7, 1).kinematics(t, 11)
    b = FourierGait([(1, 1, -7, 0)]).kinematics(t, 11)
    np.testing.assert_allclose(b.r, mirror(a.r), atol=1e-14)
    np.testing.assert_allclose(b.v, mirror(a.v), atol=1e-13)
    np.testing.assert_allclose(b.spin, -a.spin, atol=1e-14)


def test_curvature_wave_runs_from_head_to_tail():
    """kappa(s, t + dt) = kappa(s + L dt / (k T), t): the pattern moves to the tail."""
    k, dt, L = 2.0, 0.01, 1.0
    g = CurvatureWave(7, k)
    s = np.linspace(0.2, 0.6, 5)
    shift = L * dt / k
    for t in (0.1, 0.4):
        # curvature as the s-derivative of the tangent angle (central difference, 1e-6)
        def kappa(ss, tt):
            p = g.tangent_angle([tt], np.concatenate([ss - 1e-6, ss + 1e-6]))[0][0]
            return (p[ss.size:] - p[:ss.size]) / 2e-6
        np.testing.assert_allclose(kappa(s, t + dt), kappa(s + shift, t), atol=1e-6)
        assert np.abs(kappa(s, t + dt) - kappa(s - shift, t)).max() > 0.1


@pytest.mark.parametrize("b", [0.4, -0.4])
def test_serpenoid_direction(b):
    """phi_j(t + |b| T / 2 pi) = phi_{j-1}(t) for b > 0 (the wave runs from the tail to
    the head), = phi_{j+1}(t) for b < 0 (from the head to the tail)."""
    g = SerpenoidChain(9, 0.5, b, 0.05, period=2.0)
    t = np.array([0.3, 1.4])
    joints = np.diff(g.link_angles(t)[0], axis=1)                     # (nt, 8): j = 1..8
    later = np.diff(g.link_angles(t + abs(b) * 2.0 / (2 * math.pi))[0], axis=1)
    if b > 0:
        np.testing.assert_allclose(later[:, 1:], joints[:, :-1], atol=1e-14)
    else:
        np.testing.assert_allclose(later[:, :-1], joints[:, 1:], atol=1e-14)


def test_chain_approaches_the_wave_as_links_grow():
    """a = A / n, b = -2 pi k / n: the chain at t is the wave at t - T/4, positions and
    velocities to O(n^-2) (the tangent only to O(n^-1): piecewise constant)."""
    wave, t, N = CurvatureWave(7, 1), np.array([0.3, 0.8]), 30
    ref = wave.kinematics(t - 0.25, N)
    err_r, err_v = [], []
    for n in (20, 40, 80):
        kin = SerpenoidChain.from_wave(7, 1, n).kinematics(t, N)
        err_r.append(np.abs(kin.r - ref.r).max())
        err_v.append(np.abs(kin.v - ref.v).max())
    for e in (err_r, err_v):
        orders = np.log2(np.array(e[:-1]) / np.array(e[1:]))
        assert np.all((orders > 1.8) & (orders < 2.2)), e
    assert err_r[-1] < 1e-4


def test_joint_table_approaches_its_serpenoid():
    """A table sampled from a serpenoid: the periodic cubic spline converges as O(h^4)."""
    g = SerpenoidChain(6, 0.5, -0.7, period=1.0)
    t = np.linspace(0, 1, 37)[:-1] + 0.013
    ref = g.kinematics(t, 12)
    err = []
    for rows in (16, 32):
        table = np.diff(g.link_angles(np.arange(rows) / rows)[0], axis=1)
        kin = JointTable(table, period=1.0).kinematics(t, 12)
        err.append(np.abs(kin.r - ref.r).max())
    assert 3.7 < math.log2(err[0] / err[1]) < 4.3, err
    assert JointTable(table).params()["rows"] == 32


def test_units_scale_positions_and_velocities():
    t = np.array([0.1, 0.6])
    a = CurvatureWave(7, 1, period=1.0, length=1.0).kinematics(t, 21)
    b = CurvatureWave(7, 1, period=1.0, length=1000.0).kinematics(t, 21)
    c = CurvatureWave(7, 1, period=4.0, length=1.0).kinematics(4 * t, 21)
    np.testing.assert_allclose(b.r, 1000 * a.r, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(b.v, 1000 * a.v, rtol=1e-12, atol=1e-11)
    np.testing.assert_allclose(b.inertia, 1e6 * a.inertia, rtol=1e-12)
    np.testing.assert_allclose(c.r, a.r, atol=1e-14)
    np.testing.assert_allclose(c.v, a.v / 4, atol=1e-14)


def _midpoint_errors(gait, ns=(9, 27, 81), fine=2187):
    """Largest difference of r at the common points of N in ``ns`` and of N = ``fine``
    (nested midpoints: fine / N odd)."""
    t = np.array([0.2])
    ref = gait.kinematics(t, fine)
    errs = []
    for n in ns:
        kin = gait.kinematics(t, n)
        r = fine // n
        idx = np.arange(n) * r + (r - 1) // 2                 # s_i of N among the fine ones
        np.testing.assert_allclose(ref.s[idx], kin.s, rtol=1e-14)
        errs.append(np.abs(kin.r[0] - ref.r[0, idx]).max())
    return np.array(errs)


def test_positions_converge_with_points_as_the_midpoint_rule():
    """The points themselves are exact; the centre of mass is the midpoint rule of the
    continuous centroid, whose error (Euler-Maclaurin) is h^2 / 24 times the difference of
    the end tangents, and so on with the odd derivatives: O(N^-2) in general ..."""
    for gait in (CurvatureWave(7, 1.5), FourierGait([(1, 1, 7, 0), (0, 0, 1.5, 0)])):
        errs = _midpoint_errors(gait)
        orders = np.log(errs[:-1] / errs[1:]) / math.log(3)
        assert np.all((orders > 1.95) & (orders < 2.05)), errs
    # ... and faster than any power when the tangent angle is periodic in s (a whole
    # number of waves, no static bend): the end derivatives agree, the error terms vanish
    errs = _midpoint_errors(CurvatureWave(7, 1))
    assert errs[0] > 1e-11 and errs[1] < 1e-14, errs


# ---------------------------------------------------------------------------- gait files

def test_shipped_gait_files_load():
    wave = read_gait(GAITS / "wave-turning.toml")
    same = FourierGait([(1, 1, 7, 0), (0, 0, 1.5, 0)])
    t = np.array([0.1, 0.5])
    np.testing.assert_allclose(wave.kinematics(t, 9).r, same.kinematics(t, 9).r, atol=0)
    assert wave.name == "wave-turning" and wave.params()["terms"][1]["cos"] == 1.5
    robot = read_gait(GAITS / "robot-joints.toml")
    assert (robot.links, robot.period, robot.length) == (8, 2.0, 0.8)
    # the spline passes through the table's rows (degrees in the file)
    joints = np.diff(robot.link_angles(np.arange(16) * 2.0 / 16)[0], axis=1)
    np.testing.assert_allclose(np.degrees(joints), robot.angles * 180 / math.pi, atol=1e-12)
    assert abs(np.degrees(robot.angles).max() - 40.0) < 1e-9
    for g in (wave, robot):
        check_self_crossing(g)


FOURIER = 'kind = "fourier"\nlength = 1.0\nperiod = 1.0\n[[gait.terms]]\nm = 1\nn = 1\ncos = 7.0\n'
JOINTS = ('kind = "joints"\nlength = 1.0\nperiod = 1.0\nlinks = 3\n'
          'angles = [[0.1, 0.2], [0.2, 0.1], [0.0, -0.1], [-0.1, 0.0]]\n')


@pytest.mark.parametrize("text,field", [
    ("", r"missing table \[gait\]"),
    ('[gait]\nlength = 1.0\nperiod = 1.0\n', "missing key gait.kind"),
    ('[gait]\n' + FOURIER.replace("length = 1.0\n", ""), "missing key gait.length"),
    ('[gait]\n' + FOURIER.replace('"fourier"', '"spline"'), "gait.kind must be one of"),
    ('[gait]\n' + FOURIER.replace("period = 1.0", "period = 0.0"), r"gait.period must be in \["),
    ('[gait]\n' + FOURIER.replace("length = 1.0", "length = -2"), r"gait.length must be in \["),
    ('[gait]\n' + FOURIER.replace("length = 1.0", 'length = "1"'), "gait.length must be a number"),
    ('[gait]\n' + FOURIER.replace("period = 1.0", "period = nan"), "gait.period must be in .*NaN"),
    ('[gait]\n' + FOURIER.replace("period = 1.0", "period = inf"), "gait.period must be a finite"),
    ('[gait]\n' + FOURIER.replace("period = 1.0", "period = 1.0\nspeed = 3"),
     "unknown key gait.speed"),
    ('[gait]\n' + FOURIER + "speed = 3\n", r"unknown key gait.terms\[0\].speed"),
    ('color = 1\n[gait]\n' + FOURIER, "unknown key 'color'"),
    ('[gait]\nkind = "fourier"\nlength = 1.0\nperiod = 1.0\n', "missing key gait.terms"),
    ('[gait]\n' + FOURIER + "[[gait.terms]]\nm = 2\nn = 1\ncos = 3.0\n[[gait.terms]]\nm = 1\n"
     "n = 0\ncos = 300.0\n", r"gait.terms\[2\].cos must be in \[-100, 100\], got 300"),
    ('[gait]\n' + FOURIER.replace("m = 1", "m = 1.5"), r"gait.terms\[0\].m must be a whole"),
    ('[gait]\n' + FOURIER.replace("m = 1\n", ""), r"missing key gait.terms\[0\].m"),
    ('[gait]\n' + FOURIER.replace("cos = 7.0", "phase = 1.0"), r"unknown key gait.terms\[0\]"),
    ('[gait]\n' + FOURIER.replace("cos = 7.0\n", ""), r"missing key gait.terms\[0\].cos"),
    ('[gait]\n' + FOURIER.replace("n = 1", "n = 99"),
     r"gait.terms\[0\].n must be a whole .*\[-50, 50\]"),
    ('[gait]\n' + JOINTS.replace("links = 3", "links = 1"), r"gait.links must be a whole.*\[2, "),
    ('[gait]\n' + JOINTS.replace("links = 3\n", ""), "missing key gait.links"),
    ('[gait]\n' + JOINTS.replace("[-0.1, 0.0]]", "[-0.1]]"), r"gait.angles\[3\] has 1 values"),
    ('[gait]\n' + JOINTS.replace(", [-0.1, 0.0]]", "]"), "gait.angles must have 4 to"),
    ('[gait]\n' + JOINTS.replace("[0.2, 0.1]", '[0.2, "x"]'), r"gait.angles\[1\]\[1\] must be"),
    ('[gait]\n' + JOINTS.replace("[0.2, 0.1]", "[0.2, nan]"), r"gait.angles\[1\]\[1\] must be"),
    ('[gait]\n' + JOINTS.replace("[0.2, 0.1]", "[0.2, 4.0]"), r"gait.angles\[1\]\[1\] must be in"),
    ('[gait]\n' + JOINTS + 'unit = "grad"\n', "gait.unit must be one of rad, deg"),
    ('[gait]\n' + JOINTS.replace("angles = ", "angles = 3 #"), "gait.angles must be a table"),
    ('[gait]\n' + JOINTS + "terms = 1\n", "unknown key gait.terms"),
    ('[gait\n', "not valid TOML"),
])
def test_gait_file_refusals(tmp_path, text, field):
    p = tmp_path / "g.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=field) as e:
        read_gait(p)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(str(p))


def test_gait_file_in_degrees(tmp_path):
    p = tmp_path / "g.toml"
    p.write_text("[gait]\n" + JOINTS.replace("0.1", "180").replace("0.2", "-180")
                 + 'unit = "deg"\n', encoding="utf-8")
    g = read_gait(p)
    assert np.abs(g.angles).max() == pytest.approx(math.pi, rel=1e-15)


# ------------------------------------------------------------------------------ self-crossing

def curl_threshold():
    """The k = 1 wave's amplitude at which its body first touches itself, independently:
    at t = 0 the body is symmetric about the normal through s = L/2 and the points s and
    L - s meet when x(L/2) - x(s) = integral_s^(L/2) cos((A / 2 pi) sin 2 pi u) du = 0."""
    def gap(A):
        def f(s):
            return quad(lambda u: math.cos(A / (2 * math.pi) * math.sin(2 * math.pi * u)),
                        s, 0.5, epsabs=1e-14, epsrel=1e-14)[0]
        return minimize_scalar(f, bounds=(0, 0.5), method="bounded",
                               options={"xatol": 1e-10}).fun
    return brentq(gap, 12.0, 14.0, xtol=1e-8)


def test_curl_threshold_of_the_k1_wave():
    A = curl_threshold()
    assert abs(A - 13.2612) < 1e-3                       # the figure in the docstring
    check_self_crossing(CurvatureWave(7, 1))
    check_self_crossing(CurvatureWave(A - 0.01, 1))
    with pytest.raises(InputError) as e:
        check_self_crossing(CurvatureWave(A + 0.01, 1))
    m = re.fullmatch(r"the gait crosses itself at t = (\S+) s \(s = (\S+) m and (\S+) m of "
                     r"the body\): lower the amplitude.*", str(e.value))
    assert m, str(e.value)
    t, s1, s2 = map(float, m.groups())
    assert t == 0.0 and abs(s1 - 0.1336) < 0.01 and abs(s2 - (1 - 0.1336)) < 0.01


def test_crossing_reports_the_first_time():
    """kappa L = 14 sin(2 pi t / T), uniform along the body: the ends meet when kappa L
    reaches 2 pi, first at t / T = asin(2 pi / 14) / 2 pi = 0.0741, sample 19 of 256."""
    g = FourierGait([(0, 1, 0, 14.0)], period=2.0)
    with pytest.raises(InputError, match=r"at t = 0\.1484 s \(s = 0\.000\d+ m and 0\.99\d m ") as e:
        check_self_crossing(g, samples=256)
    assert "\n" not in str(e.value)
    check_self_crossing(FourierGait([(0, 1, 0, 6.2)], period=2.0))      # kappa L < 2 pi


@pytest.mark.parametrize("gait", [
    SerpenoidChain(10, 2.0, -0.6),                      # large joint angles: curls up
    SerpenoidChain(2, 0.0, 0.0, math.pi),               # the joint folded back
    SerpenoidChain(3, 0.0, 0.0, math.pi),               # both joints: links 0 and 2 meet
    CurvatureWave(40, 2),
])
def test_crossing_gaits_are_refused(gait):
    with pytest.raises(InputError, match="the gait crosses itself at t = "):
        check_self_crossing(gait)


def test_a_loop_across_chunks_is_found():
    """40 links each turned by 2 pi / 20 from the last: a regular 20-gon, closed at the
    joint between links 19 and 20, where link 0 starts (two chunks of 16 links)."""
    with pytest.raises(InputError, match=r"at t = 0 s \(s = 0\.0125 m and 0\.48[78] m "):
        check_self_crossing(SerpenoidChain(40, 0.0, 0.0, 2 * math.pi / 20))
    check_self_crossing(SerpenoidChain(19, 0.0, 0.0, 2 * math.pi / 20))   # open by a link


@pytest.mark.parametrize("gait", [SerpenoidChain(10, 0.5, -0.6), CurvatureWave(100, 20),
                                  CurvatureWave(25, 3)])
def test_open_gaits_pass(gait):
    check_self_crossing(gait)


# ------------------------------------------------------------------------ parameter refusals

@pytest.mark.parametrize("make,field", [
    (lambda: CurvatureWave(amplitude=-1), r"amplitude must be in \[0, 100\], got -1"),
    (lambda: CurvatureWave(amplitude=101), r"amplitude must be in \[0, 100\]"),
    (lambda: CurvatureWave(amplitude=float("nan")), "amplitude must be in .*NaN"),
    (lambda: CurvatureWave(amplitude="7"), "amplitude must be a number"),
    (lambda: CurvatureWave(amplitude=True), "amplitude must be a number"),
    (lambda: CurvatureWave(waves=0), r"waves must be in \(0, 20\]"),
    (lambda: CurvatureWave(waves=21), r"waves must be in \(0, 20\]"),
    (lambda: CurvatureWave(period=0), r"period must be in \[1e-06, 1e\+06\] s"),
    (lambda: CurvatureWave(period=float("inf")), "period must be a finite"),
    (lambda: CurvatureWave(length=2e6), r"length must be in \[1e-06, 1e\+06\] m"),
    (lambda: CurvatureWave(length=-1), "length must be in"),
    (lambda: FourierGait([]), "terms must hold 1 to 64 terms, got 0"),
    (lambda: FourierGait([(1, 1, 1, 0)] * 65), "terms must hold 1 to 64"),
    (lambda: FourierGait([(1, 1, 1)]), r"terms\[0\] must be \(m, n, cos, sin\)"),
    (lambda: FourierGait([(1, 1, 1, 0), (0.5, 1, 1, 0)]), r"terms\[1\].m must be a whole"),
    (lambda: FourierGait([(1, 1, 1, -101)]), r"terms\[0\].sin must be in \[-100, 100\]"),
    (lambda: FourierGait("wave"), "terms must be a list"),
    (lambda: SerpenoidChain(1, 0.1, 0.1), r"links must be a whole number in \[2, 1000\]"),
    (lambda: SerpenoidChain(1001, 0.1, 0.1), r"links must be a whole number in \[2, 1000\]"),
    (lambda: SerpenoidChain(2.5, 0.1, 0.1), "links must be a whole number"),
    (lambda: SerpenoidChain(5, 4.0, 0.1), r"amplitude must be in \[0, 3.14159\] rad"),
    (lambda: SerpenoidChain(5, 0.1, 7.0), "phase must be in"),
    (lambda: SerpenoidChain(5, 0.1, 0.1, offset=-4), "offset must be in"),
    (lambda: JointTable(np.zeros((3, 4))), "angles must have 4 to 100000 rows"),
    (lambda: JointTable([[0.1, 0.2], [0.1]] * 2), "angles must be an array"),
    (lambda: JointTable(np.zeros((5, 0))), r"links must be a whole number in \[2, "),
    (lambda: JointTable(np.full((5, 2), 3.5)), r"angles\[0\]\[0\] must be in \[-pi, pi\]"),
    (lambda: JointTable(np.full((5, 2), np.nan)), "angles must be finite"),
])
def test_parameter_refusals(make, field):
    with pytest.raises(InputError, match=field) as e:
        make()
    assert "\n" not in str(e.value)


@pytest.mark.parametrize("call,field", [
    (lambda g: g.kinematics([0.0], 2), r"n_points must be a whole number in \[3, 100000\]"),
    (lambda g: g.kinematics([0.0], 100001), r"n_points must be a whole number in \[3, 100000\]"),
    (lambda g: g.kinematics([0.0], 5.5), "n_points must be a whole number"),
    (lambda g: g.kinematics([0.0, np.nan], 5), "t must be finite"),
    (lambda g: g.kinematics([[0.0]], 5), "t must have 1 dimension"),
    (lambda g: g.kinematics("now", 5), "t must be a number"),
    (lambda g: g.kinematics([0.0], 5, np.ones(4)), r"weights must have shape \(5\)"),
    (lambda g: g.kinematics([0.0], 5, [1, 1, 0, 1, 1]), "weights must be > 0, got 0 at index 2"),
    (lambda g: g.kinematics([0.0], 5, [1, 1, -1, 1, 1]), "weights must be > 0"),
    (lambda g: g.kinematics([0.0], 5, [1, 1, np.inf, 1, 1]), "weights must be finite"),
    (lambda g: g.kinematics([0.0], 5, lambda s: s - 0.5), "weights must be > 0"),
    (lambda g: g.kinematics([0.0], 5, lambda s: s[:3]), r"weights must have shape \(5\)"),
    (lambda g: check_self_crossing(g, n_points=2), "n_points must be a whole number in"),
    (lambda g: check_self_crossing(g, samples=3), r"samples must be a whole number in \[4, "),
    (lambda g: check_self_crossing(g, tolerance=-1), "tolerance must be in"),
])
def test_call_refusals(call, field):
    with pytest.raises(InputError, match=field) as e:
        call(CurvatureWave())
    assert "\n" not in str(e.value)


def test_params_are_json_safe():
    import json
    for g in all_gaits():
        back = json.loads(json.dumps(g.params()))
        assert back["kind"] == g.kind and back["period"] == g.period
        assert repr(g).startswith(type(g).__name__ + "(")


def test_a_body_turning_through_less_than_half_a_turn_is_cleared_without_positions():
    """The fast path of the crossing check (the tangent angle's span below pi) clears the
    wave exactly where its closed-form span 2 A / (2 pi k) is below pi - margin, and agrees
    with the full pairwise test there."""
    import numpy as np

    from asperity.crawling.gait import CurvatureWave
    from asperity.crawling.gait_crossing import _turns_less_than_half, first_contact
    t = np.arange(64) / 64
    for A, clear in ((2.0, True), (7.0, True), (9.5, True), (10.5, False), (12.0, False)):
        g = CurvatureWave(amplitude=A)
        assert _turns_less_than_half(g, t, 512) is clear, A
        verts, _ = g._polyline(t, 512)
        assert first_contact(verts, 1e-9) is None          # none of these crosses


def test_the_crossing_is_placed_where_the_body_meets_itself():
    """Just past the curl threshold (A = 13.2612 for k = 1) the k = 1 wave touches itself at
    t = 0 at two places symmetric about the middle (s and L - s, s ~ 0.13 L): the message
    names them."""
    import re

    import pytest

    from asperity.crawling.gait import CurvatureWave
    from asperity.crawling.gait_crossing import check_self_crossing
    from asperity.errors import InputError
    with pytest.raises(InputError) as e:
        check_self_crossing(CurvatureWave(amplitude=13.3, length=2.0), n_points=64)
    t, a, b = map(float, re.search(r"t = (\S+) s \(s = (\S+) m and (\S+) m", str(e.value))
                  .groups())
    assert t == 0.0
    assert a + b == pytest.approx(2.0, abs=2 * 2.0 / 512)
    assert 0.05 * 2.0 < a < 0.2 * 2.0


@pytest.mark.parametrize("turn", [0.0, 0.7, 2.0, -2.5])
def test_segment_distance_is_zero_for_crossing_segments_either_way(turn):
    """Two segments crossing in an X (their ends far apart) are at distance 0 whichever way
    each runs and however the pair is turned; parallel ones at their gap; a T at 0."""
    import numpy as np

    from asperity.crawling.gait_crossing import segment_distance
    e = np.exp(1j * turn)
    a, b = e * (-1 + 0.2j), e * (1 - 0.3j)
    c, d = e * (0.1 - 1j), e * (-0.2 + 1j)
    for p1, p2, q1, q2 in ((a, b, c, d), (b, a, c, d), (a, b, d, c), (b, a, d, c),
                           (c, d, a, b)):
        got = segment_distance(*(np.array([z]) for z in (p1, p2, q1, q2)))
        assert got[0] == 0.0
    gap = segment_distance(np.array([e * -1]), np.array([e * 1]), np.array([e * (-1 + 0.5j)]),
                           np.array([e * (1 + 0.5j)]))
    assert gap[0] == pytest.approx(0.5, rel=1e-12)
    tee = segment_distance(np.array([e * -1]), np.array([e * 1]), np.array([e * 0.3]),
                           np.array([e * (0.3 + 1j)]))
    assert tee[0] == pytest.approx(0.0, abs=1e-15)


def test_a_ragged_joint_table_names_the_count_it_expects(tmp_path):
    from asperity.crawling.gait_file import read_gait
    from asperity.errors import InputError
    f = tmp_path / "j.toml"
    rows = ",\n".join("[0.1, 0.2, 0.3]" for _ in range(4))
    f.write_text('[gait]\nkind = "joints"\nlength = 1.0\nperiod = 1.0\nlinks = 6\n'
                 f"angles = [\n{rows}\n]\n")
    with pytest.raises(InputError, match=r"gait.angles\[0\] has 3 values, expected 5 "
                                         r"\(gait.links - 1\)"):
        read_gait(f)
