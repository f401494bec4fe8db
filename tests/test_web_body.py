"""The Motion page's body (issue 20, item 5), through a real ``asperity serve`` on 127.0.0.1:
a disc's job gives the library's figures for the same inputs (rest point, final angle, stop
times, terminal ratio, the CSV of the motion, the JSON download) and draws its outline and
orientation along the path and the stop times on the speed and spin plot; a body file
upload runs as :func:`asperity.bodies.read_body` reads it; a body file naming another file
(a mesh, a pressure file: any form of name) is refused in one line at its field, runs no
job and is never read; a bad field is one line at that field; the pressure field of a law
family shows only for a law family.  Runs are small (16 contact points, dt 1e-3): the body
solver is still the slow one."""
from __future__ import annotations

import csv
import html
import io
import json
import math
import re
import time
import warnings

import numpy as np
import pytest

pytest.importorskip("fastapi")
httpx = pytest.importorskip("httpx")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from web_forms import Page
from web_server import job_done, served

from asperity import ellipse_law, star_law
from asperity.bodies.body_file import read_body
from asperity.bodies.footprint import disc
from asperity.bodies.footprint import disc as disc_footprint
from asperity.dynamics.body import simulate_body
from asperity.dynamics.body_api import slide_body
from asperity.dynamics.moreau import Force

MARKER = "SECRET-b0d7-not-for-visitors"
COLUMNS = ["t_s", "x_m", "y_m", "theta_rad", "vx_m_s", "vy_m_s", "omega_rad_s"]
DISC = {"law": "ellipse", "mu1": "0.2", "mu2": "0.1", "u0": "0.5", "angle_deg": "30",
        "mass": "2", "g": "9.81", "dt": "1e-3", "body": "disc", "radius": "0.05",
        "contact_points": "16", "pressure_profile": "uniform", "omega0": "20",
        "texture_angle_deg": "15"}
RING_FILE = """name = "washer"
[body]
shape = "ring"
radius = 0.04
mass = 0.3
contact_points = 12
"""


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    yield from served(tmp_path_factory.mktemp("web-body") / "data", "--workers", "1")


def post(server, data, files=None):
    return httpx.post(server.base + "/motion/slide", data=data, files=files, timeout=120)


def done(server, r, timeout=180.0) -> str:
    return job_done(server, r, alerts, timeout)


def alerts(resp) -> list[str]:
    found = re.findall(r'<[^>]*(?:role="alert"|class="error[^"]*")[^>]*>(.*?)</',
                       resp.text, re.DOTALL)
    return [html.unescape(m).strip() for m in found]


def cell(page: str, key: str) -> str:
    return html.unescape(re.search(rf'id="{key}">([^<]*)<', page).group(1))


def figure(page: str, name: str) -> dict:
    return json.loads(html.unescape(re.search(
        rf'<script type="application/json" id="fig-{name}">(.*?)</script>', page, re.DOTALL).group(1)))


def files_of(server, jid):
    out = {n: httpx.get(f"{server.base}/jobs/{jid}/files/{n}") for n in ("path.csv",
                                                                        "body.json")}
    for r in out.values():
        assert r.status_code == 200
    rows = list(csv.reader(io.StringIO(out["path.csv"].text)))
    return rows, out["body.json"].json(), out


