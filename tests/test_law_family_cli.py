"""Law families on the command line (issue 19): fit with several --pressure values writes a
version-2 gauge file; law exports it member by member or takes it at --pressure; risk takes
it at the assembly's contact pressure (strip p, two-node N / contact_area) and says so;
slide takes it at --pressure.  Bad inputs: one line, exit 1, nothing written."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json
from test_law_family import smooth_random, synthetic, wedge_law

from asperity.laws.family import GaugeFamily
from asperity.laws.gauge_file import read_gauge, write_gauge
from asperity.microslip.friction import friction_from_gauge

SURF = Path(__file__).resolve().parents[1] / "surfaces"
WEDGE = ["--alpha", "5.71059", "--beta", "26.5651", "--mu-alpha", "0.15", "--mu-beta", "0.15"]
P0, P1 = 1e6, 1e8


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    path = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(path, smooth_random(48, 40, 7))
    return path


def files(path, *more):
    return [str(path), "--unit", "m", "--pixel-size", "1e-6", "--mu", "0.15", *more]


@pytest.fixture(scope="module")
def strong(tmp_path_factory):
    """A family whose members differ strongly: a symmetric wedge's law at P0, an asymmetric
    one's at P1 (star laws), written as a version-2 file."""
    fam = synthetic([wedge_law(10, 10, "star", mu=(0.1, 0.1)),
                     wedge_law(5.71059, 26.5651, "star", mu=(0.05, 0.3))], (P0, P1))
    path = tmp_path_factory.mktemp("fam") / "fam.json"
    write_gauge(path, fam)
    return path, fam


def assembly(folder, text_p, gauge=None, model="strip", extra=""):
    """The shipped strip (or two-node) assembly with its friction from ``gauge`` (or
    explicit coefficients) and its contact pressure replaced."""
    src = (SURF / ("bushing-strip.toml" if model == "strip" else "two-node-spec.toml"))
    lines = []
    for line in src.read_text().splitlines():
        key = line.split("=")[0].strip()
        if model == "strip" and key == "p":
            line = f"p = {text_p}"
        if model != "strip" and key == "N":
            line = f"N = 100.0\n{extra}"
        if key in ("texture", "mu_plus", "mu_minus", "slip_axis_deg", "textured"):
            continue
        if line.strip() == "[friction]":
            line += "\n" + (f'gauge = "{gauge}"\nslip_axis_deg = 0.0' if gauge else
                            "mu_plus = {mu_plus}\nmu_minus = {mu_minus}")
        lines.append(line)
    path = folder / f"asm-{model}-{len(list(folder.glob('asm-*')))}.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


# ----------------------------------------------------------------------------- fit, law

def test_fit_with_several_pressures_writes_the_family(scan, capsys, tmp_path):
    gauge, plot = tmp_path / "fam.json", tmp_path / "fam.png"
    out = run_json(capsys, "fit", *files(scan, "--elastic", "1e9", "--pressure", "1e6", "5e6",
                                         "2e7", "--directions", "72", "-o", gauge,
                                         "--plot", plot))
    assert out["family"]["pressures_Pa"] == [1e6, 5e6, 2e7] and out["output"] == str(gauge)
    fam = read_gauge(gauge)
    assert isinstance(fam, GaugeFamily) and json.loads(gauge.read_text())["version"] == 2
    for p, m, gl in zip(fam.pressures, out["members"], fam.members):
        assert m["pressure_Pa"] == p and m["contact"]["pressure_Pa"] == pytest.approx(p)
        assert m["fit"]["admissible"] and m["fit"]["n_points"] == 72
        t = gl.force(np.radians(gl.principal_direction_deg) + np.array([0, math.pi]))
        assert m["axes"]["mu_a_plus"] == pytest.approx(t.tangential[0], rel=1e-12)
        assert m["axes"]["mu_a_minus"] == pytest.approx(t.tangential[1], rel=1e-12)
    assert plot.stat().st_size > 10_000
    code, text, _ = run(capsys, "fit", *files(scan, "--elastic", "1e9", "--pressure", "1e6",
                                              "2e7", "--directions", "72"))
    assert code == 0 and "law family: 2 star laws" in text and "hardness" in text


