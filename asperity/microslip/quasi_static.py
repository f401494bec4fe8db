"""Quasi-static cycles of a slider chain: exact incremental solution per load increment
(semismooth Newton on the incremental energy; one backward-Euler increment per monotone
load segment is exact while every slider's slip is monotone over it; ``substeps``
refines), detection of the stabilised cycle, and the long-life extrapolation from it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import check_int, check_range
from .chains import TOL, Chain, MicroslipTolerances, SlideOffError, SolverError
from .loading import Loading


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
    """Thermal displacement scale alpha_T * length * dT range (or the elastic slip scale)."""
    s = chain.alpha_T * chain.length * max(loading.dT_range, float(np.abs(loading.dT).max()))
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
    from ._chain_kernels import STATUS_OK, STATUS_SLIDE_OFF, march
    cycles = check_int("cycles", cycles, 1, 100_000_000)
    check_capacity(chain, loading)
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
    scale = load_scale(chain, loading)
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