def test_a_disc_job_gives_the_librarys_figures(server):
    jid = done(server, post(server, DISC))
    fp = disc(0.05, contact_points=16)
    a = math.radians(30.0)
    ref = simulate_body(fp.points, fp.weights, ellipse_law(0.2, 0.1), mass=2.0,
                        inertia=2.0 * 0.5 * 0.05 ** 2, u0=(0.5 * math.cos(a),
                                                           0.5 * math.sin(a), 20.0),
                        dt=1e-3, g=9.81, texture_angle_deg=15.0)
    assert ref.rest
    api = slide_body(ellipse_law(0.2, 0.1), disc_footprint(0.05, contact_points=16), 0.5,
                     30.0, 20.0, mass=2.0, dt=1e-3, texture_angle_deg=15.0).summary
    ratio = api["terminal_ratio"]
    assert ratio > 0              # 10 steps before the rest (16 points, an ellipse law)
    rows, obj, got = files_of(server, jid)
    assert rows[0] == COLUMNS
    table = np.array(rows[1:], dtype=float)
    want = np.column_stack([ref.t, ref.q, ref.u])
    assert table.shape == want.shape
    np.testing.assert_array_equal(table, want)     # repr: every digit
    assert obj["rest"] == pytest.approx(list(ref.q_final[:2]), rel=1e-12, abs=1e-15)
    for key in ("final_angle_rad", "stop_time", "slide_stop_time", "spin_stop_time"):
        assert obj[key] == pytest.approx(getattr(ref, key), rel=1e-12), key
    assert obj["terminal_ratio"] == ratio and obj["together"] == api["together"]
    assert obj["body"]["contact_points"] == 16 and obj["inertia"] == pytest.approx(2.5e-3)
    assert obj["mass"] == 2.0 and obj["body"]["kind"] == "disc"
    assert obj["texture_angle_deg"] == 15.0 and obj["omega0"] == 20.0
    assert "disc_body.json" in got["body.json"].headers["content-disposition"]
    page = httpx.get(f"{server.base}/jobs/{jid}").text
    assert cell(page, "terminal-ratio") == f"{ratio:.4f}"
    assert cell(page, "final-angle").startswith(f"{ref.final_angle_rad:.6g} rad")
    assert cell(page, "slide-stop") == f"{ref.slide_stop_time:.6g} s"
    assert cell(page, "spin-stop") == f"{ref.spin_stop_time:.6g} s"
    assert cell(page, "stopped").startswith(f"{ref.stop_time:.6g} s")
    x, y = ref.q_final[:2] * 1e3                  # mm: the page's unit for ~0.1 m
    assert cell(page, "rest") == f"({x:.6g}, {y:.6g}) mm"
    # the path: outlines (the disc's circle turned and placed) at intervals, the arms
    # from the centre to the body's +x edge at the recorded angle
    path = figure(page, "path")
    outline, arms = path["data"][0], path["data"][1]
    k = np.flatnonzero([v is None for v in arms["x"]])
    assert k.size >= 10
    ends = [(arms["x"][i - 1], arms["y"][i - 1], arms["x"][i - 2], arms["y"][i - 2])
            for i in k]
    last = ends[-1]
    ang = math.atan2(last[1] - last[3], last[0] - last[2])
    assert math.remainder(ang - ref.final_angle_rad, 2 * math.pi) == pytest.approx(0, abs=1e-6)
    assert math.hypot(last[0] - last[2], last[1] - last[3]) == pytest.approx(50.0, rel=1e-6)
    centre = path["data"][2]
    assert [centre["x"][-1], centre["y"][-1]] == pytest.approx([x, y], rel=1e-6)
    assert centre["x"][0] == 0.0 and centre["y"][0] == 0.0
    ox = np.array([v for v in outline["x"] if v is not None])
    assert ox.size >= 10 * 100 and np.ptp(ox) > 100.0    # circles of 50 mm around the path
    motion = figure(page, "motion")
    marks = sorted(s["x0"] for s in motion["layout"]["shapes"])
    assert marks == pytest.approx(sorted([ref.slide_stop_time, ref.spin_stop_time]))
    omega = motion["data"][1]["y"]
    assert omega[0] == 20.0 and omega[-1] == 0.0
    listed = html.unescape(httpx.get(server.base + "/motion").text)
    assert "disc, R 50 mm, 16 points, omega0 20 rad/s, texture at 15 deg" in listed


def test_a_body_file_upload_runs_as_read_body_reads_it(server, tmp_path):
    data = dict(DISC, body="upload", law="star", mu1="0.3", mu2="0.15", omega0="-15",
                mass="999", texture_angle_deg="0", force_wave="sine", force_x="0.4",
                force_y="-0.2", torque="0.01", period="0.05", t_end="0.25")
    jid = done(server, post(server, data, {"body_file": ("washer.toml", RING_FILE.encode())}))
    (tmp_path / "washer.toml").write_text(RING_FILE)
    b = read_body(tmp_path / "washer.toml")
    assert b.mass == 0.3                           # the file's, not the form's 999 kg
    a = math.radians(30.0)
    ref = simulate_body(b.footprint.points, b.footprint.weights, star_law(0.3, 0.15),
                        mass=b.mass, inertia=b.inertia, u0=(0.5 * math.cos(a),
                                                            0.5 * math.sin(a), -15.0),
                        dt=1e-3, t_end=0.25, g=9.81,
                        force=Force(amplitude=(0.4, -0.2, 0.01), period=0.05,
                                    waveform="sine"))
    rows, obj, got = files_of(server, jid)
    table = np.array(rows[1:], dtype=float)
    np.testing.assert_array_equal(table, np.column_stack([ref.t, ref.q, ref.u]))
    assert table[-1, 0] == pytest.approx(0.25)
    assert obj["body"]["name"] == "washer" and obj["body"]["kind"] == "ring"
    assert obj["mass"] == 0.3 and obj["t_end"] == 0.25
    assert obj["force"] == {"constant": [0, 0, 0], "amplitude": [0.4, -0.2, 0.01],
                            "period": 0.05, "waveform": "sine"}
    assert obj["load"]["cycles"] == 5
    assert "washer_body-path.csv" in got["path.csv"].headers["content-disposition"]
    page = httpx.get(f"{server.base}/jobs/{jid}").text
    assert "washer sliding on" in page and "sine wave force" in page


