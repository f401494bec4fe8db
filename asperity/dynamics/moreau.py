"""Moreau midpoint time-stepping of bodies sliding on a plane with dry friction (SPEC.md 4).

Scheme over a step dt (Moreau 1988; Leine & van de Wouw 2008):

    q_M = q_A + dt/2 u_A
    M (u_E - u_A) = dt f(q_M, t_M) + sum_i W_i Lambda_i
    q_E = q_M + dt/2 u_E

q = (x, y) for a point mass, (x, y, theta) for a rigid body turning in the plane.  Contact i
sits at body-fixed offset r_i; its slip velocity is gamma_i = W_i^T u with
W_i^T = [[1, 0, -r_y], [0, 1, r_x]] (r rotated by theta_M).  Its normal impulse is fixed,
Lambda_N,i = share_i m g dt (flat plane, no lift-off).  The friction impulse P_i = -Lambda_i
obeys the contact's law (:mod:`asperity.laws.planar`), a Walker-Leine pair (C_i, D_i), as the
implicit proximal equations

    alpha_i P_i = prox_{Lambda_N,i D_i}( alpha_i (P_i + r gamma_i(u_E)) ),
    alpha_i = 1 / (k_D(P_i) - k_C(P_i) + 1)          (alpha = 1 for C = D)

(the normal cone is a cone, so r may be scaled by alpha_i), solved by the Jacobi fixed-point
iteration over all contacts with alpha_i updated in every iteration and P_i recovered from
y_i = alpha_i P_i on its ray.  r = relax / max eig(W^T M^-1 W), relax in (0, 2) (default 1,
which for a point mass gives r = m: the associated law is then solved by one projection).
The iteration stops when max_i |P_i^(k+1) - P_i^k| / Lambda_N,i <= tol; if the limit is
reached first the result's status says so (first step and residual) -- never silently.
Each step starts from the last step's P_i with alpha_i extrapolated from the last two steps
(a point mass: from P extrapolated from the last three sliding steps, with its own alpha, so
that a steady slide converges in one iteration), and the law's kernels start from their last
evaluation (laws._law_kernels.law_point_warm: the projection onto D from the last sample
interval and root, the star polygon from the last edge); a guess changes the iterations,
not the fixed point.

Exact stick: when every contact's prox argument lies inside its set (all contacts stick) and
W^T has full column rank (point mass; rigid body with two or more distinct contacts), the
discrete solution is u_E = 0 and it is set exactly; a body at rest under no force then stays
put bit for bit.

Closed forms beside the numerics: :func:`coulomb_stop_time`, :func:`coulomb_stop_distance`,
:func:`ratchet_drift_square`; :func:`reference_path` integrates the sliding-phase ODE with
scipy's solve_ivp at tight tolerances.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import progress
from ..errors import InputError, check_array, check_instance, check_int, check_range
from ..laws.planar import PlanarLaw
from ..progress import chunks
from ..resources import check_memory, check_work
from .force import Force

STATUS_NAMES = {0: "ok", 1: "not-converged", 2: "non-finite"}
#: physically meaningful ranges (SI units) of the solver's inputs
LIMITS = {"dt": (1e-9, 1.0), "t_end": (0.0, 1e9), "g": (1e-6, 1e4), "mass": (1e-9, 1e9),
          "inertia": (1e-15, 1e12), "u0": (0.0, 1e4), "mu": (1e-6, 100.0)}
#: most steps a simulation may take (~3 min for the ellipse law, ~15 min for a star law)
MAX_STEPS = 5e8
#: steps per kernel call for one contact (about 0.1 s with the slowest, star-shaped, law)
STEPS_PER_PIECE = 50_000


def check_t_end(name: str, t_end, dt: float) -> float:
    """``t_end`` (s) in (0, 1e9] and at least one step ``dt``, else one line naming ``name``."""
    t = check_range(name, t_end, 0.0, LIMITS["t_end"][1], low_open=True, unit="s")
    if t < dt * (1.0 - 1e-12):
        raise InputError(f"{name} must be at least one time step (dt = {dt:g} s), got {t:g} s")
    return t


@dataclass(frozen=True)
class Settings:
    """Fixed-point iteration settings.

    relax : r = relax / max eig(W^T M^-1 W), in (0, 2)
    tol   : tolerance on max_i |P_i^(k+1) - P_i^k| / Lambda_N,i (dimensionless)
    max_iterations : iteration limit per step
    """

    relax: float = 1.0
    tol: float = 1e-12
    max_iterations: int = 2000

    def __post_init__(self):
        check_range("relax", self.relax, 0.0, 2.0, low_open=True, high_open=True)
        check_range("tol", self.tol, 1e-15, 1e-3)
        check_int("max_iterations", self.max_iterations, 1, 1_000_000)


@dataclass(frozen=True)
class Body:
    """A body on the plane.

    mass    : kg
    inertia : kg m^2 about the centre of mass (None: a point mass, no rotation)
    contacts: (n, 2) contact points in the body frame, m (point mass: one contact at 0)
    share   : (n,) share of the weight carried by each contact (> 0, sums to 1)
    laws    : n PlanarLaw (or one law for all contacts)
    """

    mass: float
    laws: tuple
    inertia: float | None = None
    contacts: np.ndarray = field(default_factory=lambda: np.zeros((1, 2)))
    share: np.ndarray | None = None

    def __post_init__(self):
        check_range("mass", self.mass, *LIMITS["mass"], unit="kg")
        c = np.array(check_array("contacts", self.contacts, shape=(None, 2), min_size=2),
                     dtype=float)
        if np.any(np.abs(c) > 1e3) or c.shape[0] > 10_000:
            raise InputError(f"contacts must be at most 10000 points within 1 km of the centre, "
                             f"got {c.shape[0]} up to {np.abs(c).max():g} m")
        n = c.shape[0]
        laws = self.laws
        if isinstance(laws, PlanarLaw):
            laws = (laws,) * n
        laws = tuple(laws)
        if isinstance(laws, (str, bytes)) or not hasattr(laws, "__len__"):
            raise InputError(f"laws must be one PlanarLaw or {n} of them, got {laws!r}")
        if len(laws) != n or not all(isinstance(x, PlanarLaw) for x in laws):
            raise InputError(f"laws must be one PlanarLaw or {n} of them, got {len(laws)}")
        sh = np.full(n, 1.0 / n) if self.share is None else \
            np.array(check_array("share", self.share), dtype=float)
        if sh.shape != (n,) or not np.all(np.isfinite(sh)) or np.any(sh <= 0) \
                or abs(sh.sum() - 1.0) > 1e-12:
            raise InputError(f"share must be {n} positive numbers summing to 1, got {sh}")
        if self.inertia is None:
            if n != 1 or np.any(c != 0):
                raise InputError("a point mass (inertia None) has one contact at (0, 0)")
        else:
            check_range("inertia", self.inertia, *LIMITS["inertia"], unit="kg m^2")
        c.setflags(write=False)
        sh.setflags(write=False)
        object.__setattr__(self, "contacts", c)
        object.__setattr__(self, "share", sh)
        object.__setattr__(self, "laws", laws)

    @property
    def ndof(self) -> int:
        return 2 if self.inertia is None else 3

    @property
    def minv(self) -> np.ndarray:
        m = [1.0 / self.mass, 1.0 / self.mass]
        if self.inertia is not None:
            m.append(1.0 / self.inertia)
        return np.array(m)

    def W(self, theta: float = 0.0) -> np.ndarray:
        """(ndof, 2 n) force directions of the contact impulses."""
        n = self.contacts.shape[0]
        W = np.zeros((self.ndof, 2 * n))
        c, s = math.cos(theta), math.sin(theta)
        for i, (rx, ry) in enumerate(self.contacts):
            ox, oy = c * rx - s * ry, s * rx + c * ry
            W[0, 2 * i] = 1.0
            W[1, 2 * i + 1] = 1.0
            if self.ndof == 3:
                W[2, 2 * i] = -oy
                W[2, 2 * i + 1] = ox
        return W

    def delassus_max_eig(self) -> float:
        """max eig(W^T M^-1 W) (independent of theta: rotating the body rotates G's blocks)."""
        if self.inertia is None:            # a point mass: W = identity (no LAPACK call)
            return 1.0 / self.mass
        W = self.W()
        G = W.T @ (self.minv[:, None] * W)
        return float(np.linalg.eigvalsh(G).max())

    def full_rank(self) -> bool:
        """W^T has full column rank: all contacts sticking forces u = 0."""
        if self.inertia is None:            # a point mass: W = identity
            return True
        return bool(np.linalg.matrix_rank(self.W()) == self.ndof)


def point_mass(law: PlanarLaw, mass: float = 1.0) -> Body:
    """A point mass on one contact."""
    return Body(mass=mass, laws=(law,))


@dataclass(frozen=True)
class Result:
    """A simulation.

    Attributes
    ----------
    t, q, u : ndarray, shapes (k,), (k, ndof), (k, ndof)
        Recorded states (every ``record_every`` steps, the initial and the last state
        included), SI units (m, rad, m/s, rad/s).
    steps : int
        Steps integrated.
    stop_step : int or None
        Steps done when the body last came to rest (exactly u = 0), None if it moves at
        the end; ``stop_time = stop_step dt``.
    max_iterations_used, mean_iterations : int, float
        Fixed-point iterations per step.
    status : str
        ``"ok"``, ``"not-converged"`` (iteration limit above tol: ``fail_step``,
        ``fail_residual`` say where first) or ``"non-finite"``.
    max_residual : float
        Largest final residual of a step.
    """

    t: np.ndarray
    q: np.ndarray
    u: np.ndarray
    dt: float
    steps: int
    stop_step: int | None
    max_iterations_used: int
    mean_iterations: float
    status: str
    fail_step: int | None
    fail_residual: float | None
    max_residual: float
    q_final: np.ndarray
    u_final: np.ndarray
    mass_diag: np.ndarray

    @property
    def stop_time(self) -> float | None:
        return None if self.stop_step is None else self.stop_step * self.dt

    @property
    def energy(self) -> np.ndarray:
        """(k,) kinetic energy of the recorded states, J."""
        return 0.5 * np.einsum("ij,j->i", self.u * self.u, self.mass_diag)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def status_message(self) -> str:
        if self.status == "ok":
            return "ok"
        if self.status == "not-converged":
            return (f"the fixed-point iteration did not converge at step {self.fail_step} "
                    f"(residual {self.fail_residual:.3g} above the tolerance)")
        return f"the velocity became non-finite at step {self.fail_step}"


def simulate(body: Body, u0, *, dt: float, t_end: float, q0=None, force: Force | None = None,
             force_table=None, g: float = 9.81, settings: Settings = Settings(),
             record_every: int = 1, halt_at_rest: bool = False) -> Result:
    """Integrate the motion of ``body`` from q0 (default 0) with velocity u0 over [0, t_end].

    force_table : optional (n_steps, ndof) force at each step's midpoint (overrides force)
    halt_at_rest: stop as soon as the body is at rest with no external force (then nothing
        can change); the result's ``steps`` counts the steps done
    """
    check_instance("body", body, Body)
    check_instance("settings", settings, Settings)
    if force is not None:
        check_instance("force", force, Force)
    ndof = body.ndof
    u0 = check_array("u0", u0, shape=(ndof,))
    if np.any(np.abs(u0) > LIMITS["u0"][1]):
        raise InputError(f"u0 must be velocities within +-{LIMITS['u0'][1]:g} m/s, got {u0}")
    q0 = np.zeros(ndof) if q0 is None else check_array("q0", q0, shape=(ndof,))
    if np.any(np.abs(q0) > 1e9):
        raise InputError(f"q0 must be positions within +-1e9 m, got {q0}")
    dt = check_range("dt", dt, *LIMITS["dt"], unit="s")
    t_end = check_t_end("t_end", t_end, dt)
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    n_steps = int(round(t_end / dt))
    check_work(n_steps, MAX_STEPS, "this simulation (t_end / dt)", "raise dt or lower t_end")
    record_every = check_int("record_every", record_every, 1, int(MAX_STEPS))
    check_memory((n_steps // record_every + 2) * (1 + 2 * ndof) * 8.0,
                 f"recording {n_steps // record_every + 2:.3g} states",
                 "raise record_every (the CLI records at most 20000 rows)")
    from . import _moreau_kernels as K
    nc = body.contacts.shape[0]
    sets = [law.kernel_sets for law in body.laws]
    rows, offs, ns = [], np.zeros((nc, 2), np.int64), np.zeros((nc, 2), np.int64)
    kinds = np.zeros((nc, 2), np.int64)
    pars = np.zeros((nc, 2, 8))
    assoc = np.zeros(nc, np.bool_)
    total = 0
    for i, (a, ck, cp, ct, dk, dp, dtab) in enumerate(sets):
        assoc[i] = a
        for j, (k, p, tab) in enumerate(((ck, cp, ct), (dk, dp, dtab))):
            kinds[i, j] = k
            pars[i, j] = p
            offs[i, j] = total
            ns[i, j] = tab.shape[0]
            rows.append(tab)
            total += tab.shape[0]
    tabs = np.ascontiguousarray(np.vstack(rows))
    lam_n = body.share * body.mass * g * dt
    r = settings.relax / body.delassus_max_eig()
    if force_table is not None:
        ftab = np.ascontiguousarray(np.asarray(force_table, dtype=float))
        if ftab.shape != (n_steps, ndof) or not np.all(np.isfinite(ftab)):
            raise InputError(f"force_table must be finite with shape ({n_steps}, {ndof}), got "
                             f"{ftab.shape}")
        fpar = np.zeros(8)
    else:
        ftab = np.zeros((0, ndof))
        fpar = (force or Force()).params()
    n_rec = n_steps // record_every + 2
    rec_t = np.zeros(n_rec)
    rec_q = np.zeros((n_rec, ndof))
    rec_u = np.zeros((n_rec, ndof))
    info = np.zeros(K.INFO_SIZE)
    qf, uf = q0.copy(), u0.copy()
    P = np.zeros((nc, 2))
    from ..laws._law_kernels import new_warm
    warm = new_warm(nc)
    contacts = np.ascontiguousarray(body.contacts)
    full_rank = body.full_rank()
    # pieces of STEPS_PER_PIECE steps (~0.1 s for the slowest law): Ctrl-C between them
    pieces = chunks(n_steps, max(1, STEPS_PER_PIECE // nc), "Moreau steps") if n_steps else \
        [(0, 0)]
    for start, stop in pieces:
        K.integrate(qf, uf, P, warm, body.minv, contacts, lam_n, assoc, kinds, pars, tabs, offs, ns,
                    fpar, ftab, 0.0, dt, n_steps, start, stop - start, r, settings.tol,
                    settings.max_iterations, full_rank, bool(halt_at_rest), record_every,
                    rec_t, rec_q, rec_u, info)
        if info[K.INFO_HALTED]:
            progress.report(1.0, "Moreau steps")      # at rest (or failed) early: the work is done
            break
    k = int(info[K.INFO_RECORDS])
    steps = int(info[K.INFO_STEPS])
    stop = int(info[K.INFO_STOP_STEP])
    status = STATUS_NAMES[int(info[K.INFO_STATUS])]
    fail = int(info[K.INFO_FAIL_STEP])
    mdiag = 1.0 / body.minv
    return Result(t=rec_t[:k], q=rec_q[:k], u=rec_u[:k], dt=dt, steps=steps,
                  stop_step=None if stop < 0 else stop,
                  max_iterations_used=int(info[K.INFO_MAX_ITER]),
                  mean_iterations=float(info[K.INFO_ITER_TOTAL]) / max(steps, 1),
                  status=status, fail_step=None if fail < 0 else fail,
                  fail_residual=float(info[K.INFO_FAIL_RESIDUAL]) if fail >= 0 else None,
                  max_residual=float(info[K.INFO_MAX_RESIDUAL]), q_final=qf, u_final=uf,
                  mass_diag=mdiag)


def slide(law: PlanarLaw, u0: float, angle_deg: float, *, mass: float = 1.0, g: float = 9.81,
          dt: float = 1e-4, t_end: float | None = None, record_every: int = 1,
          settings: Settings = Settings()) -> Result:
    """A point mass launched on a friction law, sliding until it sticks (SPEC.md 4).

    Moreau's midpoint time-stepping with the law's implicit proximal equation, solved by
    fixed-point iteration; stick is exact (the velocity is set to 0, no drift).  The mass
    starts at the origin; positions and velocities are in the frame of the law (t_a = x,
    t_b = y), SI units.

    Parameters
    ----------
    law : PlanarLaw
        The friction law (:func:`~asperity.coulomb_law`, ...).
    u0 : float
        Launch speed, m/s, in [0, 1e4].
    angle_deg : float
        Launch direction, deg from t_a towards t_b, in [-360, 360].
    mass : float, optional
        kg, in [1e-9, 1e9]; default 1 (the motion does not depend on it).
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4]; default 9.81.
    dt : float, optional
        Time step, s, in [1e-9, 1]; default 1e-4.
    t_end : float, optional
        End time, s (at least one step).  None (default): until rest, within the horizon
        ``1.5 u0 / (g min_psi p.s) + 10 dt``, enough for any admissible law.
    record_every : int, optional
        Record every this many steps (the first and last state always); default 1.
    settings : Settings, optional
        The fixed-point iteration's ``relax`` (in (0, 2)), ``tol`` and ``max_iterations``.

    Returns
    -------
    Result
        ``t`` (k,), ``q`` (k, 2) and ``u`` (k, 2): the recorded times (s), positions (m)
        and velocities (m/s); ``q_final``, ``u_final``; ``stop_time`` (s, None if still
        moving); ``steps``; ``status`` (``"ok"``, ``"not-converged"`` or
        ``"non-finite"``, never silent: see ``status_message()``); ``energy`` (J);
        iteration counts.

    Raises
    ------
    InputError
        If a number is out of its range or ``law`` is not a PlanarLaw.

    See Also
    --------
    asperity.deflection_deg : the angle by which the path bends.
    asperity.simulate_body : a rigid body with a footprint that slides and spins.

    Notes
    -----
    Over a step ``dt``: ``q_M = q_A + dt/2 u_A``, ``M (u_E - u_A) = W Lambda`` (no
    external force), ``q_E = q_M + dt/2 u_E``.  With isotropic Coulomb friction the mass
    stops after ``u0 / (mu g)`` s and ``u0^2 / (2 mu g)`` m, along a principal axis of an
    orthotropic law the same with that axis's coefficient; off-axis the path bends
    towards the low-friction axis.

    Examples
    --------
    Coulomb, mu = 0.3, 1 m/s: ``u0 / (mu g)`` = 0.33979 s, ``u0^2 / (2 mu g)`` = 0.16989 m.

    >>> r = asperity.slide(asperity.coulomb_law(0.3), 1.0, 0.0, dt=1e-4)
    >>> r.status
    'ok'
    >>> print(f"{r.stop_time:.4f} s, {r.q_final[0]:.5f} m")
    0.3398 s, 0.16989 m
    """
    check_instance("law", law, PlanarLaw)
    u0 = check_range("u0", u0, *LIMITS["u0"], unit="m/s")
    ang = math.radians(check_range("angle", angle_deg, -360.0, 360.0, unit="deg"))
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    dt = check_range("dt", dt, *LIMITS["dt"], unit="s")
    halt = t_end is None
    if t_end is None:
        t_end = 1.5 * u0 / (g * law.min_tangential()) + 10 * dt
    v = u0 * np.array([math.cos(ang), math.sin(ang)])
    return simulate(point_mass(law, mass), v, dt=dt, t_end=t_end, g=g, settings=settings,
                    record_every=record_every, halt_at_rest=halt)


def deflection_deg(u0_angle_deg: float, rest) -> float:
    """Signed angle by which a slide's path bends: from the launch direction to the rest point.

    Parameters
    ----------
    u0_angle_deg : float
        Launch direction, deg from t_a towards t_b, in [-3600, 3600].
    rest : array_like, shape (2,)
        Rest point (m) of a slide that started at the origin (e.g. ``Result.q_final``).

    Returns
    -------
    float
        The angle (deg, in (-180, 180]) from the initial velocity to the line from the
        origin to ``rest``; positive counter-clockwise (towards t_b from t_a); 0 if the
        rest point is the origin.

    Raises
    ------
    InputError
        If ``u0_angle_deg`` is out of range or ``rest`` is not two finite numbers.

    See Also
    --------
    asperity.slide : the slide whose rest point this measures.

    Examples
    --------
    On the ellipse ``mu1 = 0.2`` (t_a), ``mu2 = 0.4`` (t_b), a launch at 45 deg bends
    towards the low-friction axis t_a:

    >>> r = asperity.slide(asperity.ellipse_law(0.2, 0.4), 1.0, 45.0, dt=1e-4)
    >>> round(asperity.deflection_deg(45.0, r.q_final), 2)
    -19.33
    >>> asperity.deflection_deg(0.0, (1.0, 1.0))
    45.0
    """
    a = math.radians(check_range("u0_angle_deg", u0_angle_deg, -3600.0, 3600.0, unit="deg"))
    x, y = (float(v) for v in check_array("rest", rest, shape=(2,)))
    if x == 0.0 and y == 0.0:
        return 0.0
    c, s = math.cos(a), math.sin(a)
    return math.degrees(math.atan2(c * y - s * x, c * x + s * y))
