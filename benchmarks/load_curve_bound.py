"""Why a warm-started load curve costs what it does: the figures behind the bound in
:mod:`asperity.contact.curve` (issue 19, "a load curve of 8 pressures ... at most 3 single
solves").

    python benchmarks/load_curve_bound.py [--n 512] [--plain] [--json]

The problem is the benchmark's (:mod:`asperity.contact.bench`: self-affine map, H 0.8, rms
slope 0.1, E* = 100 GPa, the 8 pressures p/E* = 0.00125 .. 0.005 geometric, relative
tolerance 1e-8), periodic n x n.  Printed:

* iterations of a cold solve at the benchmark's pressure for tolerances 1e-2 .. 1e-8, and
  of the warm solve of one curve step (started from the previous pressure's solution):
  the iterations a decade of the tolerance costs, cold and warm;
* per pressure of the curve: iterations warm (:func:`iter_load_curve`) and cold, the
  start's error sum |p_start - p| / sum p for the previous solution scaled to the load
  (what the curve does) and for a secant extrapolation of p / p_bar in log p_bar from the
  two previous solutions, with the iterations the secant start takes, and the share of
  the contact pixels that were not in contact at the previous pressure;
* the curve's cost in cold single solves (iterations and seconds).

``--plain``: the same with the solver's preconditioner off (Polonsky and Keer's own
iteration, :data:`asperity.contact.solver.PRECONDITION`).

Figures depend on the machine and its load (printed); nothing here is asserted.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))    # this checkout's asperity

from asperity.contact import elastic  # noqa: E402
from asperity.contact.bench import CURVE, E_STAR, LOAD, PIXEL, TOL, self_affine  # noqa: E402
from asperity.contact.curve import iter_load_curve  # noqa: E402
from asperity.contact.solver import solve_on  # noqa: E402

TOLS = (1e-2, 1e-4, 1e-6, 1e-8)


def _solve(space, h, pbar, tol, p0=None):
    t0 = time.perf_counter()
    r = solve_on(space, h, pbar, None, h.size, tol, 10_000, p0, None)
    return r, time.perf_counter() - t0


def _err(a, b) -> float:
    return float(np.abs(a - b).sum() / np.abs(b).sum())


def _per_decade(its) -> float:
    """Least-squares iterations per decade of the tolerance over TOLS."""
    x = -np.log10(np.asarray(TOLS))
    return float(np.polyfit(x, np.asarray(its, float), 1)[0])


def measure(n: int, plain: bool = False) -> dict:
    from asperity.contact import solver
    solver.PRECONDITION = not plain
    h = self_affine(n, dx=PIXEL, seed=1)
    warm = self_affine(64, dx=PIXEL, seed=9)
    _solve(elastic.HalfSpace(warm.shape, PIXEL, PIXEL, E_STAR, "periodic"), warm,
           LOAD * E_STAR, TOL)                                           # compile
    space = elastic.HalfSpace(h.shape, PIXEL, PIXEL, E_STAR, "periodic")
    out = {"n": n, "tol": TOL, "preconditioned": not plain,
           "load_average": [list(os.getloadavg())]}
    single, t_single = _solve(space, h, LOAD * E_STAR, TOL)
    out["single"] = {"iterations": single.iterations, "seconds": t_single,
                     "area_fraction": single.area_fraction}
    # a decade of the tolerance, cold and warm (one curve step: CURVE[3] -> CURVE[4])
    prev = _solve(space, h, CURVE[3] * E_STAR, TOL)[0].pressure
    cold_its = [_solve(space, h, CURVE[4] * E_STAR, tol)[0].iterations for tol in TOLS]
    warm_its = [_solve(space, h, CURVE[4] * E_STAR, tol, prev)[0].iterations for tol in TOLS]
    out["tolerances"] = list(TOLS)
    out["cold_iterations_by_tol"] = cold_its
    out["warm_iterations_by_tol"] = warm_its
    out["cold_iterations_per_decade"] = _per_decade(cold_its)
    out["warm_iterations_per_decade"] = _per_decade(warm_its)
    # the curve, as the library solves it
    rows, sols, t_curve = [], [], 0.0
    t0 = time.perf_counter()
    for k, res in enumerate(iter_load_curve(h, PIXEL, E_STAR, [f * E_STAR for f in CURVE],
                                            tol=TOL)):
        t_curve += time.perf_counter() - t0
        rows.append({"p_over_E_star": CURVE[k], "warm_iterations": res.iterations,
                     "area_fraction": res.area_fraction})
        sols.append(res.pressure)
        t0 = time.perf_counter()
    for k, row in enumerate(rows):
        row["cold_iterations"] = _solve(space, h, CURVE[k] * E_STAR, TOL)[0].iterations
        if k == 0:
            continue
        P = [c * E_STAR for c in CURVE]
        row["start_error_previous"] = _err(sols[k - 1] * (P[k] / P[k - 1]), sols[k])
        was, now = sols[k - 1] > 0, sols[k] > 0
        row["new_contact_share"] = float(np.count_nonzero(now & ~was) / np.count_nonzero(now))
        if k >= 2:
            a = math.log(P[k] / P[k - 1]) / math.log(P[k - 1] / P[k - 2])
            q1, q2 = sols[k - 2] / P[k - 2], sols[k - 1] / P[k - 1]
            ext = np.maximum(q2 + a * (q2 - q1), 0.0)
            ext *= P[k] * h.size / ext.sum()
            row["start_error_secant"] = _err(ext, sols[k])
            row["secant_iterations"] = _solve(space, h, P[k], TOL, ext)[0].iterations
    out["curve"] = rows
    out["curve_seconds"] = t_curve
    out["curve_iterations"] = sum(r["warm_iterations"] for r in rows)
    out["curve_in_single_solves_iterations"] = out["curve_iterations"] / single.iterations
    out["curve_in_single_solves_seconds"] = t_curve / t_single
    out["load_average"].append(list(os.getloadavg()))
    return out


def format_bound(o: dict) -> str:
    s = o["single"]
    kind = "preconditioned" if o["preconditioned"] else "plain Polonsky-Keer"
    lines = [f"periodic {o['n']}^2 ({kind}), tol {o['tol']:g}, load average "
             f"{o['load_average'][0][0]:.1f} -> {o['load_average'][-1][0]:.1f}",
             f"cold single solve (p/E* {LOAD}): {s['iterations']} iterations, "
             f"{s['seconds']:.2f} s, contact {s['area_fraction']:.3f}",
             "iterations for tol " + " / ".join(f"{t:g}" for t in o["tolerances"])
             + f": cold {o['cold_iterations_by_tol']}, warm {o['warm_iterations_by_tol']}"
             f" -> {o['cold_iterations_per_decade']:.1f} (cold), "
             f"{o['warm_iterations_per_decade']:.1f} (warm) iterations a decade",
             "  p/E*     warm  cold  start error (previous / secant)  secant its  new contact"]
    for r in o["curve"]:
        e = (f"{r['start_error_previous']:.3f}" if "start_error_previous" in r else "  -  ")
        e2 = f"{r['start_error_secant']:.3f}" if "start_error_secant" in r else "  -  "
        si = f"{r['secant_iterations']:4d}" if "secant_iterations" in r else "   -"
        nc = f"{r['new_contact_share']:.3f}" if "new_contact_share" in r else "  -"
        lines.append(f"  {r['p_over_E_star']:.5f} {r['warm_iterations']:5d} "
                     f"{r['cold_iterations']:5d}      {e} / {e2}               {si}"
                     f"        {nc}")
    lines.append(f"curve: {o['curve_iterations']} iterations, {o['curve_seconds']:.2f} s = "
                 f"{o['curve_in_single_solves_iterations']:.2f} single solves in iterations, "
                 f"{o['curve_in_single_solves_seconds']:.2f} in seconds")
    return "\n".join(lines)


if __name__ == "__main__":
    a = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    a.add_argument("--n", type=int, default=512, help="periodic map n x n")
    a.add_argument("--plain", action="store_true",
                   help="the solver without its preconditioner (Polonsky and Keer's)")
    a.add_argument("--json", action="store_true")
    args = a.parse_args()
    res = measure(args.n, args.plain)
    print(json.dumps(res, indent=2) if args.json else format_bound(res))