def named(outside) -> dict[str, str]:
    """Forms of a name a body file can give for a file outside its upload."""
    p = outside / "secret.stl"
    return {"absolute": str(p), "dotdot": f"../../../../..{p}", "plain": "secret.stl",
            "tilde": "~/secret.stl", "glob": str(outside / "secret.*")}


def test_a_body_file_naming_another_file_is_refused_and_never_read(server, tmp_path):
    (tmp_path / "secret.stl").write_text(MARKER)
    (tmp_path / "secret.csv").write_text(f"x_m,y_m,p_Pa\n0,0,{MARKER}\n")
    data_dir = server.data_dir
    jobs = set((data_dir / "jobs").iterdir()) if (data_dir / "jobs").exists() else set()
    tried = 0
    for key, shape in (("mesh", 'shape = "mesh"\nunit = "mm"'),
                       ("pressure_file", 'shape = "disc"\nradius = 0.03')):
        for form, value in named(tmp_path).items():
            text = f"[body]\n{shape}\nmass = 1\n{key} = {json.dumps(value)}\n"
            r = post(server, dict(DISC, body="upload"),
                     {"body_file": ("part.toml", text.encode())})
            lines = alerts(r)
            assert r.status_code == 400 and len(lines) == 1, (key, form, lines)
            assert f"body.{key} = " in lines[0] and "may not name other files" in lines[0]
            page = Page(r.text)
            f = [x for x in page.forms if x.id == "slide"][0]
            assert len(f.errors) == 1
            assert [x.name for x in f.fields if x.label == f.errors[0][0]][0] == "body_file"
            assert MARKER not in r.text and "Traceback" not in r.text
            tried += 1
    assert tried == 10
    now = set((data_dir / "jobs").iterdir()) if (data_dir / "jobs").exists() else set()
    assert now == jobs, "a refused body file ran a job"


@pytest.mark.parametrize("change, field, words", [
    ({"radius": "0"}, "radius", "radius (m)"),
    ({"radius": "2e3"}, "radius", "radius (m)"),
    ({"contact_points": "0"}, "contact_points", "contact points"),
    ({"contact_points": "20000"}, "contact_points", "contact points"),
    ({"body": "rectangle", "pressure_profile": "hertz"}, "pressure_profile", "pressure profile"),
    ({"pressure_profile": "linear", "cop_x": "0.02"}, "cop_x", "centre of pressure"),
    ({"pressure_profile": "linear", "cop_x": "0.005", "cop_y": "-0.02"}, "cop_y",
     "centre of pressure"),
    ({"body": "rectangle", "pressure_profile": "linear", "cop_x": "0.012", "cop_y": "0.001"},
     "cop_x", "centre of pressure"),
    ({"omega0": "2e6"}, "omega0", "omega0"),
    ({"texture_angle_deg": "400"}, "texture_angle_deg", "texture angle"),
    ({"force_wave": "square", "t_end": ""}, "t_end", "end time"),
    ({"force_wave": "square", "t_end": "1e-4"}, "t_end", "end time"),
    ({"force_wave": "square", "t_end": "1e8"}, "t_end", "end time"),
    ({"force_wave": "sine", "t_end": "1", "period": "0"}, "period", "period"),
    ({"force_wave": "constant", "t_end": "1", "torque": "1e13"}, "torque", "torque"),
    ({"body": "upload"}, "body_file", "body file"),
    ({"radius": "1e-9", "mass": "1e-9"}, "radius", "inertia"),
])
def test_a_bad_field_is_one_line_at_it(server, change, field, words):
    r = post(server, {**DISC, **change})
    assert r.status_code == 400, (change, r.status_code, alerts(r))
    page = Page(r.text)
    f = [x for x in page.forms if x.id == "slide"][0]
    assert len(f.errors) == 1 and len(page.page_errors) == 1, (change, f.errors)
    at = [x.name for x in f.fields if x.label == f.errors[0][0]]
    assert at[:1] == [field], (change, at, f.errors)
    msg = f.errors[0][1]
    assert words in msg and "_" not in msg.replace("body_file", ""), msg


def pressure_shows_for(page: str) -> list[str]:
    tag = re.search(r'<fieldset id="law-family-pressure"[^>]*>', page).group(0)
    return re.search(r'data-values="([^"]*)"', tag).group(1).split()


