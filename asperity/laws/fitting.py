"""Directional friction -> a friction law: the fits (SPEC.md section 3).

:func:`fit_truncated_ellipse` (4 parameters, least squares on the relative radial error)
and :func:`fit_star` (``C`` through the data, ``D`` integrated from the sliding rule
``d ln h / d psi = tan(angle(p) - psi)``).  :func:`fit_derivation` does either from a
:class:`~asperity.friction.derive.Derivation` and checks the law at directions not used in
the fit; its :class:`GaugeLaw` is what a gauge file records.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..io import json_ready
from ..friction.reservoir import Reservoir
from .convex_set import ConvexSet
from .geometry import (
    LAW_KINDS,
    TOL,
    TWO_PI,
    angle_between,
    check_mu_law,
    polar_angle,
    tan_integral,
    unit,
)
from .sets import StarSet, TruncatedEllipse
from .walker_leine import LawForce, WalkerLeineLaw, associated


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
    from ..errors import check_instance
    check_instance("reservoir", res, Reservoir)
    psi = np.asarray(res.psi, dtype=float)
    if psi.ndim != 1 or psi.size < 8:
        raise InputError(f"a fit needs at least 8 directions, got {psi.size}")
    if res.locked.any():
        from ..friction.reservoir import locked_runs
        raise InputError(
            f"the texture self-locks in {int(res.locked.sum())} of {psi.size} directions "
            f"(psi in {locked_runs(res)}): friction is unbounded there and no finite friction law "
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
    from ..errors import check_instance, check_range
    check_instance("data", data, ReservoirData)
    theta = check_range("theta", theta, -2 * TWO_PI, 2 * TWO_PI, unit="rad")
    if start is not None:
        start = [check_mu_law(f"start[{i}]", v) for i, v in enumerate(start)]
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
    from ..errors import check_instance
    check_instance("data", data, ReservoirData)
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
    from ..errors import check_instance
    check_instance("law", law, WalkerLeineLaw)
    check_instance("ref", ref, Reservoir)
    ok = ~(ref.locked | ref.set_valued)
    if not ok.any():
        return 0.0, 0.0
    f = law.force(ref.psi[ok])
    r = np.hypot(ref.p[ok, 0], ref.p[ok, 1])
    mag = np.abs(np.hypot(f.p[:, 0], f.p[:, 1]) - r) / r
    ang = angle_between(f.p, ref.p[ok])
    return float(mag.max()), float(np.degrees(ang.max()))


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
    """Fit a friction law to a derivation: directional friction -> a gauge (SPEC.md 3).

    ``"truncated-ellipse"``: the 4 semi-axes, least squares on the relative radial error
    ``(rho_E(angle p_k) - |p_k|) / |p_k|`` (associated law, C = D).  ``"star"``: C the
    polygon through the reservoir points, D integrated from the sliding rule
    ``d ln h_D / d psi = tan(angle(p) - psi)`` (a closure residual is removed by turning
    every boundary point of D by the same small angle, both reported).  The set-valued
    directions are resolved by evaluating the texture beside them (closed form); with
    ``holdout`` the law is compared with the texture at the directions midway between the
    fitted ones (not used in the fit).

    Parameters
    ----------
    d : Derivation
        What :func:`~asperity.derive` returns, at 8 directions or more.
    kind : {"star", "truncated-ellipse"}, optional
        The law to fit; default ``"star"``.
    holdout : bool, optional
        Check the law at the directions midway between the fitted ones (default True).

    Returns
    -------
    GaugeLaw
        ``kind``, ``law`` (the WalkerLeineLaw), ``data`` (the points fitted), ``fit`` (the
        fit report: radial and angle errors, admissibility, convexity of C and D, closure
        and holdout errors), ``source`` (the texture and contact regime) and
        ``principal_direction_deg`` (t_a in the frame of the forces): what a gauge file
        records (:func:`~asperity.write_gauge`).

    Raises
    ------
    InputError
        If ``kind`` is unknown, the texture self-locks in some direction (unbounded
        friction: no finite gauge), ``p.s <= 0`` somewhere (negative dissipation: no
        convex D), or, for a star law, the points are not star-shaped or their sliding
        rule does not close.

    See Also
    --------
    asperity.derive : the directional friction of a texture or surface.
    asperity.write_gauge : the gauge file of the fitted law.
    asperity.law_from_gauge : the law for the solver.

    Examples
    --------
    The SPEC.md wedge: the star law passes through the derived points (mu_a+ = 0.185697,
    mu_a- = 0.193238 along the axes), the truncated ellipse smooths them:

    >>> d = asperity.derive(asperity.load_texture("surfaces/wedge-asymmetric.toml"))
    >>> star = asperity.fit_derivation(d)
    >>> print(star.force(np.radians([0.0, 180.0])).p.round(6))
    [[ 0.185697  0.      ]
     [-0.193238  0.      ]]
    >>> star.fit.admissible, star.fit.D_convex
    (True, True)
    >>> ell = asperity.fit_derivation(d, "truncated-ellipse")
    >>> {k: round(v, 4) for k, v in ell.law.C.axes.items()}
    {'mu_a_plus': 0.1852, 'mu_a_minus': 0.1938, 'mu_b_plus': 0.1826, 'mu_b_minus': 0.1826}
    >>> print(f"{ell.fit.max_radial_error:.4f}")
    0.0044
    """
    from ..errors import check_instance
    from ..friction.derive import Derivation
    check_instance("derivation", d, Derivation)
    from ..friction.faces import compute_reservoir
    from ..errors import check_choice, check_flag
    check_choice("kind", kind, LAW_KINDS)
    check_flag("holdout", holdout)

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
    out = {"texture": json_ready(tdict), "contact": d.contact, "method": d.method,
           "n_directions": int(d.reservoir.psi.size)}
    if getattr(tex, "elastic", None) is not None:     # load shares from an elastic contact
        out["elastic_contact"] = json_ready(tex.elastic)
    return out
