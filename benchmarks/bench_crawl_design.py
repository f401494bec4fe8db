"""The gait optimiser's time and the error its modest search resolution costs (issue 26,
item 5; target: an optimisation of (A, k) in under 10 s quasi-statically).

    python benchmarks/bench_crawl_design.py [--json] [--reference-search]

For each law (Hu et al.'s componentwise 1 : 1.5 : 2, the associated rule on the same
coefficients, and the tube limit mu_t / mu_f = 1000) and objective (speed, cost): the
optimisation of (A, k) in the default box at 60 points and 100 steps a period (after a
warm-up that compiles the kernels), its crawls, infeasible gaits and seconds; then the
optimum crawled at 200 points and 400 steps a period: the search's speed and cost against
those (the error the modest resolution costs at the optimum).  ``--reference-search``
also runs the whole optimisation at 200 points and 400 steps and reports how far its
optimum lies from the modest one (slow: minutes)."""
from __future__ import annotations

import argparse
import json


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--reference-search", action="store_true",
                    help="also optimise at 200 points, 400 steps a period")
    args = ap.parse_args()
    import os

    from asperity.crawling.design import optimise_gait
    from asperity.crawling.solver import coefficient_law, crawl
    laws = {"componentwise 0.1:0.15:0.2": coefficient_law(0.1, 0.15, 0.2),
            "associated 0.1:0.15:0.2": coefficient_law(0.1, 0.15, 0.2, "associated"),
            "tube (associated 0.01:0.01:10)": coefficient_law(0.01, 0.01, 10.0, "associated")}
    crawl(laws["componentwise 0.1:0.15:0.2"], points=20, steps_per_period=40,
          quasi_static=True)                                                 # compile
    rows = []
    for name, law in laws.items():
        for objective in ("speed", "cost"):
            r = optimise_gait(law, objective=objective)
            ref = crawl(law, amplitude=r.optimum["amplitude"], waves=r.optimum["waves"],
                        points=200, steps_per_period=400, quasi_static=True)
            U, cot = ref.speed_body_lengths_per_period, ref.cost_of_transport
            row = {"law": name, "objective": objective, "amplitude": r.optimum["amplitude"],
                   "waves": r.optimum["waves"], "seconds": r.seconds,
                   "evaluations": r.evaluations, "infeasible": r.infeasible,
                   "converged": r.converged, "search_speed": r.speed, "search_cost": r.cost,
                   "speed_200_400": U, "cost_200_400": cot,
                   "speed_rel_error": (r.speed - U) / abs(U) if U else None,
                   "cost_rel_error": (r.cost - cot) / cot if r.cost and cot else None}
            if args.reference_search:
                f = optimise_gait(law, objective=objective, points=200, steps_per_period=400)
                row["reference"] = {"amplitude": f.optimum["amplitude"],
                                    "waves": f.optimum["waves"], "seconds": f.seconds,
                                    "speed": f.speed, "cost": f.cost,
                                    "evaluations": f.evaluations}
            rows.append(row)
    out = {"cases": rows, "cpus": os.cpu_count(),
           "note": "quasi-static; default box A in [0.5, 12], k in [0.5, 3]; 7 x 7 grid then "
                   "Nelder-Mead; times on this machine as loaded when run"}
    if args.json:
        print(json.dumps(out, indent=2))
        return
    for r in rows:
        print(f"{r['law']:<32}{r['objective']:<6} A {r['amplitude']:7.4f} k {r['waves']:6.4f} "
              f"{r['seconds']:6.2f} s {r['evaluations']:4d} crawls ({r['infeasible']} "
              f"infeasible); U {r['search_speed']:+.5f} (200/400: {r['speed_200_400']:+.5f}, "
              f"rel. error {r['speed_rel_error']:+.1e})" +
              ("" if r["cost_rel_error"] is None else
               f"; cost rel. error {r['cost_rel_error']:+.1e}") +
              ("" if "reference" not in r else
               f"; 200/400 optimum A {r['reference']['amplitude']:.4f} k "
               f"{r['reference']['waves']:.4f} in {r['reference']['seconds']:.1f} s"))


if __name__ == "__main__":
    main()
