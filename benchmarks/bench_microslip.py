"""Microslip speed figures: the quasi-static strip (1e4 nodes x 1e3 cycles, every cycle
marched), the long-life answer of the shipped bushing over 1e6 cycles, and the dynamic
(Moreau) mode on a small strip.

Run as a script:  python benchmarks/bench_microslip.py [--nodes N] [--cycles C] [--repeats R]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path


def bench_long_life() -> dict:
    """Seconds for the verdict of surfaces/bushing-strip.toml over 1e6 cycles (stabilised
    cycle detected, drift extrapolated), compilation excluded."""
    from asperity.microslip.assembly import load_assembly
    from asperity.microslip.friction import resolve_friction
    from asperity.microslip.verdict import assess
    asm = load_assembly(Path(__file__).resolve().parents[1] / "surfaces" / "bushing-strip.toml")
    f = resolve_friction(asm)
    chain = asm.chain(f.mu_plus, f.mu_minus)
    assess(chain, asm.loading, 10)
    t0 = time.perf_counter()
    out = assess(chain, asm.loading, 1e6, 1e-4)
    return {"seconds": time.perf_counter() - t0, "cycles_marched": out["cycles_marched"],
            "drift_after_cycles_m": out["drift_after_cycles_m"], "verdict": out["verdict"]}


def bench_dynamic(n: int = 11, steps_per_segment: int = 80_000, cycles: int = 3) -> dict:
    """Moreau steps x nodes per second on a small strip."""
    from asperity.microslip.chains import elastic_limit, strip_chain
    from asperity.microslip.dynamic import simulate_dynamic
    from asperity.microslip.loading import Loading
    h, E, p, l, aT = 2e-3, 2e11, 1e6, 0.1, 1.2e-5
    chain = strip_chain(h, E, p, l, (3.54 / l) ** 2 * E * h, aT, n, 0.2, 0.1)
    L = Loading.cycles_between(0.0, 10 * elastic_limit(chain))
    simulate_dynamic(chain, L, 1, steps_per_segment=1000)
    t0 = time.perf_counter()
    r = simulate_dynamic(chain, L, cycles, steps_per_segment=steps_per_segment)
    dt = time.perf_counter() - t0
    return {"nodes": n, "steps": r.solver["steps"], "seconds": dt,
            "node_steps_per_second": n * r.solver["steps"] / dt,
            "max_prox_iterations": r.solver["max_iterations_used"]}


def main() -> None:
    from asperity.bench import bench_microslip, format_microslip
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, default=10_000)
    ap.add_argument("--cycles", type=int, default=1_000)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    print(format_microslip(bench_microslip(a.nodes, a.cycles, a.repeats)))
    ll = bench_long_life()
    print(f"long life, bushing-strip over 1e6 cycles: {ll['seconds'] * 1e3:.1f} ms "
          f"({ll['cycles_marched']} cycles marched), {ll['verdict']}, drift after 1e6 cycles "
          f"{ll['drift_after_cycles_m']:.4g} m")
    dy = bench_dynamic()
    print(f"dynamic (Moreau), strip of {dy['nodes']} nodes: {dy['steps']} steps in "
          f"{dy['seconds']:.2f} s, {dy['node_steps_per_second']:.3e} node-steps/s, "
          f"max prox iterations {dy['max_prox_iterations']}")


if __name__ == "__main__":
    main()
