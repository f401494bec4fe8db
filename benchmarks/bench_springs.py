"""Spring-tip updates per second of the elastic (finite k_f) spring kernel.

Run as a script to print the figure:  python benchmarks/bench_springs.py
"""
from __future__ import annotations

import math
import time


def bench_spring_updates(seconds: float = 2.0) -> dict:
    """Time repeated simulate_sliding calls (finite k_f, oblique sliding) for ~seconds.

    A warm-up call first, so compilation is excluded.  Returns a dict with
    ``updates_per_second`` (spring-tip updates: springs x steps), ``updates``, ``seconds``,
    ``calls`` and the setup used.
    """
    from asperity.texture.spring_model import SpringModel
    from asperity.texture.springs import simulate_sliding
    from asperity.texture.wedges import WedgeTexture

    tex = WedgeTexture(30, 10, 0.1, 0.2)
    model = SpringModel(k_f=1e5, steps_per_period=32000)
    psi = math.radians(30.0)
    simulate_sliding(tex, psi, model)  # warm-up / compile
    updates = 0
    calls = 0
    t0 = time.perf_counter()
    while True:
        r = simulate_sliding(tex, psi, model)
        updates += r.n_springs * r.n_steps
        calls += 1
        dt = time.perf_counter() - t0
        if dt >= seconds:
            break
    return {"updates_per_second": updates / dt, "updates": updates, "seconds": dt,
            "calls": calls, "setup": "WedgeTexture(30, 10, 0.1, 0.2), k_f/k_n = 100, psi = 30 deg"}


if __name__ == "__main__":
    out = bench_spring_updates()
    print(f"spring-tip updates per second: {out['updates_per_second']:.3e} "
          f"({out['updates']} updates in {out['seconds']:.2f} s, {out['setup']})")
