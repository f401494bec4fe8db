"""The web page as a new user meets it (issue 18, section 8), in headless Chromium at
1280 x 1000 px: result pages with long values stay inside the window and their cards, plot
titles clear of Plotly's toolbar, the elapsed time of a job surviving a reload, a result
deleted from All results, the risk figure drawn by Plotly, the home steps numbered once."""
from __future__ import annotations

import json
import re
import time

import httpx
import pytest
from test_web_browser import TIMEOUT, browser, page, server, shot  # noqa: F401
from web_server import ROOT, wait_for

SURFACES = ROOT / "surfaces"
#: a long name without a break opportunity (hyphens are one)
LONG = "a_measured_surface_with_a_very_long_name_from_the_instrument_" \
       "0123456789_abcdefghij_klmnopqrst"
TWO_NODE = {"model": "two-node", "two_k": "1e6", "two_l0": "0.1", "two_alpha_T": "1.2e-5",
            "two_k_t": "5e5", "two_N": "100", "dT_min": "0", "dT_max": "125",
            "friction": "mu", "mu_plus": "0.2", "mu_minus": "0.1"}

#: every element inside a card that reaches past the card's edges (Plotly's own layers
#: excepted: the plot's box is checked), and the page's width
OVERFLOW = """() => {
  const out = [];
  for (const card of document.querySelectorAll('.card')) {
    const c = card.getBoundingClientRect();
    for (const el of card.querySelectorAll('*')) {
      if (el.closest('.plot') && !el.classList.contains('plot')) continue;
      const r = el.getBoundingClientRect();
      if (r.width === 0 || r.height === 0) continue;
      if (r.right > c.right + 1 || r.left < c.left - 1)
        out.push(el.tagName + '#' + el.id + ' ' + (el.textContent || '').slice(0, 60) +
                 ' [' + Math.round(r.left) + ', ' + Math.round(r.right) + '] in [' +
                 Math.round(c.left) + ', ' + Math.round(c.right) + ']');
    }
  }
  return {width: document.documentElement.scrollWidth, out: out};
}"""


def submit(srv, path: str, data: dict, files=None) -> str:
    """Post a form to the real server; the id of the job once finished."""
    r = httpx.post(srv.base + path, data=data, files=files, timeout=60)
    assert r.status_code == 303, (r.status_code, r.text[:300])
    jid = r.headers["location"].rsplit("/", 1)[-1]
    wait_for(lambda: httpx.get(f"{srv.base}/api/jobs/{jid}").json()["status"]
             not in ("queued", "running"), timeout=TIMEOUT / 1000)
    assert httpx.get(f"{srv.base}/api/jobs/{jid}").json()["status"] == "done"
    return jid


@pytest.fixture(scope="module")
def results(server):
    """Results with long values: a surface file with a long name, a star law fitted to it,
    a slide on that law, a risk verdict of an assembly file with a long name on it, the
    shipped bushing's verdict."""
    surf = submit(server, "/surface", {"source": "file", "unit": "um", "max_slope": "60",
                                       "directions": "72"},
                  {"file": (LONG + ".stl", (SURFACES / "wedge-30-10.stl").read_bytes())})
    law = submit(server, "/law", {"source": surf, "law": "star", "directions": "72"})
    slide = submit(server, "/motion/slide", {"law": f"job:{law}", "u0": "0.5",
                                             "angle_deg": "30"})
    risk = submit(server, "/motion/risk", {"friction": f"law:{law}"}, {"assembly_file": (
        LONG + ".toml", (SURFACES / "two-node-spec.toml").read_bytes())})
    strip = submit(server, "/motion/risk", {"friction": "file"}, {
        "assembly_file": ("bushing-strip.toml", (SURFACES / "bushing-strip.toml").read_bytes()),
        "texture_file": ("wedge-asymmetric.toml",
                         (SURFACES / "wedge-asymmetric.toml").read_bytes())})
    return {"surface": surf, "law": law, "slide": slide, "risk": risk, "strip": strip}


def test_every_page_fits_a_1280_window_and_nothing_runs_out_of_its_card(server, page,
                                                                        results):
    assert page.viewport_size["width"] == 1280
    paths = ["/", "/surface", "/law", "/motion", "/studies", "/jobs",
             f"/jobs/{results['surface']}/delete"] + [f"/jobs/{j}" for j in results.values()]
    for path in paths:
        page.goto(server.base + path)
        page.wait_for_load_state("load")
        for el in page.query_selector_all("[data-figure]"):
            page.wait_for_selector(f"#{el.get_attribute('id')}[data-drawn='1'] .main-svg")
        got = page.evaluate(OVERFLOW)
        assert got["width"] <= 1280, (path, got["width"])
        assert not got["out"], (path, got["out"][:5])
    page.goto(f"{server.base}/jobs/{results['surface']}")
    assert LONG in page.inner_text("h1")
    shot(page, "web-long-names.png")


