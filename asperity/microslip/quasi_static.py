"""Quasi-static cycles of a slider chain: the exact solution of the rate-independent chain,
event by event (every slider's start and stop located exactly along each linear load
segment: :mod:`._chain_kernels`), detection of the stabilised cycle, and the long-life
extrapolation from it.  ``substeps`` only adds load points to the trace.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_flag, check_instance, check_int
from .chains import (
    TOL,
    Chain,
    MicroslipTolerances,
    SlideOffError,
    SolverError,
    elastic_limit,
    is_uniform,
)
from .limits import MARGIN, check_cycles
from .loading import Loading
from .pacing import Pacer

#: refuse a march of more node-passes than this (about 1.5e7 per second: half an hour)
MAX_NODE_UPDATES = 3e10
#: first piece of a march, node-passes (later pieces aim at 0.1 s)
PIECE_NODE_UPDATES = 1_000_000


@dataclass
class MicroslipResult:
    """Outcome of ``simulate`` (quasi-static) or ``simulate_dynamic``.

    Attributes
    ----------
    cycles_run : int
        Cycles marched.
    mean_u : ndarray, shape (cycles_run + 1,)
        Assembly displacement (weighted mean of the nodes, m) at the start of the
        first cycle and at the end of every cycle.
    u_end : ndarray, shape (cycles_run + 1, n)
        Node displacements at the same instants.
    drift_per_cycle : float
        m per cycle, from the stabilised cycle (negative: towards -x).
    stabilised_at : int or None
        First cycle whose end state repeats the previous one up to a translation
        (None if not reached within the cycles marched).
    slip_in_cycle : bool
        A slider slips during the stabilised (or last) cycle.
    trace : dict
        ``"t"`` (load-point index or time), ``"dT"``, ``"u"`` (points, recorded nodes).
    whole_slip : bool
        In the last cycle marched every slider but at most one slides at once (a
        strip's neutral point then sits on a node: see ``pinned_resolution``).
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
    whole_slip: bool = False

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
        """Whole cycles until ``|assembly displacement|`` first reaches ``tolerance`` (m) at a
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


def march_cost(chain: Chain, loading: Loading, cycles: int, n_record: int,
               events_only: bool = False) -> tuple:
    """(bytes, node-passes) of marching ``cycles`` cycles, recording ``n_record`` nodes: a
    load segment in one increment costs about ten passes over the nodes; one marched event
    by event (its external force changes, or ``events_only``) about as many events as nodes,
    each about a pass (measured: 1.5e7 node-passes per second either way)."""
    n, m = chain.n, loading.points_per_cycle
    points = cycles * m + loading.substeps
    mem = (24 * n * 8 + m * n * 8 + cycles * (n * 8 + 300)
           + 2 * points * (n_record * 8 + 24))
    F = loading.F                         # breakpoints: a segment whose force changes
    moving = m if events_only else loading.substeps * int(np.count_nonzero(np.diff(F)))
    lead = loading.substeps * (n / 10 if events_only or loading.F[0] != 0.0 else 1)
    return mem, cycles * (10 * (m - moving) * n + moving * n * n + 2000) + 10 * lead * n


def check_march(chain: Chain, loading: Loading, cycles: int, n_record: int,
                events_only: bool = False) -> None:
    """Refuse, before any work, a march that cannot fit in memory or time."""
    from ..resources import check_memory, check_work
    mem, work = march_cost(chain, loading, cycles, n_record, events_only)
    what = (f"the quasi-static march ({cycles} cycles x {loading.points_per_cycle} load points "
            f"x {chain.n} nodes)")
    lower = ("lower the cycles marched (--max-marched), loading.substeps or the nodes "
             "(assembly.n)")
    check_memory(mem, what, lower)
    check_work(work, MAX_NODE_UPDATES, what, lower)


def simulate(chain: Chain, loading: Loading, cycles: int = 50, *, record_nodes=None,
             until_stable: bool = True, min_cycles: int = 2,
             tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """March the load cycles of a slider chain quasi-statically (SPEC.md 5).

    The exact solution of the rate-independent chain, event by event: every slider's start
    and stop is located exactly along each linear load segment.  The cycle is stabilised
    when the contact forces at the ends of two consecutive cycles agree (the state repeats
    up to a translation); its drift then repeats every cycle.  The memory and work are
    estimated first; the kernel runs in pieces of about 0.1 s (Ctrl-C is honoured,
    progress reported).

    Parameters
    ----------
    chain : Chain
        The assembly: :func:`~asperity.two_node_chain` or :func:`~asperity.strip_chain`.
    loading : Loading
        The load cycle (temperature change and tangential force), repeated.
    cycles : int, optional
        Most cycles to march, in [1, 1e8]; default 50.
    record_nodes : sequence of int, optional
        Node indices (in [0, n - 1]) whose displacement is kept at every load point;
        default the two ends.
    until_stable : bool, optional
        Stop as soon as the cycle is stabilised (and ``min_cycles`` were marched); default
        True.
    min_cycles : int, optional
        Fewest cycles to march with ``until_stable``, in [1, 1e8]; default 2.
    tol : MicroslipTolerances, optional
        The tolerances of the stabilisation and no-drift tests and of the march.

    Returns
    -------
    MicroslipResult
        ``cycles_run``; ``mean_u`` (cycles_run + 1,): the assembly displacement (m,
        weighted mean of the nodes) at the start and at the end of every cycle; ``u_end``
        (cycles_run + 1, n): the nodes'; ``drift_per_cycle`` (m, from the last cycle,
        negative towards -x); ``stabilised_at`` (the first stabilised cycle, None if not
        reached); ``regime`` (``"ratchet"``, ``"alternating slip (no net drift)"`` or
        ``"shakedown"``); ``trace`` (the recorded nodes at every load point);
        ``drift_after(cycles)`` and ``cycles_to(tolerance)``.

    Raises
    ------
    InputError
        If an argument is out of range, the temperature range is beyond the margin the
        solvers resolve (``dT range / (2 dT_c)`` above 1e4), or the march cannot fit in
        memory or time (``ResourceError``).
    SlideOffError
        If the tangential load exceeds what the sliders hold (a physical outcome).
    SolverError
        If a load segment's march does not settle or overflows (a numerical failure).

    See Also
    --------
    asperity.long_life : march until stabilised, then extrapolate.
    asperity.assess : the verdict over a number of cycles.

    Examples
    --------
    SPEC.md's two-node check: ``dT_c = 41.67`` K, cycles over [0, 3 dT_c] drift by
    ``-alpha_T l0 (dT_max - dT_min - 2 dT_c)`` = -5.0e-5 m per cycle once stabilised (the
    first cycle from the stress-free state differs):

    >>> ch = asperity.two_node_chain(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0,
    ...                              mu_plus=0.2, mu_minus=0.1)
    >>> r = asperity.simulate_microslip(ch, asperity.Loading.cycles_between(0.0, 125.0))
    >>> r.regime, r.stabilised_at, r.cycles_run
    ('ratchet', 2, 2)
    >>> print(r.mean_u.round(7), f"{r.drift_per_cycle:.2e}")
    [ 0.00e+00 -7.50e-05 -1.25e-04] -5.00e-05
    """
    from ..progress import report
    from ._chain_kernels import STATUS_NON_FINITE, STATUS_OK, STATUS_SLIDE_OFF
    from ._march_kernels import _UNSET, increment_work, march_memo
    check_inputs(chain, loading, tol)
    cycles = check_int("cycles", cycles, 1, 100_000_000)
    min_cycles = check_int("min_cycles", min_cycles, 1, 100_000_000)
    until_stable = check_flag("until_stable", until_stable)
    rec = record_indices(chain, record_nodes)
    check_margin(chain, loading)
    check_capacity(chain, loading)
    events_only = tol.events_only or not is_uniform(chain)
    check_march(chain, loading, cycles, rec.size, events_only)
    n = chain.n
    u = np.zeros(n)
    q = np.zeros(n)
    max_events = tol.max_events_per_node * n + 1000
    args = (chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw, float(chain.alpha_T))
    fin = np.concatenate([chain.cp[np.isfinite(chain.cp)], chain.cm[np.isfinite(chain.cm)]])
    cap = float(fin.max()) if fin.size and fin.max() > 0 else 1.0
    pacer = Pacer(PIECE_NODE_UPDATES)
    load = [0.0, 0.0]                     # the load (dT, F) where the next segment starts
    state = np.zeros(2)                   # progress of a segment marched in pieces
    acc = np.zeros(n)

    def run(dT, F, guess, memo, ws, more, c0):
        """March the points (dT, F) in pieces of about 0.1 s (guess, memo: the statuses of
        each point's increment and at its segment's start one cycle earlier; ws: the
        kernel's work arrays, kept from a call to the next; ``more``: the points are marched
        again after this, the next increment is solved ahead); c0: cycles done before (for
        progress)."""
        m = dT.size
        ru = np.empty((m, rec.size))
        slip = np.zeros(m)
        held = np.zeros(m, np.int64)
        ev_sum = 0
        j0 = 0
        while j0 < m:
            code, k, ev, work = march_memo(*args, load[0], load[1], dT[j0:], F[j0:], u, q,
                                           guess[j0:], memo[j0:], ws, dT[0], F[0],
                                           guess[0] if more else guess[0, :0], state, acc,
                                           slip[j0:], held[j0:], rec, ru[j0:], max_events,
                                           events_only, pacer.size())
            pacer.done(work)
            ev_sum += ev
            j = j0 + k
            if code == STATUS_SLIDE_OFF:
                raise SlideOffError(f"the assembly slides off at load point dT = "
                                    f"{dT[j]:g} K, F = {F[j]:g}: no slider can stay stuck")
            if code == STATUS_NON_FINITE:
                raise SolverError(f"the march of the load segment to dT = {dT[j]:g} K "
                                  "overflowed (a displacement beyond double precision)")
            if code != STATUS_OK:
                raise SolverError(f"the event-driven march of the load segment to dT = "
                                  f"{dT[j]:g} K did not settle (more than {max_events} slip "
                                  f"events, tol.max_events_per_node = "
                                  f"{tol.max_events_per_node}, or an undecided slider)")
            if k:
                load[0], load[1] = float(dT[j - 1]), float(F[j - 1])
            j0 = j
            report(min(1.0, (c0 + (j0 + state[0]) / m) / cycles), "quasi-static cycles")
        return ru, slip, int(held.min()), ev_sum

    tr_t, tr_dT, tr_u = [np.zeros(1)], [np.zeros(1)], [np.zeros((1, rec.size))]
    scale = load_scale(chain, loading)
    events = 0
    dT0, F0 = loading.lead_in()
    if dT0.size:
        ru, _, _, ev = run(dT0, F0, np.zeros((dT0.size, n), np.int64),
                           np.empty((dT0.size, 0), np.int64), increment_work(n), False, 0)
        events += ev
        tr_dT.append(dT0)
        tr_u.append(ru)
        tr_t = [np.linspace(-1.0, 0.0, dT0.size + 1)]
    dTc, Fc = loading.cycle_points()
    guess = np.zeros((dTc.size, n), np.int64)
    memo = np.full((dTc.size, n), _UNSET)
    ws = increment_work(n)
    mean_u = [float(chain.weight @ u)]
    u_end = np.empty((cycles + 1, n))     # rows filled as the cycles are marched
    u_end[0] = u
    q_prev, dq = q.copy(), np.empty(n)
    frac = np.arange(1, dTc.size + 1) / dTc.size
    stab = None
    slip = False
    whole = False
    for c in range(1, cycles + 1):
        ru, slips, held, ev = run(dTc, Fc, guess, memo, ws, c < cycles, c - 1)
        events += ev
        tr_t.append(c - 1 + frac)
        tr_dT.append(dTc)
        tr_u.append(ru)
        mean_u.append(float(chain.weight @ u))
        u_end[c] = u
        slip = bool(slips.max() > tol.no_drift * scale)
        whole = held <= 1
        if np.abs(np.subtract(q, q_prev, out=dq), out=dq).max() <= tol.stabilised * cap:
            stab = c if stab is None else stab
            if until_stable and c >= min_cycles:
                break
        else:
            stab = None
        q_prev[:] = q
    mean_u = np.array(mean_u)
    k = len(mean_u) - 1
    d = float(mean_u[k] - mean_u[k - 1])
    if abs(d) <= tol.no_drift * scale:
        d = 0.0
    trace = {"t": np.concatenate(tr_t), "dT": np.concatenate(tr_dT),
             "u": np.concatenate(tr_u), "nodes": rec}
    return MicroslipResult(chain, loading, "quasi-static", k, mean_u, u_end[:k + 1], q.copy(), d,
                           stab, slip, trace,
                           {"method": "event-driven: every slider's start and stop located "
                                      "exactly along each linear load segment",
                            "load_points_per_segment": loading.substeps,
                            "events_one_by_one": int(events)}, whole)


def long_life(chain: Chain, loading: Loading, cycles: float, *, max_marched: int = 200,
              record_nodes=None, tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """March a chain until its cycle is stabilised, for a life of many cycles.

    At most ``max_marched`` cycles are marched, and never more than ``cycles``; the
    result's ``drift_after(cycles)`` then extrapolates exactly from the stabilised cycle
    (its state repeats up to a translation), and ``cycles_to(tolerance)`` counts the
    cycles until the walk reaches a tolerance.

    Parameters
    ----------
    chain : Chain
        The assembly: :func:`~asperity.two_node_chain` or :func:`~asperity.strip_chain`.
    loading : Loading
        The load cycle, repeated.
    cycles : float
        The life to assess, in cycles, in [1, 1e15].
    max_marched : int, optional
        Most cycles to march, in [2, 1e6]; default 200.
    record_nodes : sequence of int, optional
        Node indices to record at every load point; default the two ends.
    tol : MicroslipTolerances, optional
        The tolerances of the march.

    Returns
    -------
    MicroslipResult
        As :func:`~asperity.simulate_microslip`; ``drift_after(cycles)`` gives the
        assembly's displacement (m) after the whole life.

    Raises
    ------
    InputError
        If an argument is out of range (see :func:`~asperity.simulate_microslip`).
    SlideOffError
        If the tangential load exceeds what the sliders hold.

    See Also
    --------
    asperity.assess : the verdict, with these figures, as a JSON-ready dict.

    Examples
    --------
    >>> ch = asperity.two_node_chain(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0,
    ...                              mu_plus=0.2, mu_minus=0.1)
    >>> r = asperity.long_life(ch, asperity.Loading.cycles_between(0.0, 125.0), 1000)
    >>> r.cycles_run, r.cycles_to(1e-3)
    (2, 20)
    >>> print(f"{r.drift_after(1000):.6f} m")
    -0.050025 m
    """
    c = check_cycles("cycles", cycles)
    max_marched = check_int("max_marched", max_marched, 2, 1_000_000)
    return simulate(chain, loading, int(min(max_marched, math.ceil(c))), record_nodes=record_nodes,
                    until_stable=True, tol=tol)
