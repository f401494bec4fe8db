"""derive --elastic E --pressure P --window W --windows K: the contact-weighted friction of
a scan estimated from windows solved on their own (asperity.friction.elastic_windows);
contact --window (the contact figures only) and derive --window at several pressures (each
window a load curve) are in test_contact_windows_more.py.

Checks: a periodic map that is one tile repeated gives every window the whole map's
friction (a window of one period is a cyclic shift of the tile); windows read from a file
in lines equal windows of the same map read whole; a map of two different halves has a
spread; the Dask path equals the serial one; the placement; bad inputs in one line."""
import json
import math

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.friction.elastic_windows import read_window, window_origins, window_strata
from asperity.surface.readers._streams import open_lines

N = 48                                   # pixels of one period


def tile(seed=3, n=N):
    """A smooth periodic random tile with an asymmetric ridge (heights in um, ~0.1 slope)."""
    rng = np.random.default_rng(seed)
    x = np.arange(n) / n
    X, Y = np.meshgrid(x, x, indexing="ij")
    t = np.zeros((n, n))
    for k in range(1, 4):
        for m in range(0, 4):
            t += rng.normal() / (k * k + m * m + 1) * np.cos(2 * np.pi * (k * X + m * Y)
                                                             + rng.uniform(0, 2 * np.pi))
    return t + 0.3 * np.sin(2 * np.pi * X) + 0.1 * np.sin(4 * np.pi * X)


def surface(path, *more):
    return [str(path), "--unit", "um", "--pixel-size", "1", "--mu", "0.15",
            "--elastic", "1e9", "--pressure", "2e6", "--directions", "24", *more]


@pytest.fixture(scope="module")
def repeated(tmp_path_factory):
    d = tmp_path_factory.mktemp("windows")
    t = tile()
    np.save(d / "rep.npy", np.tile(t, (3, 4)))       # 144 x 192 pixels
    return d, t


def test_windows_of_a_repeated_tile_all_give_the_whole_maps_friction(repeated, capsys):
    d, t = repeated
    s = run_json(capsys, "derive", *surface(d / "rep.npy", "--boundary", "periodic",
                                            "--window", str(N), "--windows", "5",
                                            "--window-placement", "random",
                                            "--window-seed", "11"))
    origins = [w["origin_px"] for w in s["per_window"]]
    assert len({tuple(o) for o in origins}) == 5
    assert any(o[0] % N or o[1] % N for o in origins)    # shifted, not only whole periods
    whole = run_json(capsys, "derive", *surface(d / "rep.npy", "--boundary", "periodic"))
    assert s["windows"]["used"] == 5
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
        assert s[k]["sd"] < 1e-9 * s[k]["mean"]
        assert s[k]["max"] - s[k]["min"] < 1e-9 * s[k]["mean"]
        assert s[k]["mean"] == pytest.approx(whole[k], rel=1e-7)
    af = whole["elastic_contact"]["area_fraction"]
    assert 0.01 < af < 0.5
    assert s["area_fraction"]["mean"] == pytest.approx(af, rel=1e-12)
    assert s["area_fraction"]["sd"] == pytest.approx(0.0, abs=1e-12)
    for row, ref in zip(s["directions"], whole["directions"]):
        T = ref["tangential"]
        assert row["mean"] == pytest.approx(T, rel=1e-7)
        assert row["max"] - row["min"] < 1e-8 * T
    assert "not the whole scan's contact" in s["estimate"]


def test_a_map_of_two_halves_has_a_spread(tmp_path, capsys):
    t = tile()
    z = np.concatenate([np.tile(t, (2, 2)), np.tile(3.0 * tile(seed=8), (2, 2))], axis=1)
    np.save(tmp_path / "halves.npy", z)                  # y < 96: one tile; y >= 96: another
    s = run_json(capsys, "derive", *surface(tmp_path / "halves.npy", "--boundary", "periodic",
                                            "--window", str(N), "--windows", "4"))
    used = [w for w in s["per_window"] if "skipped" not in w]
    left = [w for w in used if w["origin_px"][1] + N <= 96]
    right = [w for w in used if w["origin_px"][1] >= 96]
    assert left and right
    fa = [w["elastic_contact"]["area_fraction"] for w in used]
    assert s["area_fraction"]["max"] - s["area_fraction"]["min"] > 0.2 * s["area_fraction"]["mean"]
    assert s["area_fraction"]["sd"] == pytest.approx(np.std(fa, ddof=1), rel=1e-12)
    assert s["area_fraction"]["mean"] == pytest.approx(np.mean(fa), rel=1e-12)
    assert s["mu_a_plus"]["max"] - s["mu_a_plus"]["min"] > 1e-3
    code, out, _ = run(capsys, "derive", *surface(tmp_path / "halves.npy", "--window",
                                                  str(N), "--windows", "4"))
    assert code == 0 and "ESTIMATE from 4 windows of 48 x 48 pixels" in out
    assert "not the whole scan's contact" in out