def test_law_exports_every_member_or_the_law_at_a_pressure(strong, capsys, tmp_path):
    path, fam = strong
    csv, inp = tmp_path / "f.csv", tmp_path / "f.inp"
    code, text, err = run(capsys, "law", path, "--csv", csv, "--abaqus", inp,
                          "--csv-directions", "8")
    assert code == 0 and "law family: 2 star laws" in text
    rows = csv.read_text().splitlines()
    assert rows[0] == "pressure_Pa,psi_deg,p_a,p_b" and len(rows) == 1 + 2 * 8
    assert [float(r.split(",")[0]) for r in rows[1:]] == [P0] * 8 + [P1] * 8
    assert inp.read_text().count("*FRICTION, ANISOTROPIC") == 2
    assert "member 1: nominal contact pressure 1e+08 Pa" in inp.read_text()
    p = 1e7
    obj = run_json(capsys, "law", path, "--pressure", p, "--psi", 30)
    f = fam.at(p).force(np.radians([30.0]))
    assert obj["p"] == pytest.approx(f.p[0].tolist(), rel=1e-12)
    assert obj["family_pressure"] == {"pressure_Pa": p, "interpolated": True,
                                      "members_Pa": [P0, P1]}
    code, text, _ = run(capsys, "law", path, "--pressure", p)
    assert code == 0 and "interpolated linearly in ln p between its members" in text


# ----------------------------------------------------------------------------- risk

def _explicit(tmp_path, law, p):
    f = friction_from_gauge(law, 0.0)
    text = assembly(tmp_path, p).read_text()
    path = tmp_path / "explicit.toml"
    path.write_text(text.replace("{mu_plus}", repr(f.mu_plus))
                    .replace("{mu_minus}", repr(f.mu_minus)))
    return path


@pytest.mark.parametrize("p", [P0, 1e7, P1])
def test_risk_takes_the_family_at_the_assemblys_pressure(strong, capsys, tmp_path, p):
    path, fam = strong
    out = run_json(capsys, "risk", assembly(tmp_path, p, path))
    ref = run_json(capsys, "risk", _explicit(tmp_path, fam.at(p), p))
    assert out["friction"]["contact_pressure"]["pressure_Pa"] == p
    assert out["friction"]["contact_pressure"]["from"] == "assembly.p"
    assert out["friction"]["contact_pressure"]["interpolated"] == (p == 1e7)
    for k in ("mu_plus", "mu_minus", "verdict", "drift_per_cycle_m", "dT_c_K"):
        assert out[k] == ref[k]
    code, text, _ = run(capsys, "risk", assembly(tmp_path, p, path))
    assert code == 0 and f"contact pressure {p:g} Pa (assembly.p): law family taken at" in text


def test_the_verdict_follows_the_member_at_the_assemblys_pressure(strong, capsys, tmp_path):
    """The two-node model's mechanics do not depend on its contact area: only the law the
    pressure N / contact_area picks changes the verdict."""
    path, fam = strong
    light = run_json(capsys, "risk", assembly(tmp_path, None, path, "two-node",
                                              f"contact_area = {100.0 / P0!r}"))
    heavy = run_json(capsys, "risk", assembly(tmp_path, None, path, "two-node",
                                              f"contact_area = {100.0 / P1!r}"))
    assert light["mu_plus"] == pytest.approx(light["mu_minus"], rel=1e-9)   # symmetric wedge
    assert (light["verdict"], heavy["verdict"]) == ("alternating-slip", "ratchet")
    for out, law in ((light, fam.members[0]), (heavy, fam.members[1])):
        f = friction_from_gauge(law, 0.0)
        assert (out["mu_plus"], out["mu_minus"]) == (f.mu_plus, f.mu_minus)


def test_two_node_pressure_is_N_over_its_contact_area(strong, capsys, tmp_path):
    path, fam = strong
    out = run_json(capsys, "risk", assembly(tmp_path, None, path, "two-node",
                                            "contact_area = 1e-5"))
    cp = out["friction"]["contact_pressure"]
    assert cp["pressure_Pa"] == pytest.approx(100.0 / 1e-5, rel=1e-12)
    assert cp["from"] == "assembly.N / assembly.contact_area" and cp["interpolated"]
    assert out["mu_plus"] == friction_from_gauge(fam.at(1e7), 0.0).mu_plus
    assert out["assembly"]["contact_area"] == 1e-5


def test_a_single_law_fitted_at_another_pressure_is_used_with_a_note(strong, capsys,
                                                                       tmp_path):
    _, fam = strong
    one = tmp_path / "one.json"
    write_gauge(one, fam.members[0])                 # version 1, fitted at P0
    out = run_json(capsys, "risk", assembly(tmp_path, 1e7, one.name))
    cp = out["friction"]["contact_pressure"]
    assert cp["law_pressure_Pa"] == P0 and cp["pressure_Pa"] == 1e7
    assert "derived at p = 1e+06 Pa, not at the assembly's 1e+07 Pa" in cp["note"]
    assert out["mu_plus"] == friction_from_gauge(fam.members[0], 0.0).mu_plus
    same = run_json(capsys, "risk", assembly(tmp_path, P0, one.name))
    assert "contact_pressure" not in same["friction"]


