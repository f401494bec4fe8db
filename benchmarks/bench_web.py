"""Load benchmark of ``asperity serve``: N concurrent clients each upload a 512 x 512 scan
and derive its friction on the Surface page, as a browser would (POST the form, follow to
the job, poll its status, fetch the result page).

    python benchmarks/bench_web.py [--clients 20] [--size 512] [--directions 360]
                                   [--workers N] [--json]

A server is started on 127.0.0.1 with a free port and a temporary data folder, warmed up
by one request (not timed), and stopped at the end; every request goes to that loopback
address.  Prints the latency from the form's POST to the result page (p50, p95, max), the
wall time, the jobs per second and the errors (a non-200 result, a failed job, a timeout).
A benchmark, not a test: nothing is asserted.
"""
from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

#: seconds a client waits for its result at most (a bounded loop)
TIMEOUT = 600.0


def write_scan(path: Path, n: int) -> None:
    """An n x n float32 height map (um): grooves at 30 deg over random roughness."""
    rng = np.random.default_rng(1)
    x, y = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    z = 0.5 * np.sin(2 * np.pi * (x * np.cos(0.5) + y * np.sin(0.5)) / 24.0)
    np.save(path, (z + 0.1 * rng.standard_normal((n, n))).astype(np.float32))


def start_server(folder: Path, workers: int | None) -> tuple[subprocess.Popen, str]:
    cmd = [sys.executable, "-m", "asperity", "serve", "--port", "0", "--data-dir", str(folder)]
    if workers:
        cmd += ["--workers", str(workers)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                            env={**os.environ, "PYTHONUNBUFFERED": "1"})
    line = proc.stdout.readline()
    if not line.startswith("asperity serve: http"):
        proc.kill()
        raise SystemExit(f"the server did not start: {line!r}")
    return proc, line.split(": ", 1)[1].strip().rstrip("/")


def one_client(base: str, scan: bytes, directions: int, out: list, i: int) -> None:
    import httpx
    t0 = time.perf_counter()
    rec = {"client": i, "ok": False, "error": None}
    try:
        with httpx.Client(base_url=base, timeout=TIMEOUT) as c:
            r = c.post("/surface", data={"source": "file", "unit": "um", "pixel_size": "0.5",
                                         "mu": "0.2", "directions": str(directions)},
                       files={"file": ("scan.npy", scan)})
            if r.status_code == 303:
                jid = r.headers["location"].rsplit("/", 1)[-1]
                while time.perf_counter() - t0 < TIMEOUT:
                    st = c.get(f"/api/jobs/{jid}").json()
                    if st["status"] not in ("queued", "running"):
                        break
                    time.sleep(0.1)
                r = c.get(f"/jobs/{jid}")
            rec["status"] = r.status_code
            rec["ok"] = r.status_code == 200 and 'id="mu_a_plus"' in r.text
            if not rec["ok"]:
                rec["error"] = f"HTTP {r.status_code}"
    except Exception as exc:                      # a benchmark reports, never stops
        rec["error"] = f"{type(exc).__name__}: {exc}"
    rec["seconds"] = time.perf_counter() - t0
    out[i] = rec


def run(clients: int, size: int, directions: int, workers: int | None) -> dict:
    with tempfile.TemporaryDirectory(prefix="bench-web-") as tmp:
        folder = Path(tmp)
        write_scan(folder / "scan.npy", size)
        scan = (folder / "scan.npy").read_bytes()
        proc, base = start_server(folder / "data", workers)
        try:
            warm = [None]
            t = time.perf_counter()
            one_client(base, scan, directions, warm, 0)
            warm_s = time.perf_counter() - t
            out: list = [None] * clients
            threads = [threading.Thread(target=one_client, args=(base, scan, directions, out, i))
                       for i in range(clients)]
            t0 = time.perf_counter()
            for th in threads:
                th.start()
            for th in threads:
                th.join(TIMEOUT + 60)
            wall = time.perf_counter() - t0
            jobs = [json.loads(p.read_text())
                    for p in (folder / "data" / "jobs").glob("*/job.json")]
        finally:
            proc.send_signal(signal.SIGINT)
            try:
                proc.wait(30)
            except subprocess.TimeoutExpired:
                proc.kill()
    lat = np.array([r["seconds"] for r in out if r is not None])
    work = np.array([j["seconds"] for j in jobs if j.get("seconds") is not None])
    return {"clients": clients, "size": size, "directions": directions,
            "server_workers": workers or os.cpu_count(), "scan_bytes": len(scan),
            "warm_up_s": warm_s, "warm_up_ok": bool(warm[0] and warm[0]["ok"]),
            "errors": [r["error"] for r in out if r is None or not r["ok"]],
            "latency_s": {"p50": float(np.percentile(lat, 50)),
                          "p95": float(np.percentile(lat, 95)),
                          "min": float(lat.min()), "max": float(lat.max())},
            "job_seconds_p50": float(np.median(work)) if work.size else None,
            "wall_s": wall, "jobs_per_s": clients / wall}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--clients", type=int, default=20)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--directions", type=int, default=360)
    p.add_argument("--workers", type=int, default=None, help="server worker processes")
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    r = run(a.clients, a.size, a.directions, a.workers)
    if a.json:
        print(json.dumps(r, indent=2))
        return
    lat = r["latency_s"]
    print(f"{r['clients']} concurrent clients, each uploading a {r['size']} x {r['size']} scan "
          f"({r['scan_bytes'] / 2**20:.1f} MB .npy) and deriving it ({r['directions']} "
          f"directions); server with {r['server_workers']} worker processes")
    print(f"  warm-up request: {r['warm_up_s']:.2f} s ({'ok' if r['warm_up_ok'] else 'FAILED'})")
    print(f"  latency POST -> result page: p50 {lat['p50']:.2f} s, p95 {lat['p95']:.2f} s "
          f"(min {lat['min']:.2f} s, max {lat['max']:.2f} s)")
    print(f"  one derive in its worker: {r['job_seconds_p50']:.2f} s (median); wall "
          f"{r['wall_s']:.2f} s, {r['jobs_per_s']:.2f} jobs/s")
    print(f"  errors: {len(r['errors'])}" + (f" ({r['errors'][:3]})" if r["errors"] else ""))


if __name__ == "__main__":
    main()
