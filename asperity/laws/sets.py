"""Friction sets given in closed form or by vertices (SPEC.md section 3).

Each answers ``radial(phi)`` and ``gauge(x)``; the convex ones also ``support(psi)`` and
``normal_point(psi)``, the boundary point whose outward normal is ``s(psi)``:

* :class:`Disc` -- isotropic Coulomb;
* :class:`TruncatedEllipse` -- Antoni et al. eq. 18: four quarter ellipses with semi-axes
  ``mu_a+/-`` along ``+-t_a`` and ``mu_b+/-`` along ``+-t_b`` (``t_a`` at angle ``theta``);
  convex and C1;
* :class:`StarSet` -- a star-shaped set given by a closed polygon sorted by polar angle, so
  that straight segments (windward, sliding along the ridges) are exact and non-convex
  shapes are followed; ``k_C(x) = |x| / rho(angle x)``.

The convex sliding set given by its support function is :mod:`asperity.laws.convex_set`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_array, check_range
from .geometry import TOL, TWO_PI, check_mu_law, cross, points_array, polar_angle, psi_array, unit

#: distances from the origin a polygon or support function may have (numeric sanity; the
#: physical range of friction coefficients, MU_MIN..MU_MAX, is checked where data enter)
RADIUS_MIN, RADIUS_MAX = 1e-9, 1e6


@dataclass(frozen=True)
class Disc:
    """The disc of radius ``mu``: the isotropic Coulomb set."""

    mu: float
    kind = "disc"

    def __post_init__(self):
        object.__setattr__(self, "mu", check_mu_law("mu", self.mu))

    def radial(self, phi) -> np.ndarray:
        return np.full(psi_array(phi, "phi").shape, float(self.mu))

    def gauge(self, x) -> np.ndarray:
        x = points_array("x", x)
        return np.hypot(x[:, 0], x[:, 1]) / self.mu

    def support(self, psi) -> np.ndarray:
        return self.radial(psi)

    def normal_point(self, psi):
        y = self.mu * unit(psi_array(psi))
        return y, y, y


@dataclass(frozen=True)
class TruncatedEllipse:
    """The truncated ellipse of Antoni et al. (eq. 18): four quarter ellipses.

    The gauge is ``k(x) = sqrt((x_a/mu_a+-)^2 + (x_b/mu_b+-)^2)``: the sign of ``x_a``
    (component along ``t_a``) picks ``mu_a+`` or ``mu_a-``, that of ``x_b`` picks ``mu_b+``
    or ``mu_b-``.  Convex and C1: the quarter ellipses meet on the axes with a common
    tangent.  The friction criterion is ``g = k(tau) - sigma_n`` (``criterion``; stick
    where ``g <= 0``), the associated sliding rule along ``grad g`` (SPEC.md 3).

    Parameters
    ----------
    mu_a_plus, mu_a_minus : float
        Semi-axes along +t_a and -t_a (the coefficients for sliding that way), in
        [1e-6, 100].
    mu_b_plus, mu_b_minus : float
        Semi-axes along +t_b and -t_b, in [1e-6, 100].
    theta : float, optional
        Angle (rad) of ``t_a`` in the frame of the vectors, in [-4 pi, 4 pi]; default 0
        (wedge textures).

    Raises
    ------
    InputError
        If a semi-axis is not in [1e-6, 100] or ``theta`` is out of range.

    See Also
    --------
    asperity.truncated_ellipse_law : the associated law of this set.
    asperity.WalkerLeineLaw : a law made of such sets.

    Examples
    --------
    Antoni et al.'s figure 7 example (SPEC.md 3):

    >>> E = asperity.TruncatedEllipse(0.2, 0.08, 0.12, 0.15)
    >>> print(E.radial(np.radians([0.0, 90.0, 180.0, 270.0])).round(4))
    [0.2  0.12 0.08 0.15]
    >>> print(E.criterion([[0.1, 0.0], [-0.1, 0.0]], 1.0))
    [-0.5   0.25]
    """

    mu_a_plus: float
    mu_a_minus: float
    mu_b_plus: float
    mu_b_minus: float
    theta: float = 0.0
    kind = "truncated-ellipse"

    def __post_init__(self):
        for name in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            object.__setattr__(self, name, check_mu_law(name, getattr(self, name)))
        object.__setattr__(self, "theta", check_range("theta", self.theta, -2 * TWO_PI,
                                                      2 * TWO_PI, unit="rad"))

    @property
    def axes(self) -> dict:
        return {"mu_a_plus": self.mu_a_plus, "mu_a_minus": self.mu_a_minus,
                "mu_b_plus": self.mu_b_plus, "mu_b_minus": self.mu_b_minus}

    def _local(self, x) -> np.ndarray:
        c, s = math.cos(self.theta), math.sin(self.theta)
        x = points_array("x", x)
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
        return 1.0 / self.gauge(unit(psi_array(phi, "phi")))

    def support(self, psi) -> np.ndarray:
        sl = self._local(unit(psi_array(psi)))
        A, B = self._semi_axes(sl)
        return np.hypot(A * sl[:, 0], B * sl[:, 1])

    def normal_point(self, psi):
        """The boundary point with outward normal s(psi): (A^2 s_a, B^2 s_b) / h(s)."""
        sl = self._local(unit(psi_array(psi)))
        A, B = self._semi_axes(sl)
        h = np.hypot(A * sl[:, 0], B * sl[:, 1])
        y = self._global(np.column_stack([A * A * sl[:, 0], B * B * sl[:, 1]]) / h[:, None])
        return y, y, y

    def criterion(self, tau, sigma_n) -> np.ndarray:
        """Antoni et al. eq. 18: g = k(tau) - sigma_n (<= 0: stick), tau (m, 2) stresses,
        sigma_n >= 0 the normal (contact) stress, in the same unit."""
        sn = check_array("sigma_n", sigma_n)
        if np.any(sn < 0):
            raise InputError(f"sigma_n must be >= 0 (a contact pressure), got {sn.min():g}")
        return self.gauge(points_array("tau", tau)) - sn


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
        pts = np.array(check_array("points", self.points, shape=(None, 2)), dtype=float)
        if pts.shape[0] < 3:
            raise InputError(f"points must have shape (n, 2) with n >= 3, got {pts.shape}")
        r = np.hypot(pts[:, 0], pts[:, 1])
        if np.any(r <= 0):
            raise InputError(f"points must not contain the origin (point {int(np.argmin(r))})")
        far = (r < RADIUS_MIN) | (r > RADIUS_MAX)
        if np.any(far):
            k = int(np.flatnonzero(far)[0])
            raise InputError(f"points must lie at distances in [{RADIUS_MIN:g}, {RADIUS_MAX:g}] "
                             f"from the origin, got {r[k]:g} (point {k})")
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
        phi = psi_array(phi, "phi")
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
        return cross(v0, d) / cross(u, d)

    def gauge(self, x) -> np.ndarray:
        x = points_array("x", x)
        r = np.hypot(x[:, 0], x[:, 1])
        out = np.zeros(r.shape)
        nz = r > 0
        out[nz] = r[nz] / self.radial(polar_angle(x[nz]))
        return out

    def turning_angles(self) -> np.ndarray:
        """(n,) signed turning angle (rad) of the boundary at each vertex (>= 0: convex)."""
        e_in = self.points - np.roll(self.points, 1, axis=0)
        e_out = np.roll(self.points, -1, axis=0) - self.points
        return np.arctan2(cross(e_in, e_out), np.einsum("ij,ij->i", e_in, e_out))

    def is_convex(self, tol: float = TOL.convexity) -> bool:
        """Convex if no vertex turns clockwise by more than ``tol`` rad."""
        return bool(self.turning_angles().min() >= -tol)

    def support(self, psi) -> np.ndarray:
        """Support function of the convex hull: max over the vertices of v . s."""
        return (unit(psi_array(psi)) @ self.points.T).max(axis=1)
