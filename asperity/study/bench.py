"""Benchmark of the study engine (``asperity bench --only study``): cases per second of the
per-case API, of the engine in this process (one core) and on a LocalCluster, and the wall
time of a whole study (start, cases, store, summary), for three case costs.

* two-node risk (SPEC two-node assembly, dT_max varied, 1e6 cases): the closed form over
  blocks, where the store and the client decide;
* 201-node strip risk (the shipped bushing, texture and temperature varied): the exact
  block solver;
* derive of a 256 x 256 scan (a library of random-walk height maps, 72 directions).

Scheduling overhead: the share of the workers' time not spent in cases,
1 - sum(case seconds) / (workers x wall time of the batch loop).
"""
from __future__ import annotations

import contextlib
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


@contextlib.contextmanager
def _one_thread():
    """numba's kernels on one thread, as in each worker (restored after)."""
    import numba
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(threads)


def _serial(study, limit_seconds: float) -> tuple[float, int]:
    """Cases per second of a plain loop over the single-case API (no engine, no store), on
    one core."""
    with _one_thread():
        return _loop(study, limit_seconds)


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


def _in_process(study, tmp: Path, label: str) -> dict:
    """Cases per second of the engine in this process, on one core, the block path where
    it applies."""
    from .engine import run_study
    from .store import open_store
    store = open_store(tmp / f"{label}-serial", study)
    try:
        with _one_thread():
            rep = run_study(study, store, workers=0)
    finally:
        store.close()
    return {"cases": rep.ran, "cases_per_s": rep.ran / rep.seconds}


def bench_study(workers: int = 2, n_two: int = 1_000_000, n_strip: int = 40_000,
                n_scans: int = 400, serial_seconds: float = 3.0) -> dict:
    """{case kind: per-case, serial and engine cases/s, speed-up, overhead, path, the
    whole study's seconds, ...}.  Serial: the engine in this process on one core (the
    block path where it applies; a scan library: the per-case loop, its only path)."""
    from .engine import run_study
    from .spec import load_study
    from .store import open_store
    from .summary import summarise
    out = {"workers": workers, "cases": {}}
    with tempfile.TemporaryDirectory(prefix="asperity-bench-") as tmp:
        tmp = Path(tmp)
        for label, path in _studies(tmp, n_two, n_strip, n_scans).items():
            study = load_study(path)
            per_case, n_per_case = _serial(study, serial_seconds)
            serial = per_case if study.kind == "files" else \
                _in_process(study, tmp, path.stem)["cases_per_s"]
            t0 = time.perf_counter()
            store = open_store(tmp / f"{path.stem}-store", study)
            try:
                rep = run_study(study, store, workers=workers)
                summary = summarise(store)
                whole = time.perf_counter() - t0
                case_seconds = float(np.nansum(store.column("seconds")))
                counts = store.count()
            finally:
                store.close()
            if counts.get("ok", 0) != study.n_cases:
                raise RuntimeError(f"{label}: {counts} of {study.n_cases} cases")
            loop = rep.seconds - rep.startup_seconds - rep.shutdown_seconds
            rate = rep.ran / loop
            out["cases"][label] = {
                "cases": study.n_cases, "per_case_cases_per_s": per_case,
                "per_case_ms": 1e3 / per_case, "per_case_timed": n_per_case,
                "serial_cases_per_s": serial, "engine_cases_per_s": rate,
                "speedup": rate / serial, "startup_s": rep.startup_seconds,
                "shutdown_s": rep.shutdown_seconds, "loop_s": loop,
                "study_s": whole, "minutes_per_1e6_cases": 1e6 / rate / 60,
                "overhead": 1.0 - case_seconds / (rep.workers * loop),
                "solved_by": summary.get("solved_by") or {"exact": study.n_cases},
                "where": rep.where}
    return out


def format_study(out: dict) -> str:
    lines = [(f"study engine: serial = this process on one core (the block path where it "
             f"applies), engine = {out['workers']} local workers (LocalCluster; start-up, "
             "warm-up and shut-down excluded); a whole study = start, cases, store, summary:")]
    for label, r in out["cases"].items():
        by = ", ".join(f"{k} {v}" for k, v in r["solved_by"].items())
        lines.append(f"  {label:<24} {r['cases']:>8} cases: per case {r['per_case_ms']:.3g} "
                     f"ms; serial {r['serial_cases_per_s']:9.4g} cases/s, engine "
                     f"{r['engine_cases_per_s']:9.4g} cases/s = x{r['speedup']:.2f} "
                     f"(scheduling overhead {100 * r['overhead']:.1f} %); the whole study "
                     f"{r['study_s']:.1f} s (start-up {r['startup_s']:.1f} s); solved by: "
                     f"{by}")
    lines.append("  a 1e6-case study: " + "; ".join(
        f"{label} {r['minutes_per_1e6_cases']:.3g} min here"
        for label, r in out["cases"].items()))
    return "\n".join(lines)
