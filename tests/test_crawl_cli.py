"""``asperity crawl`` from the command line: its JSON, CSV and plot, the law sources, and
one-line refusals of bad input (exit 1 for a bad value, 2 for an unparsable line)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "asperity", "crawl", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=300)


def test_json_csv_and_plot(tmp_path):
    csv, png = tmp_path / "path.csv", tmp_path / "crawl.png"
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--points", 40, "--periods", 2,
            "--dt", 0.01, "--json", "--csv", csv, "--plot", png)
    assert p.returncode == 0, p.stderr
    obj = json.loads(p.stdout)
    for key in ("speed_body_lengths_per_period", "speed_per_period",
                "heading_drift_rad_per_period", "cost_of_transport", "froude", "rule",
                "quasi_static", "points", "periods"):
        assert key in obj
    assert obj["rule"] == "componentwise" and obj["quasi_static"] is False
    assert obj["points"] == 40 and obj["periods"] == 2 and len(obj["speed_per_period"]) == 2
    assert obj["steps_per_period"] == 100
    lines = csv.read_text().splitlines()
    assert lines[0] == "t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s"
    last = [float(v) for v in lines[-1].split(",")]
    assert last[0] == pytest.approx(2.0) and last[1] == pytest.approx(obj["final_state"]["x_m"])
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_rules_differ_and_are_named():
    speeds = {}
    for rule in ("componentwise", "associated", "colinear"):
        p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--rule", rule,
                "--quasi-static", "--points", 40, "--json")
        assert p.returncode == 0, p.stderr
        obj = json.loads(p.stdout)
        assert obj["rule"] == rule
        speeds[rule] = obj["speed_body_lengths_per_period"]
    assert speeds["associated"] > speeds["componentwise"] > speeds["colinear"] > 0
    assert speeds["associated"] / speeds["colinear"] > 5


def test_gauge_file_and_texture_on_the_ground(tmp_path):
    gauge = tmp_path / "cw.json"
    p = subprocess.run([sys.executable, "-m", "asperity", "law", "--mu-f", "0.1", "--mu-b",
                        "0.15", "--mu-t", "0.2", "-o", str(gauge)], capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    a = json.loads(run(gauge, "--quasi-static", "--points", 40, "--json").stdout)
    b = json.loads(run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--quasi-static",
                       "--points", 40, "--json").stdout)
    assert a["speed_body_lengths_per_period"] == pytest.approx(
        b["speed_body_lengths_per_period"], rel=1e-6)
    g = json.loads(run(gauge, "--quasi-static", "--points", 40, "--texture-on", "ground",
                       "--texture-angle", 90, "--json").stdout)
    assert g["texture_on"] == "ground" and g["texture_angle_deg"] == 90


def test_texture_file_is_fitted_on_the_fly():
    p = run(ROOT / "surfaces" / "wedge-asymmetric.toml", "--quasi-static", "--points", 40,
            "--json")
    assert p.returncode == 0, p.stderr
    obj = json.loads(p.stdout)
    assert obj["rule"] == "walker-leine" and obj["status"] == "ok"
    assert abs(obj["speed_body_lengths_per_period"]) < 1.0


@pytest.mark.parametrize("args,words", [
    (("--mu-f", 0.1, "--mu-b", 0.15), "--mu-t"),
    (("--mu-f", "nan", "--mu-b", 0.15, "--mu-t", 0.2), "--mu-f"),
    (("--mu-f", -0.1, "--mu-b", 0.15, "--mu-t", 0.2), "--mu-f"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--points", 2), "--points"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--points", 2.5), "--points"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--periods", 0), "--periods"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--amplitude", "inf"), "--amplitude"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--waves", 0), "--waves"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--length", -1), "--length"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--period", 0), "--period"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gravity", 0), "--gravity"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--texture-angle", 400), "--texture-angle"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--dt", 0.5), "--dt"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--points", "1e5", "--periods", "1e5"),
     "steps"),
    (("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--amplitude", 30), "crosses itself"),
    ((), "no law"),
])
def test_bad_input_is_one_line_exit_1(args, words, tmp_path):
    out = tmp_path / "x.csv"
    p = run(*args, "--csv", out)
    assert p.returncode == 1, (p.returncode, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and words in lines[0], p.stderr
    assert "Traceback" not in p.stderr and not out.exists()


@pytest.mark.parametrize("args,code", [(("--rule", "sideways"), 1), (("--texture-on", "wall"), 1),
                                       (("--quasi-static", "--gravity", "9.81"), 2),
                                       (("--points",), 2)])
def test_unknown_choices_exit_1_and_unparsable_lines_exit_2(args, code):
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, *args)
    assert p.returncode == code and "Traceback" not in p.stderr
    assert len(p.stderr.strip().splitlines()) <= 2


def test_help():
    p = run("--help")
    assert p.returncode == 0 and "--quasi-static" in p.stdout and "--rule" in p.stdout


@pytest.mark.parametrize("name", ["robot-joints.toml", "wave-turning.toml"])
def test_shipped_gait_files_crawl(name):
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gait",
            ROOT / "surfaces" / "gaits" / name, "--quasi-static", "--points", 40, "--json")
    assert p.returncode == 0, p.stderr
    obj = json.loads(p.stdout)
    assert obj["speed_body_lengths_per_period"] > 0.02 and obj["status"] == "ok"
    assert obj["gait"]["kind"] in ("joints", "fourier")


def test_gait_file_refusals(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[gait]\nkind = "fourier"\nlength = 1.0\nperiod = 1.0\n'
                   '[[gait.terms]]\nm = 1\nn = 1\ncos = 300.0\nsin = 0.0\n')
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gait", bad)
    assert p.returncode == 1 and "gait.terms[0].cos" in p.stderr, p.stderr
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gait", bad, "--amplitude", 3)
    assert p.returncode == 1 and "--amplitude does not apply with --gait" in p.stderr


def test_a_step_without_solution_stops_the_run_with_exit_3(tmp_path):
    """A step the solver cannot balance (a nearly straight body of three waves, A = 0.5: a
    known limit, in the README): exit 3, the step and time named, finite JSON (speed null:
    no period was completed), the plot still drawn."""
    png = tmp_path / "c.png"
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--quasi-static", "--points", 60,
            "--dt", 0.01, "--amplitude", 0.5, "--waves", 3, "--json", "--plot", png)
    assert p.returncode == 3, p.stderr
    obj = json.loads(p.stdout)
    assert obj["status"] == "not-converged" and "the run stops there" in obj["message"]
    assert obj["speed_body_lengths_per_period"] is None and obj["speed_per_period"] == []
    assert "did not converge at step" in p.stderr
    assert png.exists()


def test_serpenoid_file_crawls_as_its_sampled_joint_table():
    """surfaces/gaits/robot-serpenoid.toml (a = 40 deg, b = -360/7 deg) and
    robot-joints.toml (the same serpenoid sampled at 16 instants, a periodic spline between
    them) crawl alike: to the spline's error, 1e-4."""
    out = {}
    for name in ("robot-serpenoid.toml", "robot-joints.toml"):
        p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gait",
                ROOT / "surfaces" / "gaits" / name, "--quasi-static", "--points", 64, "--json")
        assert p.returncode == 0, p.stderr
        out[name] = json.loads(p.stdout)
    a, b = (out[n]["speed_body_lengths_per_period"] for n in sorted(out))
    assert a > 0.05 and a == pytest.approx(b, rel=1e-4)
    assert out["robot-serpenoid.toml"]["gait"]["kind"] == "serpenoid"


