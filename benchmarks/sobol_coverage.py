"""Why a Sobol study needs a base sample N of at least 64 (issue 18): how often the 95 %
bootstrap intervals of the study's Sobol path (its Saltelli sample, SALib's indices)
cover the exact indices, over seeded designs, for three functions of 3 inputs:

* linear  f = x1 + 2 x2 + 3 x3 on [-1, 1]^3: S1 = ST = a_i^2 / sum a^2;
* Ishigami f = sin x1 + 7 sin^2 x2 + 0.1 x3^4 sin x1 on [-pi, pi]^3 (closed form);
* ramp    f = max(0, 3 x1 - 1 - x2) (1 + 0.2 x3) on [0, 1]^3, shaped like the two-node drift
  above its threshold (reference: N = 2^17).

Columns: coverage of S1 and ST (share of intervals holding the exact index), share of
intervals that lie wholly outside [0, 1], share of zero-width intervals (a collapsed
bootstrap), median ST half-width.

    python benchmarks/sobol_coverage.py [--seeds 200] [--json]
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # this checkout's asperity


def _functions():
    a = np.array([1.0, 2.0, 3.0])
    lin = a * a / np.sum(a * a)
    A, B = 7.0, 0.1
    V = A * A / 8 + B * math.pi ** 4 / 5 + B * B * math.pi ** 8 / 18 + 0.5
    V1 = 0.5 * (1 + B * math.pi ** 4 / 5) ** 2
    V13 = B * B * math.pi ** 8 * (1 / 18 - 1 / 50)

    def ishigami(U):
        X = (2 * U - 1) * math.pi
        return np.sin(X[:, 0]) + A * np.sin(X[:, 1]) ** 2 + B * X[:, 2] ** 4 * np.sin(X[:, 0])

    def ramp(U):
        return np.maximum(0.0, 3 * U[:, 0] - 1 - U[:, 1]) * (1 + 0.2 * U[:, 2])
    return {"linear": (lambda U: (2 * U - 1) @ a, lin, lin),
            "ishigami": (ishigami, np.array([V1 / V, A * A / 8 / V, 0.0]),
                         np.array([(V1 + V13) / V, A * A / 8 / V, V13 / V])),
            "ramp": (ramp, None, None)}


def coverage(seeds: int = 200, bases=(1, 2, 4, 8, 16, 32, 64, 128, 256)) -> list[dict]:
    from asperity.study.influence import sobol_indices
    from asperity.study.sampling import saltelli_unit
    names = ["x1", "x2", "x3"]
    out = []
    for fname, (f, S1, ST) in _functions().items():
        if S1 is None:          # reference indices from a large design
            ref = sobol_indices(f(saltelli_unit(3, 2 ** 17, 99)), names, 1)
            S1 = np.array([ref[n]["S1"] for n in names])
            ST = np.array([ref[n]["ST"] for n in names])
        for N in bases:
            hit = {"S1": 0, "ST": 0}
            outside = zero = total = 0
            widths = []
            for seed in range(1, seeds + 1):
                si = sobol_indices(f(saltelli_unit(3, N, seed)), names, seed)
                for j, n in enumerate(names):
                    for k, exact in (("S1", S1[j]), ("ST", ST[j])):
                        e, c = si[n][k], si[n][f"{k}_conf"]
                        hit[k] += abs(e - exact) <= c
                        outside += (e + c < 0) or (e - c > 1)
                        zero += not (math.isfinite(c) and c > 1e-9)
                    widths.append(si[n]["ST_conf"])
                    total += 1
            out.append({"function": fname, "N": N, "S1": hit["S1"] / total,
                        "ST": hit["ST"] / total, "outside": outside / (2 * total),
                        "zero_width": zero / (2 * total),
                        "ST_half_width": float(np.median(widths))})
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=200)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rows = coverage(a.seeds)
    if a.json:
        print(json.dumps(rows, indent=2))
        return
    print("| function | N | S1 covered | ST covered | outside [0, 1] | zero width | "
          "ST half-width |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['function']} | {r['N']} | {r['S1']:.2f} | {r['ST']:.2f} | "
              f"{r['outside']:.3f} | {r['zero_width']:.2f} | {r['ST_half_width']:.3f} |")


if __name__ == "__main__":
    main()
