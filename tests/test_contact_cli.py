"""asperity contact: the elastic contact of a height map or a wedge texture on the command
line -- its JSON keys, the pressure file against the API, the picture, E* from the
materials, full contact as a result, and the bad inputs of issue 19 refused in one line
(exit 1; 3 when the iteration limit is reached) with nothing written."""
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.contact import solve_contact

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from contact_peers import self_affine  # noqa: E402

WEDGE = ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2"]
KEYS = {"area_fraction", "pressure_Pa", "max_pressure_Pa", "mean_gap_m", "E_star_Pa",
        "boundary", "hardness_Pa", "iterations", "residual", "converged", "full_contact",
        "plastic_fraction"}
E = 1e11


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """64 x 56 self-affine map (.npy, metres, 1 um pixels, rms slope 0.1), with a few
    undefined pixels."""
    z = self_affine(64, 56, dx=1e-6, seed=11)
    z[5, 7] = z[40, 3] = np.nan
    path = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(path, z)
    return path, z


def files(path, *more):
    return [str(path), "--unit", "m", "--pixel-size", "1e-6", *more]


def test_json_keys_and_the_map_described_as_derive_does(scan, capsys):
    path, z = scan
    d = run_json(capsys, "contact", *files(path, "--elastic", "1e11", "--pressure", "2.5e8"))
    assert set(d) == KEYS | {"texture", "data_quality"}
    t = d["texture"]
    assert t["kind"] == "heightmap" and t["grid"] == [64, 56] and t["n_undefined"] == 2
    assert t["pixel_size_m"] == [1e-6, 1e-6] and t["detrend"] == "slope"
    assert d["data_quality"]["undefined_pixels"] == 2
    assert d["boundary"] == "free" and d["hardness_Pa"] is None and d["E_star_Pa"] == E
    assert d["pressure_Pa"] == pytest.approx(2.5e8, rel=1e-10)
    assert d["converged"] and not d["full_contact"] and 0 < d["area_fraction"] < 0.2
    assert d["residual"] < 1e-8 and d["iterations"] > 1 and d["mean_gap_m"] > 0
    assert d["max_pressure_Pa"] > 10 * d["pressure_Pa"]


def test_saved_pressure_is_the_api_result_on_the_map_grid(scan, capsys, tmp_path):
    path, z = scan
    out, png = tmp_path / "p.npy", tmp_path / "c.png"
    code, text, err = run(capsys, "contact", *files(path, "--detrend", "none", "--elastic",
                                                    "1e11", "--pressure", "2.5e8",
                                                    "--save-pressure", out, "--plot", png))
    assert code == 0, err
    saved = np.load(out)
    ref = solve_contact(z, 1e-6, E, 2.5e8, boundary="free").pressure
    assert saved.shape == z.shape == ref.shape
    assert np.array_equal(np.isnan(saved), np.isnan(z))        # NaN where undefined
    ok = np.isfinite(z)
    assert np.abs(saved[ok] - ref[ok]).max() <= 1e-6 * ref[ok].max()
    assert (saved[ok] == 0).sum() > 0.5 * ok.sum()             # 0 out of contact
    assert np.nansum(saved) == pytest.approx(2.5e8 * z.size, rel=1e-10)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"pressure written to {out}" in text and f"plot written to {png}" in text
    assert "boundary free" in text and "contact area fraction" in text
    assert not list(tmp_path.glob(".*part"))


def test_periodic_boundary_and_hardness(scan, capsys):
    path, z = scan
    d = run_json(capsys, "contact", *files(path, "--elastic", "1e11", "--pressure", "1e9",
                                           "--boundary", "periodic", "--hardness", "5e9"))
    assert d["boundary"] == "periodic" and d["hardness_Pa"] == 5e9
    assert d["max_pressure_Pa"] == pytest.approx(5e9, rel=1e-12)
    assert d["texture"]["periodic"] is True and 0 < d["plastic_fraction"] < d["area_fraction"]
    code, out, _ = run(capsys, "contact", *files(path, "--elastic", "1e11", "--pressure", "1e9",
                                                 "--boundary", "periodic", "--hardness", "5e9"))
    assert code == 0 and "at the hardness (plastic)" in out and "hardness 5e+09 Pa" in out