@pytest.mark.parametrize("body,words", [
    ('links = 8\namplitude = 40.0\n', "gait.phase"),
    ('links = 8\namplitude = 400.0\nphase = -50.0\nunit = "deg"\n', "gait.amplitude"),
    ('links = 1\namplitude = 0.5\nphase = -0.9\n', "gait.links"),
    ('links = 8\namplitude = 0.5\nphase = -0.9\nunit = "grad"\n', "gait.unit"),
    ('links = 8\namplitude = 0.5\nphase = -0.9\nangles = [[0.0]]\n', "angles"),
])
def test_serpenoid_file_refusals(tmp_path, body, words):
    f = tmp_path / "s.toml"
    f.write_text('[gait]\nkind = "serpenoid"\nlength = 1.0\nperiod = 1.0\n' + body)
    p = run("--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2, "--gait", f, "--quasi-static")
    assert p.returncode == 1 and words in p.stderr and len(p.stderr.splitlines()) == 1, p.stderr


def test_texture_flags_surface_flags_and_contact_reach_the_fitted_law(tmp_path):
    """The wedge flags make the texture the same file does; a mesh needs --unit (named);
    --contact windward fits another law than all-faces."""
    base = ("--quasi-static", "--points", 40, "--json")
    f = json.loads(run(ROOT / "surfaces" / "wedge-asymmetric.toml", *base).stdout)
    import tomllib
    spec = tomllib.loads((ROOT / "surfaces" / "wedge-asymmetric.toml").read_text())
    w = spec["texture"]
    flags = ["--alpha", w["alpha_deg"], "--beta", w["beta_deg"], "--mu-alpha", w["mu_alpha"],
             "--mu-beta", w["mu_beta"]]
    g = json.loads(run(*flags, *base).stdout)
    assert g["speed_body_lengths_per_period"] == pytest.approx(
        f["speed_body_lengths_per_period"], rel=1e-9)
    p = run(ROOT / "surfaces" / "wedge-30-10.stl", *base)
    assert p.returncode == 1 and "--unit" in p.stderr
    m = json.loads(run(ROOT / "surfaces" / "wedge-30-10.stl", "--unit", "mm", *base).stdout)
    assert "mesh" in m["law"] and m["status"] == "ok"
    wind = json.loads(run(ROOT / "surfaces" / "wedge-asymmetric.toml", "--contact",
                          "windward", *base).stdout)
    assert "windward" in wind["law"]
    assert wind["speed_body_lengths_per_period"] != pytest.approx(
        f["speed_body_lengths_per_period"], rel=1e-3)
    p = run(ROOT / "surfaces" / "wedge-asymmetric.toml", "--mu-f", 0.1)
    assert p.returncode == 1 and "do not apply" in p.stderr


def test_fit_law_ellipse_fits_the_truncated_ellipse():
    base = (ROOT / "surfaces" / "wedge-asymmetric.toml", "--quasi-static", "--points", 40,
            "--json")
    star = json.loads(run(*base).stdout)
    ell = json.loads(run(*base, "--fit-law", "ellipse").stdout)
    assert "star" in star["law"] and "ellipse" in ell["law"]
    assert ell["rule"] == "associated" and star["rule"] == "walker-leine"
