"""The web page as a new user met it (issue 25, item 6), in headless Chromium: a refused
field inside a collapsed section opens it; a form's choices survive an error on another
form of the page; the Law page offers only the pressures of the result chosen; the
progress bar never goes back nor shows 100 % before the end; a map's axes span the map;
every table fits its card at 1280 and at 800 px."""
from __future__ import annotations

import json
import time
from itertools import pairwise

import numpy as np
import pytest
from test_web_browser import browser, page, server, shot  # noqa: F401
from test_web_contact import bumps
from test_web_pages_browser import submit
from web_server import ROOT

SURFACES = ROOT / "surfaces"
WEDGE = {"source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
         "mu_beta": "0.2", "contact": "all-faces", "method": "closed-form", "directions": "72"}
ELASTIC = {"load": "elastic", "E_star": "1e11"}
#: the wedge pressed on a softer support: its plane-strain solve needs far fewer nodes per
#: wedge at these p / E* (4 s a pressure at E* = 1e11 on a loaded machine, the slowest part
#: of this file), and the pages' tables are the same
SOFT = {"load": "elastic", "E_star": "1e9"}
STRIP = {"model": "strip", "strip_h": "2.5e-3", "strip_E": "1.1e11", "strip_p": "5e7",
         "strip_l": "0.04", "strip_k_t": "1e13", "strip_alpha_T": "6e-6", "strip_n": "21",
         "dT_min": "0", "dT_max": "120"}

#: the tables of the page that reach past their card's inner edge (or scroll inside),
#: and the page's width
TABLES = """() => {
  const out = [];
  for (const t of document.querySelectorAll('main table')) {
    const c = t.closest('.card') || t.closest('main');
    const r = t.getBoundingClientRect(), b = c.getBoundingClientRect();
    const pad = parseFloat(getComputedStyle(c).paddingRight) || 0;
    if (r.right > b.right - pad + 1 || t.scrollWidth > t.clientWidth + 1)
      out.push((t.id || t.className) + ' [' + Math.round(r.right) + ' > ' +
               Math.round(b.right - pad) + ']');
  }
  return {width: document.documentElement.scrollWidth, out: out};
}"""


@pytest.fixture(scope="module")
def results(server, tmp_path_factory):
    """One result of each page that has tables: the wedge, the bumps map pressed with a
    hardness, a wedge family and its law family, one member's law, a risk verdict on the
    pressed map, the shipped bushing's verdict, a ring slid, a crawl."""
    path = tmp_path_factory.mktemp("clarity-browser") / "bumps.txt"
    np.savetxt(path, bumps(), fmt="%.6f")
    out = {"wedge": submit(server, "/surface", WEDGE)}
    out["map"] = submit(server, "/surface", {
        "source": "file", "unit": "um", "pixel_size": "0.5", "mu": "0.15",
        "directions": "72", **ELASTIC, "pressure": "2e8", "hardness": "6e8"},
        files={"file": ("bumps.txt", path.read_bytes())})
    out["family"] = submit(server, "/surface", {**WEDGE, **SOFT, "pressure": "1e6 1e7 5e7"})
    out["one"] = submit(server, "/surface", {**WEDGE, **SOFT, "pressure": "2e7"})
    fam = out["family"]
    out["law_family"] = submit(server, "/law", {"source": fam, "pressure": f"{fam}:family",
                                                "law": "star", "directions": "72"})
    out["member"] = submit(server, "/law", {"source": fam, "pressure": f"{fam}:1",
                                            "law": "ellipse", "directions": "72"})
    out["risk"] = submit(server, "/motion/risk", {**STRIP, "friction": f"job:{out['map']}"})
    out["bushing"] = submit(server, "/motion/risk", {"friction": "file"}, files={
        "assembly_file": ("bushing-strip.toml", (SURFACES / "bushing-strip.toml").read_bytes()),
        "texture_file": ("wedge-asymmetric.toml",
                         (SURFACES / "wedge-asymmetric.toml").read_bytes())})
    out["ring"] = submit(server, "/motion/slide", {
        "law": "ellipse", "mu1": "0.2", "mu2": "0.1", "u0": "0.3", "angle_deg": "30",
        "dt": "1e-3", "body": "ring", "radius": "0.05", "contact_points": "64",
        "omega0": "10"})
    out["crawl"] = submit(server, "/motion/crawl", {
        "c_mu_f": "0.1", "c_mu_b": "0.15", "c_mu_t": "0.2", "c_points": "40", "c_periods": "4"})
    return out


def test_every_table_fits_its_card_at_1280_and_800_px(server, page, results):
    paths = ["/", "/surface", "/law", "/motion", "/jobs"] + [f"/jobs/{j}" for j in
                                                             results.values()]
    for width in (1280, 800):
        page.set_viewport_size({"width": width, "height": 900})
        for path in paths:
            page.goto(server.base + path)
            got = page.evaluate(TABLES)
            assert got["out"] == [] and got["width"] <= width, (width, path, got)
    page.goto(f"{server.base}/jobs/{results['family']}")
    shot(page, "web-family-800.png")


