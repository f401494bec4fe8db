"""Studies with a [crawl] table (issue 26, item 5): the cases' speeds are those of direct
crawls (`asperity crawl TEXTURE` and `asperity.crawl`), in this process and on a
LocalCluster of 2 workers (127.0.0.1); the summary ranks by speed; a gait that crosses
itself is a failed case; bad [crawl] keys are refused in one line naming crawl.KEY."""
from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest
from cli_run import run

from asperity.crawling.solver import crawl
from asperity.study.run import run_study_file

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"

WEDGES = """
[study]
kind = "grid"
[texture]
kind = "wedge"
alpha_deg = 30.0
beta_deg = 40.0
mu_alpha = 0.1
mu_beta = 0.1
height = 5.0e-6
[crawl]
points = 30
steps_per_period = 40
quasi_static = true
texture_angle_deg = 90.0
[parameters]
"texture.alpha_deg" = { values = [20.0, 50.0] }
"crawl.amplitude" = { values = [5.0, 7.0] }
"""
TEXTURE = """[texture]
kind = "wedge"
alpha_deg = ALPHA
beta_deg = 40.0
mu_alpha = 0.1
mu_beta = 0.1
height = 5.0e-6
"""


def study_file(tmp_path: Path, body: str, name="s.toml") -> Path:
    p = tmp_path / name
    p.write_text(body.replace("SURF", str(SURF)))
    return p


def stored(folder: Path) -> list[tuple]:
    con = sqlite3.connect(folder / "study.sqlite")
    try:
        return con.execute('SELECT case_id, status, message, "texture.alpha_deg", '
                           '"crawl.amplitude", speed_body_lengths_per_period, '
                           'cost_of_transport, heading_drift_rad_per_period FROM cases '
                           'ORDER BY case_id').fetchall()
    finally:
        con.close()


def test_wedge_sweep_equals_direct_crawls_in_process_and_on_two_workers(tmp_path, capsys):
    f = study_file(tmp_path, WEDGES)
    one = run_study_file(f, tmp_path / "a", workers=0, batch_size=1, plot=True)
    two = run_study_file(f, tmp_path / "b", workers=2)
    assert two["run"]["where"] == "LocalCluster (2 workers)" and two["run"]["ran"] == 4
    a, b = stored(tmp_path / "a"), stored(tmp_path / "b")
    assert a == b and {r[1] for r in a} == {"ok"}
    for cid, _, _, alpha, amp, speed, cost, drift in a:
        tex = tmp_path / f"wedge-{alpha:g}.toml"
        tex.write_text(TEXTURE.replace("ALPHA", f"{alpha!r}"))
        code, out, err = run(capsys, "crawl", tex, "--texture-angle", 90, "--quasi-static",
                             "--points", 30, "--dt", 1 / 40, "--amplitude", amp, "--json")
        assert code == 0, err
        obj = json.loads(out)
        assert speed == pytest.approx(obj["speed_body_lengths_per_period"], rel=1e-12, abs=1e-15)
        assert cost == pytest.approx(obj["cost_of_transport"], rel=1e-12)
        assert drift == pytest.approx(obj["heading_drift_rad_per_period"], abs=1e-12)
    # ranked fastest first; steeper faces across the body crawl faster
    rank = one["crawl"]["ranking"]
    speeds = [r["speed_body_lengths_per_period"] for r in rank]
    assert speeds == sorted(speeds, reverse=True) and len(rank) == 4
    assert rank[0]["texture.alpha_deg"] == 50.0 and speeds[-1] > 0
    assert (tmp_path / "a" / "crawl.png").read_bytes()[:4] == b"\x89PNG"
    md = (tmp_path / "a" / "summary.md").read_text()
    assert "ranked by crawling speed (fastest first):" in md


def test_coefficient_laws_library_and_a_gait_that_crosses_itself(tmp_path):
    body = """
[study]
kind = "grid"
[crawl]
mu_f = 0.1
mu_b = 0.15
rule = "componentwise"
points = 30
steps_per_period = 40
quasi_static = true
[parameters]
"crawl.mu_t" = { values = [0.12, 0.2, 0.4] }
"crawl.amplitude" = { values = [7.0, 20.0] }
"""
    s = run_study_file(study_file(tmp_path, body), tmp_path / "o", workers=0)
    rows = stored_coefficients(tmp_path / "o")
    ok = [r for r in rows if r[1] == "ok"]
    failed = [r for r in rows if r[1] != "ok"]
    assert len(ok) == 3 and len(failed) == 3 and s["failed"] == 3
    assert all(r[4] == 20.0 and "crosses itself" in r[2] for r in failed)
    for _, _, _, mu_t, amp, speed in ok:
        direct = crawl(mu_f=0.1, mu_b=0.15, mu_t=mu_t, points=30, steps_per_period=40,
                       quasi_static=True, amplitude=amp)
        assert speed == direct.speed_body_lengths_per_period
    speeds = [r[5] for r in sorted(ok, key=lambda r: r[3])]
    assert 0 < speeds[0] < speeds[1] < speeds[2]            # U rises with mu_t / mu_f
    rank = s["crawl"]["ranking"]
    assert [r["status"] for r in rank] == ["ok"] * 3 + ["failed"] * 3
    assert rank[0]["crawl.mu_t"] == 0.4


