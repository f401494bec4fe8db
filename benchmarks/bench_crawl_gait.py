"""Crawl gaits (issue 26, item 2): the kinematics the crawl solver precomputes and the
self-crossing check, best of ``--repeats`` runs (the machine may be shared).

    python benchmarks/bench_crawl_gait.py [--repeats 5]

Targets (issue 26 helper brief): kinematics of 1000 times x 201 points well under 0.1 s;
check_self_crossing with its defaults (201 points, 256 instants) under 0.2 s.
"""
from __future__ import annotations

import argparse
import time


def best(fn, repeats: int) -> float:
    fn()                                              # warm: imports, scipy's spline
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    import numpy as np

    from asperity.crawling.gait import CurvatureWave, FourierGait
    from asperity.crawling.gait_chain import JointTable, SerpenoidChain
    from asperity.crawling.gait_crossing import check_self_crossing
    rng = np.random.default_rng(0)
    gaits = {"curvature wave A=7 k=1": CurvatureWave(),
             "fourier, 4 terms": FourierGait([(1, 1, 7, 0), (2, 1, 0, 2), (0, 0, 1, 0),
                                              (3, -1, 1, 1)]),
             "serpenoid, 20 links": SerpenoidChain.from_wave(7, 1, 20),
             "joint table, 20 links x 64 rows": JointTable(rng.uniform(-0.3, 0.3, (64, 19)))}
    t = np.linspace(0.0, 1.0, 1000, endpoint=False)
    for name, g in gaits.items():
        kin = best(lambda g=g: g.kinematics(t, 201), a.repeats)
        cross = best(lambda g=g: check_self_crossing(g), a.repeats)
        print(f"{name:34s} kinematics 1000 x 201: {kin * 1e3:6.1f} ms   "
              f"check_self_crossing: {cross * 1e3:6.1f} ms")


if __name__ == "__main__":
    main()
