"""A body that changes shape crawls on direction-dependent friction (issue 26).

Model (Hu, Nirody, Scott and Shelley, PNAS 106:10081, 2009; Walker and Leine's snake
robots): a slender body of length L whose shape in its own frame is prescribed over time
(the gait, :mod:`asperity.crawling.gait`) rests on N contact points s_i = (i + 1/2) L / N with
load shares w_i (uniform mass).  The body frame has its origin at the centre of mass and
its orientation theta at the mean tangent angle, so the body's rigid motion is
q = (x, y, theta) with velocity u = (vx, vy, omega), and point i moves over the ground at

    gamma_i = (vx, vy) + omega e_z x o_i + R(theta) v_i        (o_i = R(theta) r_i)

with r_i, v_i its position and velocity in the body frame (the gait's).  Each point carries
the load w_i m g and obeys a planar law (:class:`~asperity.laws.planar.PlanarLaw`) turned by
its own angle: the body's tangent there (towards the head) plus ``texture_angle_deg`` for a
texture on the body (skin, scales), ``texture_angle_deg`` alone for one on the ground.

Newton-Euler with Moreau's midpoint scheme, exact stick, no regularisation (SPEC.md 4):
q_M = q_A + dt/2 u_A, the gait at t_M, then m (v_E - v_A) = sum P_i and the angular
momentum about the centre, m (I omega + S) with I = sum w_i |r_i|^2 and the gait's own spin
S = sum w_i r_i x v_i, changes by the friction's moment: I_E omega_E = I_A omega_A + S_A -
S_E + (moment)/m; q_E = q_M + dt/2 u_E.  A step is the rigid-body solver's step with moving
points (:mod:`asperity.crawling._kernels`): three unknowns, a point that sticks held exactly.

Quasi-static (``quasi_static=True``, the limit most of the literature reports): no
inertia, the net friction force and torque vanish at every instant; solved as the same step
with the momentum weighted by QS_EPS = 1e-12 against the friction impulse, i.e. the balance
holds to 1e-12 of the friction scale (stick stays exact: the law is not regularised).  The
speed then depends only on the gait and the law (not on g, m or T: tested).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_choice, check_flag, check_instance, check_int, check_range
from ..laws.planar import PlanarLaw
from ..resources import check_memory, check_work

#: the momentum's weight against the friction impulse in the quasi-static limit
QS_EPS = 1e-12
#: steps per period by default (dt = T / STEPS_PER_PERIOD): the dynamic speed within 3.3e-4
#: of its limit in dt (first order: 1.7e-4 at 400), the quasi-static one within 4e-6 (second
#: order) on the default wave
STEPS_PER_PERIOD = 200
#: most steps x points / 16 a run may take (as ``slide``'s work limit)
MAX_WORK = 5e8
MAX_PERIODS = 100_000
MAX_POINTS = 100_000
RULES = ("componentwise", "associated", "colinear")
SIDES = ("body", "ground")


@dataclass(frozen=True)
class CrawlSettings:
    """The step solver's settings of a crawl.

    Parameters
    ----------
    tol : float, optional
        Relative tolerance of a step's equation, in [1e-15, 1e-3] (default 1e-12).
    max_iterations : int, optional
        Most iterations of each Newton solve, in [1, 1e6] (default 200); a step that does
        not converge stops the run (``status`` "not-converged").

    Raises
    ------
    InputError
        A value outside its range.

    See Also
    --------
    asperity.crawl

    Examples
    --------
    >>> settings = asperity.CrawlSettings(tol=1e-10)
    >>> run = asperity.crawl(mu_f=0.11, mu_b=0.19, mu_t=0.2, quasi_static=True,
    ...                      settings=settings)
    >>> run.status, run.max_iterations_used <= settings.max_iterations
    ('ok', True)
    """

    tol: float = 1e-12
    max_iterations: int = 200

    def __post_init__(self):
        check_range("tol", self.tol, 1e-15, 1e-3)
        check_int("max_iterations", self.max_iterations, 1, 1_000_000)


def coefficient_law(mu_f: float, mu_b: float, mu_t: float, rule: str = "componentwise"
                    ) -> PlanarLaw:
    """The friction law of three coefficients as the snake literature states them.

    Forward is +x: towards the head for a texture on the body.  The set of admissible
    forces is two half-ellipses of semi-axes (mu_f or mu_b, mu_t); the rules agree for pure
    forward, backward and transverse slip and differ in between (SPEC.md 9).

    Parameters
    ----------
    mu_f : float
        Forward coefficient (+x), in [1e-6, 100].
    mu_b : float
        Backward coefficient (-x), in [1e-6, 100].
    mu_t : float
        Transverse coefficient (+-y), in [1e-6, 100].
    rule : str, optional
        "componentwise" (default; Hu et al.: each component of the unit slip scaled by
        its own coefficient), "associated" (maximum dissipation on the half-ellipses:
        Antoni et al.'s truncated ellipse) or "colinear" (the force opposite to the slip,
        its size the radius of that set).

    Returns
    -------
    PlanarLaw
        The law, as :func:`asperity.componentwise_law`,
        :func:`asperity.truncated_ellipse_law` or :func:`asperity.collinear_law` build it.

    Raises
    ------
    InputError
        A coefficient outside its range, an unknown rule.

    See Also
    --------
    asperity.crawl, asperity.componentwise_law, asperity.truncated_ellipse_law

    Examples
    --------
    Sliding at 45 deg to the body's axis, the three rules give three forces (per unit
    load, the force of slip direction psi):

    >>> for rule in ("componentwise", "associated", "colinear"):
    ...     law = asperity.coefficient_law(0.11, 0.19, 0.2, rule)
    ...     print(rule, law.force(np.array([np.pi / 4]))[0].round(4).tolist())
    componentwise [0.0778, 0.1414]
    associated [0.053, 0.1752]
    colinear [0.0964, 0.0964]
    """
    from ..laws.geometry import check_mu_law
    from ..laws.planar import collinear_law, componentwise_law, truncated_ellipse_law
    rule = check_choice("rule", rule, RULES)
    if rule == "componentwise":
        return componentwise_law(mu_f, mu_b, mu_t)
    # the coefficients named as given (not as the ellipse's mu_a+, mu_a-, mu_b+- they become)
    mu_f, mu_b, mu_t = (check_mu_law(n, v) for n, v in zip(("mu_f", "mu_b", "mu_t"),
                                                             (mu_f, mu_b, mu_t)))
    law = truncated_ellipse_law(mu_f, mu_b, mu_t, mu_t)
    if rule == "associated":
        return law
    return collinear_law(law.law.C)


#: the law fitted to a texture: --fit-law -> asperity.laws.fitting's kind
FIT_LAWS = {"star": "star", "ellipse": "truncated-ellipse"}
#: sliding directions of a texture fitted for a crawl (as ``asperity fit``'s default)
FIT_DIRECTIONS = 720


def fitted_law(texture, fit_law: str = "star", contact: str = "all-faces",
               progress=None) -> PlanarLaw:
    """The law a crawl takes from a texture or surface: derived (closed form, ``contact``
    model, FIT_DIRECTIONS directions) and fitted (``fit_law``: star or ellipse), as
    ``asperity fit`` does; the command, the web page and studies take it from here."""
    from ..friction.derive import derive
    from ..laws.fitting import fit_derivation
    from ..laws.planar import from_gauge
    kind = FIT_LAWS[check_choice("fit_law", fit_law, tuple(FIT_LAWS))]
    d = derive(texture, contact, "closed-form", FIT_DIRECTIONS, progress=progress)
    return from_gauge(fit_derivation(d, kind))


def law_rule(law: PlanarLaw) -> str:
    """The rule a law slides by, as the crawl's JSON states it."""
    if law.name == "componentwise":
        return "componentwise"
    if law.name == "collinear":
        return "colinear"
    return "associated" if law.associated else "walker-leine"