def test_the_maps_axes_span_the_map(server, page, results):
    """20 x 20 um of bumps, drawn to scale in a wide card: the axes from 0 to 20 um."""
    page.goto(f"{server.base}/jobs/{results['map']}")
    for pid in ("contact_map", "heights"):
        page.wait_for_selector(f"#{pid}[data-drawn='1'] .main-svg")
        ranges = page.evaluate(f"""() => {{ const l = document.getElementById('{pid}')
            ._fullLayout; return [l.xaxis.range, l.yaxis.range, l.xaxis.title.text]; }}""")
        assert ranges[2] == "x (um)", ranges
        for r in ranges[:2]:
            assert r == pytest.approx([0.0, 20.0], abs=1e-6), (pid, ranges)


def test_an_error_in_a_collapsed_section_opens_it(server, page):
    page.goto(server.base + "/motion")
    page.select_option("#f-law", "coulomb")
    page.evaluate("""() => { const d = document.querySelector('#slide details');
        d.open = true; document.getElementById('f-dt').value = 'abc'; d.open = false; }""")
    page.click("#run-slide")
    page.wait_for_selector("#error")
    err = page.locator("#slide .field-error")
    assert err.count() == 1 and "time step" in err.inner_text()
    assert page.evaluate("document.querySelector('#slide details').open")
    assert err.is_visible() and page.locator("#f-dt").is_visible()


def test_the_risk_forms_choice_survives_an_error_on_the_slide_form(server, page, results):
    page.goto(f"{server.base}/motion?texture={results['map']}")
    assert page.input_value("#f-friction") == f"job:{results['map']}"
    page.select_option("#f-friction", "mu")
    page.fill("#f-mu_plus", "0.31")
    page.fill("#f-dT_max", "95")
    page.fill("#f-u0", "fast")                      # the slide form refuses it
    page.click("#run-slide")
    page.wait_for_selector("#error")
    assert "u0" in page.inner_text("#slide .field-error")
    assert page.input_value("#f-friction") == "mu"
    assert page.input_value("#f-mu_plus") == "0.31" and page.input_value("#f-dT_max") == "95"
    assert page.locator("#f-mu_plus").is_visible()    # its fieldset shown for that choice
    assert page.input_value("#f-u0") == "fast"        # the refused form as it was sent
    page.goto(server.base + "/motion")                # a page opened afresh: the defaults
    assert page.input_value("#f-friction") == "wedge"


def test_the_law_page_offers_only_the_chosen_results_pressures(server, page, results):
    fam, one = results["family"], results["one"]
    page.goto(f"{server.base}/law?source={fam}")

    def offered() -> list:
        return page.evaluate("""() => [...document.getElementById('f-pressure').options]
            .filter(o => !o.hidden && !o.disabled).map(o => [o.value, o.text])""")
    got = offered()
    assert [v for v, _ in got] == [f"{fam}:family", f"{fam}:0", f"{fam}:1", f"{fam}:2"]
    assert got[2][1] == "p = 10 MPa alone" and "1 MPa to 50 MPa" in got[0][1]
    assert page.input_value("#f-pressure") == f"{fam}:family"
    page.select_option("#f-source", one)
    assert offered() == [[f"{one}:0", "its only pressure, p = 20 MPa"]]
    assert page.input_value("#f-pressure") == f"{one}:0"
    page.select_option("#f-source", "wedge")
    assert not page.locator("#f-pressure").is_visible()


def test_the_progress_bar_never_goes_back(server, page):
    """The job's answers as an older worker gave them (each piece of work from 0 to 1 on
    the whole bar): the page's bar keeps its highest value and says 99 % at most until
    the job is done."""
    from asperity.io import write_text_atomic
    from asperity.web.store import Store
    store = Store(server.data_dir)
    rec = store.new_job("derive", {"source": {"kind": "wedge"}, "form": {}}, "a long one")
    store.update(rec["id"], status="running", started_at=time.time() - 30)
    write_text_atomic(store.job_dir(rec["id"]) / "progress.json",
                      json.dumps({"fraction": 0.3, "label": "contact"}))
    answers = [0.3, 0.62, 1.0, 0.03, 0.4, 0.2, 0.7]
    served = []

    def api(route):
        f = answers[min(len(served), len(answers) - 1)]
        served.append(f)
        route.fulfill(json={"id": rec["id"], "kind": "derive", "status": "running",
                            "fraction": f, "label": "piece", "error": None, "files": [],
                            "elapsed_s": 30.0, "left_s": 20.0, "since": "running"})
    page.route(f"**/api/jobs/{rec['id']}", api)
    try:
        page.goto(f"{server.base}/jobs/{rec['id']}")
        seen = []
        while len(served) < len(answers) + 2:
            seen.append((page.evaluate("document.getElementById('progress-bar').value"),
                         page.inner_text("#progress-pct")))
            page.wait_for_timeout(100)
    finally:
        page.unroute(f"**/api/jobs/{rec['id']}")
        store.update(rec["id"], status="cancelled")
    values = [v for v, _ in seen]
    assert all(a <= b for a, b in pairwise(values)), seen
    assert max(values) == pytest.approx(0.99) and all(t != "100 %" for _, t in seen), seen
