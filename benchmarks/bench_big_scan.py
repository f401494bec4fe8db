"""Scans derived in tiles: time and peak memory of ``asperity derive`` on synthetic float32
maps on disk, against the facet kernel in memory.

Run as a script:  python benchmarks/bench_big_scan.py [N ...] [--repeats R] [--dir DIR] [--json]
(default 2048 4096 8192; 16384 writes a 1 GB map and takes minutes per run).  Same figures
as ``asperity bench --only big-scan --scan-sizes N ...``.  Each map is written to DIR (a
temporary folder by default) and deleted after its runs; check ``df -h`` first.
"""
from __future__ import annotations

import argparse
import json

from asperity.bench import bench_big_scan, format_big_scan

if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("sizes", type=int, nargs="*", default=[2048, 4096, 8192])
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--directions", type=int, default=360)
    p.add_argument("--dir", default=None)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    out = bench_big_scan(a.sizes, a.directions, a.repeats, a.dir)
    print(json.dumps(out, indent=2) if a.json else format_big_scan(out))