def rough_scan(tmp_path):
    rng = np.random.default_rng(5)
    z = np.tile(tile(seed=1, n=60), (2, 3)) + 0.05 * rng.standard_normal((120, 180))
    z[rng.integers(0, 120, 40), rng.integers(0, 180, 40)] = np.nan
    return z


def test_windows_read_in_lines_equal_windows_of_the_map_read_whole(tmp_path, capsys):
    import gzip
    z = rough_scan(tmp_path)
    np.save(tmp_path / "scan.npy", z)
    with gzip.open(tmp_path / "whole.npy.gz", "wb") as fh:    # gzip: read whole
        np.save(fh, z)
    np.save(tmp_path / "fortran.npy", np.asfortranarray(z))   # lines are columns
    flags = ("--window", "40", "--windows", "6", "--window-placement", "random",
             "--detrend", "plane", "--despike", "6")
    runs = [run_json(capsys, "derive", *surface(tmp_path / f, *flags))
            for f in ("scan.npy", "whole.npy.gz", "fortran.npy")]
    assert runs[0]["windows"]["used"] == 6
    for other in runs[1:]:
        for a, b in zip(runs[0]["per_window"], other["per_window"]):
            assert a["origin_px"] == b["origin_px"]
            for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
                assert a[k] == pytest.approx(b[k], rel=1e-12)
            assert a["elastic_contact"]["area_fraction"] == \
                b["elastic_contact"]["area_fraction"]


def test_read_window_cuts_the_files_lines(tmp_path):
    z = rough_scan(tmp_path)
    np.save(tmp_path / "c.npy", z)
    np.save(tmp_path / "f.npy", np.asfortranarray(z))
    np.savetxt(tmp_path / "m.txt", z.T, fmt="%.17g")            # one line per y
    for name in ("c.npy", "f.npy", "m.txt"):
        src = open_lines(tmp_path / name, unit="m", pixel_size=1e-6)
        assert src is not None and src.shape == z.shape
        for i0, j0, w in ((0, 0, 17), (103, 163, 17), (37, 5, 80)):
            np.testing.assert_array_equal(read_window(src, i0, j0, w), z[i0:i0 + w, j0:j0 + w])


def test_origins_lie_in_the_scan_one_a_stratum():
    for shape, w, k in (((100, 300), 20, 7), ((64, 64), 64, 3), ((500, 90), 30, 12)):
        for placement, seed in (("grid", 0), ("random", 1), ("random", 2)):
            o = np.array(window_origins(shape, w, k, placement, seed))
            assert o.shape == (k, 2)
            assert (o >= 0).all() and (o[:, 0] <= shape[0] - w).all() \
                and (o[:, 1] <= shape[1] - w).all()
    a = window_origins((100, 300), 20, 6, "random", 4)
    assert a == window_origins((100, 300), 20, 6, "random", 4)
    assert a != window_origins((100, 300), 20, 6, "random", 5)
    g = np.array(window_origins((300, 300), 20, 4, "grid"))      # 2 x 2, edge to edge
    assert sorted(set(g[:, 0])) == [0, 280] and sorted(set(g[:, 1])) == [0, 280]
    g = np.array(window_origins((100, 300), 20, 6, "grid"))      # 1 x 6 along the long side
    assert set(g[:, 0]) == {40} and list(g[:, 1]) == [0, 56, 112, 168, 224, 280]
    g = window_origins((64, 64), 32, 4, "grid")                 # four windows tile the scan
    assert sorted(g) == [(0, 0), (0, 32), (32, 0), (32, 32)]


def test_random_windows_draw_from_strata_that_tile_the_origins_exactly():
    """The strata of a random placement cover the origins available, (n - w + 1) along each
    side, once and no further (a stratum past the last origin piles its draws on the edge),
    and each random origin lies in its own stratum."""
    for shape, w, k in (((100, 300), 20, 7), ((64, 64), 64, 3), ((500, 90), 30, 12),
                        ((41, 41), 40, 5), ((200, 50), 10, 1)):
        sx, sy = shape[0] - w + 1, shape[1] - w + 1
        st = window_strata(shape, w, k)
        cells = {s[4:6]: s[:4] for s in st}
        r, c = st[0][6], st[0][7]
        assert min(s[0] for s in st) == 0 and min(s[2] for s in st) == 0
        assert max(s[1] for s in st) == pytest.approx(sx, rel=1e-15)
        assert max(s[3] for s in st) == pytest.approx(sy, rel=1e-15)
        for (a, b), (x0, x1, y0, y1) in cells.items():      # the r x c grid of equal cells
            assert (x0, x1) == pytest.approx((a * sx / r, (a + 1) * sx / r), rel=1e-15)
            assert (y0, y1) == pytest.approx((b * sy / c, (b + 1) * sy / c), rel=1e-15)
        for seed in (1, 2, 3):
            for (i, j), s in zip(window_origins(shape, w, k, "random", seed), st):
                assert math.floor(s[0]) <= i < max(math.ceil(s[1]), math.floor(s[0]) + 1)
                assert math.floor(s[2]) <= j < max(math.ceil(s[3]), math.floor(s[2]) + 1)