def test_materials_give_the_effective_modulus(scan, capsys):
    path, _ = scan
    E1, nu1, E2, nu2 = 2.1e11, 0.3, 7e10, 0.33
    d = run_json(capsys, "contact", *files(path, "--materials", E1, nu1, E2, nu2,
                                           "--pressure", "2e8"))
    assert d["E_star_Pa"] == pytest.approx(1 / ((1 - nu1 ** 2) / E1 + (1 - nu2 ** 2) / E2),
                                           rel=1e-12)
    d = run_json(capsys, "contact", *files(path, "--materials", E1, nu1, "--pressure", "2e8"))
    assert d["E_star_Pa"] == pytest.approx(E1 / (1 - nu1 ** 2), rel=1e-12)   # rigid partner


def test_max_slope_and_despike_apply_as_in_derive(scan, capsys):
    path, _ = scan
    d = run_json(capsys, "contact", *files(path, "--elastic", "1e11", "--pressure", "2.5e8",
                                           "--max-slope", "10", "--despike", "8"))
    q = d["data_quality"]
    assert q["max_slope_deg"] == 10 and q["facets_dropped_by_slope"] > 0
    assert 0 < q["dropped_load_share"] < 1 and q["spike_filter"]["threshold"] == 8


def test_wedge_texture_is_periodic_by_construction(capsys, tmp_path):
    out = tmp_path / "w.npy"
    p = 1e6
    d = run_json(capsys, "contact", *WEDGE, "--elastic", "1e9", "--pressure", p,
                 "--save-pressure", out)
    assert set(d) == KEYS | {"texture"}
    t = d["texture"]
    assert d["boundary"] == "periodic" and t["kind"] == "wedge" and t["periodic"]
    saved = np.load(out)
    assert saved.shape == (t["profile_nodes"],)
    assert saved.sum() * t["node_spacing_m"] == pytest.approx(p * t["period_m"], rel=1e-10)
    assert 0 < d["area_fraction"] < 0.1
    code, _, err = run(capsys, "contact", *WEDGE, "--elastic", "1e9", "--pressure", p,
                       "--boundary", "free", "--save-pressure", out)
    assert code == 1 and "must be periodic" in err


def test_full_contact_is_a_result(capsys, tmp_path):
    """Westergaard's sinusoid above p* = pi E* Delta / lambda: every pixel in contact."""
    n, lam, delta = 128, 1e-4, 1e-6
    x = np.arange(n) * lam / n
    path = tmp_path / "sine.npy"
    np.save(path, np.repeat((delta * np.cos(2 * np.pi * x / lam))[:, None], 4, axis=1))
    pstar = math.pi * 1e9 * delta / lam
    argv = [str(path), "--unit", "m", "--pixel-size", str(lam / n), "--boundary", "periodic",
            "--elastic", "1e9", "--pressure", str(1.05 * pstar)]
    code, out, err = run(capsys, "contact", *argv)
    assert code == 0 and "full contact: every defined pixel is in contact" in out, err
    d = run_json(capsys, "contact", *argv)
    assert d["full_contact"] and d["area_fraction"] == 1.0
    d = run_json(capsys, "contact", *argv[:-1], str(0.9 * pstar))
    assert not d["full_contact"] and d["area_fraction"] < 1


BAD = [
    (["--pressure", "0"], "--pressure must be in (0, inf) Pa, got 0"),
    (["--pressure=-1e6"], "--pressure must be in (0, inf) Pa, got -1e+06"),
    (["--pressure", "nan"], "--pressure must be in (0, inf) Pa, got NaN"),
    (["--pressure", "inf"], "--pressure must be a finite number"),
    (["--pressure", "1e13"], "--pressure / --elastic must be in"),
    (["--elastic", "0"], "--elastic must be in [1, 1e+13] Pa, got 0"),
    (["--elastic=-2e9"], "--elastic must be in [1, 1e+13] Pa"),
    (["--elastic", "nan"], "--elastic must be in [1, 1e+13] Pa, got NaN"),
    (["--elastic", "inf"], "--elastic must be a finite number"),
    (["--materials", "2e11", "0.6"], "--materials nu1 must be in (-1, 0.5]"),
    (["--materials", "0", "0.3"], "--materials E1 must be in (0, inf) Pa"),
    (["--materials", "2e11", "0.3", "1e11"], "--materials takes E1 NU1 or E1 NU1 E2 NU2"),
    (["--hardness", "1e8"], "--hardness must be in (2.5e+08, inf) Pa"),
    (["--hardness", "2.5001e8"], "--hardness must be in (2.5014e+08, inf) Pa (above the "
                                 "mean pressure over the defined pixels)"),
    (["--hardness", "nan"], "--hardness must be in"),
    (["--tol", "0"], "--tol must be in"),
    (["--tol", "nan"], "--tol must be in"),
    (["--max-iterations", "0"], "--max-iterations must be"),
    (["--max-iterations", "1.5"], "--max-iterations must be"),
    (["--boundary", "periodic", "--despike", "1"], "--despike"),
    (["--pixel-size", "0"], "--pixel-size"),
]


