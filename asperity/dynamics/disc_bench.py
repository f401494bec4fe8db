"""Steps per second of the body solver: a uniformly loaded disc sampled at N contact points
(:func:`asperity.bodies.footprint.disc`, its Gauss rings), sliding and spinning (issue 20
speed target: 256 points, >= 2e4 steps/s with the ellipse law, >= 1e4 with the star law, on
2 cores).  Called by ``benchmarks/bench_body_solver.py`` and by
``asperity bench --only body``."""
from __future__ import annotations

import time


from ..errors import check_choice, check_int, check_range

LAWS = ("ellipse", "star", "coulomb", "truncated-ellipse")


def _law(name: str):
    from ..laws import planar
    if name == "ellipse":
        return planar.ellipse_law(0.3, 0.2)
    if name == "star":
        return planar.star_law(0.3, 0.2)
    if name == "coulomb":
        return planar.coulomb_law(0.3)
    return planar.truncated_ellipse_law(0.2, 0.08, 0.12, 0.15)


def bench_disc(law_name: str, contact_points: int = 256, seconds: float = 1.0) -> dict:
    """Steps per second of a disc (R = 0.1 m, m = 1 kg) launched at (1, 0.3) m/s spinning at
    20 rad/s, integrated with dt = 1e-4 s until rest (about 7000 steps), repeated for
    ``seconds``; compilation excluded (one short warm-up run first).

    Returns dict(steps_per_second, steps, seconds, mean_iterations, contact_points, law)."""
    from ..bodies.footprint import disc
    from .body import simulate_body
    law_name = check_choice("law_name", law_name, LAWS)
    n = check_int("contact_points", contact_points, 1, 100_000)
    seconds = check_range("seconds", seconds, 0.01, 600.0, unit="s")
    law = _law(law_name)
    R = 0.1
    fp = disc(R, contact_points=n)
    pts, w = fp.points, fp.weights
    kw = dict(mass=1.0, inertia=0.5 * R * R, u0=(1.0, 0.3, 20.0), dt=1e-4, record_every=1000)
    simulate_body(pts, w, law, t_end=2e-3, **kw)                   # compile / load the cache
    steps = 0
    its = 0.0
    t0 = time.perf_counter()
    while True:
        r = simulate_body(pts, w, law, **kw)
        steps += r.steps
        its += r.mean_iterations * r.steps
        el = time.perf_counter() - t0
        if el >= seconds:
            break
    return dict(steps_per_second=steps / el, steps=steps, seconds=el,
                mean_iterations=its / max(steps, 1), contact_points=int(pts.shape[0]),
                law=law_name)
