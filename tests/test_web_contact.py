"""The Surface page's elastic contact through a real ``asperity serve`` (127.0.0.1, started
and stopped here, importing the package under test): the same numbers as ``asperity
derive --elastic ... --json``, a family of three pressures with its curves and contact
figures, the Law page fitting one chosen pressure, and hostile values in every new field
(4xx, one line next to the field, the form kept)."""
from __future__ import annotations

import json
import re
import time

import numpy as np
import pytest

pytest.importorskip("fastapi")
httpx = pytest.importorskip("httpx")
from cli_run import run_json  # noqa: E402
from web_forms import Page  # noqa: E402
from web_server import Server, wait_for  # noqa: E402

E_STAR = 1e11
#: the page's and the command line's settings of one map
SETTINGS = {"unit": "um", "pixel_size": "0.5", "mu": "0.15", "directions": "72"}


def bumps(n: int = 40) -> np.ndarray:
    """A smooth, direction-dependent map (um): asymmetric ridges along y with a cross
    ripple, so the contact spots are resolved by tens of pixels."""
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    t = (i % 20) / 20.0
    ridge = np.where(t < 0.7, t / 0.7, (1.0 - t) / 0.3)
    z = 0.8 * ridge ** 2 + 0.15 * np.cos(2 * np.pi * j / 20.0)
    z[30:33, 5:8] = np.nan                       # undefined pixels: no data, no load
    return z


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    folder = tmp_path_factory.mktemp("web-contact")
    path = folder / "bumps.txt"
    np.savetxt(path, bumps(), fmt="%.6f")
    s = Server(folder / "data", "--workers", "1")
    try:
        wait_for(lambda: any("data folder" in line for line in s.err), 30)
        with httpx.Client(base_url=s.base, timeout=120, follow_redirects=False) as c:
            yield c, path
    finally:
        s.stop()


def job(c, resp, timeout: float = 240.0) -> str:
    """The id of the job a form started, once it has finished (done)."""
    assert resp.status_code == 303, (resp.status_code, resp.text[:400])
    jid = resp.headers["location"].rsplit("/", 1)[-1]
    t0 = time.monotonic()
    while (st := c.get(f"/api/jobs/{jid}").json())["status"] in ("queued", "running"):
        assert time.monotonic() - t0 < timeout, st
        time.sleep(0.2)
    assert st["status"] == "done", st
    return jid


def surface(c, path, **fields):
    data = {"source": "file", **SETTINGS, "load": "elastic", "E_star": f"{E_STAR:g}", **fields}
    return c.post("/surface", data=data, files=[("file", (path.name, path.read_bytes()))])


def figure(html: str, name: str) -> dict:
    m = re.search(rf'<script type="application/json" id="fig-{name}">(.*?)</script>', html,
                  re.S)
    assert m, name
    return json.loads(m.group(1))


def cli(capsys, path, *pressures):
    return run_json(capsys, "derive", path, "--unit", "um", "--pixel-size", "0.5", "--mu",
                    "0.15", "--directions", "72", "--elastic", f"{E_STAR:g}", "--pressure",
                    *[f"{p:g}" for p in pressures])


