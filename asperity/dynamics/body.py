"""Moreau time stepping of a planar rigid body whose footprint is sampled at N contact points
(issue 20; SPEC.md sections 4 and 8).

The body (x, y, theta) slides on a flat support; contact i sits at body offset r_i and carries
the share w_i of the weight (normal impulse lambda_i = w_i m g dt per step, no lift-off).  All
points obey one :class:`~asperity.laws.planar.PlanarLaw`, fixed to the support with its t_a
axis at ``texture_angle_deg`` from the x axis.  The scheme is the midpoint scheme of SPEC.md 4:

    q_M = q_A + dt/2 u_A,   M (u_E - u_A) = dt f(t_M) + sum_i W_i P_i,   q_E = q_M + dt/2 u_E

with M = diag(m, m, I) and W_i^T u = (vx - omega o_y, vy + omega o_x) the slip of point i
(o_i = r_i turned by theta_M).  The motion is computed in the frame of the law (the texture)
and turned back to the x, y frame.

One step solves for the three velocities, not for 2N impulses (:mod:`._body_kernels`):

* **Stick of the body, exact.**  With u_free = u_A + dt M^-1 f and b = M u_free, the body
  sticks (u_E = 0) iff b lies in the footprint's limit set L = sum_i lambda_i W_i C, i.e. iff
  G(d) = sum_i lambda_i h_C(W_i^T d) - b.d >= 0 for every d (h_C the support function).  For
  an associated law (C = D) the step is the minimiser of the convex
  F(u) = 1/2 (u - u_free)^T M (u - u_free) + sum_i lambda_i h_C(W_i^T u), and on the ray
  u = s d (|d|_M = 1) F - F(0) = s^2/2 + s G(d): the minimiser is u = -G(d*) d* with d* the
  minimiser of G on the unit sphere, or exactly 0 when min G >= 0.  The kernel minimises G
  on the sphere (Riemannian Newton) whenever no sliding is found on the ray of the start;
  the body sticks iff min G >= -tol * scale (tol = 1e-12 of the impulse scale
  m g dt mu_max, plus the rounding floor 1e-15 |M u_free|): a margin of the law, not a
  threshold on a velocity.  A body at rest under the same impulse stays at rest without a
  solve (bit for bit).  For a star-shaped (non-convex) C the sum of the N non-convex sets
  is replaced by its convex hull, the sum of the hulls (h_C := support of conv C): by the
  Shapley-Folkman-Starr theorem the two differ by at most sqrt(3) times the largest single
  term, i.e. sqrt(3) max_i w_i m g dt rad(C) -- about 0.7 % of the limit set for 256 equal
  points, O(1/N).
* **Sliding.**  Newton with a backtracking line search on
  R(u) = M (u - u_free) + sum_i lambda_i W_i c(gamma_i / |gamma_i|) = 0 (c the law's sliding
  force per unit normal load, ``PlanarLaw.force``), started from the extrapolation
  2 u_A - u_{A-1} (one or two iterations a step on a smooth motion).  Merit: the convex F for
  associated laws, 1/2 |R|^2_M^-1 for non-associated ones.  F sums n + 3 positive terms, so
  near the solution a Newton step changes it by ~|R|^2, far below its rounding: within that
  band the step is judged by F's slope R.dx (Hager and Zhang's approximate Wolfe
  conditions), which has no cancellation (F alone made a no-spin disc creep, 65 iterations
  a step).  A Newton step below the rounding of u ends the solve (within 1e3 tol).
* **Pivots.**  Where one point (with every point at exactly its spot: a group) nearly
  sticks, F has a kink that Newton only creeps towards.  The kernel solves with that group
  sticking exactly (a rotation about it), accepted if the group's reaction lies in conv C;
  otherwise the group slides slowly, and the step is solved in polar coordinates of its
  slip (smooth through the kink) from the pivot, in the slip direction whose force points
  along the reaction the pivot needed (exact as the slip -> 0), the slip kept >= 0.  A moving
  rigid body has at most one such spot (two would stop it).  Footprints whose points all
  coincide are refused: nothing stops their spin.
* **Laws.**  Closed forms for the associated disc and (truncated) ellipse; for every other
  law tables of c(psi) and of the normal point of conv C on TABLE_SIZE = 8192 uniform
  directions, linearly interpolated: the error is at most dpsi^2/8 max|c''| = 7e-8 max|c''|
  where c is smooth (tested: < 1e-5 mu for the star law away from D's flat edges, where c
  jumps and the table smears the jump over one interval of 0.04 deg).
* **Energy.**  For an admissible law the friction impulse dissipates
  (dE = -P.gamma_E - 1/2 P^T W^T M^-1 W P <= 0): the kinetic energy never increases without
  an external force (tested on random footprints, starts and laws).

Until rest: the run ends at :func:`~asperity.dynamics.body_horizon.rest_time`, a bound
from the least slip per unit of motion (refused, saying why, when too long to compute).
Stop times: ``stop_time`` is exact (u_E = 0 bit for bit); a uniformly loaded disc and a ring
stop sliding and spinning at the same step (tested).  ``slide_stop_time`` and
``spin_stop_time`` use STOP_FRACTION of the initial velocity scale (a spin from rest keeps
v at the rounding level, not exactly 0).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import (InputError, check_array, check_flag, check_instance, check_int,
                      check_range)
from ..laws.planar import PlanarLaw
from ..resources import check_memory, check_work
from .body_horizon import rest_time
from .moreau import LIMITS, MAX_STEPS, Force, check_t_end

#: most contact points of a footprint (the kernel's memory is a few arrays of this length)
MAX_POINTS = 1_000_000
#: velocities below this fraction of the initial velocity scale count as zero for the
#: separate slide / spin stop times (the joint stop time is exact: u_E = 0 bit for bit)
STOP_FRACTION = 1e-10


@dataclass(frozen=True)
class BodySettings:
    """Settings of the body solver.

    tol : relative tolerance of a step's equation (residual / scale of the impulses)
    max_iterations : iteration limit of each Newton solve of a step (a step that does not
        converge restarts from a better point up to four times before it is reported)
    """

    tol: float = 1e-12
    max_iterations: int = 2000

    def __post_init__(self):
        check_range("tol", self.tol, 1e-15, 1e-3)
        check_int("max_iterations", self.max_iterations, 1, 1_000_000)


@dataclass(frozen=True)
class BodyResult:
    """A simulated body.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Recorded times (every ``record_every`` steps, the first and the last included), s.
    q : ndarray, shape (k, 3)
        Recorded positions ``(x, y, theta)`` (m, m, rad) in the x, y frame.
    u : ndarray, shape (k, 3)
        Recorded velocities ``(vx, vy, omega)`` (m/s, m/s, rad/s).
    dt, steps : float, int
        Step and steps integrated.
    status : str
        ``"ok"``, ``"not-converged"`` or ``"non-finite"`` (see ``status_message``).
    stop_time : float or None
        Time at which the body came to rest for good (u exactly 0), None if moving.
    slide_stop_time, spin_stop_time : float or None
        From when on ``|v|`` (resp. ``rho |omega|``, ``rho = sqrt(I/m)``) stays below STOP_FRACTION
        of the velocity scale ``|v0| + rho |omega0| + g dt`` (every step counts, not only the
        recorded ones); None if it does not.
    final_angle_rad : float
        theta at the end.
    max_iterations_used, mean_iterations : int, float
        Iterations of the step solver.
    last_moving : ndarray, shape (3,), or None
        The last velocity before the final rest (None if none), for
        :meth:`terminal_ratio`.
    """

    t: np.ndarray
    q: np.ndarray
    u: np.ndarray
    dt: float
    steps: int
    status: str
    stop_time: float | None
    slide_stop_time: float | None
    spin_stop_time: float | None
    final_angle_rad: float
    max_iterations_used: int
    mean_iterations: float
    mass: float
    inertia: float
    q_final: np.ndarray
    u_final: np.ndarray
    last_moving: np.ndarray | None
    message: str = "ok"

    @property
    def energy(self) -> np.ndarray:
        """(k,) kinetic energy of the recorded states, J."""
        u = self.u
        return 0.5 * (self.mass * (u[:, 0] ** 2 + u[:, 1] ** 2) + self.inertia * u[:, 2] ** 2)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    @property
    def rest(self) -> bool:
        return self.stop_time is not None

    def status_message(self) -> str:
        return self.message

    def terminal_ratio(self, radius: float) -> float | None:
        """v / (R omega) as the motion ends: of the last moving state before the final rest
        (of the final state if the body still moves); None without spin then."""
        R = check_range("radius", radius, 1e-9, 1e6, unit="m")
        u = self.last_moving if self.last_moving is not None else self.u_final
        if u is None or u[2] == 0.0:
            return None
        return float(math.hypot(u[0], u[1]) / (R * abs(u[2])))


# ----------------------------------------------------------------------------- input

def _check_points(points, weights) -> tuple[np.ndarray, np.ndarray]:
    p = np.array(check_array("points", points, shape=(None, 2), min_size=2), dtype=float)
    n = p.shape[0]
    if n > MAX_POINTS:
        raise InputError(f"points must be at most {MAX_POINTS} contact points, got {n}")
    check_memory(n * 8.0 * 32, f"a footprint of {n} contact points", "use fewer contact points")
    if np.any(np.abs(p) > 1e3):
        raise InputError(f"points must lie within 1 km of the centre of mass, got "
                         f"{np.abs(p).max():g} m")
    spread = float(np.ptp(p, axis=0).max())
    if spread <= 1e-12:
        raise InputError(f"points must not all lie at one spot (they span {spread:g} m): such "
                         "a footprint has no friction torque against a rotation about that "
                         "spot, so its spin never stops; use the point mass (asperity.slide, "
                         "--body point) or a footprint with an extent")
    w = np.array(check_array("weights", weights, ndim=1), dtype=float)
    if w.shape != (n,):
        raise InputError(f"weights must have shape ({n},) (one per point), got {w.shape}")
    if np.any(w <= 0) or abs(w.sum() - 1.0) > 1e-9:
        raise InputError(f"weights must be positive and sum to 1 (shares of the load), got "
                         f"min {w.min():g}, sum {w.sum():.12g}")
    return np.ascontiguousarray(p), np.ascontiguousarray(w / w.sum())


#: the slowest launch speed (m/s) and spin (rad/s) other than 0: the kernels take a slip
#: whose square underflows (below ~1e-154 m/s) for a sticking point, so a body launched
#: slower never stops (u0 = 5e-324 m/s ran to its horizon "still moving")
SLOWEST = 1e-100


def check_slow(name: str, x: float, unit: str) -> None:
    """Refuse a launch velocity below :data:`SLOWEST` other than 0."""
    if 0.0 < abs(x) < SLOWEST:
        raise InputError(f"{name} must be 0 or at least {SLOWEST:g} {unit} in size, got "
                         f"{abs(x):.3g}")


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def _turn_force(force: Force, a: float) -> Force:
    """The force in the frame of the law (turned by -a)."""
    R = _rot(-a)
    c = np.asarray(force.constant)
    m = np.asarray(force.amplitude)
    return Force(constant=(*(R @ c[:2]), c[2]), amplitude=(*(R @ m[:2]), m[2]),
                 period=force.period, waveform=force.waveform)


# ----------------------------------------------------------------------------- solver

def simulate_body(points, weights, law: PlanarLaw, *, mass: float, inertia: float,
                  u0=(0.0, 0.0, 0.0), q0=(0.0, 0.0, 0.0), dt: float, t_end: float | None = None,
                  force: Force | None = None, g: float = 9.81, texture_angle_deg: float = 0.0,
                  settings: BodySettings = BodySettings(), record_every: int = 1,
                  until_rest: bool = False) -> BodyResult:
    """Slide and spin a planar rigid body whose footprint is sampled at contact points.

    Moreau's midpoint scheme (SPEC.md 4 and 8) for ``(x, y, theta)``; every point obeys
    one law, fixed to the support with its t_a axis at ``texture_angle_deg`` from x, and
    carries its share of the weight (no lift-off).  Stick of the whole body is exact
    (``u = 0`` bit for bit); for a star-shaped C the footprint's limit set is taken as the
    sum of the hulls of C (Shapley-Folkman-Starr: off by at most
    ``sqrt(3) max_i w_i m g dt rad(C)``, O(1/N)).

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Contact points, m, body frame, origin at the centre of mass: at most 1e6 points
        within 1 km of it, not all at one spot.
    weights : array_like, shape (n,)
        Share of the load of each point, > 0, summing to 1.
    law : PlanarLaw
        The friction law of every point.
    mass : float
        kg, in [1e-9, 1e9].
    inertia : float
        kg m^2 about the centre of mass, in [1e-15, 1e12].
    u0 : array_like, shape (3,), optional
        Initial ``(vx, vy, omega)``, m/s and rad/s (within 1e4 m/s and 1e6 rad/s; 0 or at
        least 1e-100); default at rest.
    q0 : array_like, shape (3,), optional
        Initial ``(x, y, theta)``, m and rad; default 0.
    dt : float
        Time step, s, in [1e-9, 1].
    t_end : float, optional
        End time, s.  None (default): until rest (no external force allowed), up to a
        bound from the least slip per unit of motion (refused, saying why, when too long).
    force : Force, optional
        External force ``(fx, fy, torque)``, constant or periodic (:class:`~asperity.Force`).
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4]; default 9.81.
    texture_angle_deg : float, optional
        Angle of the law's t_a axis from x, deg, in [-360, 360]; default 0.
    settings : BodySettings, optional
        The step solver's relative tolerance ``tol`` and ``max_iterations``.
    record_every : int, optional
        Record every this many steps (the first and last state always); default 1.
    until_rest : bool, optional
        With ``t_end``: stop there too if the body comes to rest first (without a force).

    Returns
    -------
    BodyResult
        ``t`` (k,), ``q`` (k, 3) = ``(x, y, theta)``, ``u`` (k, 3) = ``(vx, vy, omega)``:
        the recorded states, SI units, x-y frame; ``stop_time`` (s, exact rest, None if
        moving); ``slide_stop_time``, ``spin_stop_time`` (s, from when on ``|v|``, resp.
        ``rho |omega|``, stays below 1e-10 of the initial velocity scale);
        ``final_angle_rad``; ``status`` (``"ok"``, ``"not-converged"``, ``"non-finite"``)
        and ``status_message()``; ``energy`` (J); ``terminal_ratio(R)``, the ratio
        ``v / (R omega)`` as the motion ends.

    Raises
    ------
    InputError
        If a number or array is out of its range, or ``t_end`` is None with a force.

    See Also
    --------
    asperity.slide_body : the same from a body file or a footprint.
    asperity.disc_footprint, asperity.ring_footprint : footprints.
    asperity.disc_f_m : the closed form of a disc that slides and spins.
    asperity.slide : a point mass.

    Examples
    --------
    A thin ring (64 points, ``I = m R^2``) on Coulomb friction launched at
    ``v = R omega``, its fixed point (SPEC.md 8): the friction force is ``mu m g 2/pi``
    throughout, so sliding and spinning stop together at ``pi u0 / (2 mu g)`` = 0.5338 s.

    >>> R, n = 0.05, 64
    >>> phi = 2 * np.pi * np.arange(n) / n
    >>> ring = R * np.column_stack([np.cos(phi), np.sin(phi)])
    >>> r = asperity.simulate_body(ring, np.full(n, 1 / n), asperity.coulomb_law(0.3),
    ...                            mass=1.0, inertia=R**2, u0=(1.0, 0.0, 20.0), dt=1e-4)
    >>> r.slide_stop_time == r.spin_stop_time == r.stop_time
    True
    >>> print(f"{r.stop_time:.4f} s, v / (R omega) = {r.terminal_ratio(R):.4f}")
    0.5338 s, v / (R omega) = 1.0000
    """
    check_instance("law", law, PlanarLaw)
    check_instance("settings", settings, BodySettings)
    if force is not None:
        check_instance("force", force, Force)
    pts, w = _check_points(points, weights)
    mass = check_range("mass", mass, *LIMITS["mass"], unit="kg")
    inertia = check_range("inertia", inertia, *LIMITS["inertia"], unit="kg m^2")
    u0 = np.array(check_array("u0", u0, shape=(3,)), dtype=float)
    if np.any(np.abs(u0[:2]) > LIMITS["u0"][1]) or abs(u0[2]) > 1e6:
        raise InputError(f"u0 must be (vx, vy, omega) within +-{LIMITS['u0'][1]:g} m/s and "
                         f"+-1e6 rad/s, got {u0}")
    check_slow("u0 (vx, vy)", math.hypot(u0[0], u0[1]), "m/s")
    check_slow("u0 (omega)", u0[2], "rad/s")
    q0 = np.array(check_array("q0", q0, shape=(3,)), dtype=float)
    if np.any(np.abs(q0) > 1e9):
        raise InputError(f"q0 must be (x, y, theta) within +-1e9, got {q0}")
    dt = check_range("dt", dt, *LIMITS["dt"], unit="s")
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    a = math.radians(check_range("texture_angle_deg", texture_angle_deg, -360.0, 360.0,
                                 unit="deg"))
    record_every = check_int("record_every", record_every, 1, int(MAX_STEPS))
    until_rest = check_flag("until_rest", until_rest)
    halt = t_end is None or (until_rest and force is None)
    if t_end is None:
        if force is not None:
            raise InputError("t_end must be given with an external force (the body need not "
                             "come to rest)")
        t_end = rest_time(pts, w, law, mass, inertia, u0, g, dt)
    else:
        t_end = check_t_end("t_end", t_end, dt)
    n_steps = int(round(t_end / dt))
    check_work(n_steps * max(1.0, pts.shape[0] / 16.0), MAX_STEPS,
               "this simulation (t_end / dt times the contact points / 16)",
               "raise dt, lower t_end or use fewer contact points")
    check_memory((n_steps // record_every + 2) * 7 * 8.0,
                 f"recording {n_steps // record_every + 2:.3g} states", "raise record_every")
    # the motion in the frame of the law: x, y turned by -a, theta - a
    Rm = _rot(-a)
    ul = np.array([*(Rm @ u0[:2]), u0[2]])
    ql = np.array([*(Rm @ q0[:2]), q0[2] - a])
    fl = None if force is None else _turn_force(force, a)
    rho = math.sqrt(inertia / mass)
    stop_v = STOP_FRACTION * (math.hypot(u0[0], u0[1]) + rho * abs(u0[2]) + g * dt)
    r = _run_kernel(pts, w, law, mass, inertia, ul, ql, dt, n_steps, fl, g, settings,
                    record_every, halt, stop_v)
    Rp = _rot(a)
    q = r["q"].copy()
    u = r["u"].copy()
    q[:, :2] = q[:, :2] @ Rp.T
    q[:, 2] += a
    u[:, :2] = u[:, :2] @ Rp.T
    last = r["last"]
    if last is not None:
        last = np.array([*(Rp @ last[:2]), last[2]])
    stop = r["stop_step"]
    return BodyResult(t=r["t"], q=q, u=u, dt=dt, steps=r["steps"], status=r["status"],
                      stop_time=None if stop is None else stop * dt,
                      slide_stop_time=None if r["slide_step"] is None else r["slide_step"] * dt,
                      spin_stop_time=None if r["spin_step"] is None else r["spin_step"] * dt,
                      final_angle_rad=float(q[-1, 2]), max_iterations_used=r["max_it"],
                      mean_iterations=r["mean_it"], mass=mass, inertia=inertia,
                      q_final=q[-1].copy(), u_final=u[-1].copy(), last_moving=last,
                      message=r["message"])


#: grid of the law tables (directions over a full turn): linear interpolation of c(psi)
#: errs by at most dpsi^2/8 max|c''|, 6e-8 max|c''| (tested against the law)
TABLE_SIZE = 8192
#: steps per kernel call (Ctrl-C and progress between calls), divided by the points
WORK_PER_PIECE = 5_000_000


def law_tables(law: PlanarLaw):
    """(kind, par (6,), tab (K+1, 4), associated, mu_max) of a law for the kernel.

    Closed forms for the associated disc and truncated ellipse (kind 0) and for the
    componentwise rule (kind 2: C's hull is the same truncated ellipse); else tables on
    psi_k = 2 pi k / K of the sliding force c(psi) (``law.force``) and of the normal point of
    the hull of C (the gradient of its support function h), kind 1."""
    from . import _body_kernels as K
    from ..laws.sets import Disc, StarSet, TruncatedEllipse
    C = law.law.C
    par = np.zeros(6)
    if law.name == "componentwise" and isinstance(C, TruncatedEllipse) and C.theta == 0.0:
        # Hu et al.'s rule in closed form: C the truncated ellipse (mu_f, mu_b, mu_t, mu_t)
        par[:] = (C.mu_a_plus, C.mu_a_minus, C.mu_b_plus, C.mu_b_minus, 1.0, 0.0)
        return K.KIND_COMPONENTWISE, par, np.zeros((2, 4)), False, float(par[:4].max())
    if law.associated and isinstance(C, (Disc, TruncatedEllipse)):
        if isinstance(C, Disc):
            par[:] = (C.mu, C.mu, C.mu, C.mu, 1.0, 0.0)
        else:
            par[:] = (C.mu_a_plus, C.mu_a_minus, C.mu_b_plus, C.mu_b_minus,
                      math.cos(C.theta), math.sin(C.theta))
        return K.KIND_ELLIPSE, par, np.zeros((2, 4)), True, float(par[:4].max())
    psi = 2 * math.pi * np.arange(TABLE_SIZE + 1) / TABLE_SIZE
    tab = np.zeros((TABLE_SIZE + 1, 4))
    tab[:, :2] = law.force(psi)
    if isinstance(C, StarSet):
        s = np.column_stack([np.cos(psi), np.sin(psi)])
        tab[:, 2:] = C.points[np.argmax(s @ C.points.T, axis=1)]
    else:
        tab[:, 2:] = C.normal_point(psi)[0]
    tab[-1] = tab[0]
    mu = float(np.hypot(tab[:, 2], tab[:, 3]).max())
    return K.KIND_TABLE, par, np.ascontiguousarray(tab), law.associated, mu


def _run_kernel(pts, w, law, mass, inertia, u0, q0, dt, n_steps, force, g, settings,
                record_every, halt, stop_v):
    from . import _body_kernels as K
    from .. import progress
    from ..progress import chunks
    kind, par, tab, assoc, mu = law_tables(law)
    md = np.array([mass, mass, inertia])
    lam = w * mass * g * dt
    scale = mass * g * dt * mu / math.sqrt(mass)
    fpar = (force or Force()).params()
    n_rec = n_steps // record_every + 2
    rec_t = np.zeros(n_rec)
    rec_q = np.zeros((n_rec, 3))
    rec_u = np.zeros((n_rec, 3))
    info = np.zeros(K.INFO_SIZE)
    q, u = q0.copy(), u0.copy()
    rho = math.sqrt(inertia / mass)
    per = max(1, WORK_PER_PIECE // pts.shape[0])
    pieces = chunks(n_steps, per, "body steps") if n_steps else [(0, 0)]
    for start, stop in pieces:
        K.integrate(q, u, pts, md, lam, kind, par, tab, assoc, fpar, dt, n_steps, start,
                    stop - start, settings.tol, settings.max_iterations, scale, stop_v, rho,
                    bool(halt), record_every, rec_t, rec_q, rec_u, info)
        if info[K.INFO_HALTED]:
            progress.report(1.0, "body steps")
            break
    k = int(info[K.INFO_RECORDS])
    steps = int(info[K.INFO_STEPS])
    stop = int(info[K.INFO_STOP_STEP])
    status = {K.STATUS_OK: "ok", K.STATUS_NOT_CONVERGED: "not-converged",
              K.STATUS_NON_FINITE: "non-finite"}[int(info[K.INFO_STATUS])]
    fail = int(info[K.INFO_FAIL_STEP])
    if status == "ok":
        message = "ok"
    elif status == "not-converged":
        message = (f"the step's Newton iteration did not converge at step {fail} "
                   f"(relative residual above {settings.tol:g})")
    else:
        message = f"the velocity became non-finite at step {fail}"
    last = None
    if stop > 0 and (info[K.INFO_LAST_VX] or info[K.INFO_LAST_VY] or info[K.INFO_LAST_W]):
        last = info[[K.INFO_LAST_VX, K.INFO_LAST_VY, K.INFO_LAST_W]].copy()
    slide_last = int(info[K.INFO_SLIDE_LAST])
    spin_last = int(info[K.INFO_SPIN_LAST])
    return dict(t=rec_t[:k], q=rec_q[:k], u=rec_u[:k], steps=steps,
                stop_step=None if stop < 0 else stop, status=status, message=message,
                max_it=int(info[K.INFO_MAX_ITER]),
                mean_it=float(info[K.INFO_ITER_TOTAL]) / max(steps, 1), last=last,
                slide_step=None if slide_last == steps else slide_last + 1,
                spin_step=None if spin_last == steps else spin_last + 1)
