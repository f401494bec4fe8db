"""Friction laws from directional friction: gauges and the Walker-Leine law (SPEC.md section 3).

Forces are per unit normal load (dimensionless), in the frame of the reservoir they come
from (wedge textures: ``t_a``, ``t_b``; surfaces: ``x``, ``y`` of the file).  Angles are in
radians: ``psi`` is a sliding direction ``s = (cos psi, sin psi)``, ``phi`` the polar angle of
a force.

Sets (each answers ``radial(phi)``, ``gauge(x)``; the convex ones also ``support(psi)`` and
``normal_point(psi)``, the boundary point whose outward normal is ``s(psi)``):

* :class:`Disc` -- isotropic Coulomb;
* :class:`TruncatedEllipse` -- Antoni et al. eq. 18: four quarter ellipses with semi-axes
  ``mu_a+/-`` along ``+-t_a`` and ``mu_b+/-`` along ``+-t_b`` (``t_a`` at angle ``theta``);
  convex and C1;
* :class:`StarSet` -- a star-shaped set given by a closed polygon sorted by polar angle, so
  that straight segments (windward, sliding along the ridges) are exact and non-convex
  shapes are followed; ``k_C(x) = |x| / rho(angle x)``;
* :class:`ConvexSet` -- a convex set ``D`` given by samples of its support function ``h`` and
  of ``h'``.  Between samples ``h'/h`` is linear in ``psi`` (so ``ln h`` is the exact
  trapezoidal integral of it); a repeated ``psi`` with two values of ``h'`` is a flat edge
  of ``D`` (a set-valued sliding direction).

:class:`WalkerLeineLaw` ``(C, D)``: for a sliding direction ``s`` the point ``y`` of the
boundary of ``D`` with outward normal ``s``, then ``p = -lambda_T/lambda_N`` is the point of
the boundary of ``C`` on the ray of ``y``, and ``alpha = 1/(k_D(p) - k_C(p) + 1)``.
``C = D = Disc`` is Coulomb, ``C = D = TruncatedEllipse`` the associated (normal-rule) law.

Fits: :func:`fit_truncated_ellipse` (4 parameters, least squares on the relative radial
error) and :func:`fit_star` (``C`` through the data, ``D`` integrated from the sliding rule
``d ln h / d psi = tan(angle(p) - psi)``).  :func:`fit_derivation` does either from a
:class:`~asperity.derive.Derivation` and checks the law at directions not used in the fit.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .closed_form import Reservoir
from .errors import InputError

TWO_PI = 2.0 * math.pi
LAW_KINDS = ("truncated-ellipse", "star")


@dataclass(frozen=True)
class GaugeTolerances:
    """The tolerances of this module, in one place."""

    #: a polygon vertex whose turning angle (rad) is >= -convexity counts as convex
    convexity: float = 1e-9
    #: (h + h'')/h >= -convexity counts as a convex D
    curvature: float = 1e-9
    #: two reservoir points whose polar angles differ by less than this (rad) are one vertex
    #: if their radii agree to ``same_point`` (relative); otherwise the data is not star-shaped
    same_angle: float = 1e-12
    same_point: float = 1e-9
    #: offset (rad) of the one-sided limits evaluated beside a set-valued direction
    set_valued_eps: float = 1e-7
    #: a sliding direction within this (rad) of a flat edge of D is set-valued
    edge: float = 1e-9
    #: ln h of stored support-function samples must match the integral of h'/h to this
    support_consistency: float = 1e-9
    #: p.s below -dissipation counts as negative dissipation
    dissipation: float = 1e-12


TOL = GaugeTolerances()


# ----------------------------------------------------------------------------- helpers

def unit(angle) -> np.ndarray:
    """(m, 2) unit vectors at the angles ``angle`` (rad)."""
    a = np.atleast_1d(np.asarray(angle, dtype=float))
    return np.column_stack([np.cos(a), np.sin(a)])


def polar_angle(x) -> np.ndarray:
    """(m,) polar angles in (-pi, pi] of the (m, 2) vectors ``x``."""
    x = np.atleast_2d(np.asarray(x, dtype=float))
    return np.arctan2(x[:, 1], x[:, 0])


def _cross(a, b) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _psi(psi) -> np.ndarray:
    psi = np.atleast_1d(np.asarray(psi, dtype=float))
    if not np.all(np.isfinite(psi)):
        raise InputError("psi must be finite")
    return psi


def angle_between(a, b) -> np.ndarray:
    """(m,) unsigned angles (rad) between the rows of the (m, 2) arrays a and b."""
    return np.abs(np.arctan2(_cross(a, b), np.einsum("ij,ij->i", a, b)))


# ----------------------------------------------------------------------------- sets

@dataclass(frozen=True)
class Disc:
    """The disc of radius ``mu``: the isotropic Coulomb set."""

    mu: float
    kind = "disc"

    def __post_init__(self):
        if not (math.isfinite(self.mu) and self.mu > 0):
            raise InputError(f"mu must be in (0, inf), got {self.mu!r}")

    def radial(self, phi) -> np.ndarray:
        return np.full(np.shape(np.atleast_1d(phi)), float(self.mu))

    def gauge(self, x) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, dtype=float))
        return np.hypot(x[:, 0], x[:, 1]) / self.mu

    def support(self, psi) -> np.ndarray:
        return self.radial(psi)

    def normal_point(self, psi):
        y = self.mu * unit(_psi(psi))
        return y, y, y


@dataclass(frozen=True)
class TruncatedEllipse:
    """Antoni et al. eq. 18: ``k(x) = sqrt((x_a/mu_a+-)^2 + (x_b/mu_b+-)^2)``.

    The sign of ``x_a`` (component along ``t_a``) picks ``mu_a+`` or ``mu_a-``, that of
    ``x_b`` picks ``mu_b+`` or ``mu_b-``.  ``theta``: angle (rad) of ``t_a`` in the frame of
    the vectors (0 for wedge textures).  Convex and C1: the quarter ellipses meet on the
    axes with a common tangent.
    """

    mu_a_plus: float
    mu_a_minus: float
    mu_b_plus: float
    mu_b_minus: float
    theta: float = 0.0
    kind = "truncated-ellipse"

    def __post_init__(self):
        for name in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{name} must be in (0, inf), got {v!r}")
        if not math.isfinite(self.theta):
            raise InputError(f"theta must be finite, got {self.theta!r}")

    @property
    def axes(self) -> dict:
        return {"mu_a_plus": self.mu_a_plus, "mu_a_minus": self.mu_a_minus,
                "mu_b_plus": self.mu_b_plus, "mu_b_minus": self.mu_b_minus}

    def _local(self, x) -> np.ndarray:
        c, s = math.cos(self.theta), math.sin(self.theta)
        x = np.atleast_2d(np.asarray(x, dtype=float))
        return np.column_stack([c * x[:, 0] + s * x[:, 1], -s * x[:, 0] + c * x[:, 1]])

    def _global(self, x) -> np.ndarray:
        c, s = math.cos(self.theta), math.sin(self.theta)
        return np.column_stack([c * x[:, 0] - s * x[:, 1], s * x[:, 0] + c * x[:, 1]])

    def _semi_axes(self, xl):
        A = np.where(xl[:, 0] >= 0, self.mu_a_plus, self.mu_a_minus)
        B = np.where(xl[:, 1] >= 0, self.mu_b_plus, self.mu_b_minus)
        return A, B

    def gauge(self, x) -> np.ndarray:
        xl = self._local(x)
        A, B = self._semi_axes(xl)
        return np.hypot(xl[:, 0] / A, xl[:, 1] / B)

    def radial(self, phi) -> np.ndarray:
        return 1.0 / self.gauge(unit(phi))

    def support(self, psi) -> np.ndarray:
        sl = self._local(unit(_psi(psi)))
        A, B = self._semi_axes(sl)
        return np.hypot(A * sl[:, 0], B * sl[:, 1])

    def normal_point(self, psi):
        """The boundary point with outward normal s(psi): (A^2 s_a, B^2 s_b) / h(s)."""
        sl = self._local(unit(_psi(psi)))
        A, B = self._semi_axes(sl)
        h = np.hypot(A * sl[:, 0], B * sl[:, 1])
        y = self._global(np.column_stack([A * A * sl[:, 0], B * B * sl[:, 1]]) / h[:, None])
        return y, y, y

    def criterion(self, tau, sigma_n) -> np.ndarray:
        """Antoni et al. eq. 18: g = k(tau) - sigma_n (<= 0: stick), tau (m, 2) stresses."""
        return self.gauge(tau) - np.asarray(sigma_n, dtype=float)


@dataclass(frozen=True)
class StarSet:
    """Star-shaped set (origin inside) given by a closed polygon sorted by polar angle.

    points : (n, 2) float, n >= 3, the boundary vertices in counter-clockwise order of
             strictly increasing polar angle, each step of angle below pi (the polygon is
             closed from the last vertex back to the first).
    The radial function is exact on straight edges; non-convex outlines are followed.
    """

    points: np.ndarray
    angles: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        pts = np.array(self.points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or pts.shape[0] < 3:
            raise InputError(f"points must have shape (n, 2) with n >= 3, got {pts.shape}")
        if not np.all(np.isfinite(pts)):
            raise InputError("points must be finite")
        r = np.hypot(pts[:, 0], pts[:, 1])
        if np.any(r <= 0):
            raise InputError(f"points must not contain the origin (point {int(np.argmin(r))})")
        phi = polar_angle(pts)
        step = np.mod(np.diff(np.append(phi, phi[0])), TWO_PI)
        if abs(step.sum() - TWO_PI) > 1e-9 or np.any(step <= 0) or np.any(step >= math.pi):
            k = int(np.argmin(np.where(step > 0, step, -1.0))) if np.any(step <= 0) else \
                int(np.argmax(step))
            raise InputError(
                f"points must go once round the origin in increasing polar angle with steps "
                f"in (0, 180) deg; step {k} -> {(k + 1) % pts.shape[0]} is "
                f"{math.degrees(step[k]):.6g} deg (winding {math.degrees(step.sum()):.6g} deg)")
        pts.setflags(write=False)
        ang = phi[0] + np.concatenate([[0.0], np.cumsum(step)])   # (n+1,), ang[n] = ang[0]+2pi
        ang.setflags(write=False)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "angles", ang)

    @property
    def n(self) -> int:
        return self.points.shape[0]

    def _edge(self, phi):
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        a0 = self.angles[0]
        pm = a0 + np.mod(phi - a0, TWO_PI)
        k = np.clip(np.searchsorted(self.angles, pm, side="right") - 1, 0, self.n - 1)
        return k, pm

    def radial(self, phi) -> np.ndarray:
        """rho(phi): distance from the origin to the boundary along the ray phi (ray-edge
        intersection, exact for the polygon)."""
        k, pm = self._edge(phi)
        v0 = self.points[k]
        d = self.points[(k + 1) % self.n] - v0
        u = unit(pm)
        return _cross(v0, d) / _cross(u, d)

    def gauge(self, x) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, dtype=float))
        r = np.hypot(x[:, 0], x[:, 1])
        out = np.zeros(r.shape)
        nz = r > 0
        out[nz] = r[nz] / self.radial(polar_angle(x[nz]))
        return out

    def turning_angles(self) -> np.ndarray:
        """(n,) signed turning angle (rad) of the boundary at each vertex (>= 0: convex)."""
        e_in = self.points - np.roll(self.points, 1, axis=0)
        e_out = np.roll(self.points, -1, axis=0) - self.points
        return np.arctan2(_cross(e_in, e_out), np.einsum("ij,ij->i", e_in, e_out))

    def is_convex(self, tol: float = TOL.convexity) -> bool:
        """Convex if no vertex turns clockwise by more than ``tol`` rad."""
        return bool(self.turning_angles().min() >= -tol)

    def support(self, psi) -> np.ndarray:
        """Support function of the convex hull: max over the vertices of v . s."""
        return (unit(_psi(psi)) @ self.points.T).max(axis=1)


def tan_integral(delta0, delta1, length, t):
    """Integral from 0 to t of tan(delta(u)) du, delta linear from delta0 (u = 0) to delta1
    (u = length): ``length/(delta1 - delta0) * ln(cos delta0 / cos delta(t))``, evaluated
    without cancellation (log1p), and ``t tan delta0`` when delta is constant."""
    delta0, delta1, length, t = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in
                                                      (delta0, delta1, length, t)))
    dd = (delta1 - delta0) * (t / length)                   # change of delta over [0, t]
    dt = delta0 + dd
    x = np.tan(dt) * np.sin(dd) - 2.0 * np.sin(0.5 * dd) ** 2   # cos(delta0)/cos(dt) - 1
    safe = np.where(dd != 0, dd, 1.0)
    return np.where(dd != 0, np.log1p(x) * t / safe, t * np.tan(delta0))


@dataclass(frozen=True)
class ConvexSet:
    """Convex set ``D`` from samples of its support function.

    psi : (n,) float, non-decreasing sliding directions (rad), psi[-1] < psi[0] + 2 pi;
          a value may appear twice (a flat edge of D: h' jumps there)
    h   : (n,) float, support function h_D(psi) > 0
    dh  : (n,) float, h'(psi) (left and right values at a flat edge)

    The boundary point with outward normal s(psi) is ``y = h s + h' s_perp``; its polar
    angle is ``psi + delta`` with ``delta = atan(h'/h)``.  Between distinct samples delta is
    linear in psi and ``ln h`` its exact integral ``int tan(delta) dpsi``, so the samples must
    satisfy ``ln h[k+1] - ln h[k] = tan_integral(...)`` (also across the wrap to
    psi[0] + 2 pi).  D is convex iff h + h'' = h (1 + g^2)(1 + delta') >= 0, i.e. iff the
    polar angle of y never decreases: delta' >= -1 on every interval and delta does not
    drop at a flat edge.
    """

    psi: np.ndarray
    h: np.ndarray
    dh: np.ndarray
    boundary: StarSet = field(init=False, repr=False, compare=False)
    edges: np.ndarray = field(init=False, repr=False, compare=False)

    #: boundary samples per interval for the radial function of D
    SUBDIVISIONS = 4

    def __post_init__(self):
        psi = np.array(self.psi, dtype=float)
        h = np.array(self.h, dtype=float)
        dh = np.array(self.dh, dtype=float)
        n = psi.size
        if psi.ndim != 1 or n < 3 or h.shape != psi.shape or dh.shape != psi.shape:
            raise InputError(f"psi, h and dh must have the same shape (n,), n >= 3, got "
                             f"{psi.shape}, {h.shape}, {dh.shape}")
        for name, a in (("psi", psi), ("h", h), ("dh", dh)):
            if not np.all(np.isfinite(a)):
                raise InputError(f"{name} must be finite (index {int(np.argmin(np.isfinite(a)))})")
        if np.any(h <= 0):
            raise InputError(f"h must be > 0, got {h.min():g} at index {int(np.argmin(h))}")
        step = np.diff(psi)
        if np.any(step < 0) or not psi[-1] < psi[0] + TWO_PI:
            raise InputError("psi must be non-decreasing over less than a full turn")
        if np.any((step[1:] == 0) & (step[:-1] == 0)):
            raise InputError("psi may repeat a value at most twice (a flat edge)")
        for a in (psi, h, dh):
            a.setflags(write=False)
        object.__setattr__(self, "psi", psi)
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "dh", dh)
        lnh, delta = self.ln_h, self.delta
        k0, k1, d = self._intervals()
        integral = tan_integral(delta[k0], delta[k1], d, d)
        jump = lnh[k1] - lnh[k0] - integral
        bad = np.abs(jump) > TOL.support_consistency * (1.0 + np.abs(lnh[k0]))
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise InputError(
                f"h and dh are not a consistent support function: ln h changes by "
                f"{lnh[k1[k]] - lnh[k0[k]]:.6g} from psi = {math.degrees(psi[k0[k]]):.6g} deg to "
                f"{math.degrees(psi[k1[k]]):.6g} deg, the integral of h'/h gives {integral[k]:.6g}")
        same = step == 0
        edges = psi[:-1][same]
        edges.setflags(write=False)
        object.__setattr__(self, "edges", edges)
        if self.min_turn_rate() < -TOL.curvature:
            raise InputError(f"D is not convex: the polar angle of its boundary point turns back "
                             f"(d angle / d psi = {self.min_turn_rate():.6g} < 0)")
        # boundary polygon (inscribed) for the radial function and gauge of D
        m = self.SUBDIVISIONS
        t = (np.arange(m) / m)[None, :] * d[:, None]                      # (intervals, m)
        q = (psi[k0][:, None] + t).ravel()
        pts = self._point(np.repeat(k0, m), t.ravel(), q)
        # the near end of a flat edge (left value of h') ends the interval before it
        ends = np.flatnonzero(same)
        if ends.size:
            pe = self._point(ends, np.zeros(ends.size), psi[ends])
            pts = np.insert(pts, np.searchsorted(q, psi[ends], side="left"), pe, axis=0)
        object.__setattr__(self, "boundary", StarSet(_dedupe(pts)))

    @property
    def g(self) -> np.ndarray:
        """(n,) h'/h at the samples."""
        return self.dh / self.h

    @property
    def delta(self) -> np.ndarray:
        """(n,) atan(h'/h): angle from s(psi) to the boundary point with that normal."""
        return np.arctan2(self.dh, self.h)

    @property
    def ln_h(self) -> np.ndarray:
        return np.log(self.h)

    def _intervals(self):
        """(k0, k1, length) of the intervals between distinct consecutive samples, the last
        one wrapping round to psi[0] + 2 pi."""
        n = self.psi.size
        k0 = np.arange(n)
        k1 = (k0 + 1) % n
        d = np.where(k1 > k0, self.psi[k1] - self.psi[k0], self.psi[k1] + TWO_PI - self.psi[k0])
        keep = d > 0
        return k0[keep], k1[keep], d[keep]

    def _locate(self, psi):
        """Sample k at or before each psi (the right-hand one at a flat edge) and psi - psi_k."""
        p0 = self.psi[0]
        pm = p0 + np.mod(psi - p0, TWO_PI)
        k = np.clip(np.searchsorted(self.psi, pm, side="right") - 1, 0, self.psi.size - 1)
        return k, pm - self.psi[k]

    def _lnh_delta(self, k, t):
        n = self.psi.size
        k1 = (k + 1) % n
        d = np.where(k1 > k, self.psi[k1] - self.psi[k], self.psi[k1] + TWO_PI - self.psi[k])
        d0, d1 = self.delta[k], self.delta[k1]
        safe = np.where(d > 0, d, 1.0)
        return self.ln_h[k] + tan_integral(d0, d1, safe, t), d0 + (d1 - d0) * t / safe

    def _point(self, k, t, psi):
        lnh, delta = self._lnh_delta(k, t)
        return (np.exp(lnh) / np.cos(delta))[:, None] * unit(psi + delta)

    def support(self, psi) -> np.ndarray:
        psi = _psi(psi)
        k, t = self._locate(psi)
        return np.exp(self._lnh_delta(k, t)[0])

    def normal_point(self, psi):
        """(y, y_minus, y_plus): the boundary point(s) with outward normal s(psi).

        Away from a flat edge the three are equal; on one (|psi - edge| <= TOL.edge) the
        normal cone holds the whole edge from y_minus to y_plus and y is its midpoint."""
        psi = _psi(psi)
        k, t = self._locate(psi)
        y = self._point(k, t, psi)
        ym, yp = y.copy(), y.copy()
        if self.edges.size:
            p0 = self.psi[0]
            diff = np.mod(psi[:, None] - self.edges[None, :] + math.pi, TWO_PI) - math.pi
            hit = np.abs(diff) <= TOL.edge
            for i in np.flatnonzero(hit.any(axis=1)):
                e = self.edges[int(np.argmax(hit[i]))]
                j = int(np.searchsorted(self.psi, p0 + np.mod(e - p0, TWO_PI), side="left"))
                ym[i] = self._point(np.array([j]), np.zeros(1), self.psi[j:j + 1])[0]
                yp[i] = self._point(np.array([j + 1]), np.zeros(1), self.psi[j + 1:j + 2])[0]
                y[i] = 0.5 * (ym[i] + yp[i])
        return y, ym, yp

    def radial(self, phi) -> np.ndarray:
        return self.boundary.radial(phi)

    def gauge(self, x) -> np.ndarray:
        return self.boundary.gauge(x)

    def min_turn_rate(self) -> float:
        """min of d(polar angle of the boundary point)/dpsi = 1 + delta' over the intervals,
        and of the jump of delta at the flat edges: >= 0 for a convex D (h + h'' >= 0)."""
        k0, k1, d = self._intervals()
        rate = 1.0 + (self.delta[k1] - self.delta[k0]) / d
        same = np.flatnonzero(np.diff(self.psi) == 0)
        jumps = self.delta[same + 1] - self.delta[same]
        return float(min(rate.min(), jumps.min() if jumps.size else np.inf))

    def is_convex(self, tol: float = TOL.curvature) -> bool:
        return self.min_turn_rate() >= -tol


def _dedupe(pts: np.ndarray) -> np.ndarray:
    """Drop consecutive (cyclic) repeats of the same point."""
    d = np.hypot(*(pts - np.roll(pts, 1, axis=0)).T)
    scale = np.hypot(pts[:, 0], pts[:, 1]).max()
    keep = d > 1e-14 * scale
    if not keep.any():
        keep[0] = True
    return pts[keep]


# ----------------------------------------------------------------------------- the law

@dataclass(frozen=True)
class LawForce:
    """Forces of a law for a set of sliding directions.

    psi        : (m,) sliding directions (rad)
    p          : (m, 2) p = -lambda_T/lambda_N (on a flat edge of D: the point on the ray of
                 the edge's midpoint)
    alpha      : (m,) 1/(k_D(p) - k_C(p) + 1)
    set_valued : (m,) the normal cone of D holds a flat edge: any p between p_minus and
                 p_plus slides in that direction
    p_minus, p_plus : (m, 2) the ends of that set (equal to p elsewhere)
    """

    psi: np.ndarray
    p: np.ndarray
    alpha: np.ndarray
    set_valued: np.ndarray
    p_minus: np.ndarray
    p_plus: np.ndarray

    @property
    def s(self) -> np.ndarray:
        return unit(self.psi)

    @property
    def tangential(self) -> np.ndarray:
        return np.einsum("ij,ij->i", self.p, self.s)

    @property
    def lateral(self) -> np.ndarray:
        return np.einsum("ij,ij->i", self.p, unit(self.psi + 0.5 * math.pi))

    def reservoir(self, contact: str = "law") -> Reservoir:
        m = self.psi.size
        return Reservoir(psi=self.psi, p=self.p, locked=np.zeros(m, bool),
                         locked_face=np.full(m, -1, np.int64), set_valued=self.set_valued,
                         contact=contact)


@dataclass(frozen=True)
class WalkerLeineLaw:
    """``-lambda_T in lambda_N C``, ``gamma_T in N_D(-alpha lambda_T)``,
    ``alpha = 1/(k_D(-lambda_T) - k_C(-lambda_T) + 1)`` (Walker & Leine; SPEC.md 3).

    C: any set with ``radial``/``gauge`` (star-shaped); D: a convex set with ``gauge`` and
    ``normal_point``.  While sliding k_C = 1 and alpha p lies on the boundary of D.
    """

    C: object
    D: object

    def force(self, psi) -> LawForce:
        """The sliding force for the directions ``psi`` (rad)."""
        psi = _psi(psi)
        y, ym, yp = self.D.normal_point(psi)
        p, pm, pp = (self._on_C(v) for v in (y, ym, yp))
        sv = np.any(ym != yp, axis=1)
        return LawForce(psi, p, self.alpha(p), sv, pm, pp)

    def _on_C(self, y) -> np.ndarray:
        phi = polar_angle(y)
        return self.C.radial(phi)[:, None] * unit(phi)

    def alpha(self, x) -> np.ndarray:
        """alpha(x) = 1/(k_D(x) - k_C(x) + 1) for forces x (m, 2) (sticking: x inside C)."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        return 1.0 / (self.D.gauge(x) - self.C.gauge(x) + 1.0)

    def min_dissipation(self, n: int = 3600) -> tuple[float, float]:
        """(min p.s, psi in deg where it occurs) over n directions (and both ends of every
        set-valued direction)."""
        psi = TWO_PI * np.arange(n) / n
        edges = np.asarray(getattr(self.D, "edges", np.empty(0)))
        psi = np.concatenate([psi, edges])
        f = self.force(psi)
        s = f.s
        dis = np.minimum.reduce([np.einsum("ij,ij->i", q, s) for q in (f.p, f.p_minus, f.p_plus)])
        k = int(np.argmin(dis))
        return float(dis[k]), float(np.degrees(psi[k]) % 360.0)


def coulomb(mu: float) -> WalkerLeineLaw:
    """Isotropic Coulomb friction: C = D = disc of radius mu."""
    d = Disc(float(mu))
    return WalkerLeineLaw(d, d)


def associated(ellipse: TruncatedEllipse) -> WalkerLeineLaw:
    """The associated law of a truncated ellipse (force normal rule): C = D = ellipse."""
    return WalkerLeineLaw(ellipse, ellipse)


# ----------------------------------------------------------------------------- data

@dataclass(frozen=True)
class ReservoirData:
    """Reservoir points prepared for fitting.

    psi, p        : (m,), (m, 2) the points in order of psi; a set-valued direction appears
                    twice (the two one-sided limits, the ends of the straight segment)
    limit         : (m,) int, -1 / +1 for the left / right limit at a set-valued direction,
                    0 for an ordinary point
    """

    psi: np.ndarray
    p: np.ndarray
    limit: np.ndarray

    @property
    def g(self) -> np.ndarray:
        """tan(angle(p) - psi) = L/T, the sliding rule."""
        s = unit(self.psi)
        T = np.einsum("ij,ij->i", self.p, s)
        L = np.einsum("ij,ij->i", self.p, unit(self.psi + 0.5 * math.pi))
        return L / T


def prepare_reservoir(res: Reservoir, evaluate=None) -> ReservoirData:
    """Check a reservoir for fitting and expand its set-valued directions.

    ``evaluate(psi) -> Reservoir`` gives the one-sided limits at psi -+ TOL.set_valued_eps;
    without it the neighbouring directions' points are taken.  Raises InputError for
    self-locking directions (unbounded friction: no finite gauge) or p.s <= 0 (no convex D).
    """
    psi = np.asarray(res.psi, dtype=float)
    if psi.ndim != 1 or psi.size < 8:
        raise InputError(f"a fit needs at least 8 directions, got {psi.size}")
    if res.locked.any():
        from .derive import _runs
        raise InputError(
            f"the texture self-locks in {int(res.locked.sum())} of {psi.size} directions "
            f"(psi in {_runs(res)}): friction is unbounded there and no finite friction law "
            "can be fitted")
    order = np.argsort(np.mod(psi, TWO_PI), kind="stable")
    psi = np.mod(psi[order], TWO_PI)
    p = np.asarray(res.p, dtype=float)[order]
    sv = np.asarray(res.set_valued, dtype=bool)[order]
    if np.any(np.diff(psi) <= 0):
        raise InputError("the directions of the reservoir must be distinct")
    m = psi.size
    out_psi, out_p, out_lim = [], [], []
    for k in range(m):
        if not sv[k]:
            out_psi.append(psi[k]); out_p.append(p[k]); out_lim.append(0)
            continue
        if evaluate is not None:
            e = TOL.set_valued_eps
            r = evaluate(np.array([psi[k] - e, psi[k] + e]))
            if r.locked.any() or r.set_valued.any():
                raise InputError(f"no one-sided limit beside the set-valued direction "
                                 f"psi = {math.degrees(psi[k]):g} deg")
            lo, hi = r.p[0], r.p[1]
        else:
            lo, hi = p[(k - 1) % m], p[(k + 1) % m]
        out_psi += [psi[k], psi[k]]
        out_p += [lo, hi]
        out_lim += [-1, 1]
    data = ReservoirData(np.array(out_psi), np.array(out_p), np.array(out_lim))
    dis = np.einsum("ij,ij->i", data.p, unit(data.psi))
    if np.any(dis <= TOL.dissipation):
        k = int(np.argmin(dis))
        raise InputError(f"p.s = {dis[k]:.6g} <= 0 at psi = {math.degrees(data.psi[k]):g} deg: "
                         "the reservoir is not admissible (negative dissipation), no law is fitted")
    return data


# ----------------------------------------------------------------------------- fits

@dataclass(frozen=True)
class FitReport:
    """Fit quality.  Errors are relative (|p|) and angles in degrees.

    max_radial_error, rms_radial_error : |rho_law(angle p_k) - |p_k|| / |p_k| at the data
    max_angle_error_deg : largest angle between the data p(psi_k) and the law's force for
        the same sliding direction (set-valued data directions left out)
    min_dissipation : min over 3600 directions of p.s of the fitted law (>= 0: admissible)
    C_convex, C_min_turn_deg : convexity test of C (smallest turning angle of its outline)
    D_convex, D_min_turn_rate : min over psi of d(angle of D's boundary point)/dpsi, >= 0
        iff h + h'' >= 0 (star laws)
    closure_residual : ln h(2 pi) - ln h(0) of the integrated sliding rule; it is removed
        by turning every boundary point of D by the same small angle,
        closure_max_angle_deg, about its normal (star laws)
    holdout_* : the law against the texture at directions not used in the fit (midway
        between the fitted ones): largest relative magnitude error and angle (deg)
    """

    n_points: int
    max_radial_error: float
    rms_radial_error: float
    max_angle_error_deg: float
    min_dissipation: float
    admissible: bool
    C_convex: bool
    C_min_turn_deg: float
    D_convex: bool | None = None
    D_min_turn_rate: float | None = None
    closure_residual: float | None = None
    closure_max_angle_deg: float | None = None
    holdout_directions: int | None = None
    holdout_max_magnitude_error: float | None = None
    holdout_max_angle_deg: float | None = None

    def to_dict(self) -> dict:
        from dataclasses import asdict
        return asdict(self)

    def with_holdout(self, n: int, mag: float, ang: float) -> "FitReport":
        from dataclasses import replace
        return replace(self, holdout_directions=int(n), holdout_max_magnitude_error=float(mag),
                       holdout_max_angle_deg=float(ang))


def _ellipse_residuals(params, phi, r, theta, sym):
    if sym:
        params = (params[0], params[0], params[1], params[1])
    e = TruncatedEllipse(*map(float, params), theta=theta)
    return (e.radial(phi) - r) / r


def fit_truncated_ellipse(data: ReservoirData, theta: float = 0.0, start=None,
                          symmetric: bool = False) -> TruncatedEllipse:
    """Least-squares fit of a truncated ellipse (t_a at angle theta) to the reservoir
    points on the relative radial error ``(rho_E(angle p_k) - |p_k|) / |p_k|``.

    start : (mu_a+, mu_a-, mu_b+, mu_b-); default the radii of the data nearest the axes.
    symmetric : fit the orthotropic ellipse mu_a+ = mu_a-, mu_b+ = mu_b- (2 parameters).
    """
    from scipy.optimize import least_squares
    phi = polar_angle(data.p)
    r = np.hypot(data.p[:, 0], data.p[:, 1])
    if start is None:
        start = []
        for ax in (0.0, math.pi, 0.5 * math.pi, 1.5 * math.pi):
            dist = np.abs(np.mod(phi - theta - ax + math.pi, TWO_PI) - math.pi)
            start.append(float(r[int(np.argmin(dist))]))
    x0 = np.asarray(start, dtype=float)
    if symmetric:
        x0 = np.array([0.5 * (x0[0] + x0[1]), 0.5 * (x0[2] + x0[3])])
    sol = least_squares(_ellipse_residuals, x0, args=(phi, r, theta, symmetric),
                        bounds=(1e-12 * r.max(), np.inf), x_scale=np.full(x0.size, r.mean()),
                        xtol=1e-14, ftol=1e-14, gtol=1e-14)
    x = sol.x if not symmetric else np.array([sol.x[0], sol.x[0], sol.x[1], sol.x[1]])
    return TruncatedEllipse(*map(float, x), theta=float(theta))


def _quality(law: WalkerLeineLaw, data: ReservoirData, extra: dict) -> FitReport:
    phi = polar_angle(data.p)
    r = np.hypot(data.p[:, 0], data.p[:, 1])
    rad = (law.C.radial(phi) - r) / r
    ordinary = data.limit == 0
    f = law.force(data.psi[ordinary])
    ang = angle_between(f.p, data.p[ordinary])
    dmin, _ = law.min_dissipation()
    C = law.C
    turn = C.turning_angles().min() if isinstance(C, StarSet) else 0.0
    return FitReport(
        n_points=int(data.psi.size),
        max_radial_error=float(np.abs(rad).max()),
        rms_radial_error=float(np.sqrt(np.mean(rad * rad))),
        max_angle_error_deg=float(np.degrees(ang.max())) if ang.size else 0.0,
        min_dissipation=dmin, admissible=dmin >= -TOL.dissipation,
        C_convex=bool(turn >= -TOL.convexity), C_min_turn_deg=float(np.degrees(turn)), **extra)


def fit_ellipse_law(data: ReservoirData, theta: float = 0.0, start=None):
    """(associated truncated-ellipse law, FitReport)."""
    e = fit_truncated_ellipse(data, theta, start)
    law = associated(e)
    return law, _quality(law, data, {})


def fit_star(data: ReservoirData):
    """(Walker-Leine law with star-shaped C through the data and convex D from the sliding
    rule, FitReport).

    C: the polygon of the data points (both ends of each set-valued segment included).
    D: ``d ln h/d psi = g = tan(angle(p) - psi)``, integrated by the trapezoidal rule (exact
    for g linear between samples); the closure residual ln h(2 pi) - ln h(0) is spread
    evenly (g - residual / 2 pi) and reported; D is then scaled so that its support
    function matches that of C's convex hull in the least-squares sense of ln h (D only
    matters up to scale while sliding; an associated law gets D = C).
    Raises InputError if the data are not star-shaped (polar angle of p not increasing).
    """
    psi, p = data.psi, data.p
    phi = psi + np.arctan(data.g)                       # polar angle of p, increasing with psi
    step = np.diff(np.append(phi, phi[0] + TWO_PI))
    if np.any(step < -TOL.same_angle):
        k = int(np.argmin(step))
        k1 = (k + 1) % psi.size
        raise InputError(
            f"the reservoir is not star-shaped: the polar angle of p goes back by "
            f"{-math.degrees(step[k]):.4g} deg from psi = {math.degrees(psi[k]):g} deg to "
            f"{math.degrees(psi[k1]):g} deg; a star-shaped C cannot hold it")
    # C: vertices in order; equal angles must be the same point (a corner of C)
    r = np.hypot(p[:, 0], p[:, 1])
    keep = np.ones(psi.size, bool)
    for k in np.flatnonzero(step <= TOL.same_angle):
        k1 = (k + 1) % psi.size
        if abs(r[k1] - r[k]) > TOL.same_point * max(r[k], r[k1]):
            raise InputError(
                f"the reservoir is not star-shaped: two points on the ray at "
                f"{math.degrees(phi[k]) % 360:g} deg (psi = {math.degrees(psi[k]):g} and "
                f"{math.degrees(psi[k1]):g} deg) with |p| = {r[k]:.6g} and {r[k1]:.6g}")
        keep[k1] = False
    C = StarSet(p[keep])
    # D: integrate the sliding rule d ln h/dpsi = tan(delta), delta = angle(p) - psi
    n = psi.size
    delta = phi - psi
    k0 = np.arange(n)
    k1 = (k0 + 1) % n
    d = np.where(k1 > k0, psi[k1] - psi[k0], psi[k1] + TWO_PI - psi[k0])
    keep = d > 0

    def closure(e):
        return float(tan_integral(delta[k0] - e, delta[k1] - e, np.where(keep, d, 1.0),
                                  np.where(keep, d, 0.0)).sum())

    residual = closure(0.0)
    e = 0.0
    if abs(residual) > 1e-14:
        from scipy.optimize import brentq
        lo = float(delta.max()) - 0.5 * math.pi + 1e-9
        hi = float(delta.min()) + 0.5 * math.pi - 1e-9
        if not (lo < hi and closure(lo) > 0 > closure(hi)):
            raise InputError(f"the sliding rule does not close (ln h(2 pi) - ln h(0) = "
                             f"{residual:.6g}) and no rotation of the forces within 90 deg of "
                             "the sliding directions closes it: no convex D")
        e = brentq(closure, lo, hi, xtol=1e-15, rtol=1e-15)
    dc = delta - e
    incr = tan_integral(dc[k0], dc[k1], np.where(keep, d, 1.0), np.where(keep, d, 0.0))
    lnh = np.concatenate([[0.0], np.cumsum(incr[:-1])])
    lnh += float(np.mean(np.log(C.support(psi)) - lnh))
    h = np.exp(lnh)
    D = ConvexSet(psi, h, h * np.tan(dc))
    law = WalkerLeineLaw(C, D)
    rep = _quality(law, data, dict(D_convex=D.is_convex(), D_min_turn_rate=D.min_turn_rate(),
                                   closure_residual=residual,
                                   closure_max_angle_deg=float(abs(math.degrees(e)))))
    return law, rep


def compare_with_reservoir(law: WalkerLeineLaw, ref: Reservoir) -> tuple[float, float]:
    """(max |(|p_law| - |p|)| / |p|, max angle in deg between p_law and p) over the
    directions of ``ref`` that neither self-lock nor are set-valued."""
    ok = ~(ref.locked | ref.set_valued)
    if not ok.any():
        return 0.0, 0.0
    f = law.force(ref.psi[ok])
    r = np.hypot(ref.p[ok, 0], ref.p[ok, 1])
    mag = np.abs(np.hypot(f.p[:, 0], f.p[:, 1]) - r) / r
    ang = angle_between(f.p, ref.p[ok])
    return float(mag.max()), float(np.degrees(ang.max()))


# ----------------------------------------------------------------------------- from derive

@dataclass(frozen=True)
class GaugeLaw:
    """A fitted law with what a gauge file records.

    kind : "truncated-ellipse" or "star"
    law  : the WalkerLeineLaw
    data : the reservoir points fitted (ReservoirData)
    fit  : FitReport
    source : JSON-ready description of the texture or surface and the contact regime
    principal_direction_deg : t_a in the frame of the forces (0 for wedge textures)
    """

    kind: str
    law: WalkerLeineLaw
    data: ReservoirData
    fit: FitReport
    source: dict
    principal_direction_deg: float = 0.0

    def force(self, psi) -> LawForce:
        return self.law.force(psi)


def fit_derivation(d, kind: str = "star", holdout: bool = True) -> GaugeLaw:
    """Fit a law of ``kind`` to a :class:`~asperity.derive.Derivation` (closed form).

    The set-valued directions are resolved by evaluating the texture beside them; with
    ``holdout`` the law is compared with the texture at the directions midway between the
    fitted ones (not used in the fit).
    """
    from .closed_form import compute_reservoir
    if kind not in LAW_KINDS:
        raise InputError(f"law must be one of {', '.join(LAW_KINDS)}, got {kind!r}")

    def evaluate(psi):
        return compute_reservoir(d.texture, psi, d.contact)

    data = prepare_reservoir(d.reservoir, evaluate)
    theta = math.radians(d.principal_direction_deg)
    if kind == "star":
        law, rep = fit_star(data)
    else:
        ax = d.axes
        start = [ax["mu_a_plus"], ax["mu_a_minus"], ax["mu_b_plus"], ax["mu_b_minus"]]
        if not all(math.isfinite(v) and v > 0 for v in start):
            start = None
        law, rep = fit_ellipse_law(data, theta, start)
    if holdout:
        psi = d.reservoir.psi
        mid = np.mod(psi + 0.5 * np.mod(np.roll(psi, -1) - psi, TWO_PI), TWO_PI)
        ref = evaluate(mid)
        mag, ang = compare_with_reservoir(law, ref)
        rep = rep.with_holdout(mid.size, mag, ang)
    return GaugeLaw(kind, law, data, rep, source_of(d), float(d.principal_direction_deg))


def source_of(d) -> dict:
    """JSON-ready description of where a derivation came from."""
    tex = d.texture
    try:
        tdict = tex.to_dict()
    except Exception:                                   # pragma: no cover - defensive
        tdict = {"kind": str(getattr(tex, "kind", "unknown"))}
    return {"texture": _json_ready(tdict), "contact": d.contact, "method": d.method,
            "n_directions": int(d.reservoir.psi.size)}


def _json_ready(x):
    """Plain JSON values: numpy scalars/arrays converted, non-finite floats -> None."""
    if isinstance(x, dict):
        return {str(k): _json_ready(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_ready(v) for v in x]
    if isinstance(x, np.ndarray):
        return _json_ready(x.tolist())
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if x is None or isinstance(x, str):
        return x
    return str(x)
