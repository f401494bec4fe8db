"""Planar friction laws for the Moreau solver, and their proximal maps (SPEC.md sections 3, 4).

Every law is a Walker-Leine pair ``(C, D)`` (:class:`~asperity.laws.walker_leine.WalkerLeineLaw`):
``-lambda_T in lambda_N C`` and ``gamma_T in N_D(-alpha lambda_T)``,
``alpha = 1/(k_D(-lambda_T) - k_C(-lambda_T) + 1)``.  Forces are per unit normal load, in
the frame of the law (``t_a`` = x, ``t_b`` = y).  The built-in laws:

* :func:`coulomb_law` -- isotropic Coulomb, C = D = disc (associated);
* :func:`ellipse_law` -- associated orthotropic ellipse (mu1 along t_a, mu2 along t_b);
* :func:`truncated_ellipse_law` -- Antoni et al.'s truncated ellipse (mu_a+-, mu_b+-),
  associated: asymmetric friction, e.g. for ratcheting;
* :func:`collinear_law` -- force parallel to the sliding direction with magnitude from a
  radial function (C = the given set, D = a disc: its normal cone is the ray of the force);
* :func:`componentwise_law` -- Hu et al.'s componentwise rule (forward, backward and
  transverse coefficients), a Walker-Leine law of two truncated ellipses;
* :func:`star_law` -- Walker-Leine law with a non-convex, star-shaped C and convex D: the
  windward wedge reservoir (alpha = beta = 30 deg, mu = 0.3, rigid asperities) stretched
  along t_a and t_b to mu1 and mu2 (:func:`windward_star_law` gives it unstretched);
* :func:`from_gauge` -- the law of a gauge file written by ``asperity fit`` (truncated
  ellipse or star), directly or as its collinear variant.

Inside the solver D may be rescaled (D matters only up to scale, SPEC.md 3): it is shrunk
to the largest copy that fits in C, so that k_D >= k_C on C and alpha <= 1 (the iteration's
effective r_i = alpha_i r then stays in the convergence range of r).

Proximal maps (Euclidean projections), usable outside the solver (e.g. microslip):
:func:`prox_interval` (1D asymmetric Coulomb), :func:`prox_set` (onto the D or C of a law),
:func:`law_point` (the full Walker-Leine map, prox onto D then back to C).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..errors import InputError, as_number, check_choice, check_range
from .convex_set import ConvexSet
from .geometry import points_array, polar_angle, psi_array, unit
from .sets import Disc, StarSet, TruncatedEllipse
from .walker_leine import WalkerLeineLaw, associated

#: set kinds of the kernels (same numbers as asperity.laws._set_kernels.SET_*)
SET_DISC, SET_ELLIPSE, SET_STAR, SET_SUPPORT = 0, 1, 2, 3
LAW_NAMES = ("coulomb", "ellipse", "truncated-ellipse", "collinear", "componentwise", "star")
#: directions sampled when D is fitted inside C
_SCALE_DIRECTIONS = 7200


def _set_tables(S) -> tuple[int, np.ndarray, np.ndarray]:
    """(kind, par (8,), table (n, 8)) of a set for the kernels."""
    par = np.zeros(8)
    if isinstance(S, Disc):
        par[0] = S.mu
        return SET_DISC, par, np.zeros((1, 8))
    if isinstance(S, TruncatedEllipse):
        par[:6] = (S.mu_a_plus, S.mu_a_minus, S.mu_b_plus, S.mu_b_minus,
                   math.cos(S.theta), math.sin(S.theta))
        return SET_ELLIPSE, par, np.zeros((1, 8))
    if isinstance(S, StarSet):
        tab = np.zeros((S.n, 8))
        tab[:, :2] = S.points
        tab[:, 2] = S.angles[:-1]
        return SET_STAR, par, tab
    if isinstance(S, ConvexSet):
        tab = np.zeros((S.psi.size, 8))
        tab[:, 0] = S.psi
        tab[:, 1] = S.ln_h
        tab[:, 2] = S.delta
        tab[:, 3] = S.h
        tab[:, 4] = S.dh
        tab[:, 5] = np.cos(S.psi)
        tab[:, 6] = np.sin(S.psi)
        if not np.all(np.diff(S.psi) >= 0):                      # pragma: no cover
            raise InputError("D.psi must be non-decreasing")
        return SET_SUPPORT, par, tab
    raise InputError(f"unsupported set {type(S).__name__}: expected Disc, TruncatedEllipse, "
                     "StarSet or ConvexSet")


def scale_set(S, c: float):
    """The set S scaled by c > 0 about the origin."""
    if isinstance(S, Disc):
        return Disc(S.mu * c)
    if isinstance(S, TruncatedEllipse):
        return TruncatedEllipse(S.mu_a_plus * c, S.mu_a_minus * c, S.mu_b_plus * c,
                                S.mu_b_minus * c, theta=S.theta)
    if isinstance(S, ConvexSet):
        return ConvexSet(S.psi, S.h * c, S.dh * c)
    if isinstance(S, StarSet):
        return StarSet(S.points * c)
    raise InputError(f"cannot scale {type(S).__name__}")


@dataclass(frozen=True)
class PlanarLaw:
    """A friction law of the solver: a Walker-Leine pair (C, D) with a name.

    Forces are per unit normal load, in the frame of the law (``t_a`` = x, ``t_b`` = y).
    Inside the solver a non-associated law's D is shrunk to the largest copy that fits in
    C (D matters only up to scale, SPEC.md 3), so that ``alpha <= 1``.

    Parameters
    ----------
    name : str
        One of ``"coulomb"``, ``"ellipse"``, ``"truncated-ellipse"``, ``"collinear"``,
        ``"componentwise"``, ``"star"``.
    law : WalkerLeineLaw
        C the reservoir, D the (convex) sliding set; ``law.force(psi)`` is the sliding
        force per unit normal load.
    description : str, optional
        One line saying what the law is (at most 1000 characters).

    Attributes
    ----------
    associated : bool
        C and D are the same set (the solver's prox is onto C alone).

    Raises
    ------
    InputError
        If ``name`` is not one of these, ``law`` not a WalkerLeineLaw or its D not convex.

    See Also
    --------
    asperity.coulomb_law, asperity.law_from_gauge : built-in laws (and those they list).
    asperity.slide : a point mass sliding on a law.

    Examples
    --------
    Antoni et al.'s figure 7 ellipse (SPEC.md 3) as an associated law:

    >>> C = asperity.TruncatedEllipse(0.2, 0.08, 0.12, 0.15)
    >>> law = asperity.PlanarLaw("truncated-ellipse", asperity.WalkerLeineLaw(C, C))
    >>> law.associated
    True
    >>> {k: round(v, 4) for k, v in law.axes().items()}
    {'mu_a_plus': 0.2, 'mu_a_minus': 0.08, 'mu_b_plus': 0.12, 'mu_b_minus': 0.15}
    >>> print(f"{law.min_tangential():.4f}")
    0.0800
    """

    name: str
    law: WalkerLeineLaw
    description: str = ""
    _kernel: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        from ..errors import check_instance, check_text
        check_choice("name", self.name, LAW_NAMES)
        check_instance("law", self.law, WalkerLeineLaw)
        check_text("description", self.description, 1000)
        C, D = self.law.C, self.law.D
        assoc = C is D or (type(C) is type(D) and C == D and not isinstance(C, ConvexSet))
        if not assoc:
            D = scale_set(D, self.d_scale_of(C, D))
        ck, cp, ct = _set_tables(C)
        if assoc:
            dk, dp, dt = ck, cp, ct
        else:
            dk, dp, dt = _set_tables(D)
            if dk == SET_STAR:
                raise InputError("D must be convex (Disc, TruncatedEllipse or ConvexSet), "
                                 "got a StarSet")
        object.__setattr__(self, "_kernel", (bool(assoc), ck, cp, ct, dk, dp, dt))

    @staticmethod
    def d_scale_of(C, D) -> float:
        """min over directions of rho_C / rho_D: D times this lies in C (k_D >= k_C there)."""
        phi = 2 * math.pi * np.arange(_SCALE_DIRECTIONS) / _SCALE_DIRECTIONS
        if isinstance(C, StarSet):
            phi = np.concatenate([phi, C.angles[:-1]])
        return float(np.min(C.radial(phi) / D.radial(phi)))

    @property
    def associated(self) -> bool:
        return self._kernel[0]

    @property
    def kernel_sets(self) -> tuple:
        """(assoc, c_kind, c_par, c_tab, d_kind, d_par, d_tab) as the kernels take them
        (D already scaled inside C)."""
        return self._kernel

    def force(self, psi) -> np.ndarray:
        """(m, 2) sliding force p = -lambda_T/lambda_N for the directions psi (rad)."""
        return self.law.force(psi).p

    def radial(self, phi) -> np.ndarray:
        """Radial function of the reservoir C."""
        return self.law.C.radial(np.atleast_1d(np.asarray(phi, dtype=float)))

    def min_tangential(self, n: int = 3600) -> float:
        """min over sliding directions of p.s (the smallest decelerating coefficient)."""
        psi = 2 * math.pi * np.arange(n) / n
        return float(np.min(np.einsum("ij,ij->i", self.force(psi), unit(psi))))

    def axes(self) -> dict:
        """``|p|`` for sliding along +t_a, -t_a, +t_b, -t_b."""
        f = self.force(np.array([0.0, math.pi, 0.5 * math.pi, 1.5 * math.pi]))
        r = np.hypot(f[:, 0], f[:, 1])
        return {"mu_a_plus": float(r[0]), "mu_a_minus": float(r[1]),
                "mu_b_plus": float(r[2]), "mu_b_minus": float(r[3])}


# ----------------------------------------------------------------------------- built-in laws

def _mu(name, v) -> float:
    from .geometry import check_mu_law
    return check_mu_law(name, v)


def coulomb_law(mu: float) -> PlanarLaw:
    """Isotropic Coulomb friction of coefficient ``mu``.

    C = D = the disc of radius ``mu`` (associated): the force opposes the slip with
    magnitude ``mu`` per unit normal load in every direction.

    Parameters
    ----------
    mu : float
        Friction coefficient, in [1e-6, 100].

    Returns
    -------
    PlanarLaw
        The law named ``"coulomb"``.

    Raises
    ------
    InputError
        If ``mu`` is not a number in [1e-6, 100].

    See Also
    --------
    asperity.ellipse_law, asperity.truncated_ellipse_law, asperity.collinear_law,
    asperity.componentwise_law, asperity.star_law : the other built-in laws.
    asperity.slide : a point mass on the law; it stops after ``u0 / (mu g)`` s.

    Examples
    --------
    >>> law = asperity.coulomb_law(0.3)
    >>> print(np.round(law.force(np.radians([0.0, 90.0])), 6))
    [[0.3 0. ]
     [0.  0.3]]
    >>> asperity.coulomb_law(-1)
    Traceback (most recent call last):
    ...
    asperity.errors.InputError: mu must be in [1e-06, 100], got -1
    """
    d = Disc(_mu("mu", mu))
    return PlanarLaw("coulomb", WalkerLeineLaw(d, d), f"isotropic Coulomb, mu = {mu:g}")


def ellipse_law(mu1: float, mu2: float) -> PlanarLaw:
    """Associated orthotropic ellipse: semi-axis ``mu1`` along t_a, ``mu2`` along t_b.

    C = D = the ellipse (normal sliding rule, maximum dissipation): for the unit slip
    ``s = (cos psi, sin psi)`` the force is
    :math:`p = (\\mu_1^2 s_a, \\mu_2^2 s_b) / \\sqrt{\\mu_1^2 s_a^2 + \\mu_2^2 s_b^2}`,
    not parallel to ``s`` off the axes.

    Parameters
    ----------
    mu1, mu2 : float
        Friction coefficients along +-t_a and +-t_b, in [1e-6, 100].

    Returns
    -------
    PlanarLaw
        The law named ``"ellipse"``.

    See Also
    --------
    asperity.truncated_ellipse_law : four semi-axes (asymmetric friction).
    asperity.collinear_law : the same magnitudes, force along the slip.

    Examples
    --------
    Sliding at 45 deg, the force leans towards the high-friction axis t_b:

    >>> law = asperity.ellipse_law(0.2, 0.4)
    >>> p = law.force(np.radians([45.0]))[0]
    >>> print(np.round(p, 4), round(float(np.degrees(np.arctan2(p[1], p[0]))), 2))
    [0.0894 0.3578] 75.96
    """
    mu1, mu2 = _mu("mu1", mu1), _mu("mu2", mu2)
    e = TruncatedEllipse(mu1, mu1, mu2, mu2)
    return PlanarLaw("ellipse", associated(e),
                     f"associated orthotropic ellipse, mu1 = {mu1:g} (t_a), mu2 = {mu2:g} (t_b)")


def truncated_ellipse_law(mu_a_plus, mu_a_minus, mu_b_plus, mu_b_minus,
                          theta: float = 0.0) -> PlanarLaw:
    """Associated truncated ellipse (Antoni et al. eq. 18), asymmetric in general.

    Four quarter ellipses: the gauge is
    :math:`k(x) = \\sqrt{(x_a/\\mu_a^\\pm)^2 + (x_b/\\mu_b^\\pm)^2}`, the sign of ``x_a``
    picking ``mu_a+`` or ``mu_a-`` and that of ``x_b`` ``mu_b+`` or ``mu_b-`` (SPEC.md 3).
    C = D (normal sliding rule); with ``mu_a+ != mu_a-`` the law ratchets.

    Parameters
    ----------
    mu_a_plus, mu_a_minus : float
        Coefficients for sliding along +t_a and -t_a, in [1e-6, 100].
    mu_b_plus, mu_b_minus : float
        Coefficients for sliding along +t_b and -t_b, in [1e-6, 100].
    theta : float, optional
        Angle (rad) of t_a in the frame of the forces, in [-4 pi, 4 pi]; default 0.

    Returns
    -------
    PlanarLaw
        The law named ``"truncated-ellipse"``.

    Raises
    ------
    InputError
        If a coefficient is not in [1e-6, 100] or ``theta`` out of range.

    See Also
    --------
    asperity.TruncatedEllipse : the set itself.
    asperity.fit_derivation : such a law fitted to a texture.

    Examples
    --------
    The SPEC.md wedge (alpha = 30, beta = 10 deg, mu = 0.1 / 0.2): a point mass launched
    at 1 m/s along +t_a stops after ``1 / (mu_a+ g)`` = 0.549 s, along -t_a after 0.528 s.

    >>> law = asperity.truncated_ellipse_law(0.185697, 0.193238, 0.182587, 0.182587)
    >>> [asperity.slide(law, 1.0, a, dt=1e-3).stop_time for a in (0.0, 180.0)]
    [0.549, 0.528]
    """
    e = TruncatedEllipse(_mu("mu_a_plus", mu_a_plus), _mu("mu_a_minus", mu_a_minus),
                         _mu("mu_b_plus", mu_b_plus), _mu("mu_b_minus", mu_b_minus),
                         theta=as_number("theta", theta))
    return PlanarLaw("truncated-ellipse", associated(e),
                     f"associated truncated ellipse, mu_a+ = {mu_a_plus:g}, mu_a- = "
                     f"{mu_a_minus:g}, mu_b+ = {mu_b_plus:g}, mu_b- = {mu_b_minus:g}")


def collinear_law(C=None, mu1: float | None = None, mu2: float | None = None) -> PlanarLaw:
    """Collinear law: the force is parallel to the sliding direction, ``|p| = rho_C(psi)``.

    D is a disc: its normal cone at ``y`` is the ray of ``y``, so the force ``p`` (on the
    ray of ``y``) points along the sliding direction, with the magnitude of C's radial
    function there.

    Parameters
    ----------
    C : Disc, TruncatedEllipse, StarSet or ConvexSet, optional
        The set whose radial function gives the magnitude.  Default: the orthotropic
        ellipse of ``mu1``, ``mu2``.
    mu1, mu2 : float, optional
        Semi-axes along t_a and t_b of the default C, in [1e-6, 100]; both needed
        without C (ignored with it).

    Returns
    -------
    PlanarLaw
        The law named ``"collinear"`` (not associated).

    Raises
    ------
    InputError
        If neither C nor both ``mu1`` and ``mu2`` are given, or a value is out of range.

    See Also
    --------
    asperity.ellipse_law : the associated law of the same ellipse.
    asperity.law_from_gauge : the collinear variant of a gauge file's law.

    Examples
    --------
    >>> law = asperity.collinear_law(mu1=0.2, mu2=0.4)
    >>> p = law.force(np.radians([45.0]))[0]
    >>> print(np.round(p, 4), round(float(np.hypot(*p)), 4))
    [0.1789 0.1789] 0.253
    """
    if C is None:
        if mu1 is None or mu2 is None:
            raise InputError("collinear_law needs C or both mu1 and mu2")
        mu1, mu2 = _mu("mu1", mu1), _mu("mu2", mu2)
        C = TruncatedEllipse(mu1, mu1, mu2, mu2)
        what = f"ellipse mu1 = {mu1:g}, mu2 = {mu2:g}"
    else:
        from ..errors import check_instance
        check_instance("C", C, (Disc, TruncatedEllipse, StarSet, ConvexSet))
        what = type(C).__name__
    return PlanarLaw("collinear", WalkerLeineLaw(C, Disc(1.0)),
                     f"collinear: force along the sliding direction, |p| from the radial "
                     f"function of the {what}")


def componentwise_law(mu_f: float, mu_b: float, mu_t: float) -> PlanarLaw:
    """Componentwise rule (Hu, Nirody, Scott and Shelley, PNAS 2009).

    For the unit slip ``u = (cos psi, sin psi)``, ``p = (mu_{f|b} u_x, mu_t u_y)``
    (``mu_f`` where ``u_x >= 0``; the force on the body is ``-p N``).  The Walker-Leine
    law with C the truncated ellipse ``(mu_f, mu_b, mu_t, mu_t)`` and D the one of
    semi-axes ``sqrt(mu_f)``, ``sqrt(mu_b)``, ``sqrt(mu_t)`` times ``sqrt(min mu)`` (inside
    C, touching it): D's boundary point of normal ``u`` lies on the ray of
    ``(mu_{f|b} u_x, mu_t u_y)``, which is on C (SPEC.md 9).

    Parameters
    ----------
    mu_f, mu_b, mu_t : float
        Forward (sliding along +t_a), backward (-t_a) and transverse (+-t_b) coefficients,
        each in [1e-6, 100].

    Returns
    -------
    PlanarLaw
        The law named ``"componentwise"``.

    See Also
    --------
    asperity.crawl : a crawling body on such a law.

    Examples
    --------
    >>> law = asperity.componentwise_law(0.1, 0.15, 0.2)
    >>> print(np.round(law.force(np.radians([45.0, 135.0])), 4))
    [[ 0.0707  0.1414]
     [-0.1061  0.1414]]
    """
    from .componentwise import componentwise_pair
    law = componentwise_pair(mu_f, mu_b, mu_t)
    f, b, t = law.C.mu_a_plus, law.C.mu_a_minus, law.C.mu_b_plus
    return PlanarLaw("componentwise", law, f"componentwise (Hu et al.): mu_f = {f:g} (+t_a), "
                     f"mu_b = {b:g} (-t_a), mu_t = {t:g} (+-t_b)")


def _directions(n) -> int:
    """Directions of a star law's fit: as ``derive``'s."""
    from ..errors import check_int
    return check_int("directions", n, 8, 100_000)


@lru_cache(maxsize=4)
def _windward_fit(alpha_deg: float, beta_deg: float, mu_alpha: float, mu_beta: float,
                  directions: int):
    from ..friction.derive import derive
    from ..texture.wedges import WedgeTexture
    from .fitting import fit_derivation
    d = derive(WedgeTexture(alpha_deg, beta_deg, mu_alpha, mu_beta), "windward", "closed-form",
               directions)
    return fit_derivation(d, "star", holdout=False)


def windward_star_law(alpha_deg: float = 30.0, beta_deg: float = 30.0, mu_alpha: float = 0.3,
                      mu_beta: float = 0.3, directions: int = 360) -> PlanarLaw:
    """The star-shaped Walker-Leine law fitted to a windward (rigid-asperity) wedge texture.

    Only the faces facing the motion touch (SPEC.md 2): C is non-convex and D convex with
    a flat edge, so the force is set-valued when sliding exactly along the ridges (t_b).
    The law is derived in closed form at ``directions`` sliding directions and fitted as
    ``asperity fit --contact windward`` fits it (C through the points, D from their
    sliding rule).

    Parameters
    ----------
    alpha_deg, beta_deg : float, optional
        Slope angles (deg) of the rising and falling faces; default 30.
    mu_alpha, mu_beta : float, optional
        Local friction coefficients of the two faces; default 0.3.
    directions : int, optional
        Sliding directions of the fit, in [8, 100000]; default 360.

    Returns
    -------
    PlanarLaw
        The law named ``"star"``.

    Raises
    ------
    InputError
        If a parameter is out of range (those of :class:`~asperity.WedgeTexture`) or the
        texture self-locks (no finite law).

    See Also
    --------
    asperity.star_law : the same law stretched to given axis coefficients.

    Examples
    --------
    SPEC.md's check values: ``|p| = 1.061`` at psi = 0, ``p = (0.585, 0.348)`` at 89 deg:

    >>> law = asperity.windward_star_law()
    >>> print(np.round(law.force(np.radians([0.0, 89.0])), 3))
    [[1.061 0.   ]
     [0.585 0.348]]
    """
    from ..texture.wedges import WedgeTexture
    t = WedgeTexture(alpha_deg, beta_deg, mu_alpha, mu_beta)          # checks the numbers
    gl = _windward_fit(t.alpha_deg, t.beta_deg, t.mu_alpha, t.mu_beta, _directions(directions))
    return PlanarLaw("star", gl.law,
                     f"star-shaped law of the windward wedge texture alpha = {alpha_deg:g}, "
                     f"beta = {beta_deg:g} deg, mu = {mu_alpha:g}/{mu_beta:g}")


def star_law(mu1: float, mu2: float, directions: int = 360) -> PlanarLaw:
    """Built-in star-shaped law with ``|p| = mu1`` along +-t_a and ``mu2`` along +-t_b.

    The windward wedge law (30 deg, mu = 0.3, :func:`~asperity.windward_star_law`)
    mapped by ``S = diag(mu1 / rho(0), mu2 / rho(90 deg))``.  The map keeps C star-shaped
    (non-convex) and D convex; forces map by ``S`` and sliding directions (normals of D)
    by ``S^-1``, and the law is refitted through the mapped data (C the polygon, D
    integrated from the mapped sliding rule).

    Parameters
    ----------
    mu1, mu2 : float
        Coefficients along +-t_a and +-t_b, in [1e-6, 100].
    directions : int, optional
        Sliding directions of the underlying fit, in [8, 100000]; default 360.

    Returns
    -------
    PlanarLaw
        The law named ``"star"``.

    See Also
    --------
    asperity.windward_star_law : the unstretched law.

    Examples
    --------
    >>> law = asperity.star_law(0.2, 0.4)
    >>> {k: round(v, 6) for k, v in law.axes().items()}
    {'mu_a_plus': 0.2, 'mu_a_minus': 0.2, 'mu_b_plus': 0.4, 'mu_b_minus': 0.4}
    """
    from .fitting import ReservoirData, fit_star
    mu1, mu2 = _mu("mu1", mu1), _mu("mu2", mu2)
    gl = _windward_fit(30.0, 30.0, 0.3, 0.3, _directions(directions))
    data = gl.data
    C = gl.law.C
    sa = mu1 / float(C.radial(np.array([0.0]))[0])
    sb = mu2 / float(C.radial(np.array([0.5 * math.pi]))[0])
    p = data.p * np.array([sa, sb])
    s = unit(data.psi) / np.array([sa, sb])
    psi = np.mod(polar_angle(s), 2 * math.pi)
    psi[np.isclose(psi, 2 * math.pi, rtol=0, atol=1e-15)] = 0.0
    order = np.lexsort((data.limit, psi))
    law, _ = fit_star(ReservoirData(psi[order], p[order], data.limit[order]))
    return PlanarLaw("star", law,
                     f"star-shaped (windward wedge 30/30 deg, mu = 0.3, stretched): "
                     f"mu1 = {mu1:g} along t_a, mu2 = {mu2:g} along t_b")


def from_gauge(gauge, kind: str | None = None) -> PlanarLaw:
    """The law of a gauge file, for the solver.

    Parameters
    ----------
    gauge : str, pathlib.Path or GaugeLaw
        A gauge file written by ``asperity fit`` (or :func:`~asperity.write_gauge`), or
        the fitted law itself (:func:`~asperity.fit_derivation`, :func:`~asperity.read_gauge`).
    kind : str, optional
        None (default) or the file's own law: ``"ellipse"`` for a truncated-ellipse file,
        ``"star"`` or ``"componentwise"`` for such a file; or ``"collinear"`` (force along
        the sliding direction, ``|p|`` from the file's C).

    Returns
    -------
    PlanarLaw
        A ``"truncated-ellipse"``, ``"star"``, ``"componentwise"`` or ``"collinear"`` law.

    Raises
    ------
    InputError
        If the file cannot be read (one line naming the field), ``kind`` is another law,
        or the file holds a law family over the pressure (take ``GaugeFamily.at`` first).

    See Also
    --------
    asperity.read_gauge, asperity.write_gauge : gauge files.
    asperity.collinear_law : the collinear variant.

    Examples
    --------
    >>> d = asperity.derive(asperity.load_texture("surfaces/wedge-asymmetric.toml"))
    >>> gl = asperity.fit_derivation(d, "truncated-ellipse")
    >>> law = asperity.law_from_gauge(gl)
    >>> law.name, law.associated
    ('truncated-ellipse', True)
    >>> asperity.law_from_gauge(gl, "collinear").associated
    False
    """
    from .family import GaugeFamily
    from .fitting import GaugeLaw
    if not isinstance(gauge, (GaugeLaw, GaugeFamily)):
        from .gauge_file import read_gauge
        gauge = read_gauge(gauge)
    if isinstance(gauge, GaugeFamily):
        raise InputError(f"the gauge file holds a law family over the pressures "
                         f"{gauge.pressures[0]:g} to {gauge.pressures[-1]:g} Pa: take its law "
                         "at the nominal pressure first (GaugeFamily.at, or --pressure)")
    own = {"truncated-ellipse": "ellipse"}.get(gauge.kind, gauge.kind)
    kind = own if kind is None else check_choice("kind", kind, (own, "collinear"))
    if kind == "componentwise":
        from .componentwise import coefficients
        return componentwise_law(**coefficients(gauge.law))
    src = gauge.source.get("texture", {})
    what = src.get("kind", "?") if isinstance(src, dict) else "?"
    if kind == "collinear":
        return collinear_law(gauge.law.C)
    if own == "ellipse":
        return PlanarLaw("truncated-ellipse", gauge.law,
                         f"truncated ellipse of a gauge file ({what}, {gauge.source.get('contact')})")
    return PlanarLaw("star", gauge.law,
                     f"star-shaped law of a gauge file ({what}, {gauge.source.get('contact')})")


# ----------------------------------------------------------------------------- proximal maps

def _check_law(law) -> None:
    from ..errors import check_instance
    check_instance("law", law, PlanarLaw)


def _normal(normal) -> float:
    return check_range("normal", normal, 1e-12, 1e12)


def prox_interval(x, mu_minus: float, mu_plus: float, normal=1.0) -> np.ndarray:
    """Projection of x onto the asymmetric interval [-mu_minus N, mu_plus N] (1D Coulomb).

    The implicit 1D law of a tangential impulse Lambda (force on the body, +x positive) with
    slip rate gamma: ``-Lambda = prox_interval(-Lambda + r gamma, mu_minus, mu_plus, N)``:
    sliding towards +x resists with mu_plus N, towards -x with mu_minus N."""
    from ..errors import check_array
    n = check_array("normal", normal)
    if np.any(n < 0):
        raise InputError(f"normal must be >= 0, got {n.min():g}")
    lo, hi = _mu("mu_minus", mu_minus), _mu("mu_plus", mu_plus)
    return np.clip(check_array("x", x), -lo * n, hi * n)


def prox_set(law: PlanarLaw, x, normal: float = 1.0, which: str = "D"):
    """((m, 2) projections, (m,) inside flags) of the points x onto ``normal`` times the
    convex set D of the law (or C when it is convex and ``which`` = "C").  For an
    associated law (C = D) this is the whole prox of the law.  D is the solver's scaled D."""
    from ..errors import check_choice
    _check_law(law)
    check_choice("which", which, ("C", "D"))
    normal = _normal(normal)
    from ._set_kernels import project_many
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    kind, par, tab = (dk, dp, dt) if which == "D" else (ck, cp, ct)
    if kind == SET_STAR:
        raise InputError("C of this law is a star-shaped polygon: no projection onto it")
    x = points_array("x", x) / normal
    y, ins = project_many(kind, par, tab, np.ascontiguousarray(x))
    return y * float(normal), ins


def law_point(law: PlanarLaw, x, normal: float = 1.0):
    """The Walker-Leine map at prox arguments x: y = prox_D(x), then the force P on the ray
    of y with alpha(P) P = y.  Returns ((m, 2) P, (m,) inside = sticking)."""
    _check_law(law)
    normal = _normal(normal)
    from ._law_kernels import law_point_many
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    x = points_array("x", x) / normal
    P, ins = law_point_many(assoc, ck, cp, ct, dk, dp, dt, np.ascontiguousarray(x))
    return P * float(normal), ins


def kernel_radial(law: PlanarLaw, phi, which: str = "C") -> np.ndarray:
    """Radial function of C (or of the solver's D) as the kernels compute it."""
    from ..errors import check_choice
    _check_law(law)
    check_choice("which", which, ("C", "D"))
    phi = psi_array(phi, "phi")
    from ._set_kernels import radial_many
    assoc, ck, cp, ct, dk, dp, dt = law.kernel_sets
    kind, par, tab = (ck, cp, ct) if which == "C" else (dk, dp, dt)
    return radial_many(kind, par, tab, np.atleast_1d(np.asarray(phi, dtype=float)))


def solver_D(law: PlanarLaw):
    """The D the solver uses (scaled inside C for a non-associated law)."""
    C, D = law.law.C, law.law.D
    if law.associated:
        return D
    return scale_set(D, PlanarLaw.d_scale_of(C, D))
