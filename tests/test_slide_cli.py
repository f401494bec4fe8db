"""asperity slide through the real parser, in-process."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.cli.main import main

SURF = Path(__file__).resolve().parents[1] / "surfaces"
G = 9.81





def slide_json(capsys, *argv):
    return run_json(capsys, "slide", *argv)


@pytest.fixture(scope="module")
def gauges(tmp_path_factory):
    folder = tmp_path_factory.mktemp("gauges")
    out = {}
    for law in ("star", "ellipse"):
        path = folder / f"{law}.json"
        assert main(["fit", str(SURF / "wedge-symmetric-30.toml"), "--contact", "windward",
                     "--law", law, "--directions", "360", "-o", str(path)]) == 0
        out[law] = path
    return out


def test_coulomb_json_keys_and_closed_form(capsys):
    u0, mu, dt = 2.0, 0.3, 1e-4
    d = slide_json(capsys, "--mu1", mu, "--u0", u0, "--angle", 30, "--dt", dt)
    for key in ("rest", "stop_time", "deflection_deg", "steps", "max_iterations_used", "status"):
        assert key in d
    assert d["law"] == "coulomb" and d["status"] == "ok"
    assert 0 <= d["stop_time"] - u0 / (mu * G) < dt
    x, y = d["rest"]
    assert abs(math.hypot(x, y) - u0 ** 2 / (2 * mu * G)) < u0 * dt
    assert abs(math.atan2(y, x) - math.radians(30)) < 1e-12
    assert abs(d["deflection_deg"]) < 1e-9
    assert d["steps"] == round(d["stop_time"] / dt)
    # mu1 = mu2 is Coulomb too, with the same answer bit for bit
    d2 = slide_json(capsys, "--mu1", mu, "--mu2", mu, "--u0", u0, "--angle", 30, "--dt", dt)
    assert d2["law"] == "coulomb" and d2["rest"] == d["rest"]


def test_mass_and_g_scale_as_physics_says(capsys):
    a = slide_json(capsys, "--mu1", 0.5, "--mu2", 0.2, "--u0", 1, "--angle", 50, "--dt", 1e-4)
    b = slide_json(capsys, "--mu1", 0.5, "--mu2", 0.2, "--u0", 1, "--angle", 50, "--dt", 1e-4,
                   "--mass", 7.5)
    np.testing.assert_allclose(b["rest"], a["rest"], rtol=1e-13, err_msg="the mass cancels out")
    c = slide_json(capsys, "--mu1", 0.5, "--mu2", 0.2, "--u0", 1, "--angle", 50, "--dt",
                   1e-4 / 2, "--g", 2 * G)
    np.testing.assert_allclose(c["rest"], np.array(a["rest"]) / 2, rtol=1e-12,
                               err_msg="doubling g and halving dt halves the path")


def test_deflection_sign_per_law(capsys):
    """mu1 > mu2: the ellipse and star laws deflect towards t_b, the collinear law not."""
    out = {}
    for law in ("ellipse", "collinear", "star"):
        out[law] = slide_json(capsys, "--law", law, "--mu1", 0.6, "--mu2", 0.3, "--u0", 2,
                              "--angle", 40, "--dt", 1e-4)["deflection_deg"]
    assert out["ellipse"] > 5 and out["star"] > 5 and abs(out["collinear"]) < 1e-9
    d = slide_json(capsys, "--law", "ellipse", "--mu1", 0.6, "--mu2", 0.3, "--u0", 2,
                   "--angle", -40, "--dt", 1e-4)["deflection_deg"]
    assert d == pytest.approx(-out["ellipse"], abs=1e-9), "mirror symmetry"


def test_gauge_files_drive_the_law(gauges, capsys):
    from asperity.dynamics.moreau import slide
    from asperity.laws import planar as L
    d = slide_json(capsys, gauges["star"], "--u0", 2, "--angle", 45, "--dt", 1e-4)
    assert d["law"] == "star" and d["status"] == "ok" and d["gauge"] == str(gauges["star"])
    r = slide(L.from_gauge(gauges["star"]), 2.0, 45.0, dt=1e-4)
    assert d["rest"] == [float(v) for v in r.q_final]
    # windward: the body ends sliding exactly along the ridges
    assert d["deflection_deg"] > 10
    e = slide_json(capsys, gauges["ellipse"], "--u0", 2, "--angle", 45, "--dt", 1e-4)
    assert e["law"] == "truncated-ellipse" and e["deflection_deg"] > 10
    c = slide_json(capsys, gauges["star"], "--law", "collinear", "--u0", 2, "--angle", 45)
    assert abs(c["deflection_deg"]) < 1e-9


def test_plot_and_csv(tmp_path, capsys):
    png, csv = tmp_path / "p.png", tmp_path / "p.csv"
    code, out, _ = run(capsys, "slide", "--mu1", 0.6, "--mu2", 0.3, "--u0", 2, "--angle", 30,
                       "--plot", png, "--csv", csv)
    assert code == 0 and "rest at" in out and "deflection" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert csv.read_text().splitlines()[0] == "t_s,x_m,y_m,vx_m_s,vy_m_s"
    assert rows[0, 3] == pytest.approx(2 * math.cos(math.radians(30)))
    assert np.all(rows[-1, 3:] == 0) and np.all(np.diff(rows[:, 0]) > 0)
    assert not list(tmp_path.glob(".*part")), "no temporary files left"


def test_t_end_before_the_stop_reports_a_moving_body(capsys):
    d = slide_json(capsys, "--mu1", 0.3, "--u0", 2, "--angle", 0, "--t-end", 0.1, "--dt", 1e-3)
    assert d["rest"] is None and d["stop_time"] is None and d["steps"] == 100
    assert d["final_velocity"][0] == pytest.approx(2 - 0.3 * G * 0.1)


def test_non_convergence_exits_3_with_the_step(capsys):
    code, out, err = run(capsys, "slide", "--law", "star", "--mu1", 0.6, "--mu2", 0.3, "--u0",
                         2, "--angle", 45, "--max-iterations", 1, "--json")
    assert code == 3
    d = json.loads(out)
    assert d["status"] == "not-converged" and d["fail_step"] is not None
    assert "did not converge at step" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("argv,msg", [
    (["--u0", 1, "--angle", 0], "--mu1 is required"),
    (["--mu1", -0.1, "--u0", 1, "--angle", 0], "--mu1 must be in [1e-06, 100]"),
    (["--mu1", 0.3, "--mu2", 0, "--u0", 1, "--angle", 0], "--mu2 must be in [1e-06, 100]"),
    (["--law", "ellipse", "--mu1", 0.3, "--u0", 1, "--angle", 0], "--law ellipse needs --mu2"),
    (["--law", "coulomb", "--mu1", 0.3, "--mu2", 0.2, "--u0", 1, "--angle", 0],
     "--law coulomb is isotropic"),
    (["--mu1", 0.3, "--u0", -1, "--angle", 0], "--u0 must be in [0, 10000]"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 400], "--angle must be in [-360, 360]"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 0, "--dt", 0], "--dt must be in [1e-09, 1] s"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 0, "--mass", "nan"], "--mass must be in"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 0, "--g", 0], "--g must be in [1e-06, 10000] m/s^2"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 0, "--t-end", 1e9, "--dt", 1e-3], "at most 5e+08"),
    (["--mu1", 0.3, "--u0", 1, "--angle", 0, "--max-iterations", 0], "--max-iterations"),
    (["missing.json", "--u0", 1, "--angle", 0], "does not exist"),
])
def test_bad_input_is_one_line_exit_1(capsys, argv, msg):
    code, out, err = run(capsys, "slide", *argv)
    assert code == 1 and msg in err and len(err.strip().splitlines()) == 1, err


def test_gauge_file_conflicts(gauges, capsys):
    for argv, msg in (([gauges["star"], "--mu1", 0.3], "--mu1/--mu2 do not apply"),
                      ([gauges["star"], "--law", "coulomb"], "--law coulomb"),
                      ([gauges["star"], "--law", "ellipse"], "--law ellipse needs"),
                      ([gauges["ellipse"], "--law", "star"], "--law star needs")):
        code, _, err = run(capsys, "slide", *argv, "--u0", 1, "--angle", 0)
        assert code == 1 and msg in err, err


def test_help(capsys):
    with pytest.raises(SystemExit) as e:
        main(["slide", "--help"])
    assert e.value.code == 0
    assert "--u0" in capsys.readouterr().out