@dataclass(frozen=True)
class CrawlResult:
    """A crawl: the recorded motion of the body's centre and the friction's work.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Recorded times, s.
    q, u : ndarray, shape (k, 3)
        ``(x, y, theta)`` and ``(vx, vy, omega)`` of the centre of mass and the mean tangent
        angle (SI, world frame).
    work, dissipated : ndarray, shape (k,)
        Work of the gait against friction and energy dissipated by friction so far, J.
    speed_per_period : ndarray
        One value a period: the centre's displacement over the period projected on its mean
        heading, head-ward positive, in body lengths.
    drift_per_period : ndarray
        One value a period: the heading's change, rad.
    transient_periods, periods, steps_per_period, points : int
        Periods left out as the transient, periods run, steps a period, contact points.
    dt : float
        Time step, s.
    quasi_static : bool
        Whether the crawl was quasi-static (no inertia).
    """

    t: np.ndarray
    q: np.ndarray
    u: np.ndarray
    work: np.ndarray
    dissipated: np.ndarray
    speed_per_period: np.ndarray
    drift_per_period: np.ndarray
    transient_periods: int
    periods: int
    steps_per_period: int
    dt: float
    points: int
    quasi_static: bool
    rule: str
    law_name: str
    texture_on: str
    texture_angle_deg: float
    gait: dict
    length: float
    period: float
    mass: float
    g: float
    mu_forward: float
    status: str
    message: str
    mean_iterations: float
    max_iterations_used: int
    stick_fraction: float
    records_per_period: int = 1
    law_description: str = ""
    extra: dict = field(default_factory=dict)

    def summary(self) -> dict:
        """The JSON object ``asperity crawl --json`` prints (:func:`.output.summary`)."""
        from .output import summary
        return summary(self)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    @property
    def averaged(self) -> slice:
        return slice(self.transient_periods, self.periods)

    @property
    def speed_body_lengths_per_period(self) -> float | None:
        """Mean over the averaged periods; None if no period was completed (a step that
        did not converge stops the run)."""
        s = self.speed_per_period[self.averaged]
        return float(np.mean(s)) if s.size else None

    @property
    def heading_drift_rad_per_period(self) -> float | None:
        s = self.drift_per_period[self.averaged]
        return float(np.mean(s)) if s.size else None

    @property
    def froude(self) -> float:
        """L / (g mu T^2), mu the law's forward coefficient."""
        return self.length / (self.g * self.mu_forward * self.period ** 2)

    def _window(self):
        r = self.records_per_period
        return self.transient_periods * r, self.periods * r

    @property
    def cost_of_transport(self) -> float | None:
        """Work of the gait against friction over m g times the distance the centre moved,
        over the averaged periods; None when it did not move (no distance to divide by)."""
        a, b = self._window()
        if b <= a or b >= len(self.q):
            return None
        d = float(np.hypot(*(self.q[b, :2] - self.q[a, :2])))
        if d <= 1e-12 * self.length:
            return None
        return float((self.work[b] - self.work[a]) / (self.mass * self.g * d))