def test_the_pressure_field_shows_only_for_a_law_family(server, tmp_path):
    """The nominal pressure (a law family's) is not offered for a gauge file to come nor
    for a kept single law; a kept family file shows it (app.js reads a file chosen in the
    browser the same way: format asperity-gauge, version 2)."""
    from test_law_family import synthetic, wedge_law

    from asperity import write_gauge
    one = wedge_law(20, 6, "star")
    write_gauge(tmp_path / "one.json", one)
    write_gauge(tmp_path / "family.json", synthetic([one, wedge_law(30, 6, "star")],
                                                   (1e6, 2e6)))
    assert json.loads((tmp_path / "family.json").read_text())["version"] == 2
    assert "upload" not in pressure_shows_for(httpx.get(server.base + "/motion").text)
    shown = {}
    for name in ("one.json", "family.json"):
        r = post(server, {"law": "upload", "u0": "abc", "angle_deg": "30"},
                 {"gauge": (name, (tmp_path / name).read_bytes())})
        assert r.status_code == 400, alerts(r)
        assert f"<b>{name}</b>" in r.text               # kept for the next submission
        shown[name] = "upload" in pressure_shows_for(r.text)
    assert shown == {"one.json": False, "family.json": True}


def test_a_run_too_long_for_the_solver_is_one_line_at_the_time_step(server):
    """Refused by simulate_body's work limit (in the job): the page's words, at dt."""
    r = post(server, {**DISC, "dt": "1e-9"})
    if r.status_code == 303:                   # not failed within the quick wait: its page
        jid = r.headers["location"].rsplit("/", 1)[-1]
        t0 = time.monotonic()
        while httpx.get(f"{server.base}/api/jobs/{jid}").json()["status"] in ("queued",
                                                                            "running"):
            assert time.monotonic() - t0 < 60
            time.sleep(0.1)
        r = httpx.get(f"{server.base}/jobs/{jid}")
    assert r.status_code == 422, (r.status_code, alerts(r))
    page = Page(r.text)
    f = [x for x in page.forms if x.id == "slide"][0]
    assert len(f.errors) == 1 and len(page.page_errors) == 1, f.errors
    assert [x.name for x in f.fields if x.label == f.errors[0][0]][:1] == ["dt"]
    msg = f.errors[0][1]
    assert "time step (s)" in msg and "t_end" not in msg and "steps" in msg, msg


def test_a_body_file_the_solver_cannot_take_is_one_line_at_the_file(server):
    """Read by read_body on the form (its own refusals), then the solver's ranges."""
    for text, words in (('[body]\nshape = "disc"\nradius = 0.01\nmass = 1\ninertia = 1e-20\n',
                         "inertia"),
                        ('[body]\nshape = "disc"\nradius = -1\nmass = 1\n', "body.radius"),
                        ('[body]\nshape = "disc"\nradius = 0.01\nmass = 1\n'
                         'contact_points = 20000\n', "at most 10000 contact points"),
                        ("[body\n", "not valid TOML")):
        r = post(server, dict(DISC, body="upload"), {"body_file": ("part.toml", text.encode())})
        assert r.status_code in (400, 422), (text, r.status_code, alerts(r))
        page = Page(r.text)
        f = next(x for x in page.forms if x.id == "slide")
        assert len(f.errors) == 1 and len(page.page_errors) == 1, f.errors
        assert [x.name for x in f.fields if x.label == f.errors[0][0]][0] == "body_file"
        msg = f.errors[0][1]
        assert msg.startswith("part.toml") and words in msg and "uploads" not in msg, msg


def test_the_motion_figure_marks_each_stop_at_its_own_time():
    """A body that stops sliding before it stops spinning gets two marks, each at its own
    time and named for it (a disc stops both together, which hides a swap of the two)."""
    from types import SimpleNamespace

    from asperity.web.figures_body import motion_figure
    t = np.linspace(0.0, 1.0, 11)
    u = np.zeros((11, 3))
    u[:4, 0], u[:8, 2] = 0.1, 5.0
    fig = motion_figure(SimpleNamespace(t=t, u=u),
                        {"slide_stop_time": 0.3, "spin_stop_time": 0.7})
    marks = {round(s["x0"], 12): s["line"]["color"] for s in fig["layout"]["shapes"]}
    notes = {a["text"]: a["x"] for a in fig["layout"]["annotations"]}
    assert notes == {"slide stops 0.3 s": 0.3, "spin stops 0.7 s": 0.7}
    assert marks[0.3] == fig["data"][0]["line"]["color"]      # the speed's colour
    assert marks[0.7] == fig["data"][1]["line"]["color"]      # the spin's colour
    one = motion_figure(SimpleNamespace(t=t, u=u), {"slide_stop_time": 0.3,
                                                    "spin_stop_time": None})
    assert [s["x0"] for s in one["layout"]["shapes"]] == [0.3]
