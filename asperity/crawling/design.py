"""The fastest or the cheapest gait for a law: the curvature wave's amplitude A and waves k
optimised (``asperity crawl --optimise amplitude,waves``, :func:`optimise_gait`).

The objective is the crawl's speed (body lengths per period, head-ward positive:
maximised) or its cost of transport (minimised, among gaits that move head-ward).  A gait
that crosses itself (:func:`~asperity.crawling.gait_crossing.check_self_crossing`) is
infeasible, as is, for the cost, one that does not move head-ward or whose solve did not
converge: such points get a penalty above every feasible value, not an error.

Method: a coarse grid over the bounds (``grid`` values a parameter: it finds the basin,
and it is the plot's map), then Nelder-Mead with bounds (scipy.optimize.minimize) from the
grid's best point, in coordinates scaled to [0, 1].  Nelder-Mead, not L-BFGS-B: the
objective has no gradient but by finite differences, which the penalty's jump at the
self-crossing boundary (and at U = 0 for the cost) would spoil, and it needs no smooth
objective to walk onto a bound or a corner, where the optima of the tube limit sit.  Not
differential evolution: it spends hundreds of crawls where the grid and a simplex spend
about a hundred, and the landscape has one basin in the laws tried (the grid guards
against a second).  The search runs at a modest resolution (``points``,
``steps_per_period``); the command then crawls at its own at the optimum.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_choice, check_int, check_range

PARAMS = ("amplitude", "waves")
ALIASES = {"a": "amplitude", "amplitude": "amplitude", "k": "waves", "waves": "waves"}
#: default search box
BOUNDS = {"amplitude": (0.5, 12.0), "waves": (0.5, 3.0)}
#: the box may lie within (the gait's ranges; waves' low end open)
LIMITS = {"amplitude": (0.0, 100.0), "waves": (0.0, 20.0)}
OBJECTIVES = ("speed", "cost")
#: the objective of an infeasible gait (every feasible objective is far below)
PENALTY = 1e6


@dataclass
class DesignResult:
    """An optimisation: ``optimum`` {amplitude, waves} (the fixed one too), its ``speed``
    (body lengths per period) and ``cost`` (cost of transport, None if it does not move) at
    the search's resolution; ``evaluations`` (crawls run, distinct gaits), ``infeasible``
    (of them), ``seconds``; ``grid`` the coarse grid's objective ({param: values},
    ``objective`` (n_A, n_k) or (n,), NaN where infeasible), ``path`` the evaluations
    after the grid in order, ``best_path`` the simplex's best point at each iteration."""

    params: tuple
    objective: str
    bounds: dict
    fixed: dict
    optimum: dict
    speed: float
    cost: float | None
    evaluations: int
    infeasible: int
    seconds: float
    converged: bool
    message: str
    method: str
    points: int
    steps_per_period: int
    quasi_static: bool
    rule: str
    grid: dict = field(repr=False)
    path: list = field(repr=False)
    best_path: list = field(repr=False)

    def to_json(self) -> dict:
        return {"params": list(self.params), "objective": self.objective,
                "bounds": {k: list(v) for k, v in self.bounds.items()},
                "fixed": self.fixed, "amplitude": self.optimum["amplitude"],
                "waves": self.optimum["waves"],
                "search_speed_body_lengths_per_period": self.speed,
                "search_cost_of_transport": self.cost, "evaluations": self.evaluations,
                "infeasible_evaluations": self.infeasible, "seconds": self.seconds,
                "converged": self.converged, "message": self.message, "method": self.method,
                "search_points": self.points,
                "search_steps_per_period": self.steps_per_period,
                "quasi_static": self.quasi_static, "rule": self.rule,
                "grid_size": len(next(iter(self.grid["values"].values())))}