def test_one_pressure_gives_the_numbers_of_derive_elastic_json(site, capsys):
    c, path = site
    jid = job(c, surface(c, path, pressure="2e8"))
    page = c.get(f"/jobs/{jid}").text
    got = json.loads(c.get(f"/jobs/{jid}/files/derive.json").content)
    want = cli(capsys, path, 2e8)
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus",
              "principal_direction_deg"):
        assert got[k] == pytest.approx(want[k], rel=1e-9, abs=1e-12), k
        shown = re.search(rf'id="{k.replace("_deg", "")}">([^<]+)<', page)
        if shown and k != "principal_direction_deg":
            assert float(shown.group(1)) == pytest.approx(want[k], abs=5e-7), k
    ec, wc = got["elastic_contact"], want["elastic_contact"]
    for k in ("area_fraction", "pressure_Pa", "max_pressure_Pa", "mean_gap_m", "E_star_Pa",
              "iterations"):
        assert ec[k] == pytest.approx(wc[k], rel=1e-9), k
    assert ec["boundary"] == wc["boundary"] == "free"
    assert 0.0 < ec["area_fraction"] < 1.0
    # the contact figures on the page: one row, the area fraction as derive gives it
    rows = re.findall(r'class="area-fraction">([0-9.]+)', page)
    assert [float(x) for x in rows] == [pytest.approx(wc["area_fraction"], abs=5e-5)]
    assumes = re.findall(r'class="explain small assumes">([^<]+)<', page)
    assert len(assumes) == 2 and "facet law is unchanged" in assumes[0]
    assert "hardness" in assumes[1] and "sliding redistributes" in assumes[1]
    cmap = figure(page, "contact_map")
    heat = cmap["data"][0]
    assert heat["type"] == "heatmap" and len(heat["z"]) == 40 and len(heat["z"][0]) == 40
    unit = heat["colorbar"]["title"]["text"]
    scale = {"(MPa)": 1e6, "(GPa)": 1e9, "(kPa)": 1e3}[unit[unit.index("("):]]
    top = wc["max_pressure_Pa"]
    assert scale == max(s for s in (1.0, 1e3, 1e6, 1e9) if top / s >= 1)   # from the data
    peak = max(v for row in heat["z"] for v in row if v is not None) * scale
    assert peak == pytest.approx(top, rel=1e-4)
    # undefined pixels: no value in the heat map, and drawn by the grey layer (z is (y, x);
    # a text matrix's lines are y, so the file's lines 30-32, columns 5-7 are y 30-32)
    holes = {(jy, ix) for jy in range(30, 33) for ix in range(5, 8)}
    none = {(jy, ix) for jy, row in enumerate(heat["z"]) for ix, v in enumerate(row)
            if v is None}
    grey = {(jy, ix) for jy, row in enumerate(cmap["data"][1]["z"])
            for ix, v in enumerate(row) if v is not None}
    assert none == holes and grey == holes


def test_three_pressures_give_three_curves_and_the_contact_figures(site, capsys):
    c, path = site
    ps = (5e7, 2e8, 8e8)
    jid = job(c, surface(c, path, pressure=" ".join(f"{p:g}" for p in ps)))
    page = c.get(f"/jobs/{jid}").text
    want = cli(capsys, path, *ps)
    polar = figure(page, "polar")
    assert len(polar["data"]) == 3
    assert len({t["line"]["color"] for t in polar["data"]}) == 3
    for t, member in zip(polar["data"], want["members"]):
        xs = [d["p"][0] for d in member["directions"]]
        assert [round(x, 7) for x in xs] == pytest.approx(t["x"][:-1], abs=2e-7)
    axes = figure(page, "axes")
    assert [len(t["x"]) for t in axes["data"]] == [3, 3, 3]
    assert axes["data"][0]["y"] == pytest.approx([r["mu_a_plus"] for r in want["summary"]],
                                                 rel=1e-9)
    fr = [r["area_fraction"] for r in want["summary"]]
    assert fr[0] < fr[1] < fr[2]                           # more contact under more load
    rows = [float(x) for x in re.findall(r'class="area-fraction">([0-9.]+)', page)]
    assert rows == pytest.approx(fr, abs=5e-5)
    assert len(re.findall(r'class="family-row"', page)) == 3
    # one common axis for mu_a+-, named under the table and in the figure's title
    ref = f"{want['reference_direction_deg']:.2f} deg"
    assert ref in re.search(r'id="family-reference">([^<]+)<', page).group(1)
    assert ref in axes["layout"]["title"]["text"]
    turned = [r["axes_reversed"] for r in want["summary"]]
    assert page.count("(turned)</td>") == sum(turned)
    cmap = figure(page, "contact_map")
    assert len(cmap["data"]) == 6 and len(cmap["layout"]["updatemenus"][0]["buttons"]) == 3
    # the Law page offers the three pressures and fits the one chosen, saying so
    law = c.get(f"/law?source={jid}").text
    assert all(f'value="{jid}:{k}"' in law for k in range(3))
    assert re.search(rf'<option value="{jid}:family" data-source="{jid}" selected>', law)
    # (the whole family first; each option names the result it belongs to)
    fit = job(c, c.post("/law", data={"source": jid, "law": "star", "directions": "72",
                                      "pressure": f"{jid}:1"}))
    text = c.get(f"/jobs/{fit}").text
    note = re.search(r'id="law-pressure-note">([^<]+)<', text).group(1)
    assert "p = 200 MPa" in note and "one of the 3 pressures" in note
    gauge = json.loads(c.get(f"/jobs/{fit}/files/gauge.json").content)
    src = json.dumps(gauge)
    assert f'"area_fraction": {want["summary"][1]["area_fraction"]!r}'[:30] in src


