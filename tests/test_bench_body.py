"""``asperity bench --only body`` runs and reports every figure (issue 20).  No timing is
asserted (speed targets live in the benchmark's output), and nothing is installed: the
test passes --no-install, so without MuJoCo its figures are left out, and the output says
so and how to install it; the rest is measured either way."""
from __future__ import annotations

import importlib.util
import json

import pytest

from cli_run import run


def check_body(b: dict) -> None:
    assert len(b["load_average"]) == 3 and b["dt"] > 0
    for name in ("ellipse", "star"):
        v = b["point_mass"][name]
        assert v["steps_per_second"] > 0 and v["steps"] > 0 and v["status"] == "ok"
        assert v["sliding_at_end"] is True                 # the costly phase throughout
        assert 1.0 <= v["mean_iterations"] <= 3.0
    box, disc = b["mujoco_box"], b["mujoco_disc"]
    if "skipped" in box:
        assert "mujoco is not installed" in box["skipped"] and "pip install mujoco" in \
            box["skipped"]
        assert "skipped" in disc
        assert b["point_mass"]["star"]["vs_mujoco_box"] is None
        assert b["verdict"]["star_vs_mujoco_box"]["met"] is None
    else:
        assert "error" not in box, box
        assert box["steps_per_second"] > 0 and box["mean_contacts"] > 1.0
        ratio = b["point_mass"]["star"]["vs_mujoco_box"]
        assert ratio == pytest.approx(b["point_mass"]["star"]["steps_per_second"]
                                      / box["steps_per_second"])
        assert b["verdict"]["star_vs_mujoco_box"]["met"] == (ratio >= 5.0)
        assert "error" not in disc, disc
        assert disc["torsional"] == pytest.approx(2 * disc["mu"] * disc["radius"] / 3)
        # both motions stop within the horizon; the ratio is a finite positive number
        assert 0 < disc["spin_stop_time"] < 3 and 0 < disc["slide_stop_time"] < 3
        assert disc["spin_stops_before_slide_by"] == pytest.approx(
            disc["slide_stop_time"] - disc["spin_stop_time"])
        assert 0 < disc["terminal_ratio"] < 1e6
        assert set(disc["ratio_when_below"]) == {"0.5", "0.2", "0.1", "0.05", "0.02"}
        assert disc["ratio_when_below"]["0.02"] == disc["terminal_ratio"]
    assert b["disc_terminal_ratio_expected"] == 0.653
    for name in ("ellipse", "star"):
        d = b["disc_256"][name]
        key = f"disc_256_{name}_steps_per_second"
        assert "error" not in d, d
        assert d["steps_per_second"] > 0 and d["contact_points"] > 200
        assert b["verdict"][key]["met"] == (d["steps_per_second"] >= b["targets"][key])


def test_bench_body_json(capsys):
    code, out, err = run(capsys, "bench", "--only", "body", "--seconds", "0.05", "--json",
                         "--no-install")
    assert code == 0, err
    check_body(json.loads(out)["body"])
    if importlib.util.find_spec("mujoco") is None:
        print("mujoco is not installed here: its figures were left out (stated in the JSON)")


def test_bench_body_without_mujoco_says_so(capsys, monkeypatch):
    """As on a machine without MuJoCo: the figures of asperity are measured, MuJoCo's are
    left out with the line that installs it, nothing installed."""
    from asperity.dynamics import body_bench
    real = importlib.util.find_spec
    monkeypatch.setattr(body_bench.importlib.util, "find_spec",
                        lambda name, *a: None if name == "mujoco" else real(name, *a))

    def no_pip(*a, **k):                                       # pragma: no cover
        raise AssertionError("the benchmark must not install with --no-install")
    monkeypatch.setattr(body_bench.subprocess, "run", no_pip)
    code, out, err = run(capsys, "bench", "--only", "body", "--seconds", "0.05",
                         "--no-install")
    assert code == 0, err
    assert "MuJoCo box: left out: mujoco is not installed (install it with: " in out
    assert "-m pip install mujoco)" in out
    assert "star law vs MuJoCo's box (wall time): target >= 5x: not measured" in out
    assert "asperity point mass, star" in out
    code, out, err = run(capsys, "bench", "--only", "body", "--seconds", "0.05",
                         "--no-install", "--json")
    check_body(json.loads(out)["body"])


def test_bench_body_rejects_a_bad_duration(capsys):
    code, out, err = run(capsys, "bench", "--only", "body", "--seconds", "0")
    assert code == 1 and out == "" and "--seconds must be in [0.05, 600]" in err
