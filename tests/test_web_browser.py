"""``asperity serve`` in a real browser: headless Chromium (the distribution's, driven by
Playwright) goes through the pages as a newcomer would -- the SPEC wedge, a shipped scan,
a law fitted and downloaded, a body slid, the shipped bushing's verdict, a study -- and a
screenshot of each page is taken (into reports/ with ASPERITY_SCREENSHOTS=1, which is how
the committed reports/web-*.png are refreshed; else into a scratch folder, so that a test
run leaves the tree as it was).  One server and one browser for the module."""
from __future__ import annotations

import atexit
import json
import os
import re
import shutil
import tempfile
from pathlib import Path

import pytest
from web_server import CHROMIUM, CHROMIUM_ARGS, ROOT, SHARED, Server

playwright = pytest.importorskip("playwright.sync_api")
if not Path(CHROMIUM).is_file() and not shutil.which("chromium"):
    pytest.skip("chromium is not installed (.ci/run installs it)", allow_module_level=True)

REPORTS = ROOT / "reports" if os.environ.get("ASPERITY_SCREENSHOTS") else \
    Path(tempfile.mkdtemp(prefix="asperity-shots-"))
if not os.environ.get("ASPERITY_SCREENSHOTS"):
    # the screenshots of a plain test run are thrown away with the process (they piled up
    # in /tmp, two folders a run)
    atexit.register(shutil.rmtree, REPORTS, True)
SURFACES = ROOT / "surfaces"
TIMEOUT = 90_000            # ms a result may take on a loaded 2-core machine


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    srv = Server(tmp_path_factory.mktemp("web-data"), "--workers", "2")
    yield srv
    assert srv.alive(), "the server died during the tests: " + "".join(srv.err)
    srv.stop()


@pytest.fixture(scope="module")
def browser():
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM if Path(CHROMIUM).is_file()
                              else shutil.which("chromium"), headless=True, args=CHROMIUM_ARGS)
        yield b
        b.close()


@pytest.fixture
def page(browser):
    ctx = browser.new_context(viewport={"width": 1280, "height": 1000}, accept_downloads=True)
    pg = ctx.new_page()
    pg.set_default_timeout(TIMEOUT)
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    yield pg
    ctx.close()
    assert not errors, f"JavaScript errors on the page: {errors}"


def shot(pg, name: str) -> None:
    pg.wait_for_timeout(300)                      # let Plotly finish its transitions
    pg.screenshot(path=str(REPORTS / name), full_page=True)
    assert (REPORTS / name).stat().st_size > 20_000, name


def result_page(pg):
    """Wait until the job's page shows its result (or the form with an error)."""
    pg.wait_for_selector("main h1")
    pg.wait_for_function("!document.getElementById('progress')", timeout=TIMEOUT)


def test_spec_wedge_from_the_home_page(server, page):
    page.goto(server.url)
    page.click("#start")                          # the newcomer's first button
    assert "/surface" in page.url
    for name, value in (("alpha_deg", "30"), ("beta_deg", "10"), ("mu_alpha", "0.1"),
                        ("mu_beta", "0.2")):
        page.fill(f"#wedge-form [name={name}]", value)
    page.click("#derive-wedge")
    result_page(page)
    assert page.inner_text("#mu_a_plus").strip() == "0.185697"        # SPEC.md check value
    assert page.inner_text("#mu_a_minus").strip() == "0.193238"
    assert page.inner_text("#self_locking").strip() == "none"
    page.wait_for_selector("#polar[data-drawn='1'] .main-svg")
    hover = page.evaluate("""() => { const el = document.getElementById('polar');
        Plotly.Fx.hover(el, [{curveNumber: 0, pointNumber: 30}]);
        const t = el.querySelector('.hovertext'); return t ? t.textContent : ''; }""")
    assert "psi = 30.00 deg" in hover and "T = p.s" in hover and "L = p.s_perp" in hover, hover


@pytest.mark.skipif(not SHARED.is_dir(), reason=f"measured surfaces not found in {SHARED} "
                                                "(../shared/data/surfaces/)")
def test_shipped_scan_shows_its_principal_direction(server, page):
    page.goto(server.base + "/surface")
    page.set_input_files("#f-file", str(SHARED / "SkiInfiniteFocus.x3p"))   # read in place
    page.click("#derive-file")
    result_page(page)
    angle = float(page.inner_text("#principal_direction"))
    assert 115.0 < angle < 125.0, angle          # across the grind grooves (data README)
    assert "SkiInfiniteFocus.x3p" in page.inner_text("h1")
    quality = page.inner_text("#data-quality")
    assert "undefined" in quality and "4272" in quality
    page.wait_for_selector("#heights[data-drawn='1'] .main-svg")
    shot(page, "web-surface.png")


