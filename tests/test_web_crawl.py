"""The Motion page's crawl (issue 26, item 6), through a real ``asperity serve`` on
127.0.0.1: a crawl job gives the library's numbers for the same inputs (its JSON is
``asperity crawl --json``'s, its CSV the command's ``--csv``, every digit), the page states
the speed with its rule, the drift, the cost of transport and the Froude number, and its
figures are the body's world shapes over the last period and each period's speed; a
texture fitted on the fly is the law ``asperity crawl FILE`` fits; a bad field is one line
at that field and runs no job.  Runs are small (40 points, a few periods)."""
from __future__ import annotations

import html
import json
import re
import warnings

import numpy as np
import pytest

pytest.importorskip("fastapi")
httpx = pytest.importorskip("httpx")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from web_forms import Page
from web_server import job_done, served

from asperity.crawling.gait import CurvatureWave
from asperity.crawling.output import csv_text, summary, world_shapes
from asperity.crawling.solver import coefficient_law, crawl

BASE = {"c_law": "coefficients", "c_mu_f": "0.1", "c_mu_b": "0.15", "c_mu_t": "0.2",
        "c_rule": "componentwise", "c_texture_on": "body", "c_texture_angle": "0",
        "c_amplitude": "7", "c_waves": "1", "c_length": "1", "c_period": "1",
        "c_mode": "dynamic", "c_points": "40", "c_periods": "4", "c_g": "9.81",
        "c_steps": "200"}


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    yield from served(tmp_path_factory.mktemp("web-crawl") / "data", "--workers", "1")


def post(server, data, files=None):
    return httpx.post(server.base + "/motion/crawl", data=data, files=files, timeout=120)


def done(server, r, timeout=180.0) -> str:
    return job_done(server, r, timeout=timeout)


def cell(page: str, key: str) -> str:
    return html.unescape(re.search(rf'id="{key}">([^<]*)<', page).group(1))


def figure(page: str, name: str) -> dict:
    return json.loads(html.unescape(re.search(
        rf'<script type="application/json" id="fig-{name}">(.*?)</script>', page,
        re.DOTALL).group(1)))


def test_a_crawl_job_gives_the_librarys_numbers_and_figures(server):
    data = {**BASE, "c_mu_t": "0.3", "c_texture_angle": "10"}
    jid = done(server, post(server, data))
    law = coefficient_law(0.1, 0.15, 0.3, "componentwise")
    gait = CurvatureWave(amplitude=7.0, waves=1.0, period=1.0, length=1.0)
    res = crawl(law, gait=gait, points=40, periods=4, g=9.81, texture_angle_deg=10.0)
    want = json.loads(json.dumps(summary(res, law)))
    got = httpx.get(f"{server.base}/jobs/{jid}/files/crawl.json")
    assert got.status_code == 200
    assert "componentwise-mu0.1-0.15-0.3_A7-k1_crawl.json" in \
        got.headers["content-disposition"]
    assert got.json() == want                                   # the command's JSON
    assert httpx.get(f"{server.base}/jobs/{jid}/files/path.csv").text == csv_text(res)
    api = httpx.get(f"{server.base}/api/jobs/{jid}/result").json()
    assert api["crawl"] == want and api["files"] == ["crawl.json", "path.csv"]
    U = res.speed_body_lengths_per_period
    assert U > 0.1 and res.transient_periods == 2
    page = httpx.get(f"{server.base}/jobs/{jid}").text
    assert cell(page, "speed") == f"{U:+.6g} body lengths per period"
    assert cell(page, "rule") == "componentwise"
    assert cell(page, "averaged") == "periods 3-4 of 4"
    assert cell(page, "drift") == f"{res.heading_drift_rad_per_period:+.4g} rad per period"
    assert cell(page, "cost") == f"{res.cost_of_transport:.4g}"
    assert cell(page, "froude") == f"{1.0 / (9.81 * 0.1):.4g}"      # L / (g mu_f T^2)
    # the snapshots: the body's world points at the last recorded instant (m: a 1 m body)
    snaps = figure(page, "crawl-snapshots")
    bodies = [t for t in snaps["data"] if t["name"].startswith("body at")]
    assert len(bodies) == 9
    last = world_shapes(res, gait, np.array([len(res.t) - 1]))[0]
    np.testing.assert_allclose(np.column_stack([bodies[-1]["x"], bodies[-1]["y"]]), last,
                               atol=1e-6)
    first_t = float(bodies[0]["name"].split("= ")[1].split(" s")[0])
    assert first_t == pytest.approx(3.0, abs=1e-3)            # the last period: t 3 to 4 s
    centre = snaps["data"][-1]
    assert [centre["x"][-1], centre["y"][-1]] == pytest.approx(list(res.q[-1, :2]), abs=1e-6)
    speed = figure(page, "crawl-speed")
    step = speed["data"][1]
    assert step["y"][:-1] == pytest.approx(list(res.speed_per_period), abs=1e-6)
    assert speed["data"][2]["y"] == pytest.approx([U, U], abs=1e-6)
    assert speed["data"][2]["x"] == pytest.approx([2.0, 4.0])  # averaged over periods 3-4
    assert "componentwise" in speed["layout"]["title"]["text"]
    motion = httpx.get(server.base + "/motion").text
    assert "A 7, k 1, componentwise rule, dynamic, 40 points, 4 periods" in \
        html.unescape(motion)
    for text in (page, motion):                       # no element id twice on a page
        ids = re.findall(r'\sid="([^"]+)"', text)
        assert len(ids) == len(set(ids)), sorted(i for i in ids if ids.count(i) > 1)