def test_risk_elastic_without_pressure_solves_at_the_assemblys(capsys, tmp_path):
    asm = SURF / "bushing-strip.toml"                           # p = 5e6 Pa
    a = run_json(capsys, "risk", asm, *WEDGE, "--elastic", "1e9")
    b = run_json(capsys, "risk", asm, *WEDGE, "--elastic", "1e9", "--pressure", "5e6")
    assert a["friction"]["elastic_contact"]["pressure_Pa"] == pytest.approx(5e6)
    assert a["mu_plus"] == b["mu_plus"] and a["mu_minus"] == b["mu_minus"]
    assert a["friction"]["contact_pressure"] == {"pressure_Pa": 5e6, "from": "assembly.p",
                                                 "solved": True}
    assert "note" not in b["friction"]["contact_pressure"]
    c = run_json(capsys, "risk", asm, *WEDGE, "--elastic", "1e9", "--pressure", "2e7")
    assert "not the assembly's contact pressure 5e+06 Pa" in c["friction"]["contact_pressure"][
        "note"]
    assert c["friction"]["elastic_contact"]["pressure_Pa"] == pytest.approx(2e7)


# ----------------------------------------------------------------------------- slide

def test_slide_with_a_family_is_slide_with_its_law_at_the_pressure(strong, capsys, tmp_path):
    path, fam = strong
    common = ["--u0", "1", "--angle", "30", "--dt", "1e-3"]
    for p in (P1, 1e7):
        one = tmp_path / f"one-{p:g}.json"
        write_gauge(one, fam.at(p))
        a = run_json(capsys, "slide", path, "--pressure", p, *common)
        b = run_json(capsys, "slide", one, *common)
        assert a["rest"] == b["rest"] and a["stop_time"] == b["stop_time"]
        assert a["family_pressure"]["pressure_Pa"] == p
    code, text, _ = run(capsys, "slide", path, "--pressure", 1e7, *common)
    assert code == 0 and "law family taken at p = 1e+07 Pa (interpolated" in text
    low = run_json(capsys, "slide", path, "--pressure", P0, *common)
    assert low["rest"] != a["rest"]                     # the members differ


# ----------------------------------------------------------------------------- bad input

def _bad(strong, tmp_path):
    path, _ = strong
    v1 = tmp_path / "v1.json"
    write_gauge(v1, wedge_law(10, 10, "star"))
    slide = ["--u0", "1", "--angle", "0"]
    return [
        (["slide", path, *slide], "give --pressure"),
        (["slide", path, *slide, "--pressure", "1e9"], "--pressure 1e+09 Pa is outside"),
        (["slide", path, *slide, "--pressure", "0"], "--pressure must be in (0, inf) Pa"),
        (["slide", path, *slide, "--pressure", "nan"], "--pressure must be in (0, inf) Pa"),
        (["slide", v1, *slide, "--pressure", "1e7"], "--pressure applies to a law family"),
        (["slide", "--mu1", "0.2", *slide, "--pressure", "1e7"], "built-in laws"),
        (["law", path, "--psi", "10"], "--psi needs --pressure"),
        (["law", path, "--pressure", "1e5"], "outside the law family's pressures"),
        (["law", v1, "--pressure", "1e7"], "--pressure applies to a law family"),
        (["risk", assembly(tmp_path, 1e9, path)], "assembly.p 1e+09 Pa is outside"),
        (["risk", assembly(tmp_path, None, path, "two-node")], "add assembly.contact_area"),
        (["risk", assembly(tmp_path, None, path, "two-node", "contact_area = 0")],
         "assembly.contact_area must be in [1e-12, 1e+06] m^2"),
        (["risk", assembly(tmp_path, None, path, "two-node", "contact_area = 'x'")],
         "assembly.contact_area"),
        (["risk", SURF / "two-node-spec.toml", *WEDGE, "--elastic", "1e9"],
         "add assembly.contact_area"),
        (["risk", SURF / "bushing-strip.toml", *WEDGE, "--elastic", "1e9", "--pressure",
          "1e6", "2e6"], "family"),
    ]


def test_bad_inputs_are_one_line_exit_1_nothing_written(strong, capsys, tmp_path, scan):
    cases = _bad(strong, tmp_path)
    out = tmp_path / "out.png"
    for argv, words in cases:
        extra = {"slide": ["--csv", out], "law": ["--csv", out], "risk": ["--plot", out]}
        code, _, err = run(capsys, *argv, *extra[argv[0]])
        assert code == 1, (argv, err)
        assert words in err and len(err.strip().splitlines()) == 1, (argv, err)
        assert "Traceback" not in err and not out.exists()
    gauge = tmp_path / "g.json"
    for ps in (["5e6", "1e6"], ["1e6", "1e6"]):
        code, _, err = run(capsys, "fit", *files(scan, "--elastic", "1e9", "--pressure", *ps,
                                                 "-o", gauge))
        assert code == 1 and "strictly increasing" in err and not gauge.exists()
        assert len(err.strip().splitlines()) == 1