def parse_params(params) -> tuple:
    """The parameters to optimise, in the order of PARAMS; names or A, k."""
    if isinstance(params, str):
        params = [p for p in params.split(",")]
    if not isinstance(params, (list, tuple)) or not params:
        raise InputError(f"params must name amplitude and/or waves, got {params!r}")
    out = []
    for p in params:
        name = ALIASES.get(str(p).strip().lower()) if isinstance(p, str) else None
        if name is None:
            raise InputError(f"params: unknown parameter {p!r}; allowed: amplitude (A), "
                             f"waves (k)")
        if name in out:
            raise InputError(f"params: {name} given twice")
        out.append(name)
    return tuple(n for n in PARAMS if n in out)


def check_bounds(bounds, params) -> dict:
    """{param: (lo, hi)} of the optimised parameters: the defaults, overridden by
    ``bounds`` ({name or alias: (lo, hi)}); lo < hi within the gait's range."""
    out = {p: BOUNDS[p] for p in params}
    for key, pair in (bounds or {}).items():
        name = ALIASES.get(str(key).strip().lower())
        if name is None:
            raise InputError(f"bounds: unknown parameter {key!r}; allowed: amplitude (A), "
                             f"waves (k)")
        if name not in params:
            raise InputError(f"bounds.{name}: {name} is not optimised (params: "
                             f"{', '.join(params)})")
        if not isinstance(pair, (list, tuple)) or len(pair) != 2:
            raise InputError(f"bounds.{name} must be (low, high), got {pair!r}")
        lo_lim, hi_lim = LIMITS[name]
        opn = name == "waves"
        lo = check_range(f"bounds.{name} low", pair[0], lo_lim, hi_lim, low_open=opn)
        hi = check_range(f"bounds.{name} high", pair[1], lo_lim, hi_lim, low_open=opn)
        if not lo < hi:
            raise InputError(f"bounds.{name}: low {lo:g} must be below high {hi:g}")
        out[name] = (lo, hi)
    return out