@pytest.mark.parametrize("rule", ["associated", "colinear"])
def test_the_rule_and_the_ground_texture_reach_the_solver(server, rule):
    """Quasi-static, the texture on the ground at 30 deg: the job's speed is the
    library's for that rule (the rules differ: each is stated on the page)."""
    data = {**BASE, "c_rule": rule, "c_mode": "quasi-static", "c_periods": "",
            "c_texture_on": "ground", "c_texture_angle": "30"}
    jid = done(server, post(server, data))
    res = crawl(coefficient_law(0.1, 0.15, 0.2, rule), points=40, quasi_static=True,
                texture_on="ground", texture_angle_deg=30.0)
    got = httpx.get(f"{server.base}/api/jobs/{jid}/result").json()["crawl"]
    assert got["rule"] == rule and got["quasi_static"] and got["periods"] == 1
    assert got["texture_on"] == "ground" and got["texture_angle_deg"] == pytest.approx(30.0)
    assert got["speed_body_lengths_per_period"] == res.speed_body_lengths_per_period
    page = httpx.get(f"{server.base}/jobs/{jid}").text
    assert cell(page, "rule") == rule and "(no inertia" in cell(page, "froude")


def test_a_wedge_texture_is_fitted_as_the_command_fits_it(server):
    """The wedge's law fitted on the fly (all faces, closed form, 720 directions, star):
    the speed of ``asperity crawl`` on the same texture file."""
    from asperity import WedgeTexture, law_from_gauge
    from asperity.friction.derive import derive
    from asperity.laws.fitting import fit_derivation
    data = {**BASE, "c_law": "wedge", "c_alpha_deg": "30", "c_beta_deg": "10",
            "c_mu_alpha": "0.1", "c_mu_beta": "0.2", "c_fit_law": "star",
            "c_mode": "quasi-static", "c_periods": "1"}
    jid = done(server, post(server, data))
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), "all-faces", "closed-form", 720)
    law = law_from_gauge(fit_derivation(d, "star"))
    res = crawl(law, points=40, quasi_static=True)
    got = httpx.get(f"{server.base}/api/jobs/{jid}/result").json()["crawl"]
    assert got["speed_body_lengths_per_period"] == pytest.approx(
        res.speed_body_lengths_per_period, rel=1e-9)
    assert got["law"] == law.description and got["rule"] == res.rule
    assert got["source"].startswith("wedge 30/10 deg")


