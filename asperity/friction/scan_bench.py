"""Benchmark of scans derived in tiles (``asperity bench --only big-scan``): time and peak
memory of ``asperity derive`` on synthetic float32 ``.npy`` maps of growing size, against
the facet kernel in memory.

Each map is written to disk in row blocks (bounded memory), derived by a child process
(``asperity derive MAP --unit um --pixel-size 1 --mu 0.2 --directions D --json`` in tiles
of the default size, also below the automatic threshold) that reports its own peak
resident memory (VmHWM), then deleted.
The facet-directions of a tiled run are its facets x 3 D (the sweep evaluates psi and
psi +- h for dT/dpsi); their rate over the whole run (reading, passes, everything) is
compared with the numba kernel's rate on the facets of a 2048 x 2048 map in memory.
"""
from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

#: the child reports its own peak RSS (VmHWM) on its last stderr line
_PEAK = ("import sys\nfrom asperity.cli.main import main\ncode = main(sys.argv[1:])\n"
         "hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')][0]\n"
         "print('VmHWM', int(hwm.split()[1]) * 1024, file=sys.stderr)\nsys.exit(code)\n")
#: rows of a map written at once
_BLOCK_BYTES = 64 << 20


def _waves(n: int, seed: int, rms_slope: float):
    """The rows of an n x n synthetic map (um): 24 random plane waves (wavelengths 8 to n
    pixels, rms slope about ``rms_slope``) and white noise; ``rows(a, b)`` -> (b-a, n)."""
    rng = np.random.default_rng(seed)
    k = 24
    lam = np.exp(rng.uniform(math.log(8), math.log(max(n, 16)), k))
    ang = rng.uniform(0, 2 * math.pi, k)
    kx, ky = 2 * math.pi / lam * np.cos(ang), 2 * math.pi / lam * np.sin(ang)
    amp = lam * rms_slope * math.sqrt(2.0 / k) / (2 * math.pi)       # slope rms_slope in all
    phase = rng.uniform(0, 2 * math.pi, k)
    j = np.arange(n)
    cy, sy = np.cos(np.outer(ky, j)), np.sin(np.outer(ky, j))          # (k, n)

    def rows(a, b):
        arg = np.outer(np.arange(a, b), kx) + phase                    # (rows, k)
        z = (np.sin(arg) * amp) @ cy + (np.cos(arg) * amp) @ sy
        z += rng.normal(scale=0.02 * rms_slope, size=z.shape)
        return z
    return rows


