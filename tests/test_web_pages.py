"""The web page as a new user meets it (issue 18, section 8), at the HTTP level: units chosen
from the data (checked against a hand-written prefix table and closed forms, not against the
chooser), no duplicate element ids, downloads named after their source and law kind,
results told apart by their settings, the elapsed time from the job's stored start, results
deleted with their files, nothing private on the token page, and the risk figure as an
interactive Plotly figure."""
from __future__ import annotations

import html
import json
import math
import re
import time
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
from test_web_http import SURFACES, client_for, finished, job_page  # noqa: E402

#: metres per unit, written out by hand (the chooser's own table is not used)
METRES = {"nm": 1e-9, "um": 1e-6, "mm": 1e-3, "m": 1.0}
TWO_NODE = {"model": "two-node", "two_k": "1e6", "two_l0": "0.1", "two_alpha_T": "1.2e-5",
            "two_k_t": "5e5", "two_N": "100", "dT_min": "0", "dT_max": "125",
            "friction": "mu", "mu_plus": "0.2", "mu_minus": "0.1"}
#: a long name without a break opportunity (hyphens are one)
LONG = "a_measured_surface_with_a_very_long_name_from_the_instrument_" \
       "0123456789_abcdefghij_klmnopqrst"


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with client_for(tmp_path_factory.mktemp("web-pages")) as c:
        yield c


def jid_of(page) -> str:
    return re.search(r'result <a href="/jobs/([0-9a-f-]+)"', page.text).group(1)


def length(text: str) -> tuple[float, str]:
    """``'+274.8 nm'`` -> (2.748e-7, 'nm'), by the table above."""
    m = re.fullmatch(r"\s*([+-]?[0-9.]+(?:e[+-]?\d+)?) (nm|um|mm|m)\s*", text)
    assert m, f"not a length with a unit: {text!r}"
    return float(m.group(1)) * METRES[m.group(2)], m.group(2)


def cell(page, id_: str) -> str:
    m = re.search(rf'id="{id_}"[^>]*>(.*?)</', page.text, re.S)
    assert m, id_
    return html.unescape(re.sub(r"<[^>]+>", "", m.group(1))).strip()


def figure(page, id_: str) -> dict:
    m = re.search(rf'<script type="application/json" id="fig-{id_}">(.*?)</script>', page.text,
                  re.S)
    assert m, f"no figure {id_}"
    return json.loads(m.group(1))


def well_chosen(values_m, unit: str) -> None:
    """The unit of a quantity suits its values: the largest is at least 1 in it and below
    1000 (unless the unit is the largest offered, m)."""
    top = max(abs(v) for v in values_m if v is not None) / METRES[unit]
    assert top >= 0.9999 and (top < 1000 or unit == "m"), (values_m, unit)


# --------------------------------------------------------------------------- the chooser
@pytest.mark.parametrize("values, unit", [
    (2.748e-7, "nm"), (5e-5, "um"), ([2.5e-3, 0.04], "mm"), (0.2748, "mm"), (50.0, "m"),
    ([1e-4, 0.2748], "mm"), (1e-12, "nm"), (999.99e-6, "mm"), ([None, 3e-6, float("nan")], "um"),
])
def test_the_unit_chooser_by_a_hand_table(values, unit):
    from asperity.web.units import choose, show
    u = choose(values, "m")
    assert u.name == unit
    flat = [v for v in np.ravel([values]) if v is not None and math.isfinite(v)]
    for v in flat:
        back, name = length(show(v, u, 6).replace(" x 10^", "e"))
        assert name == unit and back == pytest.approx(v, rel=1e-5)
    assert choose([0.0, None], "m").name == "m"


def test_pressures_and_forces_take_their_own_prefixes():
    from asperity.web.units import choose, show
    assert show(5e6, choose(5e6, "Pa")) == "5 MPa"
    assert show(2.1e11, choose(2.1e11, "Pa")) == "210 GPa"
    assert show(100.0, choose(100.0, "N")) == "100 N"