def _check_law(law, mu_f, mu_b, mu_t, rule) -> PlanarLaw:
    coeffs = (mu_f, mu_b, mu_t)
    given = [c is not None for c in coeffs]
    if law is not None:
        check_instance("law", law, PlanarLaw)
        if any(given):
            raise InputError("law and mu_f/mu_b/mu_t exclude each other: give one law")
        return law
    if not all(given):
        missing = [n for n, g in zip(("mu_f", "mu_b", "mu_t"), given) if not g]
        raise InputError(f"{', '.join(missing)} must be given (a law of three coefficients "
                         "needs mu_f, mu_b and mu_t), or a law")
    return coefficient_law(mu_f, mu_b, mu_t, rule)


def crawl(law: PlanarLaw | None = None, *, mu_f=None, mu_b=None, mu_t=None,
          rule: str = "componentwise", gait=None, amplitude: float | None = None,
          waves: float | None = None, length: float | None = None,
          period: float | None = None, points: int = 100,
          periods: int | None = None, quasi_static: bool = False, g: float = 9.81,
          steps_per_period: int = STEPS_PER_PERIOD, texture_on: str = "body",
          texture_angle_deg: float = 0.0, weights=None, mass: float = 1.0,
          settings: CrawlSettings = CrawlSettings()) -> CrawlResult:
    """Crawl a slender body that changes shape on direction-dependent friction (SPEC.md 9).

    The body starts from rest at the origin, heading +x, and moves its shape by ``gait``
    (default: Hu et al.'s curvature wave) on ``law`` (or the law of ``mu_f``, ``mu_b``,
    ``mu_t`` by ``rule``), for ``periods`` periods.

    Parameters
    ----------
    law : PlanarLaw or None, optional
        The friction law of each contact point, in the point's frame (t_a along the body's
        tangent towards the head for a texture on the body); or None and the three
        coefficients.
    mu_f, mu_b, mu_t : float or None, optional
        Forward, backward and transverse coefficients (see
        :func:`asperity.coefficient_law`); all three, or a ``law``.
    rule : str, optional
        How the three coefficients make a law: "componentwise" (default), "associated" or
        "colinear".
    gait : Gait or None, optional
        A prescribed gait (``asperity.crawling.gait``, or a gait file read by
        ``asperity.crawling.gait_file.read_gait``); None: the curvature wave
        kappa L = A cos 2 pi (k s / L + t / T) of the four numbers below.
    amplitude : float or None, optional
        A = kappa L of the default wave, in [0, 100] (default 7); not with ``gait``.
    waves : float or None, optional
        k, waves on the body, in (0, 20] (default 1); not with ``gait``.
    length : float or None, optional
        L, m, in [1e-6, 1e6] (default 1); not with ``gait``.
    period : float or None, optional
        T, s, in [1e-6, 1e6] (default 1); not with ``gait``.
    points : int, optional
        Contact points along the body, at s_i = (i + 1/2) L / N, in [3, 1e5] (default 100).
    periods : int or None, optional
        Periods to run, in [1, 1e5]; None: 1 quasi-static, 8 dynamic (a dynamic run averages
        its speed over the second half, the first is its transient).
    quasi_static : bool, optional
        No inertia: the net friction force and torque vanish at every instant (default
        False: Newton-Euler).
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4] (default 9.81).
    steps_per_period : int, optional
        Time steps per period, in [8, 1e7] (default 200).
    texture_on : str, optional
        "body" (default: skin, scales; the law turns with the body's tangent) or "ground"
        (the law stays in the world frame).
    texture_angle_deg : float, optional
        The law's t_a axis from the tangent (body) or from x (ground), deg, in
        [-360, 360] (default 0).
    weights : callable, array_like or None, optional
        The points' mass shares: None (default) uniform, a callable of s (m) giving N
        values, or N values; each > 0 (normalised).
    mass : float, optional
        kg, in [1e-9, 1e9] (default 1).
    settings : CrawlSettings, optional
        The step solver's tolerance and iteration limit.

    Returns
    -------
    CrawlResult
        The recorded states ``t``, ``q`` (x, y, theta: the centre of mass and the mean
        tangent angle), ``u`` (vx, vy, omega), SI, world frame; ``work`` of the gait and
        ``dissipated`` by friction (J); per period ``speed_per_period`` (body lengths,
        head-ward positive) and ``drift_per_period`` (rad);
        ``speed_body_lengths_per_period`` their mean over the averaged periods;
        ``status`` ("ok", "not-converged" or "non-finite": the run stops at that step,
        ``message`` says where); ``summary()`` the JSON object of
        ``asperity crawl --json``.

    Raises
    ------
    InputError
        Neither a law nor all three coefficients, or both; a wave parameter with a
        ``gait``; a gait that crosses itself; a value outside its range; a run too large.

    See Also
    --------
    asperity.coefficient_law, asperity.CrawlSettings, asperity.slide_body

    Notes
    -----
    The body frame has its origin at the centre of mass and its orientation at the mean
    tangent angle; each point carries the load w_i m g and obeys the law turned by its
    own angle.  Newton-Euler with Moreau's midpoint scheme, exact stick, no
    regularisation (SPEC.md 4; ``asperity.crawling.solver``'s docstring has the step).
    Quasi-static: the momentum weighted by 1e-12 against the friction impulse, so the
    balance holds to 1e-12 of the friction scale; the speed then depends only on the gait
    and the law (not on g, m or T).

    Examples
    --------
    Quasi-static, on a law whose transverse coefficient is far above the forward one, the
    body follows its own track: the speed approaches J0(A / (2 pi k)) / k = 0.7130 body
    lengths per period (SPEC.md 9):

    >>> run = asperity.crawl(mu_f=0.1, mu_b=0.1, mu_t=100.0, quasi_static=True)
    >>> print(f"{run.speed_body_lengths_per_period:.4f}")
    0.7107
    >>> run = asperity.crawl(mu_f=0.11, mu_b=0.19, mu_t=0.2, quasi_static=True)
    >>> print(f"{run.speed_body_lengths_per_period:.4f}", run.status)
    0.1371 ok
    """
    from .gait import CurvatureWave, Gait
    law = _check_law(law, mu_f, mu_b, mu_t, rule)
    check_instance("settings", settings, CrawlSettings)
    wave = {"amplitude": amplitude, "waves": waves, "period": period, "length": length}
    if gait is None:
        gait = CurvatureWave(**{k: ({"amplitude": 7.0}.get(k, 1.0) if v is None else v)
                                for k, v in wave.items()})
    else:
        check_instance("gait", gait, Gait)
        given = [k for k, v in wave.items() if v is not None]
        if given:
            raise InputError(f"{given[0]} applies to the default curvature wave, not with a "
                             "gait (the gait gives its own)")
    n = check_int("points", points, 3, MAX_POINTS)
    qs = check_flag("quasi_static", quasi_static)
    periods = (1 if qs else 8) if periods is None else check_int("periods", periods, 1,
                                                                  MAX_PERIODS)
    P = check_int("steps_per_period", steps_per_period, 8, 10_000_000)
    g = check_range("g", g, 1e-6, 1e4, unit="m/s^2")
    mass = check_range("mass", mass, 1e-9, 1e9, unit="kg")
    side = check_choice("texture_on", texture_on, SIDES)
    a = math.radians(check_range("texture_angle_deg", texture_angle_deg, -360.0, 360.0,
                                 unit="deg"))
    check_work(float(P) * periods * max(1.0, n / 16.0), MAX_WORK,
               "this crawl (steps times the contact points / 16)",
               "use fewer points, periods or steps per period")
    check_memory(P * n * 5 * 8.0 + P * periods * 9 * 8.0,
                 f"a crawl of {P} steps a period x {n} points", "use fewer steps per period")
    dt = float(gait.period) / P
    kin_mid, kin_end = _gait_tables(gait, n, P, weights)
    return _run(law, gait, kin_mid, kin_end, n, periods, P, dt, qs, g, mass, side, a,
                settings)


