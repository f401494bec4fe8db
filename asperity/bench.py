"""Benchmarks: closed-form reservoir evaluations, spring-tip updates and facet-directions
(streamed facet reservoir of a rough surface) per second.

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
    from .friction.faces import compute_reservoir
    from .texture.wedges import WedgeTexture
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    psi = np.linspace(0.0, 2 * np.pi, n_directions, endpoint=False)
    out = {}
    for contact in ("all-faces", "windward"):
        rate, n = _rate(lambda: compute_reservoir(tex, psi, contact), n_directions, seconds)
        out[contact] = {"evaluations_per_second": rate, "evaluations": n}
    return out


def bench_springs(seconds: float = 2.0) -> dict:
    """Spring-tip updates (springs x steps) per second, rigid and elastic springs."""
    from .texture.spring_model import SpringModel
    from .texture.springs import simulate_sliding
    from .texture.wedges import WedgeTexture
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


#: memory of the facet benchmark per grid point (bytes, measured peak with a margin): the
#: height map and its spectrum while it is made, then 2 facets x (gx, gy, weight, 1/|n|)
#: and the NumPy baseline's temporaries
BENCH_BYTES_PER_POINT = 112
#: largest facet-directions of the benchmark's numba and NumPy runs (~15 and ~5 min)
MAX_NUMBA_WORK = 1e12
MAX_NUMPY_WORK = 2e10


def rough_surface_facets(n_grid: int = 2048, rms_slope: float = 0.3, hurst: float = 0.8,
                         seed: int = 0):
    """(gx, gy, weight) of the 2 n_grid^2 triangles of a random periodic self-affine height
    map (unit grid spacing, two triangles per cell, gradients from the corner heights),
    scaled to the given rms facet slope.  Built in place: about 56 bytes per grid point."""
    rng = np.random.default_rng(seed)
    k = n_grid
    fy = np.fft.fftfreq(k)[:, None]
    fx = np.fft.rfftfreq(k)[None, :]
    kr = np.hypot(fx, fy)
    kr[0, 0] = 1.0
    spec = np.fft.rfft2(rng.standard_normal((k, k)))
    spec *= kr ** (-(1.0 + hurst))
    spec[0, 0] = 0.0
    del kr
    z = np.fft.irfft2(spec, s=(k, k))
    del spec
    n = k * k
    g = np.empty((2, 2 * n))
    # first half: z(x + 1, y) - z(x, y) and z(x, y + 1) - z(x, y) (periodic); the second
    # half, z(x+1, y+1) - z(x, y+1) and z(x+1, y+1) - z(x+1, y), is the first half one
    # row (column) on
    for row, axis in ((0, 1), (1, 0)):
        d = g[row, :n].reshape(k, k)
        if axis == 1:
            np.subtract(z[:, 1:], z[:, :-1], out=d[:, :-1])
            np.subtract(z[:, 0], z[:, -1], out=d[:, -1])
        else:
            np.subtract(z[1:, :], z[:-1, :], out=d[:-1, :])
            np.subtract(z[0, :], z[-1, :], out=d[-1, :])
        e = g[row, n:].reshape(k, k)
        if axis == 1:
            e[:-1], e[-1] = d[1:], d[0]
        else:
            e[:, :-1], e[:, -1] = d[:, 1:], d[:, 0]
    del z
    ms = 0.0
    for a, b in ((0, n), (n, 2 * n)):        # mean of gx^2 + gy^2 in two pieces
        ms += float(np.dot(g[0, a:b], g[0, a:b]) + np.dot(g[1, a:b], g[1, a:b]))
    g *= rms_slope / math.sqrt(ms / (2 * n))
    return g[0], g[1], np.full(2 * n, 0.5)


def check_facets_request(n_grid: int, n_directions: int, numpy_directions: int) -> None:
    """Refuse a facet benchmark that memory cannot hold or that would run for hours."""
    from .resources import check_memory, check_work
    check_memory(BENCH_BYTES_PER_POINT * float(n_grid) ** 2,
                 f"the facet benchmark on a {n_grid} x {n_grid} grid", "lower --facets")
    n = 2.0 * n_grid * n_grid
    check_work(2 * n * n_directions, MAX_NUMBA_WORK, "the facet benchmark (2 x facets x "
               "--directions)", "lower --directions or --facets")
    check_work(2 * n * min(numpy_directions, n_directions), MAX_NUMPY_WORK,
               "its NumPy baseline (2 x facets x --numpy-directions)",
               "lower --numpy-directions or --facets")


def bench_facets(n_grid: int = 2048, n_directions: int = 360, numpy_directions: int = 8,
                 mu: float = 0.2, rms_slope: float = 0.3, seed: int = 0) -> dict:
    """Facet-directions per second of the numba facet kernel and of the streamed NumPy
    version, both contact regimes, on the 2 n_grid^2 facets of a random rough surface.

    The numba figure times whole ``compute_facet_reservoir`` calls (validation and
    preparation included) over ``n_directions`` directions, after a warm-up run on a small
    input (compilation / cache load excluded); NumPy runs over ``numpy_directions`` of them
    (it is much slower) and is scaled per facet-direction.  ``max_rel_diff`` compares the
    two on those directions.
    """
    import numba

    from .friction.facet_reservoir import compute_facet_reservoir, numpy_facet_reservoir
    from .progress import report
    check_facets_request(n_grid, n_directions, numpy_directions)
    t0 = time.perf_counter()
    gx, gy, w = rough_surface_facets(n_grid, rms_slope, seed=seed)
    setup = time.perf_counter() - t0
    n = gx.shape[0]
    psi = np.linspace(0.0, 2 * np.pi, n_directions, endpoint=False)
    sub = psi[np.linspace(0, n_directions, max(1, min(numpy_directions, n_directions)),
                          endpoint=False).astype(int)]
    out = {"facets": n, "directions": n_directions, "numpy_directions": int(sub.size),
           "mu": mu, "rms_slope": rms_slope, "threads": numba.get_num_threads(),
           "surface_seconds": setup, "regimes": {}}
    for contact in ("all-faces", "windward"):
        compute_facet_reservoir(gx[:20000], gy[:20000], mu, w[:20000], psi[:4], contact)
        t0 = time.perf_counter()
        r = compute_facet_reservoir(gx, gy, mu, w, psi, contact,
                                    progress=lambda f, c=contact: report(f, f"numba, {c}"))
        t_nb = time.perf_counter() - t0
        t0 = time.perf_counter()
        r_np = numpy_facet_reservoir(gx, gy, mu, w, sub, contact,
                                     progress=lambda f, c=contact: report(f, f"NumPy, {c}"))
        t_np = time.perf_counter() - t0
        r_sub = compute_facet_reservoir(gx, gy, mu, w, sub, contact)
        ok = ~r_np.locked
        diff = np.abs(r_sub.p[ok] - r_np.p[ok]).max() / max(np.abs(r_np.p[ok]).max(), 1e-300) \
            if ok.any() else 0.0
        rate_nb = n * n_directions / t_nb
        rate_np = n * sub.size / t_np
        out["regimes"][contact] = {
            "numba": {"seconds": t_nb, "facet_directions_per_second": rate_nb},
            "numpy": {"seconds": t_np, "facet_directions_per_second": rate_np},
            "speedup": rate_nb / rate_np,
            "locked_directions": int(r.locked.sum()),
            "max_rel_diff": float(diff),
            "same_flags": bool(np.array_equal(r_sub.locked, r_np.locked)
                               and np.array_equal(r_sub.locked_face, r_np.locked_face)
                               and np.array_equal(r_sub.set_valued, r_np.set_valued)),
        }
    return out


def format_facets(out: dict) -> str:
    """Human-readable lines of :func:`bench_facets`."""
    lines = [f"facets: {out['facets']} ({out['threads']} threads), {out['directions']} "
             f"directions (NumPy: {out['numpy_directions']}), mu = {out['mu']}, "
             f"rms slope = {out['rms_slope']}"]
    for k, v in out["regimes"].items():
        lines.append(f"facets, {k:9s}: numba {v['numba']['facet_directions_per_second']:.3e}"
                     f" facet-directions/s ({v['numba']['seconds']:.2f} s), NumPy "
                     f"{v['numpy']['facet_directions_per_second']:.3e} "
                     f"({v['numpy']['seconds']:.2f} s), x{v['speedup']:.1f}; "
                     f"max rel diff {v['max_rel_diff']:.1e}")
    return "\n".join(lines)


def run(seconds: float = 1.0) -> dict:
    return {"closed_form": bench_closed_form(seconds), "springs": bench_springs(seconds)}


def bench_microslip(n_nodes: int = 10_000, cycles: int = 1_000, repeats: int = 3) -> dict:
    """Quasi-static microslip: a strip of ``n_nodes`` nodes (lam l = 3.54) through ``cycles``
    thermal cycles 0 -> 10 dT_c -> 0, every cycle marched (no stabilised-cycle shortcut);
    node-updates = nodes x load segments (two per cycle).  ``increments``: the default march
    (each segment in one certain increment); ``events``: every segment event by event
    (``tol.events_only``; a tenth of the nodes and cycles: it costs about nodes^2 per
    segment); ``force``: the force in phase with the temperature (segments marched event by
    event by the default march), on the same smaller strip.  Best and all of ``repeats``
    timings after a warm-up (compilation), and the best CPU time (the process's: the march
    runs on one core)."""
    from .microslip.chains import MicroslipTolerances, strip_chain
    from .microslip.closed_forms import strip_dT_c
    from .microslip.loading import Loading
    from .microslip.quasi_static import simulate
    h, E, p, l, aT = 2e-3, 2e11, 1e6, 0.1, 1.2e-5
    kt = (3.54 / l) ** 2 * E * h
    dT = 10 * strip_dT_c(h, E, p, l, kt, 0.2, 0.1, aT)
    L = Loading.cycles_between(0.0, dT)
    LF = Loading.cycles_between(0.0, dT, 0.0, 0.05 * p * l)
    events = MicroslipTolerances(events_only=True)
    small = max(2, n_nodes // 10), max(2, cycles // 10)
    for loads in (L, LF):
        simulate(strip_chain(h, E, p, l, kt, aT, 50, 0.2, 0.1), loads, 3, until_stable=False,
                 tol=events)
    out = {"nodes": n_nodes, "cycles": cycles}
    for key, n, c, loads, tol in (("increments", n_nodes, cycles, L, None),
                                  ("events", *small, L, events),
                                  ("force", *small, LF, None)):
        chain = strip_chain(h, E, p, l, kt, aT, n, 0.2, 0.1)
        times, cpu, r = [], [], None
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            r = simulate(chain, loads, c, until_stable=False,
                         **({"tol": tol} if tol is not None else {}))
            times.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
        best = min(times)
        out[key] = {"nodes": n, "cycles": c, "seconds": best, "all_seconds": times,
                    "cpu_seconds": min(cpu),
                    "node_updates_per_second": n * 2 * c / best,
                    "events_one_by_one": r.solver["events_one_by_one"],
                    "drift_per_cycle_m": r.drift_per_cycle}
    return out


def format_microslip(out: dict) -> str:
    """Human-readable lines of :func:`bench_microslip`."""
    what = {"increments": "thermal cycles, default march",
            "events": "thermal cycles, every segment event by event",
            "force": "force in phase, default march"}
    lines = []
    for key, label in what.items():
        v = out[key]
        lines.append(
            f"microslip, quasi-static strip ({label}): {v['nodes']} nodes x {v['cycles']} "
            f"cycles in {v['seconds']:.3g} s (runs: "
            f"{', '.join(f'{t:.3g}' for t in v['all_seconds'])} s), "
            f"{v['node_updates_per_second']:.3e} node-updates/s, {v['events_one_by_one']} "
            f"events one by one, drift {v['drift_per_cycle_m']:.6e} m/cycle; best CPU "
            f"{v['cpu_seconds']:.3g} s (on a busy machine the wall time runs longer)")
    return "\n".join(lines)


def bench_moreau(seconds: float = 1.0, steps: int = 1_000_000) -> dict:
    """Moreau time steps per second of one point mass sliding (never sticking: the costly
    phase) with each law, compilation excluded.  u0 = 1e4 m/s at 30 deg, dt = 1e-6 s, so the
    body slides through all ``steps`` steps; the velocity direction turns, so the star law's
    fixed-point iteration works at every step (mean iterations reported)."""
    from .dynamics.moreau import point_mass, simulate
    from .laws import planar as L
    cases = {"coulomb": L.coulomb_law(0.3), "ellipse": L.ellipse_law(0.6, 0.3),
             "truncated-ellipse": L.truncated_ellipse_law(0.2, 0.08, 0.12, 0.15),
             "collinear": L.collinear_law(mu1=0.6, mu2=0.3), "star": L.star_law(0.6, 0.3),
             "windward star (gauge fit)": L.windward_star_law()}
    dt = 1e-6
    u = 1e4 * np.array([math.cos(math.radians(30)), math.sin(math.radians(30))])
    out = {}
    for name, law in cases.items():
        body = point_mass(law)
        last = {}

        def run():
            last["r"] = simulate(body, u, dt=dt, t_end=steps * dt, record_every=steps)
        rate, n = _rate(run, steps, seconds)
        r = last["r"]
        out[name] = {"steps_per_second": rate, "steps": n,
                     "mean_iterations": r.mean_iterations,
                     "max_iterations_used": r.max_iterations_used, "status": r.status}
    # a whole slide to rest (u0 = 2 m/s at 45 deg, dt = 1e-6 s): direction turning, the stop
    for name in ("ellipse", "star", "windward star (gauge fit)"):
        body = point_mass(cases[name])
        v = 2.0 * np.array([math.sqrt(0.5), math.sqrt(0.5)])
        last = {}

        def run():
            last["r"] = simulate(body, v, dt=dt, t_end=2.0, record_every=10 ** 7,
                                 halt_at_rest=True)
        last["r"] = simulate(body, v, dt=dt, t_end=2.0, record_every=10 ** 7, halt_at_rest=True)
        rate, n = _rate(run, last["r"].steps, seconds)
        r = last["r"]
        out[f"{name}, slide to rest"] = {
            "steps_per_second": rate, "steps": n, "mean_iterations": r.mean_iterations,
            "max_iterations_used": r.max_iterations_used, "status": r.status}
    return out


def format_moreau(out: dict) -> str:
    """Human-readable lines of :func:`bench_moreau`."""
    return "\n".join(f"moreau, {k:38s}: {v['steps_per_second']:.3e} steps/s "
                     f"(mean {v['mean_iterations']:.2f} iterations/step, max "
                     f"{v['max_iterations_used']}, {v['status']})" for k, v in out.items())


def bench_big_scan(sizes=(2048, 4096, 8192), directions: int = 360, repeats: int = 1,
                   folder=None) -> dict:
    """Time and peak memory of ``asperity derive`` in tiles on n x n float32 maps on disk,
    against the facet kernel in memory (:mod:`asperity.friction.scan_bench`)."""
    from .friction.scan_bench import bench_big_scan as run
    return run(sizes, directions, repeats, folder)


def format_big_scan(out: dict) -> str:
    from .friction.scan_bench import format_big_scan as fmt
    return fmt(out)


def bench_contact(n: int = 1024, big: bool = False, repeats: int = 1) -> dict:
    """The elastic contact solve against ContactMechanics and a plain Polonsky-Keer
    (:mod:`asperity.contact.bench`)."""
    from .contact.bench import bench_contact as run
    return run(n, n, big, repeats=repeats)


def format_contact(out: dict) -> str:
    from .contact.bench import format_contact as fmt
    return fmt(out)
