"""Quasi-static cycles of a slider chain: exact incremental solution per load increment
(semismooth Newton on the incremental energy; one backward-Euler increment per monotone
load segment is exact while every slider's slip is monotone over it; ``substeps``
refines), detection of the stabilised cycle, and the long-life extrapolation from it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_instance, check_int
from .chains import (
    TOL,
    Chain,
    MicroslipTolerances,
    SlideOffError,
    SolverError,
    check_asymmetry,
    elastic_limit,
    stiffness_ratio,
)
from .limits import ASYMMETRY_RESOLVED, MARGIN, check_cycles
from .loading import Loading
from .pacing import Pacer

#: refuse a march of more node-updates than this (about 10 min warm, 45 min cold)
MAX_NODE_UPDATES = 2e10
#: first piece of a march, node-updates (later pieces aim at 0.1 s)
PIECE_NODE_UPDATES = 200_000


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


def load_scale(chain: Chain, loading: Loading) -> float:
    """Thermal displacement scale |alpha_T| * length * dT range (or the elastic slip scale)."""
    s = abs(chain.alpha_T) * chain.length * max(loading.dT_range, float(np.abs(loading.dT).max()))
    fin = np.isfinite(chain.cp) & np.isfinite(chain.cm)
    el = float(np.max(np.maximum(np.where(fin, chain.cp, 0), np.where(fin, chain.cm, 0))
                      / chain.kt))
    return max(s, el, 1e-300)


def check_capacity(chain: Chain, loading: Loading) -> None:
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


def check_inputs(chain, loading, tol=TOL) -> None:
    """chain, loading and tolerances of the right types (one-line InputError)."""
    check_instance("chain", chain, Chain, "slider chain (two_node_chain, strip_chain)")
    check_instance("loading", loading, Loading)
    check_instance("tol", tol, MicroslipTolerances)


def check_margin(chain: Chain, loading: Loading) -> None:
    """Refuse a temperature range so far beyond the elastic limit that the friction forces
    drown in the rounding of the thermal ones (margin above :data:`limits.MARGIN`)."""
    dT_c = elastic_limit(chain)
    margin = loading.dT_range / (2.0 * dT_c) if math.isfinite(dT_c) else 0.0
    # the asymmetry must stand out of the rounding of the thermal forces (margin) in the
    # stiffness-ratio-conditioned solves (fuzzed: below this, wrong sides and stalls)
    check_asymmetry(chain.mu_plus, chain.mu_minus,
                    max(ASYMMETRY_RESOLVED, 10.0 * max(margin, 1.0) * stiffness_ratio(chain)
                        * 2.2e-16))
    if margin > MARGIN:
        raise InputError(f"the margin dT range / (2 dT_c) = {margin:.3g} is beyond what the "
                         f"chain solvers resolve (at most {MARGIN:g}: the friction holds less "
                         "than 1e-4 of the free thermal force); lower the temperature range "
                         "or raise the normal load or friction")


def record_indices(chain: Chain, record_nodes) -> np.ndarray:
    """The node indices to record, checked: whole numbers in [0, n - 1] (default: the two
    ends), so that no kernel ever sees an index outside the chain."""
    n = chain.n
    if record_nodes is None:
        return np.array([0, n - 1], dtype=np.int64)
    if isinstance(record_nodes, (str, bytes, dict, bool)):
        raise InputError(f"record_nodes must be a list of node indices, got {record_nodes!r}")
    if isinstance(record_nodes, (list, tuple)) and any(isinstance(x, bool)
                                                       for x in record_nodes):
        raise InputError("record_nodes must be node indices, got a boolean")
    try:
        a = np.asarray(record_nodes)
    except (ValueError, TypeError):
        raise InputError("record_nodes must be a flat list of node indices") from None
    if a.ndim != 1 or a.size > n or a.dtype.kind not in "iuf" and a.size:
        raise InputError(f"record_nodes must be a flat list of at most {n} node indices, got "
                         f"shape {a.shape}, {a.dtype.name} values")
    if a.size and (not np.all(np.isfinite(a)) or np.any(a != np.round(a))
                   or a.min() < 0 or a.max() > n - 1):
        bad = a[~(np.isfinite(a) & (a == np.round(a)) & (a >= 0) & (a <= n - 1))][0].item()
        raise InputError(f"record_nodes must be whole numbers in [0, {n - 1}] (the chain has "
                         f"{n} nodes), got {bad:g}")
    return np.ascontiguousarray(a, dtype=np.int64)


def march_cost(chain: Chain, loading: Loading, cycles: int, n_record: int) -> tuple:
    """(bytes, node-updates) of marching ``cycles`` cycles, recording ``n_record`` nodes."""
    n, m = chain.n, loading.points_per_cycle
    points = cycles * m + loading.substeps
    mem = (24 * n * 8 + m * n * 8 + cycles * (n * 8 + 300)
           + 2 * points * (n_record * 8 + 24))
    return mem, cycles * (m * n + 2000) + loading.substeps * n


def check_march(chain: Chain, loading: Loading, cycles: int, n_record: int) -> None:
    """Refuse, before any work, a march that cannot fit in memory or time."""
    from ..resources import check_memory, check_work
    mem, work = march_cost(chain, loading, cycles, n_record)
    what = (f"the quasi-static march ({cycles} cycles x {loading.points_per_cycle} load points "
            f"x {chain.n} nodes)")
    lower = ("lower the cycles marched (--max-marched), loading.substeps or the nodes "
             "(assembly.n)")
    check_memory(mem, what, lower)
    check_work(work, MAX_NODE_UPDATES, what, lower)


def simulate(chain: Chain, loading: Loading, cycles: int = 50, *, record_nodes=None,
             until_stable: bool = True, min_cycles: int = 2, warm_start: bool = True,
             tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """March the loading cycles quasi-statically (exact incremental solution).

    Stops after ``cycles`` cycles, or (``until_stable``) as soon as the cycle is stabilised
    and at least ``min_cycles`` were marched.  ``record_nodes``: node indices whose
    displacement is kept at every load point (default: the two ends).  ``warm_start``: start
    each increment's Newton iteration from the same increment of the previous cycle (exact
    once the cycle is stabilised); False starts from the previous state (for timing).
    The memory and work are estimated first (ResourceError if they cannot fit); the kernel
    runs in pieces of about 0.1 s, so Ctrl-C is honoured and progress reported.
    """
    from ..progress import report
    from ._chain_kernels import STATUS_OK, STATUS_SLIDE_OFF, march
    check_inputs(chain, loading, tol)
    cycles = check_int("cycles", cycles, 1, 100_000_000)
    min_cycles = check_int("min_cycles", min_cycles, 1, 100_000_000)
    for name, flag in (("until_stable", until_stable), ("warm_start", warm_start)):
        if not isinstance(flag, (bool, np.bool_)):
            raise InputError(f"{name} must be True or False, got {flag!r}")
    rec = record_indices(chain, record_nodes)
    check_margin(chain, loading)
    check_capacity(chain, loading)
    check_march(chain, loading, cycles, rec.size)
    n = chain.n
    u = np.zeros(n)
    s = np.zeros(n)
    max_iter = tol.max_newton
    args = (chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw, float(chain.alpha_T))
    fin = np.concatenate([chain.cp[np.isfinite(chain.cp)], chain.cm[np.isfinite(chain.cm)]])
    cap = float(fin.max()) if fin.size and fin.max() > 0 else 1.0
    pacer = Pacer(max(1, PIECE_NODE_UPDATES // n))

    def run(dT, F, du, c0):
        """March the points (dT, F) in pieces; c0: cycles done before (for progress)."""
        m = dT.size
        ru = np.empty((m, rec.size))
        slip = np.zeros(m)
        it_sum = 0
        j0 = 0
        while j0 < m:
            j1 = j0 + pacer.size(m - j0)
            code, j, it = march(*args, dT[j0:j1], F[j0:j1], u, s, du[j0:j1], slip[j0:j1], rec,
                                ru[j0:j1], max_iter)
            pacer.done(j1 - j0)
            it_sum += it
            if code == STATUS_SLIDE_OFF:
                raise SlideOffError(f"the assembly slides off at load point dT = "
                                    f"{dT[j0 + j]:g} K, F = {F[j0 + j]:g}: no slider can stay "
                                    "stuck")
            if code != STATUS_OK:
                raise SolverError(f"the Newton iteration of the increment to dT = "
                                  f"{dT[j0 + j]:g} K did not converge in {max_iter} iterations "
                                  "(try loading.substeps > 1)")
            j0 = j1
            report(min(1.0, (c0 + j0 / m) / cycles), "quasi-static cycles")
        return ru, slip, it_sum

    tr_t, tr_dT, tr_u = [np.zeros(1)], [np.zeros(1)], [np.zeros((1, rec.size))]
    scale = load_scale(chain, loading)
    iters = 0
    dT0, F0 = loading.lead_in()
    if dT0.size:
        ru, _, it = run(dT0, F0, np.zeros((dT0.size, n)), 0)
        iters += it
        tr_dT.append(dT0)
        tr_u.append(ru)
        tr_t = [np.linspace(-1.0, 0.0, dT0.size + 1)]
    dTc, Fc = loading.cycle_points()
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
        ru, slips, it = run(dTc, Fc, du, c - 1)
        iters += it
        tr_t.append(c - 1 + np.arange(1, dTc.size + 1) / dTc.size)
        tr_dT.append(dTc)
        tr_u.append(ru)
        mean_u.append(float(chain.weight @ u))
        u_end.append(u.copy())
        q_end = chain.kt * (u - s)
        slip = bool(slips.max() > tol.no_drift * scale)
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
    trace = {"t": np.concatenate(tr_t), "dT": np.concatenate(tr_dT),
             "u": np.concatenate(tr_u), "nodes": rec}
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
    c = check_cycles("cycles", cycles)
    max_marched = check_int("max_marched", max_marched, 2, 1_000_000)
    return simulate(chain, loading, int(min(max_marched, math.ceil(c))), record_nodes=record_nodes,
                    until_stable=True, tol=tol)