#: gaits whose tables are kept (a study ranks many laws on one gait): key -> tables
_TABLES: dict = {}
TABLES_KEPT = 8


def _gait_tables(gait, n: int, P: int, weights):
    """The gait checked for self-crossing and tabulated at the steps' mid times and ends;
    kept for the last TABLES_KEPT gaits fully given by their parameters (uniform weights;
    not a joint table, whose parameters do not hold its angles)."""
    import json
    key = None
    if weights is None and gait.kind in ("curvature_wave", "fourier", "serpenoid"):
        key = (gait.kind, json.dumps(gait.params(), sort_keys=True), n, P)
        if key in _TABLES:
            return _TABLES[key]
    from .gait_crossing import check_self_crossing
    # the body as a polyline of 512 segments (the crossing is the continuous body's; the
    # polyline departs from it by kappa h^2 / 8, 3e-6 L at kappa L = 7), 256 instants
    check_self_crossing(gait, n_points=min(n, 64))
    dt = float(gait.period) / P
    tables = (gait.kinematics((np.arange(P) + 0.5) * dt, n, weights),
              gait.kinematics(np.arange(P + 1) * dt, n, weights))
    if key is not None:
        if len(_TABLES) >= TABLES_KEPT:
            _TABLES.pop(next(iter(_TABLES)))
        _TABLES[key] = tables
    return tables