def stored_coefficients(folder: Path) -> list[tuple]:
    con = sqlite3.connect(folder / "study.sqlite")
    try:
        return con.execute('SELECT case_id, status, message, "crawl.mu_t", "crawl.amplitude", '
                           'speed_body_lengths_per_period FROM cases ORDER BY case_id'
                           ).fetchall()
    finally:
        con.close()


def test_texture_library_ranked_by_speed(tmp_path):
    body = """
[study]
kind = "files"
files = ["SURF/wedge-asymmetric.toml", "SURF/wedge-symmetric-30.toml"]
[crawl]
points = 30
steps_per_period = 40
quasi_static = true
texture_angle_deg = 90.0
"""
    s = run_study_file(study_file(tmp_path, body), tmp_path / "o", workers=0)
    rank = s["crawl"]["ranking"]
    assert [r["status"] for r in rank] == ["ok", "ok"]
    assert rank[0]["speed_body_lengths_per_period"] > rank[1]["speed_body_lengths_per_period"]
    assert all(Path(r["file"]).name.startswith("wedge-") for r in rank)


BASE = """
[study]
kind = "grid"
[texture]
kind = "wedge"
alpha_deg = 30.0
beta_deg = 10.0
mu_alpha = 0.1
mu_beta = 0.1
height = 5.0e-6
[parameters]
"texture.alpha_deg" = { values = [20.0, 50.0] }
[crawl]
"""
BAD = [
    ("speed = 1.0", "unknown key crawl.speed; allowed: amplitude"),
    ("points = 2", "crawl.points must be a whole number in [3, 100000]"),
    ("steps_per_period = 1e9", "crawl.steps_per_period must be"),
    ("amplitude = -1.0", "crawl.amplitude must be in [0, 100]"),
    ("waves = 0.0", "crawl.waves must be in (0, 20]"),
    ("texture_on = \"sky\"", "crawl.texture_on must be one of"),
    ("quasi_static = \"yes\"", "crawl.quasi_static must be true or false"),
    ("texture_angle_deg = 400.0", "crawl.texture_angle_deg must be in [-360, 360]"),
    ("mu_t = 0.3", "crawl.mu_t makes a law of three coefficients"),
    ("rule = \"colinear\"", "crawl.rule makes a law of three coefficients"),
    ("fit_law = \"spline\"", "crawl.fit_law must be one of"),
]


@pytest.mark.parametrize("line,msg", BAD, ids=[m for _, m in BAD])
def test_bad_crawl_keys_refused_in_one_line(tmp_path, capsys, line, msg):
    f = study_file(tmp_path, BASE + line + "\n")
    code, out, err = run(capsys, "study", f, "-o", tmp_path / "out", "--workers", "0")
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err
    assert not (tmp_path / "out" / "study.sqlite").exists()


OTHER_BAD = [
    (("[study]\nkind = \"grid\"\n[crawl]\nmu_f = 0.1\n[parameters]\n"
     "\"crawl.amplitude\" = { values = [5.0] }\n"), "crawl.mu_b missing"),
    (("[study]\nkind = \"grid\"\n[crawl]\nmu_f = 0.1\nmu_b = 0.1\nmu_t = 0.2\nfit_law = \"star\"\n"
     "[parameters]\n\"crawl.amplitude\" = { values = [5.0] }\n"), "crawl.fit_law fits a texture"),
    (("[study]\nkind = \"grid\"\n[crawl]\nmu_f = 0.1\nmu_b = 0.1\nmu_t = 0.2\n[parameters]\n"
     "\"crawl.points\" = { values = [10.0, 20.0] }\n"), "the crawl parameters are crawl.amplitude"),
    (("[study]\nkind = \"grid\"\n[crawl]\nmu_f = 0.1\nmu_b = 0.1\nmu_t = 0.2\n[parameters]\n"
     "\"crawl.waves\" = { values = [-1.0, -2.0] }\n"), "crawl.waves must be in (0, 20]"),
    (("[study]\nkind = \"grid\"\ncrawl = 3\n[parameters]\n"
     "\"crawl.waves\" = { values = [1.0] }\n"), "unknown key study.crawl"),
    (("[study]\nkind = \"grid\"\n[crawl]\nmu_f = 0.1\nmu_b = 0.1\nmu_t = 200.0\n[parameters]\n"
     "\"crawl.waves\" = { values = [1.0] }\n"), "crawl.mu_t must be in [1e-06, 100]"),
]


@pytest.mark.parametrize("body,msg", OTHER_BAD, ids=[m for _, m in OTHER_BAD])
def test_bad_crawl_studies_refused_in_one_line(tmp_path, capsys, body, msg):
    f = study_file(tmp_path, body)
    code, out, err = run(capsys, "study", f, "-o", tmp_path / "out", "--workers", "0")
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err
