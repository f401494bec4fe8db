"""Cases per second of the study engine: a serial in-process loop over the single-case API
against the engine on a LocalCluster of 2 workers, for two-node risk, 201-node strip risk
and the derive of 256 x 256 scans (the same as `asperity bench --only study`).

Run as a script to print the figures and the projection for a 1e6-case study:
    python benchmarks/bench_study.py [--workers N] [--json]
Targets (issue 12): >= 1.7x the serial loop for cases of >= 10 ms; >= 1e4 two-node cases
per second on 2 workers; scheduling overhead <= 10 %.
"""
from __future__ import annotations

import argparse
import json


def main() -> None:
    from asperity.study.bench import bench_study, format_study
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    out = bench_study(workers=a.workers)
    print(json.dumps(out, indent=2) if a.json else format_study(out))


if __name__ == "__main__":
    main()
