"""Benchmark of the study engine (``asperity bench --only study``): cases per second of a
serial in-process loop against the engine on a LocalCluster, for three case costs.

* two-node risk (SPEC two-node assembly, dT_max varied): sub-millisecond cases, where
  batching decides everything;
* 201-node strip risk (the shipped bushing, texture and temperature varied);
* derive of a 256 x 256 scan (a library of random-walk height maps, 72 directions).

Scheduling overhead: the share of the workers' time not spent in cases,
1 - sum(case seconds) / (workers x wall time of the batch loop).
"""
from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def _studies(tmp: Path, n_two: int, n_strip: int, n_scans: int) -> dict[str, Path]:
    surf = ROOT / "surfaces"
    out = {}
    out["two-node risk"] = tmp / "two-node.toml"
    out["two-node risk"].write_text(f"""
[study]
kind = "monte-carlo"
samples = {n_two}
seed = 1
assembly = "{surf / 'two-node-spec.toml'}"
[parameters]
"loading.dT_max" = {{ distribution = "uniform", low = 50.0, high = 150.0 }}
""")
    out["201-node strip risk"] = tmp / "strip.toml"
    out["201-node strip risk"].write_text(f"""
[study]
kind = "monte-carlo"
samples = {n_strip}
seed = 1
texture = "{surf / 'wedge-asymmetric.toml'}"
assembly = "{surf / 'bushing-strip.toml'}"
[parameters]
"texture.alpha_deg" = {{ distribution = "normal", mean = 30.0, sd = 1.5 }}
"loading.dT_max" = {{ distribution = "uniform", low = 90.0, high = 140.0 }}
""")
    rng = np.random.default_rng(0)
    for i in range(n_scans):
        z = np.cumsum(rng.normal(size=(256, 256)), axis=1) * 0.02
        z = z + np.cumsum(rng.normal(size=(256, 256)), axis=0) * 0.01
        np.save(tmp / f"scan{i:03d}.npy", z.astype(np.float32))
    out["derive of a 256^2 scan"] = tmp / "scans.toml"
    out["derive of a 256^2 scan"].write_text("""
[study]
kind = "files"
files = ["scan*.npy"]
unit = "um"
pixel_size = 1.0
mu = 0.1
stages = ["derive"]
""")
    return out


def _serial(study, limit_seconds: float) -> tuple[float, int]:
    """Cases per second of a plain loop over the single-case API (no engine, no store), on
    one core (numba's parallel kernels limited to one thread, as in each worker)."""
    import numba
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        return _loop(study, limit_seconds)
    finally:
        numba.set_num_threads(threads)


def _loop(study, limit_seconds: float) -> tuple[float, int]:
    from .cases import run_case
    X = study.matrix()
    names = study.parameter_names
    run_case(study.spec, dict(zip(names, map(float, X[0]))) if names else {},
             study.case_files[0] if study.kind == "files" else None)     # warm the caches
    n, t0 = 0, time.perf_counter()
    while n < study.n_cases and time.perf_counter() - t0 < limit_seconds:
        values = dict(zip(names, map(float, X[n]))) if names else {}
        status, msg, _, _ = run_case(study.spec, values,
                                     study.case_files[n] if study.kind == "files" else None)
        if status != "ok":
            raise RuntimeError(f"benchmark case {n} failed: {msg}")
        n += 1
    return n / (time.perf_counter() - t0), n


def bench_study(workers: int = 2, n_two: int = 200_000, n_strip: int = 40_000,
                n_scans: int = 400, serial_seconds: float = 3.0) -> dict:
    """{case kind: serial cases/s, engine cases/s, speed-up, overhead, ...}."""
    from .engine import run_study
    from .spec import load_study
    from .store import open_store
    out = {"workers": workers, "cases": {}}
    with tempfile.TemporaryDirectory(prefix="asperity-bench-") as tmp:
        tmp = Path(tmp)
        for label, path in _studies(tmp, n_two, n_strip, n_scans).items():
            study = load_study(path)
            serial, n_serial = _serial(study, serial_seconds)
            store = open_store(tmp / f"{path.stem}-store", study)
            try:
                rep = run_study(study, store, workers=workers)
                case_seconds = float(np.nansum(store.column("seconds")))
                counts = store.count()
            finally:
                store.close()
            if counts.get("ok", 0) != study.n_cases:
                raise RuntimeError(f"{label}: {counts} of {study.n_cases} cases")
            loop = rep.seconds - rep.startup_seconds - rep.shutdown_seconds
            rate = rep.ran / loop
            out["cases"][label] = {
                "cases": study.n_cases, "serial_cases_per_s": serial,
                "serial_ms_per_case": 1e3 / serial, "serial_cases_timed": n_serial,
                "engine_cases_per_s": rate, "speedup": rate / serial,
                "startup_s": rep.startup_seconds, "shutdown_s": rep.shutdown_seconds,
                "loop_s": loop,
                "overhead": 1.0 - case_seconds / (rep.workers * loop),
                "where": rep.where}
    return out


def format_study(out: dict) -> str:
    lines = [f"study engine, serial in-process loop (one core) vs {out['workers']} local "
             "workers (LocalCluster; start-up, worker warm-up and shut-down excluded):"]
    for label, r in out["cases"].items():
        lines.append(f"  {label:<24} {r['cases']:>7} cases: serial {r['serial_cases_per_s']:9.4g} "
                     f"cases/s ({r['serial_ms_per_case']:.3g} ms), engine "
                     f"{r['engine_cases_per_s']:9.4g} cases/s = x{r['speedup']:.2f}, "
                     f"scheduling overhead {100 * r['overhead']:.1f} %, start-up "
                     f"{r['startup_s']:.1f} s")
    lines.append("  a 1e6-case study: " + "; ".join(
        f"{label} {1e6 / r['engine_cases_per_s'] / 60:.3g} min here, "
        f"{1e6 * r['serial_ms_per_case'] / 1e3 / 100 / 0.9 / 60:.3g} min on 100 workers"
        for label, r in out["cases"].items()) + " (100 workers: serial cost / 100 at 90 % "
        "efficiency)")
    return "\n".join(lines)