def test_windows_on_two_local_workers_equal_the_serial_ones(repeated, capsys):
    d, _ = repeated
    flags = surface(d / "rep.npy", "--window", "40", "--windows", "4")
    serial = run_json(capsys, "derive", *flags)
    there = run_json(capsys, "derive", *flags, "--workers", "2")
    assert there["windows"].pop("where") == "LocalCluster (2 workers)"
    assert serial["windows"].pop("where") == "in-process"
    there["windows"].pop("workers"), serial["windows"].pop("workers")
    assert json.dumps(there, sort_keys=True) == json.dumps(serial, sort_keys=True)


@pytest.mark.parametrize("flags, words", [
    (("--window", "0"), "--window must be a whole number in [16"),
    (("--window", "nan"), "--window"),
    (("--window", "12"), "--window must be a whole number in [16"),
    (("--window", "500"), "--window 500 pixels is larger than the scan (144 x 192"),
    (("--window", "40", "--windows", "0"), "--windows must be a whole number in [1, 10000]"),
    (("--window", "40", "--windows", "-3"), "--windows"),
    (("--window", "40", "--window-seed", "2"), "--window-seed applies to --window-placement"),
    (("--windows", "3"), "--windows needs --window"),
    (("--window", "40", "--tile-rows", "10"), "not with --tile-rows"),
])
def test_bad_window_flags_are_one_line(repeated, capsys, tmp_path, flags, words):
    d, _ = repeated
    png = tmp_path / "w.png"
    code, out, err = run(capsys, "derive", *surface(d / "rep.npy", *flags, "--plot", png))
    assert code == 1 and out == ""
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not png.exists()


def test_windows_without_enough_defined_pixels_are_refused(tmp_path, capsys):
    z = np.tile(tile(), (2, 2))
    z[:, ::2] = np.nan                                   # half the pixels undefined
    np.save(tmp_path / "holes.npy", z)
    png = tmp_path / "w.png"
    code, out, err = run(capsys, "derive", *surface(tmp_path / "holes.npy", "--window", "40",
                                                    "--plot", png))
    assert code == 1 and out == "" and not png.exists()
    assert "none of the 8 windows" in err and "80 %" in err
    assert len(err.strip().splitlines()) == 1
    for more, words in ((("--elastic", "0"), "--elastic"),):
        args = surface(tmp_path / "holes.npy", "--window", "40")
        args += list(more)
        code, out, err = run(capsys, "derive", *args)
        assert code in (1, 2) and words in err and "Traceback" not in err
    code, _, err = run(capsys, "derive", str(tmp_path / "holes.npy"), "--unit", "um",
                       "--pixel-size", "1", "--window", "40")
    assert code == 1 and "--window needs --elastic" in err


def test_windows_whose_axes_straddle_0_and_180_deg_are_turned_alike(capsys):
    """The shipped ridge scan: its windows find t_a near 0 deg or near 180 deg (an axis);
    those pointing the other way have + and - exchanged, so the spread is the physics',
    and the estimate is the whole map's friction along the same direction."""
    from pathlib import Path
    scan = str(Path(__file__).resolve().parents[1] / "surfaces" / "scan-ridges.txt")
    flags = [scan, "--mu", "0.15", "--elastic", "1e9", "--pressure", "1e7"]
    s = run_json(capsys, "derive", *flags, "--window", "32", "--windows", "4")
    w = s["per_window"]
    assert {x["reversed"] for x in w} == {True, False}
    for x in w:
        own = x["principal_direction_deg"]
        assert x["reversed"] == (abs((own - s["principal_direction_deg"]["mean"] + 180) % 360
                                     - 180) > 90)
        plus, minus = (x["mu_a_minus"], x["mu_a_plus"]) if x["reversed"] else \
            (x["mu_a_plus"], x["mu_a_minus"])
        assert s["mu_a_plus"]["min"] <= plus <= s["mu_a_plus"]["max"]
        assert s["mu_a_minus"]["min"] <= minus <= s["mu_a_minus"]["max"]
    assert s["mu_a_plus"]["max"] < s["mu_a_minus"]["min"]          # the asymmetry survives
    whole = run_json(capsys, "derive", *flags)
    same = abs((whole["principal_direction_deg"] - s["principal_direction_deg"]["mean"] + 180)
               % 360 - 180) <= 90
    a, b = ("mu_a_plus", "mu_a_minus") if same else ("mu_a_minus", "mu_a_plus")
    assert s["mu_a_plus"]["mean"] == pytest.approx(whole[a], rel=0.03)
    assert s["mu_a_minus"]["mean"] == pytest.approx(whole[b], rel=0.03)