def test_a_range_and_the_materials(site, capsys):
    """pressures from 1e6 to 1e8, 3 of them: 1e6, 1e7, 1e8 (spaced in log); E1 = 2e11,
    nu1 = 0.3 on a rigid counterface: E* = E1 / (1 - nu1^2)."""
    c, path = site
    jid = job(c, surface(c, path, E_star="", E1="2e11", nu1="0.3", pressure="",
                         p_min="1e6", p_max="1e8", p_count="3"))
    got = json.loads(c.get(f"/jobs/{jid}/files/derive.json").content)
    assert got["pressures_Pa"] == pytest.approx([1e6, 1e7, 1e8], rel=1e-12)
    assert got["E_star_Pa"] == pytest.approx(2e11 / 0.91, rel=1e-12)
    page = c.get(f"/jobs/{jid}").text
    assert len(re.findall(r'class="contact-row"', page)) == 3


def test_full_contact_is_a_result(site):
    c, path = site
    jid = job(c, surface(c, path, pressure="2e10", boundary="periodic"))
    page = c.get(f"/jobs/{jid}").text
    assert 'class="full-contact"' in page and 'id="full-contact"' in page


#: hostile values of the new fields (field -> values); each a 400 at the field
HOSTILE = {"E_star": ("abc", "", "nan", "inf", "-1", "0", "1e999", "1e14"),
           "pressure": ("abc", "", "nan", "-inf", "-1", "0", "1e999", "1 2 x", "1e-9"),
           "E1": ("abc", "nan", "-1", "0"), "nu1": ("abc", "inf", "0.7", "-1"),
           "E2": ("nan", "-1"), "nu2": ("abc", "0.51"),
           "p_min": ("abc", "nan", "-1", "0", "1e999"), "p_max": ("abc", "nan", "0"),
           "p_count": ("abc", "2.5", "1", "101", "inf", "1e308"),
           "boundary": ("abc", "periodic,free", "FREE"), "hardness": ("abc", "nan", "-1", "1e6"),
           "load": ("abc", "elastics")}
#: the other fields a value is tried with (materials instead of E*; a complete range)
WITH = {"E1": {"E_star": "", "E1": "2e11", "nu1": "0.3"},
        "nu1": {"E_star": "", "E1": "2e11", "nu1": "0.3"},
        "E2": {"E_star": "", "E1": "2e11", "nu1": "0.3", "E2": "2e11", "nu2": "0.3"},
        "nu2": {"E_star": "", "E1": "2e11", "nu1": "0.3", "E2": "2e11", "nu2": "0.3"},
        "p_min": {"p_min": "1e6", "p_max": "1e8", "p_count": "3"},
        "p_max": {"p_min": "1e6", "p_max": "1e8", "p_count": "3"},
        "p_count": {"p_min": "1e6", "p_max": "1e8", "p_count": "3"}}


