"""Cumulative microslip (ratcheting) of assemblies under thermal cycles (SPEC.md section 5).

An assembly is a chain of contact nodes on a rigid support along one slip axis ``x``: node
``i`` carries an elastic tangential spring ``k_t,i`` in series with a slider that moves
towards ``+x`` when the spring force ``q_i = k_t,i (u_i - s_i)`` reaches ``mu+ N_i`` and
towards ``-x`` when it reaches ``-mu- N_i`` (the regularised asymmetric Coulomb law);
consecutive nodes are joined by elastic elements of stiffness ``k_e`` and length ``l_e``
that expand freely by ``alpha_T l_e dT``.  An external tangential force ``F`` may act,
shared by the nodes in fixed proportions.

Sign convention: ``x`` is the assembly's slip axis; ``u > 0`` is a displacement towards
``+x``; ``mu+`` resists sliding towards ``+x``, ``mu-`` towards ``-x``.  With ``mu+ > mu-``
the assembly creeps towards ``-x`` (the side of the smaller coefficient): a negative drift.

* :func:`two_node_chain`, :func:`strip_chain` build the two models of Antoni et al.;
* :func:`two_node_dT_c`, :func:`two_node_drift_per_cycle`, :func:`strip_dT_c` are the closed
  forms (SPEC.md 5) beside the numerics;
* :func:`simulate` marches cycles quasi-statically (exact incremental solution of the
  slider chain: one backward-Euler increment per monotone load segment is exact while every
  slider's slip is monotone over it; ``substeps`` refines) and detects the stabilised cycle,
  from which the drift after any number of cycles is extrapolated exactly;
* :func:`simulate_dynamic` solves the same chain with small masses and slow loading by
  Moreau's midpoint time-stepping, friction impulses from the proximal equation onto
  ``[-mu- N dt, mu+ N dt]``.

Units: SI (m, N, K, Pa).  The strip is per unit width (p in Pa, k_t in Pa/m, F in N/m).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import AsperityError, InputError, check_int, check_range

MODES = ("quasi-static", "dynamic")


class SlideOffError(AsperityError):
    """A physical outcome: the external load exceeds what the sliders can hold."""


class SolverError(AsperityError):
    """The active-set or the proximal iteration did not converge (a numerical failure)."""


@dataclass(frozen=True)
class MicroslipTolerances:
    """The tolerances of this module, in one place."""

    #: the cycle is stabilised when the contact forces at the end of two consecutive cycles
    #: differ by at most this, relative to the largest slider threshold
    stabilised: float = 1e-9
    #: a drift per cycle below this, relative to the thermal displacement scale
    #: alpha_T * length * dT range, counts as no drift
    no_drift: float = 1e-9
    #: Newton iterations per load increment
    max_newton: int = 500
    #: Moreau: fixed-point tolerance (relative to the impulse bound), iteration limit, r/G
    prox_tol: float = 1e-12
    prox_max_iter: int = 100
    prox_r_factor: float = 1.0


TOL = MicroslipTolerances()


# --------------------------------------------------------------------------- closed forms

def two_node_dT_c(k, k_t, N, mu_plus, mu_minus, alpha_T, l0) -> float:
    """Elastic limit of the two-node model (SPEC.md 5):
    ``dT_c = min(mu+, mu-) N (1/k + 2/k_t) / (alpha_T l0)`` (K)."""
    return min(mu_plus, mu_minus) * N * (1.0 / k + 2.0 / k_t) / (alpha_T * l0)


def two_node_drift_per_cycle(k, k_t, N, mu_plus, mu_minus, alpha_T, l0, dT_min, dT_max) -> float:
    """Displacement of both nodes per full cycle once stabilised (m, SPEC.md 5):
    ``-alpha_T l0 (dT_max - dT_min - 2 dT_c)`` towards the side of the smaller coefficient
    (-x if mu+ > mu-), zero if the range is at most 2 dT_c or if mu+ = mu-."""
    if mu_plus == mu_minus:
        return 0.0
    dT_c = two_node_dT_c(k, k_t, N, mu_plus, mu_minus, alpha_T, l0)
    excess = max(0.0, (dT_max - dT_min) - 2.0 * dT_c)
    return (-1.0 if mu_plus > mu_minus else 1.0) * alpha_T * l0 * excess


def strip_dT_c(h, E, p, l, k_t, mu_plus, mu_minus, alpha_T) -> float:
    """Shear-lag elastic limit of the free strip on its elastic bed (SPEC.md 5):
    ``dT_c = mu p lam coth(lam l / 2) / (alpha_T k_t)``, ``lam = sqrt(k_t / (E h))``,
    ``mu = min(mu+, mu-)`` (the end x = 0 slips towards -x first when mu- < mu+)."""
    lam = math.sqrt(k_t / (E * h))
    return min(mu_plus, mu_minus) * p * lam / (alpha_T * k_t * math.tanh(0.5 * lam * l))


# --------------------------------------------------------------------------- models

@dataclass(frozen=True)
class Chain:
    """A slider chain (see :mod:`asperity._microslip_kernels` for the equations).

    kind : "two-node" or "strip"
    x    : (n,) node positions along the slip axis, m
    kb, le : (n-1,) element stiffness (N/m) and length (m)
    kt   : (n,) contact stiffness (N/m);  cp, cm : (n,) thresholds mu+ N_i, mu- N_i (N)
    fw   : (n,) share of the external force on each node (sums to 1)
    weight : (n,) contact-area share of each node (sums to 1): the assembly's displacement
             is the weighted mean of the node displacements
    """

    kind: str
    x: np.ndarray
    kb: np.ndarray
    le: np.ndarray
    kt: np.ndarray
    cp: np.ndarray
    cm: np.ndarray
    fw: np.ndarray
    weight: np.ndarray
    alpha_T: float
    mu_plus: float
    mu_minus: float
    params: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return int(self.x.size)

    @property
    def length(self) -> float:
        return float(self.le.sum())

    def with_friction(self, mu_plus: float, mu_minus: float) -> "Chain":
        """The same chain with other coefficients (thresholds scaled from the normal loads)."""
        Nn = self.normal_loads
        from dataclasses import replace
        return replace(self, cp=mu_plus * Nn, cm=mu_minus * Nn, mu_plus=float(mu_plus),
                       mu_minus=float(mu_minus))

    @property
    def normal_loads(self) -> np.ndarray:
        return np.asarray(self.params["normal_loads"])


def _check_mu(name, x) -> float:
    v = check_range(name, x, 0.0, None)
    return v


def _positive(name, x, unit="") -> float:
    v = check_range(name, x, 0.0, None, low_open=True, unit=unit)
    if not math.isfinite(v):
        raise InputError(f"{name} must be finite, got {v:g}")
    return v


def two_node_chain(k, l0, alpha_T, k_t, N, mu_plus, mu_minus) -> Chain:
    """Antoni et al.'s two-node model: a bar (stiffness k, length l0, expansion alpha_T)
    whose two ends rest on the support under the normal force N each."""
    k = _positive("k", k, "N/m")
    l0 = _positive("l0", l0, "m")
    alpha_T = _positive("alpha_T", alpha_T, "1/K")
    k_t = _positive("k_t", k_t, "N/m")
    N = _positive("N", N, "N")
    mp, mm = _check_mu("mu_plus", mu_plus), _check_mu("mu_minus", mu_minus)
    Nn = np.array([N, N])
    return Chain("two-node", np.array([0.0, l0]), np.array([k]), np.array([l0]),
                 np.array([k_t, k_t]), mp * Nn, mm * Nn, np.array([0.5, 0.5]),
                 np.array([0.5, 0.5]), alpha_T, mp, mm,
                 {"k": k, "l0": l0, "alpha_T": alpha_T, "k_t": k_t, "N": N,
                  "normal_loads": Nn})


def strip_chain(h, E, p, l, k_t, alpha_T, n, mu_plus, mu_minus) -> Chain:
    """The continuous strip (per unit width) discretised into ``n`` equally spaced nodes:
    linear elements of stiffness E h / dx; node i carries the bed over its tributary length
    (dx, dx/2 at the free ends): stiffness k_t dx, normal load p dx (lumped)."""
    h = _positive("h", h, "m")
    E = _positive("E", E, "Pa")
    p = _positive("p", p, "Pa")
    l = _positive("l", l, "m")
    k_t = _positive("k_t", k_t, "Pa/m")
    alpha_T = _positive("alpha_T", alpha_T, "1/K")
    n = check_int("n", n, 2, 10_000_000)
    mp, mm = _check_mu("mu_plus", mu_plus), _check_mu("mu_minus", mu_minus)
    dx = l / (n - 1)
    trib = np.full(n, dx)
    trib[0] = trib[-1] = 0.5 * dx
    Nn = p * trib
    return Chain("strip", np.linspace(0.0, l, n), np.full(n - 1, E * h / dx), np.full(n - 1, dx),
                 k_t * trib, mp * Nn, mm * Nn, trib / l, trib / l, alpha_T, mp, mm,
                 {"h": h, "E": E, "p": p, "l": l, "k_t": k_t, "alpha_T": alpha_T, "n": n,
                  "normal_loads": Nn})


# --------------------------------------------------------------------------- loading

@dataclass(frozen=True)
class Loading:
    """One load cycle, repeated: temperature change ``dT`` (K) and external tangential
    force ``F`` (N; strip: N per m of width) at breakpoints, linear in between.

    The assembly starts stress-free at dT = 0, F = 0 and is first brought to the cycle's
    first point; each cycle then runs through the breakpoints and ends where it started
    (``dT[-1] == dT[0]``, ``F[-1] == F[0]``).  ``substeps`` load increments per segment.
    """

    dT: np.ndarray
    F: np.ndarray
    substeps: int = 1

    def __post_init__(self):
        dT = np.asarray(self.dT, dtype=float).ravel()
        F = np.asarray(self.F, dtype=float).ravel()
        if dT.size < 2:
            raise InputError(f"loading.history needs at least 2 points, got {dT.size}")
        if not np.all(np.isfinite(dT)):
            raise InputError("loading.history must hold finite temperature changes (K)")
        if F.size == 1:
            F = np.full(dT.size, float(F[0]))
        if F.size != dT.size:
            raise InputError(f"loading.force_history must have as many points as "
                             f"loading.history ({dT.size}), got {F.size}")
        if not np.all(np.isfinite(F)):
            raise InputError("loading.force_history must hold finite forces")
        if dT[-1] != dT[0] or F[-1] != F[0]:
            raise InputError(f"loading.history must end where it starts (a closed cycle), got "
                             f"{dT[0]:g} K ... {dT[-1]:g} K")
        object.__setattr__(self, "dT", dT)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "substeps", check_int("substeps", self.substeps, 1, 100_000))

    @classmethod
    def cycles_between(cls, dT_min, dT_max, force_min=0.0, force_max=None, substeps=1):
        """Cycles dT_min -> dT_max -> dT_min; the force goes force_min -> force_max -> force_min
        in phase (constant force_min if force_max is None)."""
        lo = check_range("dT_min", dT_min)
        hi = check_range("dT_max", dT_max)
        if not math.isfinite(lo) or not math.isfinite(hi) or hi < lo:
            raise InputError(f"loading needs finite dT_min <= dT_max, got dT_min = {lo:g} K, "
                             f"dT_max = {hi:g} K")
        f0 = check_range("force_min", force_min)
        f1 = f0 if force_max is None else check_range("force_max", force_max)
        return cls(np.array([lo, hi, lo]), np.array([f0, f1, f0]), substeps)

    @property
    def dT_range(self) -> float:
        return float(self.dT.max() - self.dT.min())

    def _refine(self, a, b):
        m = self.substeps
        return [a + (b - a) * (j + 1) / m for j in range(m)]

    def lead_in(self) -> tuple[np.ndarray, np.ndarray]:
        """Points from the stress-free state (0, 0) to the first point of the cycle."""
        if self.dT[0] == 0.0 and self.F[0] == 0.0:
            return np.zeros(0), np.zeros(0)
        return np.array(self._refine(0.0, self.dT[0])), np.array(self._refine(0.0, self.F[0]))

    def cycle_points(self) -> tuple[np.ndarray, np.ndarray]:
        """Load points of one cycle (after its first point), ``substeps`` per segment."""
        dT, F = [], []
        for j in range(self.dT.size - 1):
            dT += self._refine(self.dT[j], self.dT[j + 1])
            F += self._refine(self.F[j], self.F[j + 1])
        return np.array(dT), np.array(F)


# --------------------------------------------------------------------------- analysis

def elastic_limit(chain: Chain, sign: float = 1.0) -> float:
    """dT_c of the chain: the temperature change (heating if ``sign`` > 0, else cooling),
    from the stress-free state without external force, at which the first slider slips
    (K; inf if none ever does)."""
    from ._microslip_kernels import _solve_tridiag
    n = chain.n
    rhs = np.zeros(n)
    e = chain.kb * chain.alpha_T * chain.le * sign
    rhs[1:] += e
    rhs[:-1] -= e
    u = np.empty(n)
    _solve_tridiag(chain.kb, chain.kt, rhs, u, np.empty(n), np.empty(n))
    q = chain.kt * u                                     # contact forces per K
    with np.errstate(divide="ignore"):
        lim = np.where(q > 0, chain.cp / np.where(q > 0, q, 1.0),
                       np.where(q < 0, chain.cm / np.where(q < 0, -q, 1.0), np.inf))
    return float(lim.min())


@dataclass
class MicroslipResult:
    """Outcome of :func:`simulate` (quasi-static) or :func:`simulate_dynamic`.

    cycles_run : cycles marched
    mean_u     : (cycles_run + 1,) assembly displacement (weighted mean of the nodes, m) at
                 the start of the first cycle and at the end of every cycle
    u_end      : (cycles_run + 1, n) node displacements at the same instants
    drift_per_cycle : m per cycle, from the stabilised cycle (negative: towards -x)
    stabilised_at : first cycle whose end state repeats the previous one up to a translation
                 (None if not reached within the cycles marched)
    slip_in_cycle : a slider slips during the stabilised (or last) cycle
    trace      : dict with "t" (load-point index or time), "dT", "u" (points, recorded nodes)
    """

    chain: Chain
    loading: Loading
    mode: str
    cycles_run: int
    mean_u: np.ndarray
    u_end: np.ndarray
    q_end: np.ndarray
    drift_per_cycle: float
    stabilised_at: int | None
    slip_in_cycle: bool
    trace: dict
    solver: dict

    @property
    def ratchet(self) -> bool:
        return self.drift_per_cycle != 0.0

    @property
    def regime(self) -> str:
        if self.ratchet:
            return "ratchet"
        return "alternating slip (no net drift)" if self.slip_in_cycle else "shakedown"

    def drift_after(self, cycles: float) -> float:
        """Assembly displacement after ``cycles`` full cycles (m): marched values where
        available, else the last stabilised state plus the drift per cycle."""
        c = float(cycles)
        k = self.cycles_run
        if c <= k and c.is_integer():
            return float(self.mean_u[int(c)])
        return float(self.mean_u[k] + (c - k) * self.drift_per_cycle)

    def cycles_to(self, tolerance: float) -> int | None:
        """Whole cycles until |assembly displacement| first reaches ``tolerance`` (m) at a
        cycle end (None if never: no drift and not reached in the cycles marched)."""
        a = np.abs(self.mean_u)
        hit = np.flatnonzero(a >= tolerance)
        if hit.size:
            return int(hit[0])
        d = self.drift_per_cycle
        if d == 0.0:
            return None
        k = self.cycles_run
        # |mean_u[k] + j d| >= tol, j > 0
        j = math.ceil((tolerance - abs(self.mean_u[k])) / abs(d)) if \
            np.sign(self.mean_u[k]) in (0.0, np.sign(d)) else \
            math.ceil((tolerance + abs(self.mean_u[k])) / abs(d))
        return int(k + max(j, 1))


def _scale(chain: Chain, loading: Loading) -> float:
    """Thermal displacement scale alpha_T * length * dT range (or the elastic slip scale)."""
    s = chain.alpha_T * chain.length * max(loading.dT_range, float(np.abs(loading.dT).max()))
    fin = np.isfinite(chain.cp) & np.isfinite(chain.cm)
    el = float(np.max(np.maximum(np.where(fin, chain.cp, 0), np.where(fin, chain.cm, 0))
                      / chain.kt))
    return max(s, el, 1e-300)


def _check_capacity(chain: Chain, loading: Loading) -> None:
    F = np.concatenate([[0.0], loading.F])
    plus, minus = float(chain.cp.sum()), float(chain.cm.sum())
    hi, lo = float(F.max()), float(F.min())
    unit = "N/m" if chain.kind == "strip" else "N"
    if hi >= plus:
        raise SlideOffError(f"the assembly slides off towards +x: the tangential load reaches "
                            f"{hi:g} {unit}, the sliders hold at most mu+ sum N = {plus:g} {unit}")
    if -lo >= minus:
        raise SlideOffError(f"the assembly slides off towards -x: the tangential load reaches "
                            f"{lo:g} {unit}, the sliders hold at most mu- sum N = {minus:g} {unit}")


def simulate(chain: Chain, loading: Loading, cycles: int = 50, *, record_nodes=None,
             until_stable: bool = True, min_cycles: int = 2, warm_start: bool = True,
             tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """March the loading cycles quasi-statically (exact incremental solution).

    Stops after ``cycles`` cycles, or (``until_stable``) as soon as the cycle is stabilised
    and at least ``min_cycles`` were marched.  ``record_nodes``: node indices whose
    displacement is kept at every load point (default: the two ends).  ``warm_start``: start
    each increment's Newton iteration from the same increment of the previous cycle (exact
    once the cycle is stabilised); False starts from the previous state (for timing).
    """
    from ._microslip_kernels import STATUS_OK, STATUS_SLIDE_OFF, march
    cycles = check_int("cycles", cycles, 1, 100_000_000)
    _check_capacity(chain, loading)
    n = chain.n
    rec = np.array([0, n - 1] if record_nodes is None else record_nodes, dtype=np.int64)
    u = np.zeros(n)
    s = np.zeros(n)
    max_iter = tol.max_newton
    args = (np.ascontiguousarray(chain.kb), np.ascontiguousarray(chain.le), chain.kt,
            chain.cp, chain.cm, chain.fw, float(chain.alpha_T))
    fin = np.concatenate([chain.cp[np.isfinite(chain.cp)], chain.cm[np.isfinite(chain.cm)]])
    cap = float(fin.max()) if fin.size and fin.max() > 0 else 1.0

    def run(dT, F, du, status):
        ru = np.empty((dT.size, rec.size))
        slip = np.zeros(dT.size)
        slips.append(slip)
        code, j, it = march(*args, dT, F, u, s, du, status, slip, rec, ru, max_iter)
        if code == STATUS_SLIDE_OFF:
            raise SlideOffError(f"the assembly slides off at load point dT = {dT[j]:g} K, "
                                f"F = {F[j]:g}: no slider can stay stuck")
        if code != STATUS_OK:
            raise SolverError(f"the Newton iteration of the increment to dT = {dT[j]:g} K did "
                              f"not converge in {max_iter} iterations (try loading.substeps > 1)")
        return ru, it

    tr_t, tr_dT, tr_u = [0.0], [0.0], [np.zeros(rec.size)]
    slips = []
    scale = _scale(chain, loading)
    iters = 0
    dT0, F0 = loading.lead_in()
    if dT0.size:
        ru, it = run(dT0, F0, np.zeros((dT0.size, n)), np.zeros((dT0.size, n), np.int8))
        iters += it
        tr_dT += list(dT0); tr_u += list(ru)
        tr_t += list(np.linspace(-1.0, 0.0, dT0.size + 1)[1:])
        tr_t[0] = -1.0
    dTc, Fc = loading.cycle_points()
    status = np.zeros((dTc.size, n), np.int8)
    du = np.zeros((dTc.size, n))          # increments of the previous cycle: the guesses
    mean_u = [float(chain.weight @ u)]
    u_end = [u.copy()]
    q_prev = chain.kt * (u - s)
    q_end = q_prev
    stab = None
    slip = False
    for c in range(1, cycles + 1):
        if not warm_start:
            du[:] = 0.0
        ru, it = run(dTc, Fc, du, status)
        iters += it
        tr_t += list(c - 1 + np.arange(1, dTc.size + 1) / dTc.size)
        tr_dT += list(dTc); tr_u += list(ru)
        mean_u.append(float(chain.weight @ u))
        u_end.append(u.copy())
        q_end = chain.kt * (u - s)
        slip = bool(slips[-1].max() > tol.no_drift * scale)
        if np.max(np.abs(q_end - q_prev)) <= tol.stabilised * cap:
            stab = c if stab is None else stab
            if until_stable and c >= min_cycles:
                break
        else:
            stab = None
        q_prev = q_end
    mean_u = np.array(mean_u)
    k = len(mean_u) - 1
    d = float(mean_u[k] - mean_u[k - 1])
    if abs(d) <= tol.no_drift * scale:
        d = 0.0
    trace = {"t": np.array(tr_t), "dT": np.array(tr_dT), "u": np.array(tr_u), "nodes": rec}
    return MicroslipResult(chain, loading, "quasi-static", k, mean_u, np.array(u_end), q_end, d,
                           stab, slip, trace,
                           {"method": "semismooth Newton on the incremental energy, one "
                                      "increment per load segment x substeps",
                            "increments_per_segment": loading.substeps,
                            "iterations": int(iters)})


def long_life(chain: Chain, loading: Loading, cycles: float, *, max_marched: int = 200,
              record_nodes=None, tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """Simulate until the cycle is stabilised (at most ``max_marched`` cycles, and never
    more than ``cycles``); :meth:`MicroslipResult.drift_after` then extrapolates exactly."""
    c = check_range("cycles", cycles, 1.0, 1e15)
    return simulate(chain, loading, int(min(max_marched, math.ceil(c))), record_nodes=record_nodes,
                    until_stable=True, tol=tol)


def dynamic_parameters(chain: Chain, steps_per_segment: int) -> dict:
    """Masses, damping and time step of the dynamic mode: every segment of the loading
    lasts one time unit; node and slider masses m w_i (w: area shares) with m such that
    the highest frequency (Gershgorin bound) gives omega_max dt = 0.5; mass-proportional
    damping at the rate 2 omega_low (omega_low^2 = min k_t,i / (2 m w_i))."""
    n = chain.n
    kb = np.zeros(n)
    kb[:-1] += chain.kb
    kb[1:] += chain.kb
    dt = 1.0 / steps_per_segment
    om_max = 0.5 / dt
    m = float(np.max(2.0 * (kb + chain.kt) / chain.weight) / om_max**2)
    om_low = float(np.sqrt(np.min(chain.kt / (2.0 * m * chain.weight))))
    return {"dt": dt, "mass": m, "omega_max": om_max, "omega_low": om_low,
            "damping": 2.0 * om_low,
            "natural_periods_per_segment": om_low / (2.0 * math.pi)}


def simulate_dynamic(chain: Chain, loading: Loading, cycles: int = 3, *,
                     steps_per_segment: int = 20000, record_nodes=None, record_points: int = 400,
                     tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """The same chain with small masses and slow loading, by Moreau's midpoint scheme.

    Loading breakpoints are reached at whole time units (one unit per segment, the lead-in
    included).  The drift per cycle is the change of the assembly displacement over the
    last cycle.  ``solver`` reports r, the tolerance, the iteration limit, the largest
    number of fixed-point iterations used and the status."""
    from ._microslip_kernels import STATUS_OK, moreau_chain
    cycles = check_int("cycles", cycles, 1, 1_000_000)
    steps_per_segment = check_int("steps_per_segment", steps_per_segment, 10, 100_000_000)
    _check_capacity(chain, loading)
    n = chain.n
    par = dynamic_parameters(chain, steps_per_segment)
    lead = not (loading.dT[0] == 0.0 and loading.F[0] == 0.0)
    dT_pts = [0.0] + ([loading.dT[0]] if lead else [])
    F_pts = [0.0] + ([loading.F[0]] if lead else [])
    start = len(dT_pts) - 1
    for _ in range(cycles):
        dT_pts += list(loading.dT[1:])
        F_pts += list(loading.F[1:])
    t_pts = np.arange(len(dT_pts), dtype=float)
    seg = loading.dT.size - 1
    rec = np.array([0, n - 1] if record_nodes is None else record_nodes, dtype=np.int64)
    u, v, s, w, xi = (np.zeros(n) for _ in range(5))
    mass = par["mass"] * chain.weight
    args = (chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw, float(chain.alpha_T))
    mean_u, u_end = [], []
    tr_t, tr_u = [], []
    max_it, sum_it, steps = 0, 0, 0
    t0 = 0.0
    every = max(1, int(seg * steps_per_segment // max(1, record_points)))
    # march to the start of the first cycle, then one cycle at a time
    bounds = [float(start)] + [float(start + seg * (c + 1)) for c in range(cycles)]
    for t_end in bounds:
        span = t_end - t0
        if span > 0:
            nrec = int(span * steps_per_segment // every) + 1
            ru, rt = np.zeros((nrec, rec.size)), np.zeros(nrec)
            code, st, mi, si = moreau_chain(*args, t_pts - t0, np.array(dT_pts), np.array(F_pts),
                                            span, par["dt"], mass, mass, par["damping"],
                                            tol.prox_r_factor, tol.prox_tol, tol.prox_max_iter,
                                            u, v, s, w, xi, every, rec, ru, rt)
            steps += st
            max_it = max(max_it, mi)
            sum_it += si
            if code != STATUS_OK:
                raise SolverError(f"Moreau: the proximal fixed point did not converge in "
                                  f"{tol.prox_max_iter} iterations (step {steps})")
            k = min(nrec, int(span * steps_per_segment) // every)
            tr_t += list(rt[:k] + t0)
            tr_u += list(ru[:k])
        t0 = t_end                       # the kernel restarts at t = 0 on a shifted axis
        mean_u.append(float(chain.weight @ u))
        u_end.append(u.copy())
    mean_u = np.array(mean_u)
    d = float(mean_u[-1] - mean_u[-2]) if cycles >= 1 else 0.0
    if abs(d) <= 1e-6 * _scale(chain, loading):
        d = 0.0
    tt = np.array(tr_t)
    trace = {"t": (tt - start) / seg, "dT": np.interp(tt, t_pts, dT_pts), "u": np.array(tr_u),
             "nodes": rec}
    solver = {"method": "Moreau midpoint, friction impulses by the proximal fixed point",
              "r": f"{tol.prox_r_factor:g} / G (G = 1 / (m_slider (1 + c dt/2)), "
                   f"the slider's Delassus term)",
              "tolerance": tol.prox_tol, "iteration_limit": tol.prox_max_iter,
              "max_iterations_used": int(max_it),
              "mean_iterations": sum_it / max(1, steps * n), "steps": int(steps),
              "status": "converged", **{k: v for k, v in par.items()}}
    return MicroslipResult(chain, loading, "dynamic", cycles, mean_u, np.array(u_end),
                           chain.kt * (u - s), d, None, True, trace, solver)


# --------------------------------------------------------------------------- risk verdict

SIGN_CONVENTION = ("x is the assembly's slip axis; displacements and drift are positive "
                   "towards +x; mu+ resists sliding of the assembly towards +x over the "
                   "support, mu- towards -x; with mu+ > mu- the assembly creeps towards -x "
                   "(negative drift)")


def _jnum(x) -> float | None:
    return float(x) if x is not None and math.isfinite(x) else None


def assess(chain: Chain, loading: Loading, cycles: float = 1e6, tolerance: float | None = None,
           *, dT_c_closed_form: float | None = None, max_marched: int = 200,
           tol: MicroslipTolerances = TOL) -> dict:
    """The ratchet verdict of an assembly over ``cycles`` load cycles (JSON-ready dict).

    verdict "ratchet" if the stabilised cycle drifts, "shakedown" if not, "slides-off" if
    the tangential load exceeds what the sliders hold (a physical outcome, with the reason).
    dT_c: the elastic limit of the model (heating from the stress-free state, no external
    force); margin = dT range / (2 dT_c) (for the two-node model ratcheting iff margin > 1;
    for the strip margin > 1 is necessary, not sufficient: its ends can slip back and forth
    while its middle sticks)."""
    cycles = check_range("cycles", cycles, 1.0, 1e15)
    if tolerance is not None:
        tolerance = check_range("tolerance", tolerance, 0.0, None, low_open=True, unit="m")
    dT_c = elastic_limit(chain)
    rng = loading.dT_range
    out = {"sign_convention": SIGN_CONVENTION,
           "mu_plus": _jnum(chain.mu_plus), "mu_minus": _jnum(chain.mu_minus),
           "dT_c_K": _jnum(dT_c), "dT_c_closed_form_K": _jnum(dT_c_closed_form),
           "dT_range_K": rng,
           "margin": (rng / (2.0 * dT_c)) if math.isfinite(dT_c) and dT_c > 0 else 0.0,
           "cycles": cycles, "tolerance_m": tolerance,
           "max_tangential_load": float(np.abs(loading.F).max())}
    try:
        r = long_life(chain, loading, cycles, max_marched=max_marched, tol=tol)
    except SlideOffError as exc:
        out.update({"verdict": "slides-off", "regime": "slides off", "reason": str(exc),
                    "drift_per_cycle_m": None, "drift_direction": None,
                    "drift_after_cycles_m": None, "cycles_to_tolerance": 0 if tolerance else None,
                    "stabilised_at_cycle": None, "cycles_marched": 0})
        return out
    d = r.drift_per_cycle
    out.update({
        "verdict": "ratchet" if r.ratchet else "shakedown",
        "regime": r.regime,
        "drift_per_cycle_m": d,
        "drift_direction": "-x" if d < 0 else "+x" if d > 0 else "none",
        "drift_after_cycles_m": r.drift_after(cycles),
        "cycles_to_tolerance": None if tolerance is None else r.cycles_to(tolerance),
        "stabilised_at_cycle": r.stabilised_at,
        "cycles_marched": r.cycles_run,
        "extrapolated": bool(cycles > r.cycles_run),
        "solver": r.solver,
    })
    if r.stabilised_at is None:
        out["warning"] = (f"the cycle did not stabilise within {r.cycles_run} cycles: the drift "
                          "per cycle is that of the last cycle marched")
    out["_result"] = r
    return out
