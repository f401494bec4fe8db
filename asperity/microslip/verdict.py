"""The verdict of a slider chain under its load cycles, with dT_c, the margin, the drift per
cycle, the drift after N cycles and the cycles until a tolerance is reached (the JSON keys
of ``asperity risk``).  The verdicts (:data:`VERDICTS`):

* ``shakedown``: after the first cycles no slider slips any more; the assembly stays put
  (elastic shakedown);
* ``alternating-slip``: sliders slip back and forth in every cycle but the assembly does
  not drift (fretting at the ends of a strip: wear, no walk);
* ``ratchet``: the stabilised cycle drifts; the assembly walks a fixed distance per cycle;
* ``slides-off``: the tangential load exceeds what the sliders hold (no cyclic state).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import check_int, check_range
from .chains import TOL, Chain, MicroslipTolerances, SlideOffError, elastic_limit
from .limits import check_cycles, check_tolerance
from .loading import Loading
from .quasi_static import check_inputs, long_life

#: the verdict values, in order of severity
VERDICTS = ("shakedown", "alternating-slip", "ratchet", "slides-off")

SIGN_CONVENTION = ("x is the assembly's slip axis; displacements and drift are positive "
                   "towards +x; mu+ resists sliding of the assembly towards +x over the "
                   "support, mu- towards -x; with mu+ > mu- the assembly creeps towards -x "
                   "(negative drift)")


def _jnum(x) -> float | None:
    return float(x) if x is not None and math.isfinite(x) else None


def verdict_of(result) -> str:
    """The verdict word of a marched result (:data:`VERDICTS`, not slides-off)."""
    if result.ratchet:
        return "ratchet"
    return "alternating-slip" if result.slip_in_cycle else "shakedown"


def assess(chain: Chain, loading: Loading, cycles: float = 1e6, tolerance: float | None = None,
           *, dT_c_closed_form: float | None = None, max_marched: int = 200,
           tol: MicroslipTolerances = TOL) -> dict:
    """The ratchet verdict of an assembly over a number of load cycles (what ``asperity risk`` prints).

    The verdict is ``"ratchet"`` if the stabilised cycle drifts (the assembly walks a fixed
    distance per cycle), else ``"alternating-slip"`` if sliders still slip in it (fretting:
    wear, no walk), else ``"shakedown"``; ``"slides-off"`` if the tangential load exceeds
    what the sliders hold (a physical outcome, with the reason).  Sign convention: ``x`` is
    the slip axis, displacements positive towards +x; ``mu+`` resists sliding towards +x,
    ``mu-`` towards -x; with ``mu+ > mu-`` the assembly creeps towards -x.

    Parameters
    ----------
    chain : Chain
        The assembly: :func:`~asperity.two_node_chain` or :func:`~asperity.strip_chain`.
    loading : Loading
        The load cycle, repeated.
    cycles : float, optional
        The life to assess, in cycles, in [1, 1e15]; default 1e6.
    tolerance : float, optional
        Displacement (m, in [1e-9, 1e3]) the design tolerates: the cycles until the walk
        reaches it are counted.
    dT_c_closed_form : float, optional
        A closed-form elastic limit (K, > 0 or inf) reported beside the model's.
    max_marched : int, optional
        Most cycles to march before extrapolating, in [2, 1e6]; default 200.
    tol : MicroslipTolerances, optional
        The tolerances of the march.

    Returns
    -------
    dict
        JSON-ready (but for ``"_result"``, the MicroslipResult): ``verdict``, ``regime``,
        ``dT_c_K`` (the elastic limit: heating from the stress-free state, no external
        force), ``margin`` (``dT range / (2 dT_c)``), ``drift_per_cycle_m``,
        ``drift_direction``, ``drift_after_cycles_m``, ``cycles_to_tolerance`` (None if
        never), ``stabilised_at_cycle``, ``cycles_marched``, ``mu_plus``, ``mu_minus``,
        ``asymmetry``, ``sign_convention``, and ``reason`` when it slides off.

    Raises
    ------
    InputError
        If an argument is out of range (see :func:`~asperity.simulate_microslip`).

    See Also
    --------
    asperity.assess_assembly : the verdict of an assembly file with a texture.
    asperity.long_life : the march behind it.

    Notes
    -----
    For the two-node model the assembly ratchets iff ``margin > 1``; for the strip
    ``margin > 1`` is necessary, not sufficient: its ends can slip back and forth while
    its middle sticks (SPEC.md 5).

    Examples
    --------
    SPEC.md's two-node check over [0, 3 dT_c], then a tangential force beyond what the
    sliders hold (``mu+ sum N`` = 40 N):

    >>> ch = asperity.two_node_chain(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0,
    ...                              mu_plus=0.2, mu_minus=0.1)
    >>> v = asperity.assess(ch, asperity.Loading.cycles_between(0.0, 125.0), 1e6,
    ...                     tolerance=1e-3)
    >>> v["verdict"], round(v["dT_c_K"], 2), v["margin"], v["cycles_to_tolerance"]
    ('ratchet', 41.67, 1.5, 20)
    >>> print(f"{v['drift_per_cycle_m']:.2e} m per cycle towards {v['drift_direction']}")
    -5.00e-05 m per cycle towards -x
    >>> asperity.assess(ch, asperity.Loading.cycles_between(0.0, 80.0))["verdict"]
    'shakedown'
    >>> v = asperity.assess(ch, asperity.Loading.cycles_between(0.0, 125.0, 0.0, 50.0))
    >>> print(v["verdict"], "--", v["reason"])
    slides-off -- the assembly slides off towards +x: the tangential load reaches 50 N,
    the sliders hold at most mu+ sum N = 40 N
    """
    check_inputs(chain, loading, tol)
    cycles = check_cycles("cycles", cycles)
    if tolerance is not None:
        tolerance = check_tolerance("tolerance", tolerance)
    if dT_c_closed_form is not None:
        dT_c_closed_form = check_range("dT_c_closed_form", dT_c_closed_form, 0.0, None,
                                       low_open=True, unit="K", allow_inf=True)
    max_marched = check_int("max_marched", max_marched, 2, 1_000_000)
    dT_c = elastic_limit(chain)
    rng = loading.dT_range
    out = {"sign_convention": SIGN_CONVENTION,
           "mu_plus": _jnum(chain.mu_plus), "mu_minus": _jnum(chain.mu_minus),
           "asymmetry": asymmetry(chain.mu_plus, chain.mu_minus),
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
        "verdict": verdict_of(r),
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
    out["resolution"] = pinned_resolution(chain, loading, r)
    out["_result"] = r
    return out


def asymmetry(mu_plus: float, mu_minus: float) -> float | None:
    """(mu+ - mu-) / max(mu+, mu-), None when a side self-locks."""
    if not (math.isfinite(mu_plus) and math.isfinite(mu_minus)):
        return None
    return (mu_plus - mu_minus) / max(mu_plus, mu_minus)


def pinned_resolution(chain: Chain, loading: Loading, result) -> dict | None:
    """A strip that slides whole (every node but at most one at once) slides about its
    neutral point, where the friction forces balance; with nodes, that point is a node.
    With mu+ and mu- closer than about 2/(n - 1) of their value the nodes, not the friction,
    decide the drift: an odd strip's middle node holds the imbalance in both half cycles
    (no drift), an even strip's two middle nodes take turns (about one element's thermal
    expansion per cycle), where the continuum drifts at most alpha_T l dT_range |mu+ - mu-|
    / (mu+ + mu-) per cycle.  That case (nonzero asymmetry below 2/(n - 1)) as a dict, else
    None."""
    a = asymmetry(chain.mu_plus, chain.mu_minus)
    n = chain.n
    if chain.kind != "strip" or not result.whole_slip or not a or abs(a) >= 2.0 / (n - 1):
        return None
    mp, mm = chain.mu_plus, chain.mu_minus
    return {"nodes": n, "asymmetry_resolved": 2.0 / (n - 1),
            "continuum_drift_bound_m": abs(chain.alpha_T) * chain.length * loading.dT_range
            * abs(mp - mm) / (mp + mm),
            "nodes_to_resolve": int(min(math.ceil(2.0 / abs(a)) + 1, 1e9))}
