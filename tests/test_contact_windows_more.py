"""asperity contact --window W --windows K (the windows' contact figures and their spread),
derive --window at several pressures (each window solved as a load curve, the spread per
pressure), random windows with too few defined pixels redrawn in their stratum, and
asperity.derive_windows.

Checks: on a periodic map that is one tile repeated every window's contact is the whole
map's (a window of one period is a cyclic shift of the tile), at every pressure, and its
friction family is the whole map's family; the spread is the windows' own (NumPy's); a
redrawn window is one whose earlier draws had too few defined pixels, drawn again in its
own stratum, the same for the same seed; the Dask path equals the serial one; bad input
in one line."""
import json

import numpy as np
import pytest
from cli_run import run, run_json
from test_contact_windows import N, surface, tile

import asperity
from asperity.friction.elastic_windows import MAX_REDRAWS, window_strata
from asperity.friction.window_summary import MIN_DEFINED_SHARE


def contact(path, *more):
    return [str(path), "--unit", "um", "--pixel-size", "1", "--elastic", "1e9",
            "--pressure", "2e6", *more]


@pytest.fixture(scope="module")
def repeated(tmp_path_factory):
    d = tmp_path_factory.mktemp("cwindows")
    np.save(d / "rep.npy", np.tile(tile(), (3, 4)))       # 144 x 192 pixels
    return d


def test_contact_windows_of_a_repeated_tile_are_the_whole_maps_contact(repeated, capsys,
                                                                        tmp_path):
    png = tmp_path / "c.png"
    s = run_json(capsys, "contact", *contact(repeated / "rep.npy", "--boundary", "periodic",
                                             "--window", str(N), "--windows", "5",
                                             "--window-placement", "random",
                                             "--window-seed", "3", "--plot", png))
    whole = run_json(capsys, "contact", *contact(repeated / "rep.npy", "--boundary",
                                                 "periodic"))
    assert s["windows"]["used"] == 5 and s["windows"]["redraws"] == 0
    assert len({tuple(w["origin_px"]) for w in s["per_window"]}) == 5
    for k in ("area_fraction", "max_pressure_Pa", "mean_gap_m"):
        assert s[k]["n"] == 5
        assert s[k]["mean"] == pytest.approx(whole[k], rel=1e-6), k
        assert s[k]["max"] - s[k]["min"] <= 1e-6 * abs(s[k]["mean"]), k
    assert s["pressure_Pa"] == 2e6 and s["boundary"] == "periodic"
    assert "not the whole scan's contact" in s["estimate"]
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "mu_a_plus" not in s and "mu_a_plus" not in s["per_window"][0]


def test_contact_window_spread_is_the_windows_own(tmp_path, capsys):
    t = tile()
    z = np.concatenate([np.tile(t, (2, 2)), np.tile(3.0 * tile(seed=8), (2, 2))], axis=1)
    np.save(tmp_path / "halves.npy", z)
    s = run_json(capsys, "contact", *contact(tmp_path / "halves.npy", "--window", str(N),
                                             "--windows", "4"))
    for k in ("area_fraction", "max_pressure_Pa", "mean_gap_m"):
        v = [w["elastic_contact"][k] for w in s["per_window"]]
        assert s[k]["mean"] == pytest.approx(np.mean(v), rel=1e-12)
        assert s[k]["sd"] == pytest.approx(np.std(v, ddof=1), rel=1e-12)
        assert s[k]["min"] == min(v) and s[k]["max"] == max(v)
    assert s["area_fraction"]["max"] - s["area_fraction"]["min"] > 0.2 * s["area_fraction"][
        "mean"]
    code, out, _ = run(capsys, "contact", *contact(tmp_path / "halves.npy", "--window",
                                                   str(N), "--windows", "4"))
    assert code == 0 and "ESTIMATE from 4 windows of 48 x 48 pixels" in out
    assert "contact fraction" in out and "max pressure (Pa)" in out


def test_windows_at_several_pressures_give_the_whole_maps_family(repeated, capsys, tmp_path):
    png = tmp_path / "f.png"
    ps = ["1e6", "4e6", "1.6e7"]
    flags = surface(repeated / "rep.npy", "--boundary", "periodic")
    flags[flags.index("--pressure") + 1:flags.index("--pressure") + 2] = ps
    s = run_json(capsys, "derive", *flags, "--window", str(N), "--windows", "3",
                 "--window-placement", "random", "--plot", png)
    fam = run_json(capsys, "derive", *flags)
    assert s["family"] == "pressure" and s["pressures_Pa"] == [float(p) for p in ps]
    assert len(s["per_pressure"]) == 3 and png.exists()
    fractions = []
    for row, member in zip(s["per_pressure"], fam["members"]):
        assert row["pressure_Pa"] == pytest.approx(member["elastic_contact"]["pressure_Pa"],
                                                   rel=1e-12)
        af = member["elastic_contact"]["area_fraction"]
        assert row["area_fraction"]["mean"] == pytest.approx(af, rel=1e-7)
        fractions.append(af)
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            assert row[k]["max"] - row[k]["min"] < 1e-7 * row[k]["mean"]
            assert row[k]["mean"] == pytest.approx(member[k], rel=1e-6), k
    assert fractions == sorted(fractions) and fractions[0] < 0.5 * fractions[-1]
    w = s["per_window"][0]
    assert [m["elastic_contact"]["pressure_Pa"] for m in w["members"]] == \
        pytest.approx([1e6, 4e6, 1.6e7], rel=1e-12)
    code, out, _ = run(capsys, "derive", *flags, "--window", str(N), "--windows", "3")
    assert code == 0 and "law family over 3 pressures (each window solved as a load curve)" \
        in out and "not the whole scan's contact" in out
    one = run_json(capsys, "derive", *surface(repeated / "rep.npy", "--boundary", "periodic",
                                              "--pressure", "4e6", "--window", str(N),
                                              "--windows", "3", "--window-placement",
                                              "random"))
    assert one["mu_a_plus"]["mean"] == pytest.approx(s["per_pressure"][1]["mu_a_plus"]["mean"],
                                                     rel=1e-9)


