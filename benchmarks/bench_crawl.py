"""Crawl timings and the side-by-side with PyElastica's continuum snake (issue 26).

    python benchmarks/bench_crawl.py [--json]

Times (after a warm-up that compiles the kernels; a new gait, checked and tabulated, and the
same gait again, its tables kept): a dynamic crawl of 201 points over 8 periods at 400
steps a period, a quasi-static speed at the defaults (100 points, 1 period),
and the crawl of PyElastica's case (L = 0.35 m, T = 2 s, Froude 0.1, componentwise
1 : 1.5 : 2, its fitted curvature's main term A = 7, k = 1) beside PyElastica's own speed
and wall time from benchmarks/crawl_pyelastica_results.json (written by
benchmarks/crawl_pyelastica.py, which installs PyElastica)."""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def timed(fn, repeat=3):
    best = float("inf")
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--pyelastica", action="store_true",
                    help="run PyElastica's example in this run (installs pyelastica when "
                         "missing; ~20 s) instead of reading its recorded results")
    args = ap.parse_args()
    import os
    from asperity.crawling.gait import CurvatureWave
    from asperity.crawling.solver import coefficient_law, crawl
    law = coefficient_law(0.1, 0.15, 0.2)
    crawl(law, points=20, periods=1, steps_per_period=40)                     # compile
    crawl(law, points=20, periods=1, steps_per_period=40, quasi_static=True)
    from asperity.crawling import solver

    def cold(**kw):
        solver._TABLES.clear()            # the gait checked and tabulated anew
        return crawl(law, **kw)
    t_dyn, dyn = timed(lambda: cold(points=201, periods=8))
    t_dyn_warm, _ = timed(lambda: crawl(law, points=201, periods=8))
    t_qs, qs = timed(lambda: cold(quasi_static=True))
    t_qs_warm, _ = timed(lambda: crawl(law, quasi_static=True))
    pe = json.loads((HERE / "crawl_pyelastica_results.json").read_text())
    if args.pyelastica:
        import sys
        sys.path.insert(0, str(HERE))
        from crawl_pyelastica import run_pyelastica
        live = run_pyelastica(11.0)
        pe["pyelastica"]["speed_body_lengths_per_period"] = live["speed_body_lengths_per_period"]
        pe["pyelastica"]["wall_time_s"] = live["wall_time_s"]
        pe["pyelastica"]["measured"] = "in this run"
    prm = pe["parameters"]
    mu = prm["mu_forward"]
    pe_law = coefficient_law(mu, 1.5 * mu, 2.0 * mu)
    gait = CurvatureWave(amplitude=7.0, waves=1.0, period=prm["period_s"],
                         length=prm["length_m"])
    t_pe, ours = timed(lambda: crawl(pe_law, gait=gait, points=51, periods=11,
                                     g=prm["gravity_m_s2"]), repeat=1)
    ours_qs = crawl(pe_law, gait=gait, points=201, quasi_static=True)
    out = {
        "dynamic_201_points_8_periods_s": t_dyn,
        "dynamic_speed": dyn.speed_body_lengths_per_period,
        "dynamic_mean_iterations": dyn.mean_iterations,
        "dynamic_201_points_8_periods_same_gait_again_s": t_dyn_warm,
        "quasi_static_default_s": t_qs,
        "quasi_static_default_same_gait_again_s": t_qs_warm,
        "quasi_static_speed": qs.speed_body_lengths_per_period,
        "pyelastica_case": {
            "froude": ours.froude,
            "ours_dynamic_speed": ours.speed_body_lengths_per_period,
            "ours_dynamic_s_11_periods_51_points": t_pe,
            "ours_quasi_static_speed": ours_qs.speed_body_lengths_per_period,
            "pyelastica_speed": pe["pyelastica"]["speed_body_lengths_per_period"],
            "pyelastica_wall_time_s": pe["pyelastica"]["wall_time_s"],
            "speedup_vs_pyelastica": pe["pyelastica"]["wall_time_s"] / t_pe,
            "speedup_201_points_8_periods_vs_pyelastica_11": pe["pyelastica"]["wall_time_s"]
            / t_dyn,
        },
        "load_average": os.getloadavg(),
    }
    if args.json:
        print(json.dumps(out, indent=2))
        return
    for k, v in out.items():
        print(f"{k}: {v}")


if __name__ == "__main__":
    main()
