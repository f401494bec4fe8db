"""Studies with an elastic contact (issue 19, item 5): a [contact] table and the
contact.pressure / contact.E_star / contact.hardness parameters.  Each case equals
``derive --elastic E --pressure P`` at its values; a scan library runs every file at every
point of the contact grid; the fingerprint follows the pressures; bad values are refused
in one line naming the key."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json
from test_study_cases import table

from asperity.study.run import run_study_file
from asperity.study.spec import load_study

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
WEDGE = '[texture]\nkind = "wedge"\nalpha_deg = 20.0\nbeta_deg = 8.0\nmu_alpha = 0.12\n' \
        'mu_beta = 0.2\n'


def write(tmp_path: Path, body: str, name: str = "s.toml") -> Path:
    p = tmp_path / name
    p.write_text(body)
    return p


@pytest.fixture(scope="module")
def scans(tmp_path_factory):
    d = tmp_path_factory.mktemp("lib")
    rng = np.random.default_rng(4)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(40), np.fft.fftfreq(36), indexing="ij"))
    for i in range(2):
        z = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((40, 36)))
                                 * np.exp(-(q * (6 + 4 * i)) ** 2)))
        z *= 0.1 / np.abs(np.diff(z, axis=0)).mean()          # um, 1 um pixels
        np.save(d / f"scan{i}.npy", z)
    return d


LIBRARY = """
[study]
kind = "files"
files = ["scan*.npy"]
unit = "um"
pixel_size = 1.0
mu = 0.15
stages = ["derive"]
directions = 24

[contact]
E_star = 1.0e9
{more}

[parameters]
"contact.pressure" = {{ values = [{pressures}] }}
"""


def test_a_library_over_pressures_equals_derive_elastic_at_each(scans, capsys):
    study = write(scans, LIBRARY.format(more="", pressures="1.0e6, 5.0e6"))
    s = run_study_file(study, scans / "out", workers=0, plot=True)
    got = table(scans / "out")
    assert [(Path(r["file"]).name, r["contact.pressure"]) for r in got] == [
        ("scan0.npy", 1e6), ("scan0.npy", 5e6), ("scan1.npy", 1e6), ("scan1.npy", 5e6)]
    for r in got:
        assert r["status"] == "ok", r["message"]
        d = run_json(capsys, "derive", r["file"], "--unit", "um", "--pixel-size", "1",
                     "--mu", "0.15", "--directions", "24", "--elastic", "1e9",
                     "--pressure", repr(r["contact.pressure"]))
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus",
                  "principal_direction_deg", "anisotropy"):
            assert r[k] == d[k]
        assert r["contact_area_fraction"] == d["elastic_contact"]["area_fraction"]
        assert r["pressure_Pa"] == d["elastic_contact"]["pressure_Pa"]
        assert r["E_star_Pa"] == 1e9
    fr = [r["contact_area_fraction"] for r in got]
    assert 0 < fr[0] < fr[1] < 1 and 0 < fr[2] < fr[3] < 1        # more load, more contact
    rows = s["load_dependence"]
    assert [(Path(r["file"]).name, r["pressure_Pa"]) for r in rows] == \
        [(Path(r["file"]).name, r["pressure_Pa"]) for r in got]
    assert rows[1]["p_over_E_star"] == pytest.approx(5e-3, rel=1e-6)
    assert any(f.endswith("load.png") for f in s["figures"]) and (scans / "out" / "load.png").stat().st_size > 1000
    code, out, _ = run(capsys, "study", str(scans / "out"))
    assert code == 0 and "load dependence (elastic contact):" in out


def test_a_grid_over_pressure_and_modulus_of_a_wedge_equals_derive_elastic(tmp_path, capsys):
    study = write(tmp_path, WEDGE + """
[study]
kind = "grid"
stages = ["derive"]
directions = 24

[contact]
pressure = 2.0e6
hardness = 1.0e9

