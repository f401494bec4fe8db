"""derive | fit | risk --elastic E* --pressure P [P ...]: the contact-force weighting on the
command line (one pressure: the `elastic_contact` block; several: a law family), and its
bad inputs refused in one line, exit 1 (3 when the solve does not converge), nothing
written."""
import json
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.contact import solve_contact

SURF = Path(__file__).resolve().parents[1] / "surfaces"
WEDGE = ["--alpha", "5.71059", "--beta", "26.5651", "--mu-alpha", "0.15", "--mu-beta", "0.15"]
TWO_NODE = SURF / "two-node-spec.toml"


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """A 48 x 40 height map (.npy, metres, 1 um pixels): smooth random, rms slope ~0.1."""
    rng = np.random.default_rng(7)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(48), np.fft.fftfreq(40), indexing="ij"))
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((48, 40))) * np.exp(-(q * 10) ** 2)))
    z *= 0.1e-6 / np.abs(np.diff(z, axis=0)).mean()
    path = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(path, z)
    return path, z


def files(path, *more):
    return [str(path), "--unit", "m", "--pixel-size", "1e-6", "--mu", "0.15", *more]


def test_one_pressure_adds_the_contact_block(scan, capsys):
    path, z = scan
    area = run_json(capsys, "derive", *files(path))
    d = run_json(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "5e6"))
    c = d["elastic_contact"]
    ref = solve_contact(z - 0.0, 1e-6, 1e9, 5e6, boundary="periodic").to_dict()
    assert set(c) == set(ref)                    # the keys of `asperity contact --json`
    assert c["boundary"] == "free" and c["E_star_Pa"] == 1e9 and c["hardness_Pa"] is None
    assert c["pressure_Pa"] == pytest.approx(5e6, rel=1e-12) and c["converged"]
    assert 0 < c["area_fraction"] < 0.5
    assert abs(d["mu_a_plus"] - area["mu_a_plus"]) > 1e-3      # the weighting matters
    assert d["n_facets"] < area["n_facets"]                     # facets out of contact: none
    code, out, _ = run(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "5e6",
                                                 "--boundary", "periodic", "--hardness", "1e8"))
    assert code == 0
    assert "frictionless elastic contact" in out and "facet law is unchanged" in out
    assert "hardness 1e+08 Pa" in out and "boundary periodic" in out
    assert "of the surface at the hardness (plastic)" in out
    assert "sliding redistributes the load" in out


def test_several_pressures_make_a_law_family(scan, capsys, tmp_path):
    path, _ = scan
    png = tmp_path / "family.png"
    fam = run_json(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "1e6", "5e6",
                                             "2e7", "--directions", "36", "--plot", png))
    assert fam["family"] == "pressure" and fam["pressures_Pa"] == [1e6, 5e6, 2e7]
    assert fam["E_star_Pa"] == 1e9 and fam["boundary"] == "free"
    assert len(fam["summary"]) == len(fam["members"]) == 3
    fractions = [m["elastic_contact"]["area_fraction"] for m in fam["members"]]
    assert fractions == sorted(fractions) and fractions[0] < fractions[-1]
    for p, row, m in zip(fam["pressures_Pa"], fam["summary"], fam["members"]):
        assert m["elastic_contact"]["pressure_Pa"] == pytest.approx(p, rel=1e-12)
        assert row["mu_a_plus"] == m["mu_a_minus" if row["axes_reversed"] else "mu_a_plus"] \
            and row["area_fraction"] == \
            m["elastic_contact"]["area_fraction"]
        assert len(m["directions"]) == 36
    one = run_json(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "5e6",
                                             "--directions", "36"))
    assert fam["members"][1]["mu_a_plus"] == pytest.approx(one["mu_a_plus"], rel=1e-6)
    assert png.stat().st_size > 10_000
    code, out, _ = run(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "1e6",
                                                 "5e6"))
    assert code == 0 and "law family over 2 pressures" in out and "p/E*" in out


def test_wedge_texture_is_periodic_by_construction(capsys):
    d = run_json(capsys, "derive", *WEDGE, "--elastic", "1e9", "--pressure", "1e7")
    assert d["elastic_contact"]["boundary"] == "periodic"
    assert d["elastic_contact"]["area_fraction"] == pytest.approx(0.132, rel=0.03)
    assert d["mu_a_plus"] == pytest.approx(0.15724, abs=2e-3)
    code, _, err = run(capsys, "derive", *WEDGE, "--elastic", "1e9", "--pressure", "1e7",
                       "--boundary", "free")
    assert code == 1 and "periodic" in err and len(err.strip().splitlines()) == 1


def test_fit_records_the_contact_in_the_gauge_source(scan, capsys, tmp_path):
    path, _ = scan
    gauge = tmp_path / "g.json"
    run_json(capsys, "fit", *files(path, "--elastic", "1e9", "--pressure", "5e6", "-o", gauge,
                                   "--directions", "72"))
    src = json.loads(gauge.read_text())["source"]
    assert src["elastic_contact"]["pressure_Pa"] == pytest.approx(5e6)
    bad = tmp_path / "h.json"                   # a family must be increasing
    code, _, err = run(capsys, "fit", *files(path, "--elastic", "1e9", "--pressure", "5e6",
                                             "1e6", "-o", bad))
    assert code == 1 and "strictly increasing" in err and not bad.exists()


