"""Scans in tiles (issue 13): ``derive_scan`` against ``derive(load_surface(...))`` on maps
that fit both (every detrend, both contact regimes, friction maps, rest levels, spikes,
undefined pixels on tile edges, tiles of one line and of the whole map, every format read
in lines), the same result on Dask workers, the spike filter, ``--max-slope`` accounting
against NumPy, the self-locking advice, the new flags' refusals, and memory that does not
grow with the scan."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from cli_run import run
from hostile import assert_refused, cli, interrupt
from x3p_files import x3p_bytes

from asperity.friction.derive import derive, to_json
from asperity.friction.diagnostics import SURFACE_DERIVATIVE_STEP
from asperity.friction.tiled import derive_scan
from asperity.surface.facets import load_surface
from asperity.surface.quality import find_spikes

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "surfaces"
NPY = {"unit": "um", "pixel_size": 1.0}


def rough(nx, ny, seed=0, slope=0.4):
    """A random self-affine height map (um) with a tilt and some form."""
    rng = np.random.default_rng(seed)
    k = np.hypot(np.fft.fftfreq(nx)[:, None], np.fft.fftfreq(ny)[None, :])
    k[0, 0] = 1.0
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.normal(size=(nx, ny))) * k ** -1.6))
    z *= slope / np.std(np.diff(z, axis=0))
    x, y = np.arange(nx)[:, None], np.arange(ny)[None, :]
    return z + 0.05 * x - 0.02 * y + 2e-3 * (x - nx / 2) ** 2


def close(a, b, path, rel=1e-12):
    """JSON objects equal: numbers to ``rel`` (with the tolerances noted), the rest exactly."""
    if isinstance(a, dict):
        a, b = ({k: v for k, v in x.items() if k != "tiling"} for x in (a, b))
        assert a.keys() == b.keys(), (path, set(a) ^ set(b))
        for k in a:
            close(a[k], b[k], f"{path}.{k}", rel)
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, f"{path}[{i}]", rel)
    elif isinstance(a, float) and isinstance(b, float):
        if path.endswith("max_abs_L_minus_dT_dpsi"):
            # dT/dpsi is a difference quotient of step h = 1e-3 of T ~ 0.1-1: sums taken in
            # another order change it by rounding / h
            tol = 1e-12 / SURFACE_DERIVATIVE_STEP
        elif path.endswith("principal_direction_deg"):
            tol = 1e-12 * 180
        else:
            tol = rel * max(abs(a), abs(b)) + 1e-15
        assert abs(a - b) <= tol, f"{path}: {a!r} != {b!r}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def same(path, kw, contact, n=16, tiles=(1, 5, None)):
    """The tiled result equals the in-memory one for every tile size in ``tiles``."""
    ref = to_json(derive(load_surface(path, **kw), contact, n_directions=n))
    out = []
    for t in tiles:
        d = derive_scan(path, **kw, contact=contact, n_directions=n,
                        tile_lines=10 ** 6 if t is None else t)
        got = to_json(d)
        close(ref, got, f"{Path(path).name} {kw} {contact} tiles of {t}")
        out.append(d)
    return ref, out


@pytest.fixture(scope="module")
def scans(tmp_path_factory):
    """The same map (37 x 29, undefined pixels on the edges of 5-line tiles) in every format
    read in lines, and friction maps."""
    d = tmp_path_factory.mktemp("scans")
    z = rough(37, 29, seed=3)
    for i, j in ((4, 3), (5, 3), (9, 10), (10, 0), (36, 28), (0, 7), (20, 14), (21, 15)):
        z[i, j] = np.nan                 # lines 4, 5, 9, 10: both sides of tile edges
    np.save(d / "c.npy", z)
    np.save(d / "f.npy", np.asfortranarray(z))
    np.savetxt(d / "s.txt", z.T, header="bare matrix, one line per y")
    valid = np.isfinite(z)
    valid[12, 6] = False
    zz = np.nan_to_num(z, nan=np.nan) * 1e-6
    (d / "s.x3p").write_bytes(x3p_bytes(zz, code="F", valid=valid))
    (d / "stored.x3p").write_bytes(x3p_bytes(zz, code="D", compress=False))
    mu = np.random.default_rng(4).uniform(0.05, 0.9, z.shape)
    np.save(d / "mu.npy", mu)
    np.savetxt(d / "mu.txt", mu.T)
    return d


DETRENDS = ["slope", "none", "mean", "plane", "poly2", "poly3"]


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
@pytest.mark.parametrize("detrend", DETRENDS)
def test_every_detrend_in_tiles_as_in_memory(scans, detrend, contact):
    same(scans / "c.npy", dict(NPY, detrend=detrend), contact)


OPTIONS = {
    "friction map .npy": {"friction_map": "mu.npy"},
    "friction map text": {"friction_map": "mu.txt"},
    "rest level": {"rest_level": 2e-6},
    "bearing fraction": {"bearing_fraction": 0.3},
    "bearing fraction, poly2": {"bearing_fraction": 0.6, "detrend": "poly2"},
    "max slope": {"max_slope": 30.0},
    "spikes": {"despike": 3.0},
    "self-locking": {"mu": 2.5},
    "everything": {"mu": 2.5, "max_slope": 55.0, "bearing_fraction": 0.5, "despike": 3.0,
                   "despike_window": 3, "detrend": "plane"},
}


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
@pytest.mark.parametrize("name", list(OPTIONS))
def test_options_in_tiles_as_in_memory(scans, name, contact):
    kw = {k: (str(scans / v) if k == "friction_map" else v) for k, v in OPTIONS[name].items()}
    ref, _ = same(scans / "c.npy", dict(NPY, **kw), contact)
    if name == "self-locking":
        assert ref["self_locking"], "the first self-locking facet must be compared"


@pytest.mark.parametrize("name,kw", [("f.npy", NPY), ("s.txt", NPY), ("s.x3p", {}),
                                     ("stored.x3p", {})])
@pytest.mark.parametrize("opts", [{"mu": 2.5}, {"mu": 0.3, "detrend": "poly2", "despike": 3.0}])
def test_formats_read_in_lines(scans, name, kw, opts):
    """Fortran-ordered .npy, text and x3p (valid-points member, deflated and stored) are
    read along their own lines (axis 1): the same facets, the same first locking facet."""
    ref, ds = same(scans / name, dict(kw, **opts), "all-faces", tiles=(1, 4, None))
    assert ds[0].texture.tiling["axis"] == 1 and ds[0].texture.tiling["streamed"]
    assert bool(ref["self_locking"]) == (opts["mu"] > 1)


def test_level_facets_along_ridges_in_tiles(tmp_path):
    """Windward sliding exactly along ridges: no facet is climbed, the level facets take
    the load (set-valued), from one more pass over the tiles."""
    x = np.arange(48)
    prof = np.where(x % 12 < 9, (x % 12) * 0.5, (12 - x % 12) * 1.5)
    np.save(tmp_path / "ridges.npy", np.repeat(prof[:, None], 20, axis=1))
    for mu in (0.2, 3.0):
        ref, ds = same(tmp_path / "ridges.npy", dict(NPY, mu=mu, detrend="none"), "windward")
        assert sum(x["set_valued"] for x in ref["directions"]) == 2


def test_preview_and_other_regime_of_a_tiled_scan(scans):
    """The plot's preview is the in-memory one (downsampled, collected tile by tile) and the
    other contact regime is computed in the same passes."""
    from asperity.surface._previews import height_preview
    from asperity.surface.readers import read_surface
    mem = load_surface(scans / "c.npy", **NPY)
    d = derive_scan(scans / "c.npy", **NPY, tile_lines=3, other_contact="windward",
                    n_directions=16)
    np.testing.assert_array_equal(d.texture.preview, mem.preview)
    big = rough(300, 90, seed=1)
    hm = read_surface(scans / "c.npy", **NPY)
    assert d.texture.preview.shape == height_preview(hm.heights).shape
    np.save(scans / "big.npy", big)
    d2 = derive_scan(scans / "big.npy", **NPY, tile_lines=7, n_directions=8)
    np.testing.assert_array_equal(d2.texture.preview, height_preview(big * 1e-6))
    ref = derive(mem, "windward", n_directions=16).reservoir
    np.testing.assert_allclose(d.texture.other["windward"].p, ref.p, rtol=1e-12)


@pytest.mark.skipif(not (DATA / "SkiInfiniteFocus.x3p").exists(), reason="no shared data")
def test_a_measured_x3p_in_tiles_as_in_memory():
    """The ski scan (1197 x 940, +inf dropouts) streamed from its x3p member in 25 tiles."""
    same(DATA / "SkiInfiniteFocus.x3p", {"mu": 0.3, "max_slope": 70.0}, "all-faces", n=8,
         tiles=(40,))


# ----------------------------------------------------------------------------- Dask

def test_local_cluster_gives_the_in_process_result_bit_for_bit(scans, capsys):
    """Tiles as tasks on a LocalCluster of 2 workers (started and stopped by the command)."""
    argv = ["derive", scans / "c.npy", "--unit", "um", "--pixel-size", "1", "--mu", "0.6",
            "--tile-rows", "4", "--despike", "3", "--bearing-fraction", "0.4", "--json"]
    here = json.loads(run(capsys, *argv)[1])
    code, out, err = run(capsys, *argv, "--workers", "2")
    assert code == 0, err
    there = json.loads(out)
    assert here.pop("tiling")["where"] == "in-process"
    assert there.pop("tiling")["where"] == "LocalCluster (2 workers)"
    assert here == there


@pytest.mark.slow
def test_external_cluster_workers_read_the_file_themselves(scans, tmp_path, monkeypatch):
    """`dask scheduler` + `dask worker` on 127.0.0.1; the client cannot read a tile (its
    reader raises), so the workers read theirs from the path."""
    from test_study_engine import external_cluster

    from asperity.surface.readers import _streams
    ref = to_json(derive_scan(scans / "s.x3p", mu=0.6, tile_lines=3, n_directions=16))
    with external_cluster(tmp_path, n_workers=2) as (sched, address, _):
        from distributed import Client

        def refuse(*a, **k):
            raise AssertionError("the client read a tile")
        monkeypatch.setattr(_streams.X3pLines, "lines", refuse)
        with Client(address, timeout="20s") as client:
            got = to_json(derive_scan(scans / "s.x3p", mu=0.6, tile_lines=3, n_directions=16,
                                      client=client))
        monkeypatch.undo()
        code, out, err = cli("derive", scans / "s.x3p", "--mu", "0.6", "--tile-rows", "3",
                             "--directions", "16", "--json", "--scheduler", address)
    assert code == 0, err
    ref.pop("tiling"), got.pop("tiling")
    assert got == ref
    cli_out = json.loads(out)
    assert cli_out.pop("tiling")["where"] == address and cli_out == ref


# ----------------------------------------------------------------------------- data quality

def smooth(n, seed):
    rng = np.random.default_rng(seed)
    k = np.hypot(np.fft.fftfreq(n)[:, None], np.fft.fftfreq(n)[None, :])
    k[0, 0] = 1.0
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.normal(size=(n, n))) * k ** -2.0))
    return z / z.std()


def test_spike_filter_finds_every_planted_spike_and_nothing_else(tmp_path):
    n = 160
    z = smooth(n, 5)
    rng = np.random.default_rng(6)
    z[rng.random((n, n)) < 0.02] = np.nan                 # dropouts stay as they are
    free = np.flatnonzero(np.isfinite(z).ravel())
    planted = rng.choice(free, 80, replace=False)
    planted = planted[np.argsort(planted)]
    zs = z.copy().ravel()
    zs[planted] += rng.choice([-1.0, 1.0], planted.size) * rng.uniform(2.0, 20.0, planted.size)
    zs = zs.reshape(n, n)
    found = np.flatnonzero(find_spikes(zs, (6.0, 5)).ravel())
    np.testing.assert_array_equal(found, planted)
    # through the reader and in tiles whose edges cut the windows: the same pixels removed
    np.save(tmp_path / "spiky.npy", zs)
    mem = load_surface(tmp_path / "spiky.npy", **NPY, despike=6.0)
    assert mem.quality["spikes_removed"] == planted.size
    assert mem.info["n_undefined"] == int(np.isnan(z).sum())       # as measured
    for t in (1, 3, 17):
        d = derive_scan(tmp_path / "spiky.npy", **NPY, despike=6.0, tile_lines=t,
                        n_directions=8)
        assert d.texture.quality["spikes_removed"] == planted.size
        assert d.texture.info["n_skipped_undefined"] == mem.info["n_skipped_undefined"]


def facets_numpy(z, dx, dy):
    """(gx, gy, centroid x, y, z) of the two triangles of every cell, defined ones only: the
    triangulation written out independently."""
    i, j = np.meshgrid(np.arange(z.shape[0] - 1), np.arange(z.shape[1] - 1), indexing="ij")
    out = []
    for tri in (((0, 0), (1, 0), (0, 1)), ((1, 1), (0, 1), (1, 0))):
        (a, b), (c, d), (e, f) = tri
        p0, p1, p2 = z[i + a, j + b], z[i + c, j + d], z[i + e, j + f]
        if a == 0:        # lower: p1 - p0 along x, p2 - p0 along y
            gx, gy = (p1 - p0) / dx, (p2 - p0) / dy
        else:             # upper: (1,1)-(0,1) along x, (1,1)-(1,0) along y
            gx, gy = (p0 - p1) / dx, (p0 - p2) / dy
        cx = (i + (a + c + e) / 3) * dx
        cy = (j + (b + d + f) / 3) * dy
        out.append(np.stack([gx, gy, cx, cy, (p0 + p1 + p2) / 3]).reshape(5, -1))
    f = np.concatenate(out, axis=1)
    return f[:, np.isfinite(f).all(axis=0)]


@pytest.mark.parametrize("rest", [None, 0.0])
def test_max_slope_counts_and_load_share_against_numpy(scans, rest):
    z = np.load(scans / "c.npy") * 1e-6
    gx, gy, cx, cy, zc = facets_numpy(z, 1e-6, 1e-6)
    a, b = gx.mean(), gy.mean()                       # the mean-slope removal
    gx, gy, zc = gx - a, gy - b, zc - a * cx - b * cy
    steep = np.degrees(np.arctan(np.hypot(gx, gy))) > 35.0
    w = np.ones_like(gx) if rest is None else np.maximum(zc - rest, 0.0)
    kw = dict(NPY, max_slope=35.0, rest_level=rest)
    for q in (load_surface(scans / "c.npy", **kw).quality,
              derive_scan(scans / "c.npy", **kw, tile_lines=4, n_directions=8).texture.quality):
        assert q["facets_dropped_by_slope"] == int(steep.sum()) > 0
        assert q["dropped_load_share"] == pytest.approx(w[steep].sum() / w.sum(), rel=1e-12)
        assert q["steepest_facet_deg"] == pytest.approx(
            np.degrees(np.arctan(np.hypot(gx, gy)[~steep].max())), rel=1e-12)
        assert q["pixels"] == z.size and q["undefined_pixels"] == int(np.isnan(z).sum())


def test_self_locking_on_a_few_steep_facets_names_the_flag_and_its_cost(tmp_path, capsys):
    """Cliffs at a dropout edge (what a focus-variation scan gives): mu = 0.1 self-locks on
    a tiny load share; the message names --max-slope and what it drops; with it the law is
    finite and data_quality says what was removed."""
    z = 0.2 * smooth(96, 7)
    z[40:44, 30:36] = np.nan
    z[44, 30:36] += 40.0                     # a wall of bad pixels along the dropout's edge
    np.save(tmp_path / "scan.npy", z)
    argv = ["derive", tmp_path / "scan.npy", "--unit", "um", "--pixel-size", "1", "--mu", "0.1"]
    code, out, _ = run(capsys, *argv)
    assert code == 0 and "SELF-LOCKING" in out
    gx, gy, *_ = facets_numpy(z * 1e-6, 1e-6, 1e-6)
    g = np.hypot(gx - gx.mean(), gy - gy.mean())
    limit = 84.28                            # atan(1/0.1) = 84.289 deg, on a 0.01 step
    n_steep = int((g > math.tan(math.radians(limit))).sum())
    assert f"--max-slope {limit:g} drops them and gives a finite law (cost: {n_steep} facets" \
        in out, out
    for extra in ([], ["--tile-rows", "7"]):
        d = json.loads(run(capsys, *argv, "--json", *extra)[1])
        fw = d["data_quality"]["finite_with"]
        assert fw["flag"] == f"--max-slope {limit:g}" and fw["facets_dropped"] == n_steep
        assert fw["load_share"] == pytest.approx(n_steep / g.size, rel=1e-12)
        assert fw["load_share"] < 1e-2
        fixed = json.loads(run(capsys, *argv, "--json", "--max-slope", str(limit), *extra)[1])
        assert not fixed["self_locking"] and math.isfinite(fixed["mu_a_plus"])
        q = fixed["data_quality"]
        assert q["facets_dropped_by_slope"] == n_steep and q["finite_with"] is None
        assert q["steepest_facet_deg"] <= limit


# ----------------------------------------------------------------------------- command line

BAD_FLAGS = [
    (["--max-slope", "0"], "--max-slope must be in (0, 90) deg, got 0"),
    (["--max-slope", "90"], "--max-slope must be in (0, 90) deg"),
    (["--max-slope", "nan"], "--max-slope must be in (0, 90) deg, got NaN"),
    (["--max-slope", "0.001"], "--max-slope 0.001 deg drops every facet"),
    (["--max-slope", "0.001", "--tile-rows", "3"], "--max-slope 0.001 deg drops every facet"),
    (["--despike", "1"], "--despike must be in [2, 1e+06], got 1"),
    (["--despike", "inf"], "--despike must be a finite number"),
    (["--despike", "5", "--despike-window", "4"], "--despike-window must be an odd whole"),
    (["--despike", "5", "--despike-window", "17"],
     "--despike-window must be a whole number in [3, 15]"),
    (["--despike-window", "5"], "--despike-window needs --despike"),
    (["--tile-rows", "-1"], "--tile-rows must be a whole number in [0, 1000000000]"),
    (["--tile-rows", "2.5"], "--tile-rows must be a whole number"),
    (["--tile-rows", "many"], "--tile-rows must be a number"),
    (["--workers", "-2"], "--workers must be a whole number in [0, 4096]"),
    (["--tile-rows", "0", "--workers", "2"], "--tile-rows 0 keeps the map in memory"),
    (["--tile-rows", "3", "--directions", "7"], "directions must be a whole number in [8"),
    (["--tile-rows", "3", "--rest-level", "1"], "lies above the highest facet"),
]


@pytest.mark.parametrize("flags,msg", BAD_FLAGS)
def test_new_flags_refused_in_one_line(scans, capsys, flags, msg):
    code, out, err = run(capsys, "derive", scans / "c.npy", "--unit", "um", "--pixel-size",
                         "1", *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


WRONG_PLACE = [
    (["wedge-asymmetric.toml", "--tile-rows", "5"], "--tile-rows applies to height-map files"),
    (["wedge-asymmetric.toml", "--max-slope", "5"], "--max-slope applies to surface files"),
    (["wedge-30-10.stl", "--unit", "um", "--despike", "5"], "--despike applies to height maps"),
    (["wedge-30-10.stl", "--unit", "um", "--workers", "2"], "a mesh is derived whole"),
]


@pytest.mark.parametrize("argv,msg", WRONG_PLACE)
def test_new_flags_where_they_do_not_apply(capsys, argv, msg):
    code, out, err = run(capsys, "derive", ROOT / "surfaces" / argv[0], *argv[1:])
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


def test_new_flags_refused_by_the_real_command(scans):
    """One line on stderr, exit 1, no cluster started for a file workers cannot read."""
    assert_refused(cli("derive", scans / "c.npy", "--unit", "um", "--pixel-size", "1",
                       "--scheduler", "tcp://127.0.0.1:9"),
                   contains="nothing listens on 127.0.0.1:9")
    gz = scans / "c.npy.gz"                 # gzip is read whole: tiles only in this process
    import gzip
    gz.write_bytes(gzip.compress((scans / "c.npy").read_bytes()))
    assert_refused(cli("derive", gz, "--unit", "um", "--pixel-size", "1", "--workers", "1"),
                   contains="tiles on Dask workers need .npy, .x3p or a text matrix")


def test_claimed_grid_in_tiles_is_refused_for_its_missing_data(tmp_path, scans, capsys,
                                                             monkeypatch):
    """An x3p claiming 65536 x 65536 points without them: tiles would hold little, the
    missing member is what gets it refused, at once.  Work beyond MAX_SCAN_WORK is refused
    before any pass, naming the flag that lowers it."""
    from x3p_files import main_xml

    from asperity.friction import tiled
    p = tmp_path / "claim.x3p"
    p.write_bytes(x3p_bytes(np.zeros((3, 3)), members={"main.xml": main_xml(nx=65536,
                                                                            ny=65536)}))
    assert_refused(cli("derive", p), contains="bindata/data.bin holds")
    monkeypatch.setattr(tiled, "MAX_SCAN_WORK", 1e5)
    code, out, err = run(capsys, "derive", scans / "c.npy", "--unit", "um", "--pixel-size",
                         "1", "--tile-rows", "3", "--directions", "100")
    assert code == 1 and "c.npy: a 37 x 29 grid x 100 directions" in err, err
    assert "lower --directions or crop the scan" in err and err.count("\n") == 1


def test_automatic_tiles_above_the_size(scans, capsys, monkeypatch):
    from asperity.friction import tiled
    argv = ["derive", scans / "c.npy", "--unit", "um", "--pixel-size", "1", "--json"]
    assert "tiling" not in json.loads(run(capsys, *argv)[1])
    monkeypatch.setattr(tiled, "AUTO_TILE_PIXELS", 1000)
    d = json.loads(run(capsys, *argv)[1])
    assert d["tiling"]["tiles"] == 1 and d["tiling"]["where"] == "in-process"
    assert "tiling" not in json.loads(run(capsys, *argv, "--tile-rows", "0")[1])
    code, _, err = run(capsys, *argv, "--plot", scans / "tiles.png")
    assert code == 0 and (scans / "tiles.png").stat().st_size > 0, err


# ----------------------------------------------------------------------------- memory, Ctrl-C

PEAK = ("import sys\nfrom asperity.cli.main import main\ncode = main(sys.argv[1:])\n"
        "hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')][0]\n"
        "print(int(hwm.split()[1]) * 1024, file=sys.stderr)\nsys.exit(code)\n")


def peak_rss(*argv) -> int:
    """Peak RSS (VmHWM, bytes) of ``asperity ARGV`` in a child process."""
    r = subprocess.run([sys.executable, "-c", PEAK, *map(str, argv)], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return int(r.stderr.strip().splitlines()[-1])


def test_memory_does_not_grow_with_the_scan(tmp_path):
    """Peak RSS of derive in tiles of 64 lines: a map 8 times longer takes no more; held
    whole, it takes ~120 MB more."""
    z = np.tile(rough(512, 512, seed=2).astype(np.float32), (8, 1))
    np.save(tmp_path / "long.npy", z)
    np.save(tmp_path / "short.npy", z[:512])
    flags = ["--unit", "um", "--pixel-size", "1", "--directions", "8"]
    short = peak_rss("derive", tmp_path / "short.npy", *flags, "--tile-rows", "64")
    long = peak_rss("derive", tmp_path / "long.npy", *flags, "--tile-rows", "64")
    whole = peak_rss("derive", tmp_path / "long.npy", *flags, "--tile-rows", "0")
    assert long - short < 15 << 20, (short, long)
    assert whole - long > 100 << 20, (whole, long)


@pytest.mark.slow
def test_ctrl_c_stops_a_tiled_derive(tmp_path):
    np.save(tmp_path / "big.npy", rough(1500, 1500, seed=8).astype(np.float32))
    status, err = interrupt("derive", tmp_path / "big.npy", "--unit", "um", "--pixel-size",
                            "1", "--directions", "20000", "--tile-rows", "100")
    assert status == 130 and "interrupted" in err and "Traceback" not in err, err
    assert err.count("\n") == 1, err


BENCH_FLAGS = [(["--scan-sizes", "10"], "--scan-sizes must be a whole number in [64, 32768], got 10"),
               (["--repeats", "0"], "--repeats must be a whole number in [1, 20], got 0"),
               (["--scan-dir", "/no/such/folder"], "--scan-dir '/no/such/folder' is not a folder")]


@pytest.mark.parametrize("flags,msg", BENCH_FLAGS)
def test_big_scan_benchmark_flags_refused(capsys, flags, msg):
    code, out, err = run(capsys, "bench", "--only", "big-scan", *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


@pytest.mark.slow
def test_big_scan_benchmark_runs_and_cleans_up(tmp_path, capsys):
    code, out, err = run(capsys, "bench", "--only", "big-scan", "--scan-sizes", "64", "96",
                         "--directions", "8", "--scan-dir", tmp_path, "--json")
    assert code == 0, err
    b = json.loads(out)["big_scan"]
    assert [r["n"] for r in b["sizes"]] == [64, 96] and list(tmp_path.iterdir()) == []
    for r in b["sizes"]:
        assert r["tiling"]["tiles"] >= 1 and r["runs"][0]["peak_rss_bytes"] > 0
        assert r["in_memory"]["mu_a_plus"] == pytest.approx(r["mu_a_plus"], rel=1e-12)