def test_fit_download_the_gauge_file_and_validate_it(server, page, tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    page.goto(server.base + "/law")
    page.select_option("#f-source", "wedge")
    page.select_option("#f-law", "star")
    page.click("#fit")
    result_page(page)
    assert page.inner_text("#law-kind") == "star"
    assert float(page.inner_text("#max_radial_error")) < 1e-6
    assert page.inner_text("#law_mu_a_plus").startswith("0.1856")
    with page.expect_download() as dl:
        page.click("#dl-gauge-json")
    path = tmp_path / "gauge.json"
    dl.value.save_as(str(path))
    schema = json.loads((ROOT / "asperity" / "schemas" / "gauge-1.schema.json").read_text())
    gauge = json.loads(path.read_text())
    jsonschema.validate(gauge, schema)
    assert gauge["format"] == "asperity-gauge" and gauge["law"] == "star"
    from asperity import read_gauge
    assert read_gauge(path).kind == "star"        # the library reads what the page gave
    for name, head in (("dl-law-csv", "psi_deg,p_a,p_b"), ("dl-law-inp", "** asperity")):
        with page.expect_download() as dl:
            page.click(f"#{name}")
        out = tmp_path / name
        dl.value.save_as(str(out))
        assert out.read_text().startswith(head)
    page.wait_for_selector("#plane[data-drawn='1'] .main-svg")
    shot(page, "web-law.png")
    page.click("#to-slide")                       # step 3 with this law chosen
    assert page.input_value("#f-law").startswith("job:")
    page.click("#run-slide")
    result_page(page)
    assert re.fullmatch(r"\(\d+\.?\d*, \d+\.?\d*\) (nm|um|mm|m)", page.inner_text("#rest"))
    assert re.match(r"[+-]\d+\.\d{4} deg", page.inner_text("#deflection"))
    page.wait_for_selector("#path[data-drawn='1'] .main-svg")


def test_shipped_bushing_ratchets(server, page):
    page.goto(server.base + "/motion")
    page.set_input_files("#f-assembly_file", str(SURFACES / "bushing-strip.toml"))
    page.select_option("#f-friction", "file")
    page.set_input_files("#f-texture_file", str(SURFACES / "wedge-asymmetric.toml"))
    page.click("#run-risk")
    result_page(page)
    assert page.inner_text("#verdict").strip().lower() == "ratchet"
    assert re.fullmatch(r"\+274\.\d nm", page.inner_text("#drift"))  # README's +0.27 um
    assert page.inner_text("#cycles_to_tolerance").strip() == "364"
    page.wait_for_selector("#risk-plot[data-drawn='1'] .main-svg")
    page.wait_for_selector("#risk-profiles[data-drawn='1'] .main-svg")
    shot(page, "web-motion.png")


def test_the_defaults_alone_give_a_verdict(server, page):
    """A newcomer who only presses the button gets the illustrative bushing's verdict."""
    page.goto(server.base + "/motion")
    page.select_option("#f-friction", "wedge")
    page.click("#run-risk")
    result_page(page)
    assert page.inner_text("#verdict").strip().lower() == "ratchet"


def test_the_shipped_study_runs_with_progress_summary_and_downloads(server, page, tmp_path):
    """The 10 000 cases of the shipped tolerance study (a few seconds): the page shows the
    progress bar, then the summary, the figures and the downloads."""
    page.goto(server.base + "/studies")
    page.set_input_files("#f-study", str(SURFACES / "bushing-tolerance.toml"))
    page.set_input_files("#f-companions", [str(SURFACES / "wedge-asymmetric.toml"),
                                           str(SURFACES / "bushing-strip.toml")])
    page.click("#run-study")
    page.wait_for_selector("#progress-bar")      # the job outlives the form's short wait
    seen = 0.0
    for _ in range(3000):                        # until the page shows the result
        try:
            v = page.evaluate("() => { const b = document.getElementById('progress-bar');"
                              " return b ? b.value : -1; }")
        except playwright.Error:                  # the page reloading with the result
            v = 0.0
        if v == -1:
            break
        seen = max(seen, v)
        page.wait_for_timeout(50)
    assert 0.0 < seen <= 1.0, seen                # the bar moved before the result came
    page.wait_for_selector("#study-text", timeout=TIMEOUT)
    assert page.inner_text("#study-completed") == "10000"
    assert "ratchet" in page.inner_text("#study-verdicts")
    assert 0.9 < float(page.inner_text("#p-ratchet")) <= 1.0
    page.wait_for_function("[...document.querySelectorAll('img.figure')].length > 0 && "
                           "[...document.querySelectorAll('img.figure')]"
                           ".every(i => i.naturalWidth > 0)")
    for name, rows in (("dl-cases-parquet", "parquet"), ("dl-cases-csv", "csv")):
        with page.expect_download() as dl:
            page.click(f"#{name}")
        out = tmp_path / f"cases.{rows}"
        dl.value.save_as(str(out))
        if rows == "parquet":
            import pyarrow.parquet as pq
            assert pq.read_table(out).num_rows == 10000
        else:
            assert len(out.read_text().splitlines()) == 10001
    shot(page, "web-studies.png")


def test_every_page_answers_without_javascript_errors(server, page):
    for path in ("/", "/surface", "/law", "/motion", "/studies", "/jobs"):
        page.goto(server.base + path)
        assert page.locator("header nav a").count() == 5
    page.goto(server.base + "/")
    shot(page, "web-home.png")


def test_a_crawl_from_the_motion_page(server, page):
    """The crawl form's defaults (three coefficients, componentwise, dynamic): the speed
    with its rule, and the body's snapshots and the speed drawn by Plotly."""
    page.goto(server.base + "/motion")
    page.select_option("#f-c_law", "coefficients")
    page.select_option("#f-c_rule", "associated")
    page.click("#run-crawl")
    result_page(page)
    assert re.fullmatch(r"\+0\.3\d{4,5} body lengths per period", page.inner_text("#speed"))
    assert page.inner_text("#rule").strip() == "associated"
    page.wait_for_selector("#crawl-snapshots[data-drawn='1'] .main-svg")
    page.wait_for_selector("#crawl-speed[data-drawn='1'] .main-svg")
    shot(page, "web-crawl.png")
