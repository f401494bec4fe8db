"""Bodies on a plane (issue 20): asperity's point mass on the ellipse and the star law
against MuJoCo's box on a plane, MuJoCo's spinning disc, the body solver's 256-point disc.

Run as a script to print the figures (``asperity bench --only body`` does the same once;
here ``--repeats`` runs, the machine may be shared):
    python benchmarks/bench_body.py [--repeats 3] [--seconds 1] [--no-install]
Targets (issue 20): star law >= 5x MuJoCo's box; the 256-point disc >= 2e4 steps/s with the
ellipse law, >= 1e4 with the star law.
"""
from __future__ import annotations

import argparse


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--seconds", type=float, default=1.0)
    p.add_argument("--no-install", action="store_true", help="do not pip install MuJoCo")
    a = p.parse_args(argv)
    from asperity.dynamics.body_bench import bench_body, format_body
    for k in range(max(1, a.repeats)):
        print(f"--- run {k + 1}")
        print(format_body(bench_body(a.seconds, install=not a.no_install)))


if __name__ == "__main__":
    main()
