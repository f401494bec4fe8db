"""Benchmark of the contact solver (``asperity bench --only contact``, issue 19): time,
iterations and peak memory of :func:`solve_contact` against two peers measured in the same
run, ContactMechanics' constrained conjugate gradient and a plain NumPy / scipy.fft
Polonsky-Keer (``benchmarks/plain_contact.py``).

Problem (the issue's): a random self-affine map (Hurst 0.8, rms slope 0.1, pixel 1 um),
E* = 100 GPa, p / E* = 0.0025, relative tolerance 1e-8; periodic n x n, free n x n, a
load curve of 8 pressures (p / E* from 0.00125 to 0.005, geometric; each solve starts from
the previous pressure) in units of the cold single solve, and with ``big`` a free
4096 x 4096 solve of asperity alone (memory per pixel).

Each solver runs in a child process of its own: imports and a warm-up solve on a 64 x 64
map first (compilation, FFT plans), then the peak resident memory is reset (Linux
``/proc/self/clear_refs``), the map is loaded and solved; ``bytes_per_pixel`` is the
child's peak resident memory over its resident memory before loading the map, per pixel
(the map, the solver's work arrays and its result).  The peers' children run
``benchmarks/bench_contact.py`` of the repository: the package never imports
ContactMechanics.  Figures depend on the machine and on its load (reported); they are
printed, never asserted in unit tests.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
PEERS_SCRIPT = ROOT / "benchmarks" / "bench_contact.py"
PEERS = ("contactmechanics", "plain")
E_STAR = 1e11
PIXEL = 1e-6
LOAD = 0.0025
CURVE = tuple(float(f) for f in np.geomspace(LOAD / 2, LOAD * 2, 8))
TOL = 1e-8
BIG = 4096
#: peak memory a pixel of the hungriest solver on a free map (ContactMechanics, measured
#: 370 at 128^2), with a margin
PEER_BYTES_PER_PIXEL = 450.0
#: the issue's targets: speed-ups (at least), bytes per pixel and curve cost (at most)
TARGETS = {"speedup_vs_contactmechanics": 2.0, "speedup_vs_plain": 1.0,
           "bytes_per_pixel_periodic": 120.0, "bytes_per_pixel_free": 400.0,
           "curve_in_single_solves": 3.0}


def self_affine(nx, ny=None, hurst=0.8, rms_slope=0.1, dx=1.0, dy=None, seed=0):
    """(nx, ny) periodic random height map (m when dx is): power spectrum C(q) ~
    q^-2(1+H) with random phases, zero mean, scaled to the given rms slope (periodic
    forward differences, sqrt(mean(dz/dx^2 + dz/dy^2)))."""
    ny = nx if ny is None else ny
    dy = dx if dy is None else dy
    rng = np.random.default_rng(seed)
    q = np.hypot(np.fft.fftfreq(nx, dx)[:, None], np.fft.rfftfreq(ny, dy)[None, :])
    q[0, 0] = np.inf
    spec = np.fft.rfft2(rng.standard_normal((nx, ny))) * q ** (-(1.0 + hurst))
    del q
    z = np.fft.irfft2(spec, s=(nx, ny))
    del spec
    z -= z.mean()
    gx = (np.roll(z, -1, 0) - z) / dx
    gy = (np.roll(z, -1, 1) - z) / dy
    return z * (rms_slope / np.sqrt(np.mean(gx * gx + gy * gy)))


# ---- the child: one solver, one case ---------------------------------------------------

def _proc_status() -> dict:
    out = {}
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(("VmRSS", "VmHWM")):
                key, value = line.split(":")
                out[key] = int(value.split()[0]) * 1024
    return out


def _reset_peak() -> bool:
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def asperity_solver(h, dx, E, p, boundary, tol, initial):
    """(pressure, iterations) of :func:`solve_contact`."""
    from . import solve_contact
    r = solve_contact(h, dx, E, p, boundary=boundary, tol=tol, initial=initial)
    return r.pressure, r.iterations


def asperity_curve(h, dx, E, pressures, boundary, tol):
    """(pressure, iterations) at each of ``pressures`` in turn, from
    :func:`iter_load_curve` (one half-space, each solve from the previous solution)."""
    from .curve import iter_load_curve
    for r in iter_load_curve(h, dx, E, pressures, boundary=boundary, tol=tol):
        yield r.pressure, r.iterations


def run_case(solve, spec: dict, curve=None) -> dict:
    """Warm up, reset the peak memory, load the map and solve ``spec["pressures"]`` in
    turn (each from the previous pressure: with ``curve``, a generator of (pressure,
    iterations) over the pressures, the solver's own load curve); seconds, iterations and
    memory."""
    warm = self_affine(64, dx=PIXEL, seed=9)
    solve(warm, PIXEL, E_STAR, LOAD * E_STAR, spec["boundary"], spec["tol"], None)
    del warm
    reset = _reset_peak()
    rss0 = _proc_status()["VmRSS"]
    h = np.load(spec["map"])
    seconds, iterations, prev = [], [], None
    if curve is not None and len(spec["pressures"]) > 1:
        t0 = time.perf_counter()
        for prev, it in curve(h, PIXEL, E_STAR, [f * E_STAR for f in spec["pressures"]],
                              spec["boundary"], spec["tol"]):
            seconds.append(time.perf_counter() - t0)
            iterations.append(int(it))
            t0 = time.perf_counter()
    else:
        for f in spec["pressures"]:
            t0 = time.perf_counter()
            prev, it = solve(h, PIXEL, E_STAR, f * E_STAR, spec["boundary"], spec["tol"],
                             prev)
            seconds.append(time.perf_counter() - t0)
            iterations.append(int(it))
    peak = _proc_status()["VmHWM"] - rss0
    np.save(spec["out"], np.asarray(prev, float))
    return {"seconds": float(sum(seconds)), "seconds_each": seconds,
            "iterations": int(sum(iterations)), "iterations_each": iterations,
            "peak_bytes": int(peak), "bytes_per_pixel": peak / h.size,
            "peak_reset": reset, "pixels": int(h.size)}


def worker_main(argv, solvers: dict, curves: dict | None = None) -> int:
    """``--worker NAME --spec JSON``: run one case, print its figures as one JSON line
    (``curves``: the solvers' own load curves, by name, where they have one)."""
    from ..lifeline import die_with_parent
    die_with_parent()
    name, spec = argv[argv.index("--worker") + 1], json.loads(argv[argv.index("--spec") + 1])
    print(json.dumps(run_case(solvers[name], spec, (curves or {}).get(name))))
    return 0


# ---- the parent ------------------------------------------------------------------------

def _child(solver: str, spec: dict) -> dict:
    from ..lifeline import preexec
    if solver == "asperity":
        argv = [sys.executable, "-m", "asperity.contact.bench"]
    elif PEERS_SCRIPT.is_file():
        argv = [sys.executable, str(PEERS_SCRIPT)]
    else:
        return {"error": f"{PEERS_SCRIPT} not found (the peers run from a repository "
                         f"checkout)"}
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    r = subprocess.run(argv + ["--worker", solver, "--spec", json.dumps(spec)],
                       capture_output=True, text=True, env=env, preexec_fn=preexec())
    if r.returncode != 0:
        lines = r.stderr.strip().splitlines()
        return {"error": lines[-1] if lines else f"exit status {r.returncode}"}
    return json.loads(r.stdout.strip().splitlines()[-1])


def _rel_l2(a, b) -> float:
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def bench_contact(n: int = 1024, free_n: int = 1024, big: bool = False,
                  peers=PEERS, repeats: int = 1, curve: bool = True) -> dict:
    """Every solver on every case, best of ``repeats`` (interleaved: each round runs every
    solver once, so a change of the machine's load touches all of them)."""
    from ..progress import report
    from ..resources import check_memory, cpu_cores
    # the peers take up to ~370 bytes a pixel free (measured), asperity's target is 400
    check_memory(PEER_BYTES_PER_PIXEL * max(n, free_n) ** 2,
                 f"the contact benchmark on {max(n, free_n)} x {max(n, free_n)} maps",
                 "lower --contact-size")
    if big:
        check_memory(TARGETS["bytes_per_pixel_free"] * BIG * BIG + 8.0 * BIG * BIG,
                     f"the free {BIG} x {BIG} contact benchmark", "leave out --big")
    out = {"E_star_Pa": E_STAR, "pixel_m": PIXEL, "p_over_E_star": LOAD, "tol": TOL,
           "hurst": 0.8, "rms_slope": 0.1, "cores": cpu_cores(),
           "load_average": [list(os.getloadavg())], "curve_p_over_E_star": list(CURVE),
           "cases": {}, "targets": TARGETS}
    cases = [("periodic", "periodic", n, (LOAD,), ("asperity", *peers)),
             ("free", "free", free_n, (LOAD,), ("asperity", *peers))]
    if curve:
        cases.append(("periodic curve", "periodic", n, CURVE, ("asperity", *peers)))
    if big:
        cases.append((f"free {BIG}", "free", BIG, (LOAD,), ("asperity",)))
    with tempfile.TemporaryDirectory(prefix="asperity-bench-contact-") as tmp:
        maps = {}
        for size in sorted({c[2] for c in cases}):
            maps[size] = str(Path(tmp) / f"map-{size}.npy")
            np.save(maps[size], self_affine(size, dx=PIXEL, seed=1))
        todo = [(c, s) for c in cases for s in c[4]]
        for k, ((key, boundary, size, pressures, _), solver) in enumerate(todo):
            report(k / len(todo), f"contact benchmark: {key}, {solver}")
            spec = {"map": maps[size], "boundary": boundary, "pressures": list(pressures),
                    "tol": TOL, "out": str(Path(tmp) / f"{key}-{solver}.npy")}
            runs = [_child(solver, spec) for _ in range(repeats)]
            good = [r for r in runs if "error" not in r]
            row = min(good, key=lambda r: r["seconds"]) if good else runs[0]
            row["runs_seconds"] = [r["seconds"] for r in good]
            entry = out["cases"].setdefault(key, {"boundary": boundary, "n": size,
                                                  "pressures": len(pressures)})
            entry[solver] = row
        for key, entry in out["cases"].items():
            ref = Path(tmp) / f"{key}-asperity.npy"
            for s in peers:
                other = Path(tmp) / f"{key}-{s}.npy"
                if ref.is_file() and other.is_file() and "error" not in entry.get(s, {}):
                    entry[s]["rel_l2_vs_asperity"] = _rel_l2(np.load(ref), np.load(other))
    out["load_average"].append(list(os.getloadavg()))
    out["verdict"] = verdict(out)
    return out


def verdict(out: dict) -> dict:
    """The issue's targets, each met or not (None: not measured)."""
    c = out["cases"]

    def t(case, solver):
        r = c.get(case, {}).get(solver, {})
        return r.get("seconds")

    def ratio(a, b):
        return None if a is None or b is None else b / a
    v = {}
    for peer, key in (("contactmechanics", "speedup_vs_contactmechanics"),
                      ("plain", "speedup_vs_plain")):
        for case in ("periodic", "free"):
            s = ratio(t(case, "asperity"), t(case, peer))
            v[f"{case} {key}"] = {"value": s, "target": TARGETS[key],
                                  "met": None if s is None else s >= TARGETS[key]}
    for case, key in (("periodic", "bytes_per_pixel_periodic"), ("free", "bytes_per_pixel_free"),
                      (f"free {BIG}", "bytes_per_pixel_free")):
        b = c.get(case, {}).get("asperity", {}).get("bytes_per_pixel")
        v[f"{case} bytes_per_pixel"] = {"value": b, "target": TARGETS[key],
                                        "met": None if b is None else b <= TARGETS[key]}
    cost = ratio(t("periodic", "asperity"), t("periodic curve", "asperity"))
    v["load curve in single solves"] = {"value": cost, "target": TARGETS[
        "curve_in_single_solves"], "met": None if cost is None else
        cost <= TARGETS["curve_in_single_solves"]}
    return v


def format_contact(out: dict) -> str:
    """Human-readable lines of :func:`bench_contact`."""
    lines = [f"contact: self-affine (H 0.8, rms slope 0.1), p/E* = {LOAD}, tol {TOL:g}, "
             f"{out['cores']} cores, load average {out['load_average'][0][0]:.1f} -> "
             f"{out['load_average'][-1][0]:.1f}"]
    for key, e in out["cases"].items():
        for s in ("asperity", *PEERS):
            if s not in e:
                continue
            r = e[s]
            head = f"contact, {key} {e['n']}^2 ({e['pressures']} p), {s:16s}:"
            if "error" in r:
                lines.append(f"{head} not run ({r['error']})")
                continue
            acc = (f", rel L2 vs asperity {r['rel_l2_vs_asperity']:.1e}"
                   if "rel_l2_vs_asperity" in r else "")
            lines.append(f"{head} {r['seconds']:8.2f} s, {r['iterations']:5d} iterations, "
                         f"{r['bytes_per_pixel']:6.1f} B/pixel{acc}")
    curve = out["cases"].get("periodic curve", {}).get("asperity", {})
    single = out["cases"].get("periodic", {}).get("asperity", {})
    if "iterations_each" in curve and "iterations" in single:
        lines.append(f"contact, periodic curve, asperity: iterations per pressure "
                     f"{curve['iterations_each']} against {single['iterations']} for the cold "
                     f"single solve (why: benchmarks/load_curve_bound.py)")
    for name, v in out["verdict"].items():
        if v["value"] is None:
            lines.append(f"target {name}: not measured")
        else:
            word = "met" if v["met"] else "NOT met"
            lines.append(f"target {name}: {v['value']:.2f} (target {v['target']:g}) {word}")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(worker_main(sys.argv[1:], {"asperity": asperity_solver},
                         {"asperity": asperity_curve}))