[parameters]
"contact.E_star" = { values = [5.0e8, 2.0e9] }
"contact.pressure" = { values = [1.0e6, 4.0e6] }
""")
    run_study_file(study, tmp_path / "out", workers=0)
    got = table(tmp_path / "out")
    assert len(got) == 4
    for r in got:
        d = run_json(capsys, "derive", "--alpha", "20", "--beta", "8", "--mu-alpha", "0.12",
                     "--mu-beta", "0.2", "--directions", "24", "--hardness", "1e9",
                     "--elastic", repr(r["contact.E_star"]),
                     "--pressure", repr(r["contact.pressure"]))
        assert r["mu_a_plus"] == d["mu_a_plus"] and r["mu_a_minus"] == d["mu_a_minus"]
        assert r["contact_area_fraction"] == d["elastic_contact"]["area_fraction"]
    # the contact fraction grows with p / E*: (E*, p) = (2e9, 1e6) < (5e8, 1e6) < (5e8, 4e6)
    af = {(r["contact.E_star"], r["contact.pressure"]): r["contact_area_fraction"] for r in got}
    assert af[(2e9, 1e6)] < af[(5e8, 1e6)] < af[(5e8, 4e6)]


def test_the_fingerprint_follows_the_pressures(scans, tmp_path):
    def fp(pressures, more=""):
        return load_study(write(scans, LIBRARY.format(more=more, pressures=pressures),
                                "fp.toml")).fingerprint()
    a = fp("1.0e6, 5.0e6")
    assert fp("1.0e6, 5.0e6") == a
    assert fp("1.0e6, 6.0e6") != a
    assert fp("1.0e6") != a
    assert fp("1.0e6, 5.0e6", "hardness = 1e9") != a
    assert fp("1.0e6, 5.0e6", 'boundary = "periodic"') != a
    st = load_study(write(scans, LIBRARY.format(more="", pressures="1.0e6, 5.0e6, 2e7"),
                          "n.toml"))
    assert st.n_cases == 6 and st.case_files[:3] == (st.files[0],) * 3
    # a study without [contact] keeps its former spec (and fingerprint): no "elastic" key
    plain = load_study(SURF / "texture-library.toml")
    assert "elastic" not in plain.spec


@pytest.mark.parametrize("edit, words", [
    (("pressure = [1e6]", "pressure = -1.0"), "contact.pressure must be"),
    (("E_star = 1.0e9", "E_star = nan"), "contact.E_star must be"),
    (("E_star = 1.0e9", ""), "contact.E_star missing"),
    (("E_star = 1.0e9", "E_star = 1.0e9\nfoo = 1"), "unknown key contact.foo"),
    (("E_star = 1.0e9", 'E_star = 1.0e9\nboundary = "round"'), "contact.boundary must be"),
    (("E_star = 1.0e9", "E_star = 1.0e9\nhardness = 1.0e5"), "contact.hardness must be"),
    (("values = [1e6]", "values = [1e6, -2e6]"), "parameters.contact.pressure must be"),
    (("{ values = [1e6] }", '{ distribution = "normal", mean = 1e6, sd = 1e5 }'),
     "parameters.contact.pressure: a normal distribution reaches values <= 0"),
    (("{ values = [1e6] }", '{ distribution = "uniform", low = 0.0, high = 1e6 }'),
     "parameters.contact.pressure.low must be"),
    (('"contact.pressure"', '"contact.boundary"'), "the contact parameters are"),
    (('"contact.pressure"', '"texture.alpha_deg"'), "kind = \"files\" takes no [parameters]"),
])
def test_bad_contact_values_are_refused_naming_the_key(tmp_path, edit, words, capsys):
    body = """
[study]
kind = "files"
files = ["*.npy"]
unit = "um"
pixel_size = 1.0
stages = ["derive"]

[contact]
E_star = 1.0e9
pressure = [1e6]

[parameters]
"contact.pressure" = { values = [1e6] }
"""
    np.save(tmp_path / "a.npy", np.zeros((20, 20)))
    if "normal" in edit[1] or "uniform" in edit[1]:
        body = body.replace('kind = "files"', 'kind = "monte-carlo"\nsamples = 4').replace(
            'files = ["*.npy"]\nunit = "um"\npixel_size = 1.0\n',
            'texture = "wedge.toml"\n')
        (tmp_path / "wedge.toml").write_text(WEDGE)
    body = body.replace("pressure = [1e6]\n", "")
    if edit[0] == "pressure = [1e6]":
        body = body.replace("E_star = 1.0e9", "E_star = 1.0e9\npressure = -1.0")
    else:
        body = body.replace(*edit)
    study = write(tmp_path, body)
    code, out, err = run(capsys, "study", str(study), "-o", str(tmp_path / "out"),
                         "--workers", "0")
    assert code == 1 and out == ""
    assert words in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "out").exists()


def test_contact_needs_a_texture_or_scans(tmp_path, capsys):
    study = write(tmp_path, f"""
[study]
kind = "grid"
stages = ["risk"]
assembly = "{SURF / 'two-node-spec.toml'}"

[contact]
E_star = 1e9
pressure = 1e6

[parameters]
"loading.dT_max" = {{ values = [60.0, 120.0] }}
""")
    code, _, err = run(capsys, "study", str(study), "-o", str(tmp_path / "out"),
                       "--workers", "0")
    assert code == 1 and "[contact] weighs the faces of a texture or scan" in err


def test_the_study_benchmark_gives_each_case_its_own_file(scans, monkeypatch):
    """A library with a contact grid has several cases per file: the benchmark's serial
    loop must hand case n the file of case n (study.case_files), not study.files[n]."""
    from asperity.study import bench, cases
    study = load_study(write(scans, LIBRARY.format(more="", pressures="1e6, 2e6, 4e6"),
                             "bench.toml"))
    assert study.n_cases == 6 and len(study.files) == 2
    seen = []

    def fake(spec, values, file):
        seen.append((file, values["contact.pressure"]))
        return "ok", "", None, None
    monkeypatch.setattr(cases, "run_case", fake)
    rate, n = bench._loop(study, 60.0)
    assert n == 6
    assert [f for f, _ in seen[1:]] == list(study.case_files)
    assert [p for _, p in seen[1:]] == [float(v) for v in study.matrix()[:, 0]]
    assert len(set(f for f, _ in seen[1:])) == 2