def test_risk_takes_the_weighted_friction(capsys, tmp_path):
    asm = TWO_NODE
    out = run_json(capsys, "risk", str(asm), *WEDGE, "--elastic", "1e9", "--pressure", "1e7")
    assert out["friction"]["elastic_contact"]["pressure_Pa"] == pytest.approx(1e7)
    assert out["mu_plus"] == pytest.approx(0.15724, abs=2e-3)
    code, text, _ = run(capsys, "risk", str(asm), *WEDGE, "--elastic", "1e9", "--pressure",
                        "1e7")
    assert code == 0 and "elastic contact: p = 1e+07 Pa" in text
    for extra, words in ((["--elastic", "1e9", "--pressure", "1e7"], "texture or surface"),
                         ([*WEDGE, "--elastic", "1e9", "--pressure", "1e7", "--map",
                           "alpha=5:10:2", "beta=5:10:2"], "--map"),
                         ([*WEDGE, "--elastic", "1e9", "--pressure", "1e6", "1e7"], "family")):
        code, _, err = run(capsys, "risk", str(asm), *extra)
        assert code == 1 and words in err and len(err.strip().splitlines()) == 1


BAD = [
    (["--pressure", "0"], "--pressure must be in (0, inf) Pa, got 0"),
    (["--pressure=-1e6"], "--pressure must be in (0, inf) Pa, got -1e+06"),
    (["--pressure", "nan"], "--pressure must be in (0, inf) Pa, got NaN"),
    (["--pressure", "inf"], "--pressure must be a finite number"),
    (["--pressure", "1e6", "0"], "--pressure must be in (0, inf) Pa, got 0"),
    (["--pressure", "1e11"], "--pressure / --elastic must be in"),
    (["--elastic", "0"], "--elastic must be in [1, 1e+13] Pa, got 0"),
    (["--elastic=-2e9"], "--elastic must be in [1, 1e+13] Pa"),
    (["--elastic", "nan"], "--elastic must be in [1, 1e+13] Pa, got NaN"),
    (["--elastic", "inf"], "--elastic must be a finite number"),
    (["--hardness", "1e5"], "--hardness must be in (1e+06, inf) Pa"),
    (["--hardness", "nan"], "--hardness must be in"),
    (["--hardness=-1"], "--hardness must be in"),
]


@pytest.mark.parametrize("command", ["derive", "fit", "risk"])
@pytest.mark.parametrize("flags,words", BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_values_are_one_line_exit_1_nothing_written(scan, capsys, tmp_path, command,
                                                       flags, words):
    path, _ = scan
    base = {"elastic": ["--elastic", "1e9"], "pressure": ["--pressure", "1e6"]}
    for f in flags:
        base.pop(f.lstrip("-").split("=")[0], None)
    plot = tmp_path / "p.png"
    asm = [TWO_NODE] if command == "risk" else []
    argv = [str(path), *asm, *files(path)[1:], *base.get("elastic", []),
            *base.get("pressure", []), *flags]
    code, out, err = run(capsys, command, *argv, "--plot", plot)
    assert code == 1, (out, err)
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not plot.exists() and not list(tmp_path.glob(".*part"))


USAGE = [
    (["--pressure", "1e6"], "--pressure needs --elastic"),
    (["--boundary", "free"], "--boundary needs --elastic"),
    (["--hardness", "1e7"], "--hardness needs --elastic"),
    (["--elastic", "1e9"], "--elastic needs --pressure"),
    (["--elastic", "1e9", "--pressure", "1e6", "--rest-level", "0"], "not with --rest-level"),
    (["--elastic", "1e9", "--pressure", "1e6", "--bearing-fraction", "0.5"],
     "not with --bearing-fraction"),
    (["--elastic", "1e9", "--pressure", "1e6", "--tile-rows", "10"], "not with --tile-rows"),
    (["--elastic", "1e9", "--pressure", "1e6", "--workers", "2"], "not with --workers"),
    (["--elastic", "1e9", "--pressure", *["1e6"] * 101], "--pressure (number of values)"),
]


@pytest.mark.parametrize("flags,words", USAGE, ids=[" ".join(b[0][:4]) for b in USAGE])
def test_inconsistent_flags_are_one_line_exit_1(scan, capsys, tmp_path, flags, words):
    path, _ = scan
    plot = tmp_path / "p.png"
    code, _, err = run(capsys, "derive", *files(path, *flags), "--plot", plot)
    assert code == 1 and words in err and len(err.strip().splitlines()) == 1
    assert not plot.exists()


def test_what_has_no_height_grid_is_refused(capsys, tmp_path):
    """(A mesh is pressed as its upper envelope on a grid: tests/test_contact_mesh.py.)"""
    plot = tmp_path / "p.png"
    for argv, words in (
            ([*WEDGE, "--method", "springs"], "--method springs"),):
        code, _, err = run(capsys, "derive", *argv, "--elastic", "1e9", "--pressure", "1e6",
                           "--plot", plot)
        assert code == 1 and words in err and len(err.strip().splitlines()) == 1
    nan = tmp_path / "nan.npy"
    np.save(nan, np.full((8, 8), np.nan))
    code, _, err = run(capsys, "derive", *files(nan, "--elastic", "1e9", "--pressure", "1e6"),
                       "--plot", plot)
    assert code == 1 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not plot.exists()


def test_a_solve_that_does_not_converge_exits_3_and_writes_nothing(scan, capsys, tmp_path,
                                                                   monkeypatch):
    import asperity.contact.solver as solver
    monkeypatch.setattr(solver, "MAX_ITERATIONS", 2)
    path, _ = scan
    plot = tmp_path / "p.png"
    code, out, err = run(capsys, "derive", *files(path, "--elastic", "1e9", "--pressure", "5e6",
                                                   "--plot", plot))
    assert code == 3 and out == ""
    assert "did not converge at --pressure 5e+06 in 2 iterations (residual" in err
    assert len(err.strip().splitlines()) == 1 and not plot.exists()