@pytest.mark.parametrize("change, field, words", [
    ({"c_mu_f": "abc"}, "c_mu_f", "mu_f (forward)"),
    ({"c_mu_t": ""}, "c_mu_t", "mu_t (transverse)"),
    ({"c_mu_b": "-0.1"}, "c_mu_b", "mu_b (backward)"),
    ({"c_rule": "sideways"}, "c_rule", "rule"),
    ({"c_amplitude": "200"}, "c_amplitude", "amplitude A"),
    ({"c_amplitude": "15"}, "c_amplitude", "crosses itself"),
    ({"c_waves": "0"}, "c_waves", "waves k"),
    ({"c_length": "0"}, "c_length", "body length L"),
    ({"c_period": "nan"}, "c_period", "gait period T"),
    ({"c_points": "2"}, "c_points", "contact points"),
    ({"c_periods": "0"}, "c_periods", "periods"),
    ({"c_periods": "1000", "c_points": "100000"}, "c_periods", "more than a crawl runs"),
    ({"c_texture_angle": "400"}, "c_texture_angle", "texture angle (deg)"),
    ({"c_texture_on": "wall"}, "c_texture_on", "texture on the"),
    ({"c_g": "0"}, "c_g", "g (m/s^2)"),
    ({"c_steps": "4"}, "c_steps", "steps per period"),
    ({"c_mode": "fast"}, "c_mode", "inertia"),
    ({"c_law": "upload"}, "c_gauge", "gauge file"),
    ({"c_law": "file"}, "c_texture_file", "texture or surface file"),
    ({"c_law": "wedge", "c_alpha_deg": "95", "c_beta_deg": "10", "c_mu_alpha": "0.1",
      "c_mu_beta": "0.2"}, "c_alpha_deg", "alpha (deg)"),
    ({"c_law": "job:nope"}, "c_law", "no law"),
])
def test_a_bad_field_is_one_line_at_it_and_runs_no_job(server, change, field, words):
    jobs = server.data_dir / "jobs"
    before = set(jobs.iterdir()) if jobs.exists() else set()
    r = post(server, {**BASE, **change})
    assert r.status_code == 400, (change, r.status_code)
    page = Page(r.text)
    f = next(x for x in page.forms if x.id == "crawl")
    assert len(f.errors) == 1 and len(page.page_errors) == 1, (change, f.errors)
    at = [x.name for x in f.fields if x.label == f.errors[0][0]]
    assert at[:1] == [field], (change, at, f.errors)
    msg = f.errors[0][1]
    assert words in msg and "\n" not in msg and "Traceback" not in r.text, msg
    for other in page.forms:                     # the other forms show no error
        assert other.id == "crawl" or not other.errors, other.id
    after = set(jobs.iterdir()) if jobs.exists() else set()
    assert after == before, "a refused form ran a job"


def test_a_law_family_crawls_at_the_pressure_given(server, tmp_path):
    """An uploaded version-2 gauge file: the pressure is asked for at its field, then the
    crawl runs on the family's law at that pressure (the library's law_at)."""
    from test_law_family import synthetic, wedge_law

    from asperity import law_from_gauge, read_gauge, write_gauge
    from asperity.laws.family import law_at
    write_gauge(tmp_path / "family.json", synthetic([wedge_law(20, 6, "star"),
                                                    wedge_law(30, 6, "star")], (1e6, 2e6)))
    data = {**BASE, "c_law": "upload", "c_mode": "quasi-static", "c_periods": "1"}
    r = post(server, data, {"c_gauge": ("family.json", (tmp_path / "family.json").read_bytes())})
    assert r.status_code == 400
    f = next(x for x in Page(r.text).forms if x.id == "crawl")
    assert [x.name for x in f.fields if x.label == f.errors[0][0]][:1] == ["c_law_pressure"]
    kept = re.search(r'name="c_gauge_upload" value="([^"]+)"', r.text).group(1)
    jid = done(server, post(server, {**data, "c_gauge_upload": kept,
                                     "c_law_pressure": "1.5e6"}))
    got = httpx.get(f"{server.base}/api/jobs/{jid}/result").json()
    law = law_from_gauge(law_at(read_gauge(tmp_path / "family.json"), 1.5e6)[0])
    res = crawl(law, points=40, quasi_static=True)
    assert got["crawl"]["speed_body_lengths_per_period"] == pytest.approx(
        res.speed_body_lengths_per_period, rel=1e-12)
    assert got["family"]["pressure_Pa"] == 1.5e6 and got["family"]["interpolated"]
    page = httpx.get(f"{server.base}/jobs/{jid}").text
    assert 'id="slide-pressure"' in page                 # the page states the pressure