def test_hostile_values_in_every_new_field_are_a_line_at_the_field(site):
    c, path = site
    upload = None
    tried = 0
    for name, values in HOSTILE.items():
        for v in values:
            data = {"source": "file", **SETTINGS, "load": "elastic", "E_star": "1e11",
                    "pressure": "1e7", **WITH.get(name, {}), name: v}
            files = None
            if upload is None:
                files = [("file", (path.name, path.read_bytes()))]
            else:
                data["upload"] = upload
            r = c.post("/surface", data=data, files=files)
            assert r.status_code == 400, (name, v, r.status_code, r.text[:300])
            page = Page(r.text)
            assert len(page.page_errors) == 1 and "Traceback" not in r.text, (name, v)
            msg = page.page_errors[0]
            assert "\n" not in msg and 0 < len(msg) < 300, msg
            assert "--" not in msg and "E_star" not in msg, msg      # the page's words
            form = [f for f in page.forms if f.id == "file-form"][0]
            here = form.by_name(name)[0]
            assert form.errors == [(here.label, msg)], (name, v, msg, form.errors)
            for k, sent in data.items():                  # what was typed, kept
                for f in form.by_name(k):
                    if f.kind not in ("hidden", "file", "select"):
                        assert f.value == sent, (name, v, k, f.value, sent)
            kept = [f.value for f in form.fields if f.name == "upload"]
            assert kept, (name, v)
            upload = kept[0]
            tried += 1
    assert tried == sum(len(v) for v in HOSTILE.values())


def test_wedge_form_takes_the_contact_and_refuses_a_free_boundary(site, capsys):
    c, _ = site
    data = {"source": "wedge", "alpha_deg": "5.71059", "beta_deg": "26.5651",
            "mu_alpha": "0.15", "mu_beta": "0.15", "directions": "72", "load": "elastic",
            "E_star": "1e9", "pressure": "1e7"}
    r = c.post("/surface", data={**data, "boundary": "free"})
    assert r.status_code == 400
    form = [f for f in Page(r.text).forms if f.id == "wedge-form"][0]
    assert form.errors[0][0] == form.by_name("boundary")[0].label
    jid = job(c, c.post("/surface", data=data))
    got = json.loads(c.get(f"/jobs/{jid}/files/derive.json").content)
    want = run_json(capsys, "derive", "--alpha", "5.71059", "--beta", "26.5651", "--mu-alpha",
                    "0.15", "--mu-beta", "0.15", "--directions", "72", "--elastic", "1e9",
                    "--pressure", "1e7")
    assert got["mu_a_plus"] == pytest.approx(want["mu_a_plus"], rel=1e-9)
    assert got["mu_a_minus"] == pytest.approx(want["mu_a_minus"], rel=1e-9)
    assert got["mu_a_plus"] < got["mu_a_minus"]          # the sawtooth's asymmetry kept
    assert got["elastic_contact"]["boundary"] == "periodic"
    cmap = figure(c.get(f"/jobs/{jid}").text, "contact_map")
    assert cmap["data"][0]["type"] == "scatter"


def test_a_solve_that_does_not_converge_is_one_line_with_the_residual(tmp_path):
    """The iteration limit (not a field of the page: set in the job here) gives the job's
    one line, which the page puts above the form."""
    from asperity.errors import InputError
    from asperity.web.tasks_contact import derive_task
    ctx = {"job_dir": tmp_path, "uploads": tmp_path, "jobs": tmp_path, "names": {}}
    params = {"source": {"kind": "wedge", "alpha_deg": 5.71059, "beta_deg": 26.5651,
                         "mu_alpha": 0.15, "mu_beta": 0.15}, "directions": 8,
              "elastic": {"E_star": 1e9, "pressures": [1e6], "boundary": None,
                          "hardness": None, "max_iterations": 2}}
    with pytest.raises(InputError) as e:
        derive_task(params, ctx, lambda *a: None)
    msg = str(e.value)
    assert "did not converge" in msg and "residual" in msg and "2 iterations" in msg
    assert "\n" not in msg and not (tmp_path / "derive.json").exists()


def test_a_large_contact_map_is_shown_as_block_means_with_its_holes():
    """A 600 x 300 field shown at most 256 a side: 3 x 3 block means of the defined
    pixels (against a loop here); a block without a defined pixel stays undefined."""
    from asperity.web.figures_contact import block_means
    rng = np.random.default_rng(4)
    p = rng.random((600, 300))
    p[30:36, 60:63] = np.nan                      # two whole blocks undefined
    p[90, 90] = np.nan                            # one pixel of a block
    got = block_means(p, 256)
    assert got.shape == (200, 100)
    for i, j in ((10, 20), (10, 21), (30, 30), (0, 0), (199, 99)):
        block = p[3 * i:3 * i + 3, 3 * j:3 * j + 3]
        ok = np.isfinite(block)
        want = block[ok].mean() if ok.any() else np.nan
        np.testing.assert_allclose(got[i, j], want, rtol=1e-12)
    assert np.isnan(got[10:12, 20]).all() and np.isfinite(got[30, 30])
    assert np.isfinite(got).sum() == 200 * 100 - 2