# --------------------------------------------------------------------------- ids, names
class Ids(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.ids += [v for k, v in attrs if k == "id"]


def duplicate_ids(text: str) -> set[str]:
    p = Ids()
    p.feed(text)
    return {i for i in p.ids if p.ids.count(i) > 1}


def download_name(client, jid: str, name: str) -> str:
    r = client.get(f"/jobs/{jid}/files/{name}")
    assert r.status_code == 200, name
    m = re.search(r"filename\*?=(?:utf-8'')?\"?([^\";]+)", r.headers["content-disposition"])
    from urllib.parse import unquote
    return unquote(m.group(1))


@pytest.fixture(scope="module")
def chain(client):
    """A surface file with a long name, a star law and an ellipse fitted to it, a slide on
    the star law and a risk verdict on it: (surface, star, ellipse, slide, risk) pages."""
    name = LONG + ".stl"
    surf = finished(client, client.post("/surface", data={
        "source": "file", "unit": "um", "max_slope": "60", "directions": "72"},
        files={"file": (name, (SURFACES / "wedge-30-10.stl").read_bytes())}))
    assert surf.status_code == 200, surf.text[:300]
    sid = jid_of(surf)
    laws = [finished(client, client.post("/law", data={"source": sid, "law": kind,
                                                        "directions": "72"}))
            for kind in ("star", "ellipse")]
    assert all(p.status_code == 200 for p in laws)
    slide = finished(client, client.post("/motion/slide", data={
        "law": f"job:{jid_of(laws[0])}", "u0": "0.5", "angle_deg": "30"}))
    risk = finished(client, client.post("/motion/risk", data={
        **TWO_NODE, "friction": f"law:{jid_of(laws[0])}"}))
    assert slide.status_code == 200 and risk.status_code == 200
    return surf, laws[0], laws[1], slide, risk


def test_no_page_repeats_an_element_id(client, chain):
    pages = [client.get(p) for p in ("/", "/surface", "/law", "/motion", "/studies", "/jobs")]
    pages += list(chain) + [client.get(f"/jobs/{jid_of(chain[0])}/delete")]
    pages.append(finished(client, client.post("/surface", data={
        "source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
        "mu_beta": "0.2", "directions": "72"})))
    for page in pages:
        assert page.status_code == 200
        assert not duplicate_ids(page.text), (page.url, duplicate_ids(page.text))


def test_downloads_are_named_after_the_source_and_the_law_kind(client, chain):
    surf, star, ellipse, slide, risk = chain
    stem = LONG
    assert download_name(client, jid_of(surf), "derive.json") == f"{stem}_friction.json"
    for page, kind in ((star, "star"), (ellipse, "truncated-ellipse")):
        jid = jid_of(page)
        assert download_name(client, jid, "gauge.json") == f"{stem}_{kind}.gauge.json"
        assert download_name(client, jid, "law.csv") == f"{stem}_{kind}.csv"
        assert download_name(client, jid, "law.inp") == f"{stem}_{kind}.inp"
    assert download_name(client, jid_of(slide), "path.csv") == f"{stem}_star_slide-path.csv"
    assert download_name(client, jid_of(risk), "risk.json") == \
        f"two-node-assembly-form_{stem}_star_risk.json"
    # a gauge file opened keeps its own name, the law kind added once
    gauge = client.get(f"/jobs/{jid_of(star)}/files/gauge.json").content
    opened = finished(client, client.post("/law/open", files={"gauge": ("bench 7.json", gauge)}))
    assert download_name(client, jid_of(opened), "law.inp") == "bench-7_star.inp"
    wedge = finished(client, client.post("/law", data={
        "source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
        "mu_beta": "0.2", "law": "star", "directions": "72"}))
    assert download_name(client, jid_of(wedge), "gauge.json") == \
        "wedge-30-10-mu0.1-0.2_star.gauge.json"


def test_results_are_told_apart_by_source_law_and_settings(client, chain):
    surf, star, ellipse, slide, risk = chain
    sid = jid_of(surf)
    other = finished(client, client.post("/surface", data={
        "source": "file", "unit": "um", "directions": "72", "rest_level": "2e-6"},
        files={"file": (LONG + ".stl", (SURFACES / "wedge-30-10.stl").read_bytes())}))
    listing = client.get("/jobs").text
    row = re.search(rf"<tr><td><a href=\"/jobs/{sid}\">.*?</tr>", listing, re.S).group(0)
    assert "max slope 60 deg" in row and "unit um" in row and "72 directions" in row
    row2 = re.search(rf"<tr><td><a href=\"/jobs/{jid_of(other)}\">.*?</tr>", listing,
                     re.S).group(0)
    assert "rest level 2 um" in row2 and "max slope" not in row2
    star_row = re.search(rf"<tr><td><a href=\"/jobs/{jid_of(star)}\">.*?</tr>", listing,
                         re.S).group(0)
    assert f"star law of surface {LONG}.stl" in star_row and "max slope 60 deg" in star_row
    assert "truncated-ellipse law" in listing
    law_form = client.get("/motion").text             # the lists that offer the results
    assert re.search(rf'value="job:{jid_of(star)}"[^>]*>[^<]*star law of surface {LONG}'
                     rf'[^<]*max slope 60 deg', law_form)
    assert "gauge file" not in cell(slide, "settings")
    h1 = html.unescape(re.search(r"<h1>(.*?)</h1>", slide.text, re.S).group(1))
    assert f"star law of surface {LONG}.stl" in h1 and "law of a gauge file" not in h1
    assert "max slope 60 deg" in cell(surf, "settings")
    assert "surface: unit um" in cell(star, "settings")


# --------------------------------------------------------------------------- units
def test_one_unit_per_quantity_on_the_risk_page(client):
    """The SPEC two-node bar: drift -5.0e-5 m per cycle (SPEC.md section 5); the
    tolerance, beside the cycles to reach it, and the drift over the life (an
    extrapolation, below them) each in the unit its value calls for."""
    for tol in ("1e-4", "2e-6", "300"):
        page = finished(client, client.post("/motion/risk", data={
            **TWO_NODE, "tolerance": tol, "cycles": "1000"}))
        assert page.status_code == 200
        d, du = length(cell(page, "drift"))
        assert du == "um" and d == pytest.approx(-5.0e-5, rel=2e-3)
        after, au = length(cell(page, "drift-after"))
        t, tu = length(cell(page, "tolerance"))
        assert t == pytest.approx(float(tol), rel=1e-3)
        assert after == pytest.approx(1000 * -5.0e-5, rel=2e-3)
        well_chosen([after], au)
        well_chosen([t], tu)
        assert page.text.index('id="cycles_to_tolerance"') < page.text.index('id="drift"') \
            < page.text.index('id="drift-after"')           # the cycles lead
        assert "after 1\u202f000 cycles" in page.text and "1e+03" not in page.text
        res = client.get(f"/api/jobs/{jid_of(page)}/result").json()["risk"]
        assert res["drift_per_cycle_m"] == pytest.approx(d, rel=1e-3)


def test_the_risk_figure_is_plotly_with_the_nodes_in_the_unit_of_their_values(client):
    page = finished(client, client.post("/motion/risk", data=TWO_NODE))
    fig = figure(page, "risk-plot")
    nodes = [t for t in fig["data"] if t["name"].startswith("node ")]
    assert [t["name"].split(" (")[0] for t in nodes] == ["node 1", "node 2"]
    assert any(t.get("yaxis") == "y2" and "dT" in t["name"] for t in fig["data"])
    unit = re.search(r"\((nm|um|mm|m)\)", fig["layout"]["yaxis"]["title"]["text"]).group(1)
    u = [np.array(t["y"], dtype=float) * METRES[unit] for t in nodes]
    t = np.array(nodes[0]["x"], dtype=float)
    well_chosen([float(np.max(np.abs(v))) for v in u], unit)
    ends = [int(np.argmin(np.abs(t - c))) for c in (4, 5, 6)]
    per_cycle = np.diff(u[0][ends])                  # node 1 at the end of the late cycles
    assert per_cycle == pytest.approx([-5.0e-5] * 2, rel=0.02)     # SPEC.md section 5
    assert "risk-profiles" not in page.text          # a two-node bar has no profile

    strip = finished(client, client.post("/motion/risk", data={"friction": "file"}, files={
        "assembly_file": ("bushing-strip.toml", (SURFACES / "bushing-strip.toml").read_bytes()),
        "texture_file": ("wedge-asymmetric.toml",
                         (SURFACES / "wedge-asymmetric.toml").read_bytes())}))
    prof = figure(strip, "risk-profiles")
    ends = [t for t in prof["data"] if t["name"].startswith("end of cycle")]
    assert len(ends) == 6
    unit = re.search(r"\((nm|um|mm|m)\)", prof["layout"]["yaxis"]["title"]["text"]).group(1)
    last = [np.array(t["y"], dtype=float) * METRES[unit] for t in ends[-3:]]
    drift, _ = length(cell(strip, "drift"))
    assert np.mean(np.diff(last, axis=0)) == pytest.approx(drift, rel=0.05)
    xunit = re.search(r"\((nm|um|mm|m)\)", prof["layout"]["xaxis"]["title"]["text"]).group(1)
    assert max(ends[0]["x"]) * METRES[xunit] == pytest.approx(0.04, rel=1e-3)   # l = 40 mm


@pytest.mark.parametrize("amplitude, unit", [(3e-3, "mm"), (2e-6, "um"), (5e-9, "nm")])
def test_the_colour_bar_unit_follows_the_heights(client, tmp_path, amplitude, unit):
    x = np.linspace(0.0, 6 * np.pi, 96)
    z = amplitude * np.add.outer(np.sin(x), np.zeros(64))      # heights in m
    path = tmp_path / "map.npy"
    np.save(path, z)
    page = finished(client, client.post("/surface", data={
        "source": "file", "unit": "m", "pixel_size": f"{amplitude:g}", "directions": "36"},
        files={"file": ("map.npy", path.read_bytes())}))
    assert page.status_code == 200, page.text[:300]
    fig = figure(page, "heights")
    heat = fig["data"][0]
    assert heat["colorbar"]["title"]["text"] == f"height ({unit})"
    assert f"z = %{{z:.4g}} {unit}" in heat["hovertemplate"]
    top = np.nanmax(np.abs(np.array(heat["z"], dtype=float)))
    assert top * METRES[unit] == pytest.approx(amplitude, rel=0.02)
    side = re.search(r"\((nm|um|mm|m)\)", fig["layout"]["xaxis"]["title"]["text"]).group(1)
    extent = 96 * amplitude                                   # 96 pixels of that size
    assert max(heat["x"]) * METRES[side] == pytest.approx(extent, rel=0.02)
    well_chosen([extent], side)


# --------------------------------------------------------------------------- jobs
def running_job(client, seconds: float, fraction: float) -> str:
    """A job record that says it started ``seconds`` ago and is ``fraction`` done (no
    worker runs it: only its page is looked at)."""
    from asperity.io import write_text_atomic
    store = client.app.app.state.web.store
    rec = store.new_job("derive", {"source": {"kind": "wedge"}, "form": {}}, "a long one")
    store.update(rec["id"], status="running", started_at=time.time() - seconds)
    write_text_atomic(store.job_dir(rec["id"]) / "progress.json",
                      json.dumps({"fraction": fraction, "label": "directions"}))
    return rec["id"]


def seconds_of(text: str) -> float:
    """'2 min 05 s' -> 125, '1 h 02 min' -> 3720."""
    m = re.fullmatch(r"(?:(\d+) h )?(?:(\d+) min ?)?(?:(\d+) s)?", text.strip())
    assert m and any(m.groups()), text
    h, mi, s = (int(g or 0) for g in m.groups())
    return 3600 * h + 60 * mi + s


def test_the_elapsed_time_comes_from_the_stored_start_and_the_time_left_from_progress(client):
    jid = running_job(client, 125.0, 0.25)
    try:
        for _ in range(2):                         # a reload shows the same, a little later
            text = cell(client.get(f"/jobs/{jid}"), "progress-time")
            m = re.fullmatch(r"(.+) elapsed, about (.+) left", text)
            assert m, text
            elapsed, left = seconds_of(m.group(1)), seconds_of(m.group(2))
            assert 125 <= elapsed <= 140 and left == pytest.approx(3 * elapsed, abs=2)
            api = client.get(f"/api/jobs/{jid}").json()
            assert 125 <= api["elapsed_s"] <= 140 and api["since"] == "running"
            assert api["left_s"] == pytest.approx(3 * api["elapsed_s"], rel=1e-3)
            time.sleep(1.1)
        assert elapsed >= 126
    finally:
        client.app.app.state.web.store.update(jid, status="cancelled")


def test_delete_removes_the_files_and_the_entry_and_refuses_a_running_job(client):
    page = finished(client, client.post("/motion/risk", data=TWO_NODE))
    jid = jid_of(page)
    store = client.app.app.state.web.store
    folder = store.job_dir(jid)
    assert (folder / "risk.json").is_file()
    confirm = client.get(f"/jobs/{jid}/delete")
    assert confirm.status_code == 200 and 'id="confirm-delete"' in confirm.text
    assert folder.is_dir()                            # asking is not deleting
    assert f'id="delete-{jid}"' in client.get("/jobs").text
    r = client.post(f"/jobs/{jid}/delete")
    assert r.status_code == 303 and r.headers["location"] == f"/jobs?deleted={jid}"
    assert not folder.exists()
    assert not [p for p in store.jobs_dir.iterdir() if jid in p.name]   # nothing left over
    listing = client.get(r.headers["location"]).text
    assert f"result {jid} deleted" in listing and f'href="/jobs/{jid}"' not in listing
    assert client.get(f"/jobs/{jid}").status_code == 404
    assert client.get(f"/jobs/{jid}/files/risk.json").status_code == 404
    assert client.post(f"/jobs/{jid}/delete").status_code == 404

    busy = running_job(client, 5.0, 0.5)
    try:
        page = client.get(f"/jobs/{busy}/delete")
        assert 'id="delete-busy"' in page.text and 'id="confirm-delete"' not in page.text
        r = client.post(f"/jobs/{busy}/delete")
        assert r.status_code == 409 and "stop it first" in r.text
        assert (store.job_dir(busy) / "job.json").is_file()
    finally:
        store.update(busy, status="cancelled")


def test_a_deletion_cut_short_is_finished_at_the_next_start(tmp_path):
    folder = tmp_path / "data"
    with client_for(folder) as c:
        jid = jid_of(finished(c, c.post("/motion/risk", data=TWO_NODE)))
    jobs = folder / "jobs"
    (jobs / jid).rename(jobs / f".deleted-{jid}-0000")         # killed after the rename
    with client_for(folder) as c:
        assert not list(jobs.glob(".deleted-*"))
        assert jid not in c.get("/jobs").text


# --------------------------------------------------------------------------- token, home
def test_the_token_refused_page_shows_nothing_private(tmp_path):
    data = tmp_path / "private-data-folder"
    with client_for(data, host="0.0.0.0", allow_remote=True, token="s3cret") as c:
        for r in (c.get("/"), c.get("/jobs"), c.get("/", headers={"host": "evil.example"})):
            assert r.status_code == 401
            assert str(data) not in r.text and "private-data-folder" not in r.text
            assert not re.search(r"(?<![\w.:])/(tmp|home|root|var|usr|etc|Users)/", r.text)
            assert "s3cret" not in r.text
        ok = c.get("/", headers={"Authorization": "token s3cret"})
        assert ok.status_code == 200 and "private-data-folder" in ok.text   # with the token
    with client_for(tmp_path / "other-folder") as c:         # the Host refusal, loopback
        r = c.get("/", headers={"host": "evil.example"})
        assert r.status_code == 403 and "other-folder" not in r.text


def test_the_home_steps_are_numbered_once(client):
    page = client.get("/").text
    steps = re.search(r'<ol class="steps" id="steps">(.*?)</ol>', page, re.S).group(1)
    items = re.findall(r'<li><a class="button big"[^>]*>([^<]*)</a>', steps)
    assert [i.split(".")[0] for i in items[:3]] == ["1", "2", "3"]
    css = client.get("/static/style.css").text
    rule = re.search(r"(?:^|\n)\.steps \{([^}]*)\}", css).group(1)
    assert "list-style: none" in rule            # the list's own numbers are not drawn


def test_nearly_symmetric_friction_gets_a_verdict_with_its_meaning(client):
    """Issue 18 item 7 on the page: mu+ and mu- 7.7e-5 apart (an isotropic scan's pair) get
    a verdict, not a refusal: the two-node bar ratchets by the SPEC closed form's full
    amount, towards the smaller coefficient, and the page says what that rests on."""
    page = finished(client, client.post("/motion/risk", data={
        **TWO_NODE, "dT_max": "300", "mu_plus": "0.200000", "mu_minus": "0.2000154"}))
    assert page.status_code == 200, page.text[:300]
    res = client.get(f"/api/jobs/{jid_of(page)}/result").json()
    r = res["risk"]
    assert r["verdict"] == "ratchet" and r["drift_per_cycle_m"] > 0
    from asperity.microslip.closed_forms import two_node_drift_per_cycle
    want = two_node_drift_per_cycle(1e6, 5e5, 100.0, 0.2, 0.2000154, 1.2e-5, 0.1, 0.0, 300.0)
    assert r["drift_per_cycle_m"] == pytest.approx(want, rel=1e-9)
    assert r["asymmetry"] == pytest.approx(-0.0000154 / 0.2000154, rel=1e-9)
    assert len(res["notes"]) == 1 and "ratchets by the full amount" in res["notes"][0]
    assert 'id="near-symmetric"' in page.text