def optimise_gait(law=None, *, mu_f=None, mu_b=None, mu_t=None, rule="componentwise",
                  params=PARAMS, objective="speed", bounds=None, amplitude=7.0,
                  waves=1.0, length=1.0, period=1.0, points=60, steps_per_period=100,
                  periods=None, quasi_static=True, g=9.81, texture_on="body",
                  texture_angle_deg=0.0, grid=7, max_evaluations=300, xatol=1e-3,
                  fatol=1e-7, settings=None) -> DesignResult:
    """Optimise the curvature wave's ``params`` (amplitude and/or waves; the other held at
    its ``amplitude`` / ``waves``) within ``bounds`` (default A in [0.5, 12], k in [0.5,
    3]) for ``objective`` "speed" (the largest head-ward speed) or "cost" (the least cost
    of transport at a speed > 0).  The crawls run on ``law`` (or mu_f, mu_b, mu_t by
    ``rule``), quasi-statically by default, at ``points`` and ``steps_per_period``.
    ``grid``: the coarse grid's values per parameter (3 to 41); ``max_evaluations``: crawls
    of the Nelder-Mead stage at most; ``xatol`` (of the box scaled to 1) and ``fatol``
    its tolerances.  Returns a :class:`DesignResult`."""
    from scipy.optimize import minimize

    from ..progress import report, silenced
    from .gait import CurvatureWave
    from .solver import CrawlSettings, _check_law, crawl
    law = _check_law(law, mu_f, mu_b, mu_t, rule)
    names = parse_params(params)
    box = check_bounds(bounds, names)
    objective = check_choice("objective", objective, OBJECTIVES)
    n_grid = check_int("grid", grid, 3, 41)
    max_ev = check_int("max_evaluations", max_evaluations, 1, 100_000)
    xatol = check_range("xatol", xatol, 1e-9, 0.5, low_open=True)
    fatol = check_range("fatol", fatol, 0.0, 1.0)
    CurvatureWave(amplitude=amplitude, waves=waves, period=period, length=length)  # checks
    fixed = {p: float(amplitude if p == "amplitude" else waves) for p in PARAMS
             if p not in names}
    kw = {"length": length, "period": period, "points": points,
          "steps_per_period": steps_per_period, "periods": periods,
          "quasi_static": quasi_static, "g": g, "texture_on": texture_on,
          "texture_angle_deg": texture_angle_deg,
          "settings": settings if settings is not None else CrawlSettings()}
    lo = np.array([box[p][0] for p in names])
    span = np.array([box[p][1] - box[p][0] for p in names])
    seen: dict = {}
    t0 = time.perf_counter()

    def gait_of(z):
        x = lo + span * np.clip(z, 0.0, 1.0)
        v = dict(fixed)
        v.update({p: float(x[i]) for i, p in enumerate(names)})
        return v

    def evaluate(z):
        v = gait_of(z)
        key = (round(v["amplitude"], 12), round(v["waves"], 12))
        if key not in seen:
            try:
                with silenced():          # one bar for the search, not one per crawl
                    res = crawl(law, amplitude=v["amplitude"], waves=v["waves"], **kw)
            except InputError as exc:
                if "crosses itself" not in str(exc):
                    raise
                seen[key] = (v, None, None, PENALTY)
                return seen[key]
            U = res.speed_body_lengths_per_period if res.ok else None
            cot = res.cost_of_transport if res.ok else None
            if U is None or not math.isfinite(U):
                f = PENALTY
            elif objective == "speed":
                f = -U
            else:
                f = cot if (U > 0 and cot is not None and math.isfinite(cot)) else PENALTY
            seen[key] = (v, U, cot, f)
        return seen[key]

    axes = [np.linspace(0.0, 1.0, n_grid) for _ in names]
    mesh = np.meshgrid(*axes, indexing="ij")
    zs = np.stack([m.ravel() for m in mesh], axis=1)
    fg = np.empty(len(zs))
    for i, z in enumerate(zs):
        fg[i] = evaluate(z)[3]
        report(0.5 * (i + 1) / len(zs), "gait search (grid)")
    n_grid_eval = len(seen)
    if not np.any(fg < PENALTY):
        why = "crosses itself, moves tail-ward" if objective == "cost" else "crosses itself"
        raise InputError(f"no gait of the grid is feasible for the {objective} objective "
                         f"(every one {why} or did not converge): change bounds")
    z0 = zs[int(np.argmin(fg))]
    h = 0.5 / (n_grid - 1)
    simplex = [z0] + [np.clip(z0 + h * e, 0, 1) if z0[i] + h <= 1 else z0 - h * e
                      for i, e in enumerate(np.eye(len(names)))]
    path, best_path = [], [gait_of(z0)]

    def fun(z):
        v, _U, _cot, f = evaluate(z)
        report(0.5 + 0.5 * min(1.0, len(path) / max_ev), "gait search (Nelder-Mead)")
        path.append({**v, "objective": f if f < PENALTY else None})
        return f

    opt = minimize(fun, z0, method="Nelder-Mead", bounds=[(0.0, 1.0)] * len(names),
                   callback=lambda zk: best_path.append(gait_of(zk)),
                   options={"initial_simplex": np.array(simplex), "xatol": xatol,
                            "fatol": fatol, "maxfev": max_ev})
    z_best = opt.x if opt.fun <= fg.min() else z0
    v, U, cot, _f = evaluate(z_best)
    best_path.append(v)
    obj_grid = np.where(fg < PENALTY, -fg if objective == "speed" else fg, np.nan)
    return DesignResult(
        params=names, objective=objective, bounds=box, fixed=fixed,
        optimum={"amplitude": v["amplitude"], "waves": v["waves"]}, speed=U, cost=cot,
        evaluations=len(seen), infeasible=sum(1 for s in seen.values() if s[3] >= PENALTY),
        seconds=time.perf_counter() - t0, converged=bool(opt.success),
        message=f"{n_grid_eval} grid gaits, then Nelder-Mead: {opt.message}",
        method="grid + Nelder-Mead (scipy.optimize.minimize, bounded)",
        points=int(points), steps_per_period=int(steps_per_period),
        quasi_static=bool(quasi_static), rule=_rule(law),
        grid={"values": {p: (lo[i] + span[i] * axes[i]).tolist()
                         for i, p in enumerate(names)},
              "objective": obj_grid.reshape([n_grid] * len(names))},
        path=path, best_path=best_path)


def _rule(law) -> str:
    from .solver import law_rule
    return law_rule(law)
