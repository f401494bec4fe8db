"""Facet-directions per second of the streamed facet reservoir: numba kernel vs NumPy.

Run as a script:  python benchmarks/bench_facets.py [N_GRID [N_DIRECTIONS [NUMPY_DIRECTIONS]]]
(default 2048 360 8: 8.4 million facets of a random rough surface x 360 directions).
Same figures as ``asperity bench --only facets``.
"""
from __future__ import annotations

import json
import sys

from asperity.bench import bench_facets, format_facets

if __name__ == "__main__":
    args = [int(a) for a in sys.argv[1:4] if not a.startswith("-")]
    out = bench_facets(*args)
    print(json.dumps(out, indent=2) if "--json" in sys.argv else format_facets(out))
