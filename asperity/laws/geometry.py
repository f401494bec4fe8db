"""Plane geometry shared by the friction sets and laws, and their tolerances.

Forces are per unit normal load (dimensionless); angles in radians: ``psi`` is a sliding
direction ``s = (cos psi, sin psi)``, ``phi`` the polar angle of a force.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

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
    #: a gauge file's recorded fit report must match the one recomputed from its own law
    #: and data to this (relative, and absolute for values near 0): they are computed by
    #: the same code, so only a hand-edited file differs
    fit_report: float = 1e-9
    #: |mean ln(h_D / h_hull(C))| of a fitted star law (D is scaled to C's hull) above this
    #: means C and D were not fitted together
    d_scale: float = 1e-6


#: friction coefficients and force magnitudes per unit normal load that a law may hold
#: (a smaller or larger value is no physical friction, and overflows the computations)
MU_MIN, MU_MAX = 1e-6, 100.0


TOL = GaugeTolerances()


def unit(angle) -> np.ndarray:
    """(m, 2) unit vectors at the angles ``angle`` (rad)."""
    a = np.atleast_1d(np.asarray(angle, dtype=float))
    return np.column_stack([np.cos(a), np.sin(a)])


def polar_angle(x) -> np.ndarray:
    """(m,) polar angles in (-pi, pi] of the (m, 2) vectors ``x``."""
    x = np.atleast_2d(np.asarray(x, dtype=float))
    return np.arctan2(x[:, 1], x[:, 0])


def cross(a, b) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


#: largest |angle| (rad) taken as a direction (beyond, cos and sin lose all precision)
MAX_ANGLE = 1e4


def psi_array(psi, name: str = "psi") -> np.ndarray:
    """(m,) finite sliding directions (rad), else InputError."""
    from ..errors import check_array
    a = np.atleast_1d(check_array(name, psi))
    if np.any(np.abs(a) > MAX_ANGLE):
        raise InputError(f"{name} must be angles in radians within +-{MAX_ANGLE:g}, got "
                         f"{a[np.abs(a) > MAX_ANGLE][0]:g}")
    return a


def points_array(name: str, x) -> np.ndarray:
    """(m, 2) finite vectors, else InputError."""
    from ..errors import check_array
    a = check_array(name, x)
    if a.ndim == 1 and a.size == 2:
        a = a.reshape(1, 2)
    if a.ndim != 2 or a.shape[1] != 2:
        raise InputError(f"{name} must have shape (m, 2), got {a.shape}")
    return a


def check_mu_law(name: str, value) -> float:
    """A friction coefficient or force magnitude of a law: in [MU_MIN, MU_MAX]."""
    from ..errors import check_range
    return check_range(name, value, MU_MIN, MU_MAX)


def angle_between(a, b) -> np.ndarray:
    """(m,) unsigned angles (rad) between the rows of the (m, 2) arrays a and b."""
    return np.abs(np.arctan2(cross(a, b), np.einsum("ij,ij->i", a, b)))


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
