"""A crawling study on 2 local Dask workers (issue 26, item 5; target: 1e4 texture x gait
cases in under 10 minutes).

    python benchmarks/bench_study_crawl.py [--cases 1000] [--workers 2] [--json]

The study: wedge skins (alpha x beta, 10 deg to 60 deg) x curvature waves (amplitude x
waves), quasi-static, 60 points, 100 steps a period, the texture across the body
(texture_angle_deg = 90); the gait parameters vary fastest, so a worker fits each texture
once per batch or from its cache.  ``--cases`` is rounded to textures x gaits with 10
gaits (amplitude 5 values x waves 2) a texture.  Reports the wall time (with the cluster's
start), the cases a second and the time 1e4 cases would take at that rate (a projection,
the fits' share scaling with the textures)."""
from __future__ import annotations

import argparse
import json
import math
import tempfile
import time
from pathlib import Path

STUDY = """
[study]
kind = "grid"
[texture]
kind = "wedge"
alpha_deg = 30.0
beta_deg = 30.0
mu_alpha = 0.1
mu_beta = 0.1
height = 5.0e-6
[crawl]
points = 60
steps_per_period = 100
quasi_static = true
texture_angle_deg = 90.0
[parameters]
"texture.alpha_deg" = {{ low = 10.0, high = 60.0, n = {na} }}
"texture.beta_deg" = {{ low = 10.0, high = 60.0, n = {nb} }}
"crawl.amplitude" = {{ low = 3.0, high = 9.0, n = 5 }}
"crawl.waves" = {{ values = [1.0, 1.5] }}
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    from asperity.study.run import run_study_file
    textures = max(1, args.cases // 10)
    na = max(1, int(math.sqrt(textures)))
    nb = max(1, textures // na)
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "bench-crawl.toml"
        f.write_text(STUDY.format(na=na, nb=nb))
        t0 = time.perf_counter()
        s = run_study_file(f, Path(tmp) / "out", workers=args.workers)
        wall = time.perf_counter() - t0
    n = s["cases"]
    out = {"cases": n, "textures": na * nb, "gaits_per_texture": 10,
           "workers": s["run"]["workers"], "where": s["run"]["where"],
           "completed": s["completed"], "failed": s["failed"], "wall_s": wall,
           "run_s": s["run"]["seconds"], "cases_per_s": n / wall,
           "projected_1e4_cases_s": 1e4 * wall / n,
           "fastest": {k: v for k, v in s["crawl"]["ranking"][0].items()
                       if k not in ("message", "status")},
           "note": "times on this machine as loaded when run"}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"{n} cases ({na * nb} textures x 10 gaits) on {out['where']}: {wall:.1f} s "
              f"({n / wall:.1f} cases/s; {out['failed']} failed); 1e4 cases projected "
              f"{out['projected_1e4_cases_s']:.0f} s")


if __name__ == "__main__":
    main()
