"""The Walker-Leine friction law ``(C, D)`` (SPEC.md section 3).

For a sliding direction ``s`` the point ``y`` of the boundary of ``D`` with outward normal
``s``, then ``p = -lambda_T/lambda_N`` is the point of the boundary of ``C`` on the ray of
``y``, and ``alpha = 1/(k_D(p) - k_C(p) + 1)``.  ``C = D = Disc`` is Coulomb,
``C = D = TruncatedEllipse`` the associated (normal-rule) law.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..friction.reservoir import Reservoir
from .geometry import TWO_PI, polar_angle, psi_array, unit
from .sets import Disc, TruncatedEllipse


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
    """The Walker-Leine friction law: a star-shaped reservoir C and a convex sliding set D.

    ``-lambda_T in lambda_N C`` and ``gamma_T in N_D(-alpha lambda_T)`` with
    ``alpha = 1/(k_D(-lambda_T) - k_C(-lambda_T) + 1)`` (Walker & Leine; SPEC.md 3),
    forces per unit normal load.  For a sliding direction ``s`` the law takes the point
    ``y`` of the boundary of D with outward normal ``s``; the force
    ``p = -lambda_T / lambda_N`` is the point of the boundary of C on the ray of ``y``.
    While sliding ``k_C(p) = 1`` and ``alpha p`` lies on the boundary of D; D matters only
    up to scale.  C = D = a disc is Coulomb, C = D = a truncated ellipse the associated
    (normal-rule) law.

    Parameters
    ----------
    C : Disc, TruncatedEllipse, StarSet or ConvexSet
        The reservoir: any star-shaped set with ``radial`` and ``gauge`` (possibly
        non-convex).
    D : Disc, TruncatedEllipse or ConvexSet
        The sliding set: a convex set with ``gauge`` and ``normal_point``.

    Raises
    ------
    InputError
        If C or D is not one of these sets.

    See Also
    --------
    asperity.PlanarLaw : a law with a name, as the solver takes it.
    asperity.fit_derivation : C and D fitted to a texture.

    Examples
    --------
    C an orthotropic ellipse, D a disc: a collinear law (the force along the slip).  While
    sliding, ``alpha = 1 / k_D(p) = 1 / |p|``:

    >>> C = asperity.TruncatedEllipse(0.2, 0.2, 0.4, 0.4)
    >>> D = asperity.TruncatedEllipse(1.0, 1.0, 1.0, 1.0)
    >>> f = asperity.WalkerLeineLaw(C, D).force(np.radians([45.0]))
    >>> print(np.round(f.p, 4), np.round(f.alpha, 4))
    [[0.1789 0.1789]] [3.9528]
    """

    C: object
    D: object

    def __post_init__(self):
        from ..errors import check_instance
        from .convex_set import ConvexSet
        from .sets import Disc, StarSet, TruncatedEllipse
        check_instance("C", self.C, (Disc, TruncatedEllipse, StarSet, ConvexSet),
                       "Disc, TruncatedEllipse, StarSet or ConvexSet")
        check_instance("D", self.D, (Disc, TruncatedEllipse, ConvexSet, StarSet),
                       "Disc, TruncatedEllipse or ConvexSet (a convex set)")

    def force(self, psi) -> LawForce:
        """The sliding force for the directions ``psi`` (rad)."""
        psi = psi_array(psi)
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
    d = Disc(mu)
    return WalkerLeineLaw(d, d)


def associated(ellipse: TruncatedEllipse) -> WalkerLeineLaw:
    """The associated law of a truncated ellipse (force normal rule): C = D = ellipse."""
    from ..errors import check_instance
    check_instance("ellipse", ellipse, TruncatedEllipse)
    return WalkerLeineLaw(ellipse, ellipse)
