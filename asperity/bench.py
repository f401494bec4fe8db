"""Benchmarks: closed-form reservoir evaluations and spring-tip updates per second.

Timings exclude numba compilation (a warm-up call runs first).  Figures depend on the
machine; they are printed, never asserted in unit tests.
"""
from __future__ import annotations

import math
import time

import numpy as np


def _rate(fn, work: int, seconds: float) -> tuple[float, int]:
    fn()  # warm-up (compilation, caches)
    done, t0 = 0, time.perf_counter()
    while True:
        fn()
        done += work
        dt = time.perf_counter() - t0
        if dt >= seconds:
            return done / dt, done


def bench_closed_form(seconds: float = 1.0, n_directions: int = 1_000_000) -> dict:
    """Wedge reservoir points p(psi) per second (vectorised over directions)."""
    from .closed_form import compute_reservoir
    from .texture import WedgeTexture
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    psi = np.linspace(0.0, 2 * np.pi, n_directions, endpoint=False)
    out = {}
    for contact in ("all-faces", "windward"):
        rate, n = _rate(lambda: compute_reservoir(tex, psi, contact), n_directions, seconds)
        out[contact] = {"evaluations_per_second": rate, "evaluations": n}
    return out


def bench_springs(seconds: float = 2.0) -> dict:
    """Spring-tip updates (springs x steps) per second, rigid and elastic springs."""
    from .springs import SpringModel, simulate_sliding
    from .texture import WedgeTexture
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    psi = math.radians(30.0)
    out = {}
    for name, model in (("rigid (k_f = inf)", SpringModel(steps_per_period=32000)),
                        ("elastic (k_f/k_n = 100)", SpringModel(k_f=1e5, steps_per_period=32000))):
        r = simulate_sliding(tex, psi, model)
        work = r.n_springs * r.n_steps
        rate, n = _rate(lambda: simulate_sliding(tex, psi, model), work, seconds)
        out[name] = {"updates_per_second": rate, "updates": n, "springs": r.n_springs,
                     "steps": r.n_steps}
    return out


def run(seconds: float = 1.0) -> dict:
    return {"closed_form": bench_closed_form(seconds), "springs": bench_springs(seconds)}
