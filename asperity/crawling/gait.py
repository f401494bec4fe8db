"""Gaits: the shape of a slender body in its own frame over time (issue 26, SPEC.md section 9).

Conventions (the crawl solver is written against them):

* a body of length L (m), arc length s from the tail (0) to the head (L), carried by N
  contact points at the midpoints s_i = (i + 1/2) L / N, i = 0..N-1, with weights w_i > 0,
  sum 1 (mass shares: uniform by default, or a weight profile);
* the **body frame**: origin at the centre of mass sum w_i x_i, orientation such that the
  arc-length mean of the tangent angle is 0 (Hu et al. 2009: thetabar = (1/L) integral of
  theta(s) ds; for a chain of links the length-weighted mean of the link angles).  The world
  orientation of the body is then the mean tangent angle;
* :meth:`Gait.kinematics` gives, at an array of times, the points' positions ``r`` and
  velocities ``v`` (the shape change only: sum w_i v_i = 0, the mean-angle rate is 0) in
  the body frame, the tangent angle at each point (towards the head), the inertia
  sum w_i |r_i|^2 and the internal angular momentum sum w_i r_i x v_i (per unit mass).

Positions are exact to ~1e-13 L whatever N: the unit tangent (cos phi, sin phi), phi in
closed form, is integrated by Gauss-Legendre on sub-intervals between the points, short
enough for the curvature and the wave number (error below 1e-13 L per unit length by
the Gauss-Legendre estimate).  Velocities are integrated the same way from the analytic rate,
dx/dt(s) = integral_0^s (-sin phi, cos phi) dphi/dt ds', not by differences in time; the
centre-of-mass velocity is then removed (the mean-angle rate is zero by construction).
The centre of mass is the weighted sum over the N points: with uniform weights it is the
midpoint rule of the continuous centroid, so r_i (and I, h) converge to the continuous
body's as O(N^-2); faster than any power of N when the tangent angle is periodic in s (a
whole number of waves and no static bend: the end terms of the Euler-Maclaurin error
cancel).

Gaits here: :class:`CurvatureWave` (kappa L = A cos 2 pi (k s / L + t / T)) and
:class:`FourierGait` (kappa L as a Fourier series in s and t, the gait files' "fourier"
kind).  Chains of rigid links are in :mod:`.gait_chain`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_array, check_int, check_range, is_array

LENGTH_RANGE = (1e-6, 1e6)          #: m
PERIOD_RANGE = (1e-6, 1e6)          #: s
AMPLITUDE_RANGE = (0.0, 100.0)      #: A, the curvature wave's kappa L amplitude
WAVES_RANGE = (0.0, 20.0)           #: k (low end open)
COEFFICIENT_RANGE = (-100.0, 100.0)  #: a Fourier term's cos and sin (kappa L)
HARMONIC_RANGE = (-50, 50)          #: a Fourier term's m (in s) and n (in t)
MAX_TERMS = 64
POINTS_RANGE = (3, 100_000)
#: nodes per chunk of times when integrating (bounds the temporaries: ~32 bytes a node)
_CHUNK_NODES = 2_000_000
#: Gauss-Legendre error per unit length allowed, by the estimate c_G (h scale)^(2G)
_QUAD_TOL = 1e-13


@dataclass(frozen=True, eq=False)
class Kinematics:
    """A gait at ``nt`` times on N points, in the body frame (per unit mass).

    t : (nt,) s; s : (N,) m, arc length from the tail; weights : (N,), sum 1;
    r : (nt, N, 2) m, positions; v : (nt, N, 2) m/s, their time derivative (shape change
    only); tangent : (nt, N) rad, tangent angle towards the head; inertia : (nt,) m^2,
    sum w |r|^2; spin : (nt,) m^2/s, sum w r x v.
    """

    t: np.ndarray
    s: np.ndarray
    weights: np.ndarray
    r: np.ndarray
    v: np.ndarray
    tangent: np.ndarray
    inertia: np.ndarray
    spin: np.ndarray


def midpoints(n_points, length: float) -> np.ndarray:
    """s_i = (i + 1/2) L / N, i = 0..N-1 (m), after checking N."""
    n = check_int("n_points", n_points, *POINTS_RANGE)
    return (np.arange(n) + 0.5) * (length / n)


def point_weights(weights, s: np.ndarray, length: float) -> np.ndarray:
    """The points' mass shares (N,), sum 1: uniform for None, else a callable of s (m)
    giving N values or an array of N values, each finite and > 0, normalised."""
    n = s.size
    if weights is None:
        return np.full(n, 1.0 / n)
    if callable(weights):
        values = weights(s.copy())
        if np.ndim(values) == 0:          # a constant profile
            values = np.full(n, check_range("weights", values))
    else:
        values = weights
    w = check_array("weights", values, shape=(n,))
    bad = np.flatnonzero(w <= 0)
    if bad.size:
        raise InputError(f"weights must be > 0, got {w[bad[0]]:g} at index {bad[0]}")
    total = float(w.sum())
    if not math.isfinite(total) or total <= 0:
        raise InputError("weights must sum to a finite positive number")
    return w / total


def check_times(t) -> np.ndarray:
    """Times (s) as a finite 1-D array (a single number gives one time)."""
    if is_array(t):
        return check_array("t", t, ndim=1, min_size=1)
    return np.array([check_range("t", t)])


class Gait:
    """A prescribed shape of the body over one period.  Subclasses give ``_curve(t, s)``:
    at times t (nt,) and sorted arc lengths s (ns,), the positions x + i y (any origin,
    zero-mean tangent angle) and their rates, (nt, ns) complex, and the tangent angles."""

    kind = ""
    length: float
    period: float
    name: str

    def params(self) -> dict:                    # pragma: no cover - every subclass has one
        raise NotImplementedError

    def _curve(self, t: np.ndarray, s: np.ndarray):   # pragma: no cover
        raise NotImplementedError

    def kinematics(self, t, n_points, weights=None) -> Kinematics:
        """The gait at times ``t`` (s, array (nt,)) on ``n_points`` points at the midpoints,
        weighted by ``weights`` (None: uniform; a callable of s in m or N values > 0)."""
        from ..resources import check_memory
        t = check_times(t)
        s = midpoints(n_points, self.length)
        w = point_weights(weights, s, self.length)
        check_memory(t.size * s.size * 8.0 * 10, f"the gait's kinematics at {t.size} times "
                     f"x {s.size} points", "ask for fewer times or points")
        z, zd, tangent = self._curve(t, s)        # x + i y and its rate, (nt, N) complex
        for a in (z, zd):                         # the centre of mass and its velocity
            a -= (a.real @ w + 1j * (a.imag @ w))[:, None]
        inertia = (z.real ** 2 + z.imag ** 2) @ w
        spin = (z.real * zd.imag - z.imag * zd.real) @ w
        r, v = (np.ascontiguousarray(a).view(np.float64).reshape(t.size, s.size, 2)
                for a in (z, zd))
        return Kinematics(t, s, w, r, v, tangent, inertia, spin)

    def _polyline(self, t: np.ndarray, segments: int):
        """The body as a polyline of ``segments`` equal segments at times ``t``: vertices
        x + i y (nt, segments + 1) complex in a frame of the body (to 1e-10 L), and their
        arc lengths (m)."""
        s = np.linspace(0.0, self.length, segments + 1)
        return self._curve(t, s, rates=False, tol=1e-10)[0], s

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.params().items() if k != "kind")
        return f"{type(self).__name__}({args})"


def _check_size(length, period) -> tuple[float, float]:
    return (check_range("length", length, *LENGTH_RANGE, unit="m"),
            check_range("period", period, *PERIOD_RANGE, unit="s"))


class _CurvatureGait(Gait):
    """kappa(s, t) L = sum_j c_j cos 2 pi (m_j s / L + n_j t / T)
    + d_j sin 2 pi (m_j s / L + n_j t / T).

    The tangent angle psi = integral_0^s kappa is separable, psi(s, t) = sum_q G_q(t) F_q(s)
    with F = sin(2 pi m s / L), cos(2 pi m s / L) (or s / L where m = 0): the zero-mean
    angle phi = psi - (1/L) integral psi ds takes F_q minus its arc-length mean.
    """

    def _setup(self, m, n, c, d, length: float, period: float) -> None:
        self.length, self.period = float(length), float(period)
        self._m, self._n = np.asarray(m, float), np.asarray(n, float)
        self._c, self._d = np.asarray(c, float), np.asarray(d, float)
        #: the scale (1/m) of the tangent's derivatives: curvature plus wave number
        self._scale = (float(np.sum(np.abs(self._c) + np.abs(self._d)))
                       + 2 * math.pi * float(np.max(np.abs(self._m)))) / self.length

    def _basis(self, s: np.ndarray) -> np.ndarray:
        """F_q(s) minus its mean over [0, L]: (ns, 2 * terms)."""
        x = s / self.length
        out = np.zeros((s.size, 2 * self._m.size))
        for j, m in enumerate(self._m):
            if m == 0:
                out[:, 2 * j] = x - 0.5
                continue
            a = 2 * math.pi * m
            out[:, 2 * j] = np.sin(a * x) - (1 - math.cos(a)) / a
            out[:, 2 * j + 1] = np.cos(a * x) - math.sin(a) / a
        return out

    def _amplitudes(self, t: np.ndarray):
        """G_q(t) and dG_q/dt: (nt, 2 * terms) each."""
        beta = 2 * math.pi * np.mod(t / self.period, 1.0)[:, None] * self._n
        cb, sb = np.cos(beta), np.sin(beta)
        p = self._c * cb + self._d * sb           # sin(alpha) coefficient (times 2 pi m)
        q = self._c * sb - self._d * cb           # cos(alpha) coefficient
        rate = 2 * math.pi * self._n / self.period
        zero = self._m == 0
        g1 = np.where(zero, 1.0, 1.0 / np.where(zero, 1.0, 2 * math.pi * self._m))
        g2 = np.where(zero, 0.0, g1)
        g = np.empty((t.size, 2 * self._m.size))
        gt = np.empty_like(g)
        g[:, 0::2], g[:, 1::2] = p * g1, q * g2
        gt[:, 0::2], gt[:, 1::2] = -rate * q * g1, rate * p * g2
        return g, gt

    def tangent_angle(self, t, s) -> tuple[np.ndarray, np.ndarray]:
        """phi(s, t) (rad, body frame: zero arc-length mean) and dphi/dt (rad/s) at times
        ``t`` (nt,) and arc lengths ``s`` (ns,) m: (nt, ns) each."""
        t = check_times(t)
        s = check_array("s", np.atleast_1d(s), ndim=1)
        f = self._basis(s)
        g, gt = self._amplitudes(t)
        return _combine(g, f), _combine(gt, f)

    def _nodes(self, s: np.ndarray, tol: float = _QUAD_TOL):
        """Gauss-Legendre nodes and weights on [0, s_0], [s_0, s_1], ...: each interval cut
        into the same number of sub-intervals, h * scale <= 1, the order G chosen for the
        error bound.  Returns nodes and weights, (nodes per interval, ns) each: node j of
        every interval in row j (the sums over an interval's nodes add whole rows)."""
        edges = np.concatenate(([0.0], s))
        h = np.diff(edges)
        parts = max(1, math.ceil(float(np.max(h)) * self._scale))
        worst = float(np.max(h)) / parts * self._scale
        order = 2
        while order < 8 and _gl_error(order) * worst ** (2 * order) > tol:
            order += 1
        xg, wg = np.polynomial.legendre.leggauss(order)
        u = ((np.arange(parts)[:, None] + 0.5 * (xg + 1)) / parts).ravel()    # on [0, 1]
        nodes = edges[:-1] + u[:, None] * h
        weights = np.tile(wg / (2 * parts), parts)[:, None] * h
        return nodes, weights

    def _curve(self, t: np.ndarray, s: np.ndarray, rates: bool = True,
               tol: float = _QUAD_TOL):
        nodes, wq = self._nodes(s, tol)
        shape = (-1,) + nodes.shape                       # (times, nodes per interval, ns)
        wq = wq.ravel()
        f_nodes, f_pts = self._basis(nodes.ravel()), self._basis(s)
        z = np.empty((t.size, s.size), complex)
        zd = np.empty_like(z)
        tangent = np.empty((t.size, s.size))
        step = max(1, _CHUNK_NODES // wq.size)
        for a in range(0, t.size, step):
            b = min(a + step, t.size)
            g, gt = self._amplitudes(t[a:b])
            phi = _combine(g, f_nodes)
            c, sn = np.cos(phi), np.sin(phi)
            z.real[a:b] = np.cumsum((c * wq).reshape(shape).sum(1), axis=1)
            z.imag[a:b] = np.cumsum((sn * wq).reshape(shape).sum(1), axis=1)
            tangent[a:b] = _combine(g, f_pts)
            if not rates:
                continue
            rate = _combine(gt, f_nodes)
            rate *= wq
            c *= rate
            sn *= rate
            zd.real[a:b] = -np.cumsum(sn.reshape(shape).sum(1), axis=1)
            zd.imag[a:b] = np.cumsum(c.reshape(shape).sum(1), axis=1)
        return z, zd, tangent


def _combine(g: np.ndarray, f: np.ndarray) -> np.ndarray:
    """sum_q g[:, q] f[:, q]: (nt, ns) from (nt, K) and (ns, K); products of two columns
    each for a few terms (a threaded BLAS call costs milliseconds on a busy machine)."""
    if g.shape[1] > 8:
        return g @ f.T
    out = np.multiply.outer(g[:, 0], f[:, 0])
    for q in range(1, g.shape[1]):
        out += np.multiply.outer(g[:, q], f[:, q])
    return out


def _gl_error(order: int) -> float:
    """The constant of the G-point Gauss-Legendre error on an interval of length h,
    h^(2G+1) (G!)^4 / ((2G+1) ((2G)!)^3) f^(2G), per unit length and f^(2G) ~ scale^(2G)."""
    g = math.factorial(order)
    return g ** 4 / ((2 * order + 1) * math.factorial(2 * order) ** 3)


class CurvatureWave(_CurvatureGait):
    """The travelling curvature wave of Hu et al. (2009): kappa(s, t) L =
    A cos 2 pi (k s / L + t / T), s from the tail (0) to the head (L).

    The wave runs from the head to the tail (its crests move towards s = 0), so the body
    crawls towards its head on friction with mu_t > mu_f.  The tangent angle has the closed
    form phi = (A / 2 pi k) [sin 2 pi (k s / L + t / T) - mean].  Shifting t by T/2 changes
    the sign of kappa: the shape at t + T/2 is the mirror image of the shape at t (r_y ->
    -r_y in the body frame), for every k.

    amplitude : A = kappa L amplitude, in [0, 100] (7 by default: Hu et al.'s snakes);
    waves : k, waves on the body, in (0, 20]; period : T (s); length : L (m).
    Self-contact: a k = 1 wave first touches itself at A = 13.2612, at t = 0 (and T/2),
    where s = 0.134 L and 0.866 L meet on the body's axis of symmetry (found by
    :func:`~.gait_crossing.check_self_crossing` and, independently, from
    integral_s^(L/2) cos((A / 2 pi) sin 2 pi u / L) du = 0); above it the wave is refused.
    """

    kind = "curvature_wave"

    def __init__(self, amplitude=7.0, waves=1.0, period=1.0, length=1.0):
        self.amplitude = check_range("amplitude", amplitude, *AMPLITUDE_RANGE)
        self.waves = check_range("waves", waves, *WAVES_RANGE, low_open=True)
        length, period = _check_size(length, period)
        self._setup([self.waves], [1.0], [self.amplitude], [0.0], length, period)
        self.name = f"curvature wave A = {self.amplitude:g}, k = {self.waves:g}"

    def params(self) -> dict:
        return {"kind": self.kind, "amplitude": self.amplitude, "waves": self.waves,
                "period": self.period, "length": self.length}


class FourierGait(_CurvatureGait):
    """Curvature as a Fourier series in s and t: kappa(s, t) L = sum over the terms of
    cos * cos 2 pi (m s / L + n t / T) + sin * sin 2 pi (m s / L + n t / T).

    terms : a sequence of (m, n, cos, sin) or of dicts with those keys; m and n whole
    numbers in [-50, 50] (n = 0: a static curvature; m = 0: a curvature uniform along
    the body), cos and sin in [-100, 100]; at most 64 terms.  A term with n > 0 and m > 0
    is a wave running from the head to the tail (m / n < 0: from the tail to the head).
    """

    kind = "fourier"

    def __init__(self, terms, period=1.0, length=1.0, name: str | None = None):
        rows = fourier_terms(terms)
        length, period = _check_size(length, period)
        m, n, c, d = (np.array([row[i] for row in rows], float) for i in range(4))
        self._setup(m, n, c, d, length, period)
        self.terms = tuple(rows)
        self.name = name if name is not None else f"fourier gait ({len(rows)} terms)"

    def params(self) -> dict:
        return {"kind": self.kind, "period": self.period, "length": self.length,
                "terms": [{"m": m, "n": n, "cos": c, "sin": d} for m, n, c, d in self.terms]}


def fourier_terms(terms, prefix: str = "") -> list[tuple[int, int, float, float]]:
    """The terms of a :class:`FourierGait`, checked, as (m, n, cos, sin) tuples; fields
    named as ``{prefix}terms[2].cos``."""
    if isinstance(terms, (str, bytes, dict)) or not hasattr(terms, "__len__"):
        raise InputError(f"{prefix}terms must be a list of (m, n, cos, sin) terms")
    if not 1 <= len(terms) <= MAX_TERMS:
        raise InputError(f"{prefix}terms must hold 1 to {MAX_TERMS} terms, got {len(terms)}")
    rows = []
    for i, term in enumerate(terms):
        where = f"{prefix}terms[{i}]"
        if isinstance(term, dict):
            unknown = sorted(set(term) - {"m", "n", "cos", "sin"})
            if unknown:
                raise InputError(f"unknown key {where}.{unknown[0]}; allowed: cos, m, n, sin")
            for k in ("m", "n"):
                if k not in term:
                    raise InputError(f"missing key {where}.{k}")
            if "cos" not in term and "sin" not in term:
                raise InputError(f"missing key {where}.cos (or {where}.sin): the term's "
                                 f"amplitude")
            values = (term["m"], term["n"], term.get("cos", 0.0), term.get("sin", 0.0))
        else:
            if isinstance(term, (str, bytes)) or not hasattr(term, "__len__") \
                    or len(term) != 4:
                raise InputError(f"{where} must be (m, n, cos, sin), four numbers")
            values = tuple(term)
        rows.append((check_int(f"{where}.m", values[0], *HARMONIC_RANGE),
                     check_int(f"{where}.n", values[1], *HARMONIC_RANGE),
                     check_range(f"{where}.cos", values[2], *COEFFICIENT_RANGE),
                     check_range(f"{where}.sin", values[3], *COEFFICIENT_RANGE)))
    return rows