def write_map(path: Path, n: int, seed: int = 0, rms_slope: float = 0.3) -> None:
    """An n x n float32 height map (um, :func:`_waves`) on disk, written in row blocks."""
    rows = _waves(n, seed, rms_slope)
    out = np.lib.format.open_memmap(path, mode="w+", dtype=np.float32, shape=(n, n))
    step = max(1, _BLOCK_BYTES // (8 * n))
    for a in range(0, n, step):
        b = min(n, a + step)
        out[a:b] = rows(a, b)
    out.flush()
    del out


def run_derive(path: Path, directions: int, *flags) -> dict:
    """seconds, peak RSS (bytes) and the JSON of one ``asperity derive`` child."""
    argv = [sys.executable, "-c", _PEAK, "derive", str(path), "--unit", "um", "--pixel-size",
            "1", "--mu", "0.2", "--directions", str(directions), "--json", *flags]
    from ..lifeline import preexec
    t0 = time.perf_counter()
    r = subprocess.run(argv, capture_output=True, text=True, preexec_fn=preexec())
    seconds = time.perf_counter() - t0
    if r.returncode != 0:
        from ..errors import AsperityError
        last = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else r.returncode
        raise AsperityError(f"the benchmark's derive of {path.name} failed: {last}")
    peak = int(r.stderr.strip().splitlines()[-1].split()[1])
    return {"seconds": seconds, "peak_rss_bytes": peak, "result": json.loads(r.stdout)}


def kernel_rate(directions: int = 360) -> float:
    """Facet-directions per second of the facet kernel on the facets of a 2048 x 2048
    synthetic map held in memory (what ``derive`` runs on a map in memory)."""
    from ..surface.facets import heightmap_facets
    from ..surface.topography import HeightMap
    from .facet_reservoir import compute_facet_reservoir
    z = _waves(2048, 0, 0.3)(0, 2048).astype(np.float32).astype(np.float64) * 1e-6
    f = heightmap_facets(HeightMap(z, 1e-6, 1e-6, "synthetic"), mu=0.2, level_slope=True)
    gx, gy, w = f.gx, f.gy, f.weight
    del z
    psi = np.linspace(0, 2 * np.pi, directions, endpoint=False)
    compute_facet_reservoir(gx[:20000], gy[:20000], 0.2, w[:20000], psi[:4])
    took = []
    for _ in range(3):                       # the median of three (the machine is shared)
        t0 = time.perf_counter()
        compute_facet_reservoir(gx, gy, 0.2, w, psi)
        took.append(time.perf_counter() - t0)
    return gx.size * directions / float(np.median(took))


def check_disk(folder: Path, need: float) -> None:
    from ..errors import ResourceError
    from ..resources import format_bytes
    free = shutil.disk_usage(folder).free
    if need > 0.8 * free:
        raise ResourceError(f"the big-scan benchmark writes {format_bytes(need)} to {folder}, "
                            f"which has {format_bytes(free)} free; lower --scan-sizes or "
                            f"pass --scan-dir")


def bench_big_scan(sizes=(2048, 4096, 8192), directions: int = 360, repeats: int = 1,
                   folder=None, in_memory_upto: int = 4096) -> dict:
    """Time and peak RSS of derive on n x n float32 maps in tiles of the default size, and
    the same map held in memory (``--tile-rows 0``) up to ``in_memory_upto``."""
    from ..progress import report
    tmp = None
    if folder is None:
        tmp = tempfile.TemporaryDirectory(prefix="asperity-big-scan-")
        folder = tmp.name
    folder = Path(folder)
    out = {"directions": directions, "repeats": repeats, "kernel_rate": kernel_rate(directions),
           "sizes": []}
    try:
        for k, n in enumerate(sizes):
            check_disk(folder, 4.0 * n * n + 4096)
            path = folder / f"scan-{n}.npy"
            report(k / len(sizes), f"big scan {n} x {n}")
            t0 = time.perf_counter()
            write_map(path, n)
            row = {"n": n, "file_bytes": path.stat().st_size,
                   "write_seconds": time.perf_counter() - t0, "runs": [], "in_memory": None}
            try:
                from ..surface.readers._streams import open_lines
                from .tiled import default_tile_lines
                lines = default_tile_lines(open_lines(path, unit="um", pixel_size=1.0))
                for _ in range(repeats):
                    r = run_derive(path, directions, "--tile-rows", str(lines))
                    res = r.pop("result")
                    row["runs"].append(r)
                    row["facets"] = res["n_facets"]
                    row["tiling"] = res.get("tiling")
                    row["mu_a_plus"] = res["mu_a_plus"]
                if n <= in_memory_upto:
                    r = run_derive(path, directions, "--tile-rows", "0")
                    r["mu_a_plus"] = r.pop("result")["mu_a_plus"]
                    row["in_memory"] = r
            finally:
                path.unlink(missing_ok=True)
            secs = [r["seconds"] for r in row["runs"]]
            row["facet_directions_per_second"] = row["facets"] * 3 * directions / min(secs)
            row["of_kernel_rate"] = row["facet_directions_per_second"] / out["kernel_rate"]
            out["sizes"].append(row)
    finally:
        if tmp is not None:
            tmp.cleanup()
    return out


def format_big_scan(out: dict) -> str:
    """The table of :func:`bench_big_scan`."""
    gb = 1 << 30
    lines = [f"big scans, {out['directions']} directions, float32 .npy; facet kernel in memory: "
             f"{out['kernel_rate']:.3e} facet-directions/s",
             f"{'n':>6} {'tiles':>6} {'seconds (runs)':>24} {'peak RSS GB':>12} "
             f"{'fd/s':>10} {'of kernel':>9} {'in memory: s, GB':>18}"]
    for r in out["sizes"]:
        secs = ", ".join(f"{x['seconds']:.1f}" for x in r["runs"])
        rss = max(x["peak_rss_bytes"] for x in r["runs"]) / gb
        t = r.get("tiling") or {}
        mem = r["in_memory"]
        m = f"{mem['seconds']:.1f}, {mem['peak_rss_bytes'] / gb:.2f}" if mem else "-"
        lines.append(f"{r['n']:>6} {t.get('tiles', 1):>6} {secs:>24} {rss:>12.2f} "
                     f"{r['facet_directions_per_second']:>10.3e} {r['of_kernel_rate']:>9.2f} "
                     f"{m:>18}")
    return "\n".join(lines)