def _run(law, gait, km, ke, n, periods, P, dt, qs, g, mass, side, a, settings):
    from ..dynamics.body import law_tables
    from ..progress import chunks
    from . import _kernels as K
    kind, par, tab, assoc, mu = law_tables(law)
    r = np.ascontiguousarray(km.r, dtype=float)
    v = np.ascontiguousarray(km.v, dtype=float)
    tau = np.ascontiguousarray(km.tangent, dtype=float)
    inertia = np.ascontiguousarray(ke.inertia, dtype=float)
    spin = np.ascontiguousarray(ke.spin, dtype=float)
    w = np.ascontiguousarray(km.weights, dtype=float)
    steps = P * periods
    record_every = max(1, P // 200) if P % max(1, P // 200) == 0 else 1
    n_rec = steps // record_every + 1
    rec_t, rec_q, rec_u = np.zeros(n_rec), np.zeros((n_rec, 3)), np.zeros((n_rec, 3))
    rec_e = np.zeros((n_rec, 2))
    info = np.zeros(K.INFO_SIZE)
    q, u, up = np.zeros(3), np.zeros(3), np.zeros(6)
    per = max(P, (5_000_000 // n) // P * P)
    for start, stop in chunks(steps, per, "crawl steps"):
        K.integrate(q, u, up, r, v, tau, inertia, spin, w, mass, g, dt,
                    QS_EPS if qs else 0.0, side == "body", math.cos(a), math.sin(a), kind,
                    par, tab, assoc, mu, settings.tol, settings.max_iterations, start,
                    stop - start, record_every, rec_t, rec_q, rec_u, rec_e, info)
    k = int(info[K.INFO_RECORDS])
    st = int(info[K.INFO_STATUS])
    status = {K.STATUS_OK: "ok", K.STATUS_NOT_CONVERGED: "not-converged",
              K.STATUS_NON_FINITE: "non-finite"}[st]
    fail = int(info[K.INFO_FAIL_STEP])
    message = {"ok": "ok",
               "not-converged": f"the step's Newton iteration did not converge at step {fail} "
                                f"(t = {fail * dt:.6g} s; relative residual above "
                                f"{settings.tol:g}); the run stops there",
               "non-finite": f"the velocity became non-finite at step {fail}"}[status]
    t, qr, ur, e = rec_t[:k], rec_q[:k], rec_u[:k], rec_e[:k]
    per_rec = P // record_every             # records a period (the first state aside)
    done = (k - 1) // per_rec
    speed, drift = _per_period(qr, per_rec, done, float(gait.length))
    steps_done = int(info[K.INFO_STEPS])
    mu_fwd = float(np.hypot(*law.force(np.array([0.0]))[0]))
    return CrawlResult(
        t=t, q=qr, u=ur, work=e[:, 0], dissipated=e[:, 1], speed_per_period=speed,
        drift_per_period=drift, transient_periods=0 if qs else done // 2, periods=done,
        steps_per_period=P, dt=dt, points=n, quasi_static=qs, rule=law_rule(law),
        law_name=law.name, texture_on=side, texture_angle_deg=math.degrees(a),
        gait={"kind": gait.name, **gait.params()}, length=float(gait.length),
        period=float(gait.period), mass=mass, g=g, mu_forward=mu_fwd, status=status,
        message=message, mean_iterations=float(info[K.INFO_ITER_TOTAL]) / max(steps_done, 1),
        max_iterations_used=int(info[K.INFO_MAX_ITER]),
        stick_fraction=float(info[K.INFO_STICK]) / max(steps_done * n, 1),
        records_per_period=per_rec, law_description=law.description)


def _per_period(q, per_rec, periods, L):
    """Speed (body lengths, on the period's mean heading) and heading drift of each period."""
    speed = np.zeros(periods)
    drift = np.zeros(periods)
    for p in range(periods):
        a, b = p * per_rec, (p + 1) * per_rec
        th = float(np.mean(q[a:b + 1, 2]))
        d = q[b, :2] - q[a, :2]
        speed[p] = (d[0] * math.cos(th) + d[1] * math.sin(th)) / L
        drift[p] = q[b, 2] - q[a, 2]
    return speed, drift