@pytest.fixture(scope="module")
def holes(tmp_path_factory):
    """A 144 x 192 repeated tile with an undefined block of 50 x 60 pixels at a corner."""
    d = tmp_path_factory.mktemp("holes")
    z = np.tile(tile(), (3, 4))
    z[:50, :60] = np.nan
    np.save(d / "holes.npy", z)
    return d / "holes.npy", z


def test_random_windows_with_too_few_defined_pixels_are_redrawn(holes, capsys):
    path, z = holes
    flags = contact(path, "--window", "40", "--windows", "4", "--window-placement", "random",
                    "--window-seed", "3")
    s = run_json(capsys, "contact", *flags)
    wi = s["windows"]
    assert wi["redraws"] > 0 and wi["redrawn"] >= 1 and wi["max_redraws"] == MAX_REDRAWS
    assert wi["used"] == 4 and wi["skipped"] == 0
    strata = window_strata(z.shape, 40, 4)
    for w in s["per_window"]:
        i0, j0 = w["origin_px"]
        assert np.isfinite(z[i0:i0 + 40, j0:j0 + 40]).mean() >= MIN_DEFINED_SHARE
        x0, x1, y0, y1 = strata[w["index"]][:4]
        for a, b in [*w["redrawn_from"], w["origin_px"]]:     # all in the window's stratum
            assert x0 <= a < x1 + 1 and y0 <= b < y1 + 1
        for a, b in w["redrawn_from"]:
            assert np.isfinite(z[a:a + 40, b:b + 40]).mean() < MIN_DEFINED_SHARE
    assert sum(len(w["redrawn_from"]) for w in s["per_window"]) == wi["redraws"]
    assert json.dumps(run_json(capsys, "contact", *flags)) == json.dumps(s)   # same seed
    code, out, _ = run(capsys, "contact", *flags)
    assert code == 0 and f"{wi['redraws']} random draws had too few defined pixels" in out


def test_a_window_whose_stratum_is_undefined_stays_skipped(tmp_path, capsys):
    z = np.tile(tile(), (3, 4))
    z[:, :96] = np.nan                                 # the left half: no window fits there
    np.save(tmp_path / "half.npy", z)
    s = run_json(capsys, "contact", *contact(tmp_path / "half.npy", "--window", "40",
                                             "--windows", "2", "--window-placement",
                                             "random"))
    wi = s["windows"]
    assert wi["skipped"] == 1 and wi["used"] == 1
    bad = [w for w in s["per_window"] if "skipped" in w][0]
    assert len(bad["redrawn_from"]) == MAX_REDRAWS and "after 16 redraws" in bad["skipped"]
    grid = run_json(capsys, "contact", *contact(tmp_path / "half.npy", "--window", "40",
                                                "--windows", "2"))
    assert grid["windows"]["redraws"] == 0 and grid["windows"]["skipped"] == 1  # not redrawn


def test_contact_windows_on_two_local_workers_equal_the_serial_ones(repeated, capsys):
    flags = contact(repeated / "rep.npy", "--window", "40", "--windows", "3")
    serial = run_json(capsys, "contact", *flags)
    there = run_json(capsys, "contact", *flags, "--workers", "2")
    assert there["windows"].pop("where") == "LocalCluster (2 workers)"
    assert serial["windows"].pop("where") == "in-process"
    there["windows"].pop("workers"), serial["windows"].pop("workers")
    assert json.dumps(there, sort_keys=True) == json.dumps(serial, sort_keys=True)


def test_derive_windows_is_public(repeated):
    from asperity.surface.contact_facets import ElasticContact
    assert "derive_windows" in asperity.__all__
    s = asperity.derive_windows(repeated / "rep.npy", ElasticContact(1e9, 2e6),
                                window=N, windows=2, unit="um", pixel_size=1.0,
                                n_directions=8)
    assert s["windows"]["used"] == 2 and "not the whole scan's contact" in s["estimate"]


@pytest.mark.parametrize("flags, words", [
    (("--window", "500"), "--window 500 pixels is larger than the scan (144 x 192"),
    (("--window", "8"), "--window must be a whole number in [16"),
    (("--window", "40", "--windows", "0"), "--windows must be a whole number in [1, 10000]"),
    (("--window", "40", "--windows", "10001"), "--windows must be a whole number in [1, 10000]"),
    (("--windows", "3"), "--windows needs --window"),
    (("--window", "40", "--save-pressure", "NPY"), "not with --save-pressure"),
    (("--window", "40", "--max-slope", "30"), "--max-slope"),
    (("--workers", "2",), "--workers runs windows"),
])
def test_bad_contact_window_flags_are_one_line(repeated, capsys, tmp_path, flags, words):
    png = tmp_path / "w.png"
    flags = [str(tmp_path / "p.npy") if f == "NPY" else f for f in flags]
    code, out, err = run(capsys, "contact", *contact(repeated / "rep.npy", *flags,
                                                     "--plot", png))
    assert code == 1 and out == "", err
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not png.exists()