@pytest.mark.parametrize("flags,words", BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_values_are_one_line_exit_1_nothing_written(scan, capsys, tmp_path, flags, words):
    path, _ = scan
    base = {"--elastic": ["--elastic", "1e11"], "--pressure": ["--pressure", "2.5e8"]}
    for f in flags:
        base.pop(f.split("=")[0], None)
    if "--materials" in flags:
        base.pop("--elastic")
    plot, saved = tmp_path / "p.png", tmp_path / "p.npy"
    argv = [*files(path), *base.get("--elastic", []), *base.get("--pressure", []), *flags]
    code, out, err = run(capsys, "contact", *argv, "--plot", plot, "--save-pressure", saved)
    assert code == 1, (out, err)
    assert words in err, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and out == ""
    assert not plot.exists() and not saved.exists() and not list(tmp_path.glob(".*part"))


def test_a_map_without_a_finite_pixel_is_refused_and_a_mesh_is_pressed(capsys, tmp_path):
    plot, saved = tmp_path / "p.png", tmp_path / "p.npy"
    nan = tmp_path / "nan.npy"
    np.save(nan, np.full((8, 8), np.nan))
    code, out, err = run(capsys, "contact", *files(nan), "--elastic", "1e9", "--pressure",
                         "1e6", "--plot", plot, "--save-pressure", saved)
    assert code == 1 and "every pixel is undefined" in err, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not plot.exists() and not saved.exists()
    # a mesh: its upper envelope on a grid (tests/test_contact_mesh.py checks the physics)
    d = run_json(capsys, "contact", str(ROOT / "surfaces" / "wedge-30-10.stl"), "--unit", "mm",
                 "--elastic", "1e9", "--pressure", "1e6", "--plot", plot)
    assert d["texture"]["kind"] == "mesh" and d["boundary"] == "free"
    assert 0 < d["area_fraction"] < 1 and plot.exists()


def test_the_iteration_limit_exits_3_with_the_residual_nothing_written(scan, capsys, tmp_path):
    path, _ = scan
    plot, saved = tmp_path / "p.png", tmp_path / "p.npy"
    code, out, err = run(capsys, "contact", *files(path, "--elastic", "1e11", "--pressure",
                                                   "2.5e8", "--max-iterations", "3", "--json",
                                                   "--plot", plot, "--save-pressure", saved))
    assert code == 3 and out == ""
    assert "did not converge at --pressure 2.5e+08 in 3 iterations (residual" in err
    residual = float(err.split("(residual ")[1].split(")")[0])
    assert residual > 1e-8
    assert len(err.strip().splitlines()) == 1 and not plot.exists() and not saved.exists()


@pytest.mark.parametrize("flags", [[], ["--elastic", "1e9", "--materials", "1e9", "0.3"]])
def test_exactly_one_modulus_is_a_usage_error(scan, capsys, flags):
    path, _ = scan
    with pytest.raises(SystemExit) as exc:
        run(capsys, "contact", *files(path, "--pressure", "1e6", *flags))
    err = capsys.readouterr().err
    assert exc.value.code == 2 and "--elastic" in err and len(err.strip().splitlines()) == 1


def test_help(capsys):
    with pytest.raises(SystemExit) as exc:
        run(capsys, "contact", "--help")
    out = capsys.readouterr().out
    assert exc.value.code == 0
    for flag in ("--elastic", "--materials", "--pressure", "--boundary", "--hardness", "--tol",
                 "--max-iterations", "--save-pressure", "--plot", "--json", "--unit",
                 "--detrend", "--max-slope", "--despike"):
        assert flag in out
    assert "--friction-map" not in out and "--rest-level" not in out
    json.dumps(out)