STRIP = {"model": "strip", "strip_h": "2.5e-3", "strip_E": "1.1e11", "strip_p": "5e7",
         "strip_l": "0.04", "strip_k_t": "1e13", "strip_alpha_T": "6e-6", "strip_n": "21",
         "dT_min": "0", "dT_max": "120"}
STRIP_TOML = """name = "strip"
[assembly]
model = "strip"
h = 2.5e-3
E = 1.1e11
p = 5.0e7
l = 0.04
k_t = 1.0e13
alpha_T = 6.0e-6
n = 21
[loading]
dT_min = 0.0
dT_max = 120.0
force = 0.0
cycles = 1e6
tolerance = 1e-4
"""


def test_risk_of_an_elastic_surface_result_solves_the_contact_at_the_assembly_pressure(
        site, capsys, tmp_path):
    """A Surface result weighted by an elastic contact at 2e8 Pa, chosen as the friction of
    a strip at p = 5e7 Pa, gives the verdict of ``asperity risk --elastic E`` (the contact
    solved again at the strip's p), not the area-weighted surface's nor the 2e8 Pa one's."""
    c, path = site
    jid = job(c, surface(c, path, pressure="2e8"))
    rid = job(c, c.post("/motion/risk", data={**STRIP, "friction": f"job:{jid}"}))
    got = json.loads(c.get(f"/jobs/{rid}/files/risk.json").content)
    asm = tmp_path / "strip.toml"
    asm.write_text(STRIP_TOML)
    flags = ["--unit", "um", "--pixel-size", "0.5", "--mu", "0.15"]
    want = run_json(capsys, "risk", path, asm, *flags, "--elastic", f"{E_STAR:g}")
    at_2e8 = run_json(capsys, "risk", path, asm, *flags, "--elastic", f"{E_STAR:g}",
                      "--pressure", "2e8")
    area = run_json(capsys, "risk", path, asm, *flags)
    assert got["friction"]["contact_pressure"] == {"pressure_Pa": 5e7, "from": "assembly.p",
                                                   "solved": True}
    assert got["friction"]["elastic_contact"]["pressure_Pa"] == pytest.approx(5e7, rel=1e-9)
    for k in ("mu_plus", "mu_minus", "drift_per_cycle_m"):
        assert got[k] == pytest.approx(want[k], rel=1e-9, abs=1e-15), k
    for other in (at_2e8, area):            # the pressure matters on this map
        assert abs(other["mu_plus"] - want["mu_plus"]) > 1e-3
    assert got["verdict"] == want["verdict"]
    # a two-node assembly from the form has no contact pressure: one line says what to give
    two = {"model": "two-node", "two_k": "1e6", "two_l0": "0.1", "two_alpha_T": "1.2e-5",
           "two_k_t": "5e5", "two_N": "100", "dT_min": "0", "dT_max": "125"}
    page = c.post("/motion/risk", data={**two, "friction": f"job:{jid}"})
    if page.status_code == 303:                 # the form did not wait long enough
        fid = page.headers["location"].rsplit("/", 1)[-1]
        t0 = time.monotonic()
        while c.get(f"/api/jobs/{fid}").json()["status"] in ("queued", "running"):
            assert time.monotonic() - t0 < 120
            time.sleep(0.2)
        page = c.get(f"/jobs/{fid}")
    assert page.status_code == 422 and "Traceback" not in page.text
    msg = re.search(r'<p class="error" id="error" role="alert">(.*?)</p>', page.text,
                    re.S).group(1)
    assert "\n" not in msg and "contact_area" in msg and "strip" in msg, msg