def test_plot_titles_are_clear_of_the_plotly_toolbar(server, page, results):
    seen = 0
    for key in ("surface", "law", "slide", "strip"):
        page.goto(f"{server.base}/jobs/{results[key]}")
        for el in page.query_selector_all("[data-figure]"):
            pid = el.get_attribute("id")
            page.wait_for_selector(f"#{pid}[data-drawn='1'] .main-svg")
            page.hover(f"#{pid} .main-svg")            # the toolbar shows on hover
            fig = json.loads(page.inner_text(f"#fig-{pid}"))
            boxes = page.evaluate("""(pid) => {
              const box = (e) => { const r = e.getBoundingClientRect();
                                   return [r.left, r.top, r.right, r.bottom]; };
              const plot = document.getElementById(pid);
              const bar = plot.querySelector('.modebar');
              const titles = [...plot.querySelectorAll('.gtitle')].map(box);
              const cap = document.getElementById(pid + '-title');
              if (cap) titles.push(box(cap));
              return {bar: bar ? box(bar) : null, titles: titles,
                      caption: cap ? cap.textContent : null}; }""", pid)
            assert boxes["bar"] is not None, pid
            assert boxes["caption"] == fig["layout"]["title"]["text"], pid
            left, top, right, bottom = boxes["bar"]
            for t in boxes["titles"]:
                apart = t[2] <= left or t[0] >= right or t[3] <= top or t[1] >= bottom
                assert apart, (key, pid, boxes)
            seen += 1
    assert seen >= 7


def test_the_elapsed_time_survives_a_reload(server, page):
    from asperity.io import write_text_atomic
    from asperity.web.store import Store
    store = Store(server.data_dir)
    rec = store.new_job("derive", {"source": {"kind": "wedge"}, "form": {}}, "a long one")
    store.update(rec["id"], status="running", started_at=time.time() - 125)
    write_text_atomic(store.job_dir(rec["id"]) / "progress.json",
                      json.dumps({"fraction": 0.25, "label": "directions"}))

    def shown() -> tuple[int, int]:
        text = page.inner_text("#progress-time")
        m = re.fullmatch(r"(\d+) min (\d+) s elapsed, about (\d+) min (\d+) s left", text)
        assert m, text
        a, b, c, d = (int(g) for g in m.groups())
        return 60 * a + b, 60 * c + d
    try:
        page.goto(f"{server.base}/jobs/{rec['id']}")
        first, left = shown()
        assert 125 <= first < 140 and abs(left - 3 * first) <= 3
        page.wait_for_timeout(1500)                       # the page's own clock ticks on
        ticked, _ = shown()
        assert ticked > first
        page.reload()
        again, left = shown()
        assert again >= ticked and abs(left - 3 * again) <= 3        # not back to 0
    finally:
        store.update(rec["id"], status="cancelled")


def test_a_result_is_deleted_from_all_results_after_a_confirmation(server, page):
    jid = submit(server, "/motion/risk", TWO_NODE)
    folder = server.data_dir / "jobs" / jid
    assert folder.is_dir()
    page.goto(server.base + "/jobs")
    page.click(f"#delete-{jid}")
    page.wait_for_selector("#confirm-delete")
    assert folder.is_dir()
    shot(page, "web-delete.png")
    page.click("#confirm-delete")
    page.wait_for_selector("#notice")
    assert f"result {jid} deleted" in page.inner_text("#notice")
    assert page.query_selector(f"#delete-{jid}") is None
    assert not folder.exists()


def test_the_risk_figure_is_interactive(server, page, results):
    page.goto(f"{server.base}/jobs/{results['strip']}")
    page.wait_for_selector("#risk-plot[data-drawn='1'] .main-svg")
    names = page.evaluate("document.getElementById('risk-plot').data.map(t => t.name)")
    assert [n.split(" (")[0] for n in names[:3]] == ["node 1", "node 101", "node 201"]
    hover = page.evaluate("""() => { const el = document.getElementById('risk-plot');
        Plotly.Fx.hover(el, [{curveNumber: 2, pointNumber: 40}]);
        const t = el.querySelector('.hovertext'); return t ? t.textContent : ''; }""")
    assert re.search(r"u = -?[\d.]+ (nm|um|mm)", hover), hover
    page.wait_for_selector("#risk-profiles[data-drawn='1'] .main-svg")


def test_the_home_steps_are_numbered_once(server, page):
    page.goto(server.base + "/")
    got = page.evaluate("""() => [...document.querySelectorAll('#steps > li')].map(li =>
        [getComputedStyle(li).listStyleType, li.innerText.trim().slice(0, 3)])""")
    assert len(got) == 4
    for style, text in got:
        assert style == "none" or not re.match(r"\d", text), got
