"""Steps per second of the rigid-body solver: a disc with 256 contact points sliding and
spinning, ellipse law and star law (compilation excluded).

Run as a script (figures measured three times: the machine may be shared):
    python benchmarks/bench_body_solver.py [--points N] [--seconds S]
Targets (issue 20): >= 2e4 steps/s with the ellipse law, >= 1e4 with the star law on 2 cores.
"""
from __future__ import annotations

import argparse
import os


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=256, help="contact points of the disc")
    ap.add_argument("--seconds", type=float, default=1.0, help="timing per law and repeat")
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args(argv)
    from asperity.dynamics.disc_bench import bench_disc
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    for law in ("ellipse", "star"):
        runs = [bench_disc(law, a.points, a.seconds) for _ in range(a.repeats)]
        print(f"disc, {runs[0]['contact_points']} points, {law:8s}: "
              + "  ".join(f"{r['steps_per_s']:.3e}" for r in runs)
              + f"  steps/s ({runs[0]['mean_iterations']:.2f} Newton iterations/step)")


if __name__ == "__main__":
    main()
