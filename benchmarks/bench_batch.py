"""Cases per second of the block solver ``assess_batch`` (issue 28, item 1) against the
per-case loop over ``assess_assembly``, serial, on two study blocks:

* two-node: surfaces/two-node-spec.toml with the scatter of surfaces/two-node-sobol.toml
  (dT_max in [90, 160] K, N in [80, 120] N, k_t lognormal about 5e5 N/m);
* strip: surfaces/bushing-strip.toml (201 nodes) with dT_max in [90, 140] K and mu+, mu-
  each within 5 % of 0.19.

Both with 1e6 cycles and a 1e-4 m tolerance.  The loop runs on the first ``--loop`` cases
of each block (its assemblies built before the clock starts) and its answers are compared
with the block's (verdicts and every stored number; displacements to 1e-12 of the case's
scale).  Compilation is excluded (one warm call first).

Run as a script:  python benchmarks/bench_batch.py [--two-node 10000] [--strip 2000]
                  [--loop 300] [--json]
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

SURF = Path(__file__).resolve().parents[1] / "surfaces"


def two_node_block(m: int, seed: int = 2) -> dict:
    rng = np.random.default_rng(seed)
    par = {"k": np.full(m, 1e6), "l0": np.full(m, 0.1), "alpha_T": np.full(m, 1.2e-5),
           "k_t": 5e5 * np.exp(0.3 * rng.standard_normal(m)), "N": rng.uniform(80, 120, m)}
    dT = np.column_stack([np.zeros(m), rng.uniform(90, 160, m), np.zeros(m)])
    return {"model": "two-node", "params": par, "mu_plus": np.full(m, 0.2),
            "mu_minus": np.full(m, 0.1), "dT": dT, "F": np.zeros((m, 3))}


def strip_block(m: int, seed: int = 3) -> dict:
    rng = np.random.default_rng(seed)
    base = {"h": 2.5e-3, "E": 1.1e11, "p": 5.0e6, "l": 0.04, "k_t": 1.0e13, "alpha_T": 6e-6}
    par = {k: np.full(m, v) for k, v in base.items()}
    par["n"] = 201
    dT = np.column_stack([np.zeros(m), rng.uniform(90, 140, m), np.zeros(m)])
    return {"model": "strip", "params": par, "mu_plus": 0.19 * rng.uniform(0.95, 1.05, m),
            "mu_minus": 0.19 * rng.uniform(0.95, 1.05, m), "dT": dT, "F": np.zeros((m, 3))}


def run_batch(b: dict, lo: int = 0, hi: int | None = None) -> dict:
    from asperity.microslip.batch import assess_batch
    sl = slice(lo, hi)
    par = {k: (v if np.ndim(v) == 0 else v[sl]) for k, v in b["params"].items()}
    m = b["mu_plus"][sl].size
    return assess_batch(b["model"], par, b["mu_plus"][sl], b["mu_minus"][sl], b["dT"][sl],
                        b["F"][sl], substeps=1, force_at="uniform", cycles=np.full(m, 1e6),
                        tolerance=np.full(m, 1e-4))


def assemblies(b: dict, m: int) -> list:
    from asperity.microslip.assembly import assembly_from_dict
    out = []
    for j in range(m):
        a = {"model": b["model"], **{k: (v if np.ndim(v) == 0 else float(v[j]))
                                     for k, v in b["params"].items()}}
        lo = {"history": [float(x) for x in b["dT"][j]],
              "force_history": [float(x) for x in b["F"][j]]}
        out.append(assembly_from_dict({"assembly": a, "loading": lo}, "bench.toml"))
    return out


def _same(x, y, scale) -> bool:
    if y is None:
        return x is None or not math.isfinite(x)
    return abs(x - y) <= 1e-12 * scale


def bench(b: dict, loop: int) -> dict:
    from asperity.microslip.friction import Friction
    from asperity.microslip.quasi_static import load_scale
    from asperity.microslip.risk import assess_assembly
    from asperity.microslip.verdict import VERDICTS
    m = b["mu_plus"].size
    run_batch(b, 0, 1)                                        # compile / load the cache
    t0 = time.perf_counter()
    out = run_batch(b)
    t_batch = time.perf_counter() - t0
    k = min(loop, m)
    asms = assemblies(b, k)
    fr = [Friction(float(b["mu_plus"][j]), float(b["mu_minus"][j]), "explicit")
          for j in range(k)]
    assess_assembly(asms[0], fr[0], cycles=1e6, tolerance=1e-4)
    t0 = time.perf_counter()
    refs = [assess_assembly(a, f, cycles=1e6, tolerance=1e-4) for a, f in zip(asms, fr)]
    t_loop = time.perf_counter() - t0
    differ = 0
    for j, r in enumerate(refs):
        s = load_scale(r["_chain"], asms[j].loading)
        same = (out["code"][j] != 2 and VERDICTS[out["verdict"][j]] == r["verdict"]
                and _same(out["drift_per_cycle"][j], r["drift_per_cycle_m"], s)
                and _same(out["drift_after_cycles"][j], r["drift_after_cycles_m"], s)
                and out["dT_c"][j] == r["dT_c_K"] and out["margin"][j] == r["margin"]
                and (None if np.isnan(out["cycles_to_tolerance"][j]) else
                     out["cycles_to_tolerance"][j]) == r["cycles_to_tolerance"]
                and (None if out["stabilised_at"][j] < 0 else out["stabilised_at"][j])
                == r["stabilised_at_cycle"])
        differ += not same
    verdicts = {v: int(np.sum(out["verdict"] == i)) for i, v in enumerate(VERDICTS)}
    return {"cases": m, "batch_seconds": t_batch, "batch_cases_per_second": m / t_batch,
            "loop_cases": k, "loop_seconds": t_loop, "loop_cases_per_second": k / t_loop,
            "speed_up": (m / t_batch) / (k / t_loop), "not_handled": int(np.sum(out["code"] == 2)),
            "loop_cases_differing": differ, "verdicts": verdicts}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--two-node", type=int, default=10_000, help="two-node cases (block)")
    ap.add_argument("--strip", type=int, default=2_000, help="201-node strip cases (block)")
    ap.add_argument("--loop", type=int, default=300, help="cases of the per-case loop")
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    a = ap.parse_args()
    res = {"two-node": bench(two_node_block(a.two_node), a.loop),
           "strip-201": bench(strip_block(a.strip), a.loop)}
    if a.json:
        print(json.dumps(res, indent=2))
        return
    for name, r in res.items():
        print(f"{name}: assess_batch {r['batch_cases_per_second']:.4g} cases/s "
              f"({r['cases']} cases in {r['batch_seconds']:.3g} s), per-case loop "
              f"{r['loop_cases_per_second']:.4g} cases/s ({r['loop_cases']} cases): "
              f"{r['speed_up']:.3g}x; not handled {r['not_handled']}, loop cases differing "
              f"{r['loop_cases_differing']}; verdicts {r['verdicts']}")


if __name__ == "__main__":
    main()
