"""The Law page fits the law family of a Surface result with several pressures, through a
real ``asperity serve`` (127.0.0.1, started and stopped here): the same members as
``asperity fit ... --elastic E --pressure P1 P2 P3`` (coefficients to 1e-9), a version-2
gauge file that reads back as the family, the CSV table with its pressure column and one
Abaqus block a member; a version-2 file opened on the Law page and on the Motion page; the
Motion page's pressure field (required for a family, within its pressures, hostile values
refused at the field), and a slide at a pressure equal to ``asperity slide --pressure``."""
from __future__ import annotations

import csv
import io
import json
import re

import numpy as np
import pytest

pytest.importorskip("fastapi")
httpx = pytest.importorskip("httpx")
from test_web_contact import E_STAR, SETTINGS, figure, job, site  # noqa: E402,F401
from web_forms import Page  # noqa: E402

#: the pressures, typed out of order on the Surface page (the family sorts them)
TYPED = (8e8, 5e7, 2e8)
PS = sorted(TYPED)
FIELD = "law_pressure"


@pytest.fixture(scope="module")
def fitted(site):
    """(Surface job, Law job of its family, the command line's family file and JSON)."""
    c, path = site
    folder = path.parent
    data = {"source": "file", **SETTINGS, "load": "elastic", "E_star": f"{E_STAR:g}",
            "pressure": " ".join(f"{p:g}" for p in TYPED)}
    surf = job(c, c.post("/surface", data=data,
                         files=[("file", (path.name, path.read_bytes()))]))
    law_page = c.get(f"/law?source={surf}").text
    assert f'<option value="{surf}:family" data-source="{surf}" selected>' in law_page
    # (the family, first)
    assert "not yet" not in law_page
    fit = job(c, c.post("/law", data={"source": surf, "law": "star", "directions": "72",
                                      "pressure": f"{surf}:family"}))
    out = folder / "cli_family.json"
    want = cli("fit", path, "--unit", "um", "--pixel-size", "0.5", "--mu",
                    "0.15", "--directions", "72", "--elastic", f"{E_STAR:g}", "--pressure",
                    *[f"{p:g}" for p in PS], "-o", out)
    return surf, fit, out, want


def cli(*argv) -> dict:
    """The JSON object ``asperity ARGV... --json`` prints (in-process, its real parser)."""
    import contextlib

    from asperity.cli.main import main
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main([str(a) for a in argv] + ["--json"]) == 0
    return json.loads(buf.getvalue())


def test_the_family_fitted_on_the_page_is_the_command_lines(site, fitted):
    from asperity import read_gauge
    from asperity.laws.family import GaugeFamily
    from asperity.laws.family_report import common_axes
    c, path = site
    folder = path.parent
    surf, fit, out, want = fitted
    raw = c.get(f"/jobs/{fit}/files/gauge.json")
    assert raw.status_code == 200
    assert "family" in raw.headers["content-disposition"]
    assert "bumps" in raw.headers["content-disposition"]
    (folder / "page.json").write_bytes(raw.content)
    got, ref = read_gauge(folder / "page.json"), read_gauge(out)
    assert isinstance(got, GaugeFamily) and got.pressures == pytest.approx(PS, rel=1e-12)
    assert len(got.members) == len(ref.members) == 3
    # the contact solves started from other solutions (the pressures typed out of order):
    # equal to the solver's tolerance, 1e-9 on coefficients of order 0.1
    # the command line's JSON gives each member's axes along the family's common axis:
    # the page's family read the same way
    aligned, _ = common_axes(got)
    for g, r, w, gm in zip(got.members, ref.members, want["members"], aligned):
        np.testing.assert_allclose(g.law.C.points, r.law.C.points, rtol=0, atol=1e-9)
        for k, v in w["axes"].items():
            assert gm[k] == (v if isinstance(v, bool) else pytest.approx(v, abs=1e-9)), k
        assert g.principal_direction_deg == pytest.approx(r.principal_direction_deg, abs=1e-9)
        assert g.source["elastic_contact"]["area_fraction"] == pytest.approx(
            w["contact"]["area_fraction"], rel=1e-9)
    page = c.get(f"/jobs/{fit}").text
    assert "not yet" not in page and 'id="law-family-note"' in page
    rows = re.findall(r'<tr class="member-row"><td class="member-pressure">([^<]+)</td>', page)
    unit = re.search(r'id="family-members"><tr><th>p \((\w+)\)</th>', page).group(1)
    assert unit == "MPa"                          # 50 to 800 MPa: one unit for the column
    assert [float(x) * 1e6 for x in rows] == pytest.approx(PS, rel=1e-5)
    fr = [float(x) for x in re.findall(r'class="member-fraction">([^<]+)<', page)]
    assert fr == pytest.approx([m["contact"]["area_fraction"] for m in want["members"]],
                               abs=5e-5)
    mus = [float(x) for x in re.findall(r'class="member-mu">([^<]+)<', page)]
    axes = [m["axes"][k] for m in want["members"]
            for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus")]
    assert mus == pytest.approx(axes, abs=5e-7)
    polar = figure(page, "family")["data"]
    assert len(polar) == 3 and len({t["line"]["color"] for t in polar}) == 3
    for t, r in zip(polar, ref.members):
        assert t["x"][:-1] == pytest.approx(r.law.C.points[:, 0].tolist(), abs=2e-6)


def test_the_family_downloads_the_table_and_one_abaqus_block_a_member(site, fitted):
    c, _ = site
    _, fit, out, want = fitted
    table = c.get(f"/jobs/{fit}/files/law.csv")
    assert "family" in table.headers["content-disposition"]
    rows = list(csv.DictReader(io.StringIO(table.text)))
    assert list(rows[0]) == ["pressure_Pa", "psi_deg", "p_a", "p_b"]
    by_p = {}
    for r in rows:
        by_p.setdefault(float(r["pressure_Pa"]), []).append(r)
    assert sorted(by_p) == pytest.approx(PS, rel=1e-12)
    assert {len(v) for v in by_p.values()} == {360}
    # the member's own principal frame: p_a at psi = 0 is its mu_a+
    for p, m in zip(PS, want["members"]):
        first = [r for r in by_p[min(by_p, key=lambda q: abs(q - p))]
                 if float(r["psi_deg"]) == 0.0][0]
        assert float(first["p_a"]) == pytest.approx(m["axes"]["mu_a_plus"], rel=1e-6)
    inp = c.get(f"/jobs/{fit}/files/law.inp").text
    assert inp.count("*FRICTION, ANISOTROPIC") == 3
    assert len(re.findall(r"\*\* member \d: nominal contact pressure", inp)) == 3


def test_one_pressure_chosen_is_that_members_law_alone(site, fitted):
    c, _ = site
    surf, _, out, _ = fitted
    from asperity import read_gauge
    from asperity.laws.fitting import GaugeLaw
    one = job(c, c.post("/law", data={"source": surf, "law": "star", "directions": "72",
                                      "pressure": f"{surf}:2"}))        # typed third: 2e8
    note = re.search(r'id="law-pressure-note">([^<]+)<', c.get(f"/jobs/{one}").text).group(1)
    assert "p = 200 MPa" in note and "alone" in note and "not yet" not in note
    raw = json.loads(c.get(f"/jobs/{one}/files/gauge.json").content)
    assert raw["version"] == 1
    ref = read_gauge(out).members[1]
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        p = f"{d}/one.json"
        open(p, "wb").write(c.get(f"/jobs/{one}/files/gauge.json").content)
        gl = read_gauge(p)
    assert isinstance(gl, GaugeLaw)
    np.testing.assert_allclose(gl.law.C.points, ref.law.C.points, rtol=0, atol=1e-9)


def test_a_version_2_file_opens_on_the_law_page(site, fitted):
    c, _ = site
    _, _, out, want = fitted
    r = c.post("/law/open", files=[("gauge", ("cli_family.json", out.read_bytes()))])
    jid = job(c, r)
    page = c.get(f"/jobs/{jid}").text
    assert "Traceback" not in page
    rows = re.findall(r'class="member-pressure">([^<]+)<', page)
    assert [float(x) * 1e6 for x in rows] == pytest.approx(PS, rel=1e-5)
    assert len(figure(page, "family")["data"]) == 3
    g = c.get(f"/jobs/{jid}/files/gauge.json")
    assert "cli_family" in g.headers["content-disposition"]
    assert json.loads(g.content)["version"] == 2
    assert c.get(f"/jobs/{jid}/files/law.inp").text.count("*FRICTION, ANISOTROPIC") == 3
    motion = c.get("/motion").text
    assert f"job:{jid}" in re.search(r'id="law-family-pressure"[^>]*', motion).group(0)


SLIDE = {"u0": "0.5", "angle_deg": "30", "mass": "1", "g": "9.81", "dt": "1e-4"}


def slide_error(c, data, files=None) -> tuple[str, str]:
    """(field, message) of a refused slide form: HTTP 400, one line at one field."""
    r = c.post("/motion/slide", data=data, files=files)
    assert r.status_code == 400, (data, r.status_code, r.text[:300])
    page = Page(r.text)
    assert len(page.page_errors) == 1 and "Traceback" not in r.text
    msg = page.page_errors[0]
    assert "\n" not in msg and "--" not in msg and 0 < len(msg) < 300, msg
    form = [f for f in page.forms if f.id == "slide"][0]
    assert len(form.errors) == 1, form.errors
    at = [f for f in form.fields if f.label == form.errors[0][0]]
    return (at[0].name if at else None), msg


def test_slide_on_the_family_at_the_pressure_given(site, fitted):
    c, _ = site
    _, fit, out, _ = fitted
    for v in ("", "abc", "nan", "inf", "-1", "0", "1e999", "4.9e7", "8.01e8"):
        where, msg = slide_error(c, {"law": f"job:{fit}", **SLIDE, FIELD: v})
        assert where == FIELD and "nominal pressure" in msg, (v, where, msg)
    assert "50 MPa to 800 MPa" in slide_error(c, {"law": f"job:{fit}", **SLIDE})[1]
    assert "(got 49 MPa)" in slide_error(c, {"law": f"job:{fit}", **SLIDE, FIELD: "4.9e7"})[1]
    rests = []
    for p in (2e8, 8e8):
        jid = job(c, c.post("/motion/slide", data={"law": f"job:{fit}", **SLIDE,
                                                  FIELD: f"{p:g}"}))
        got = c.get(f"/jobs/{jid}").text
        want = cli("slide", out, "--pressure", f"{p:g}", "--u0", "0.5", "--angle", "30",
                   "--dt", "1e-4")
        assert f"at p = {p / 1e6:g} MPa" in got and \
            f'<b id="slide-pressure">p = {p / 1e6:g} MPa</b>' in got
        res = json.loads(c.get(f"/api/jobs/{jid}").content)
        assert res["status"] == "done"
        path = c.get(f"/jobs/{jid}/files/path.csv").text.strip().splitlines()
        last = [float(x) for x in path[-1].split(",")]
        assert last[1:3] == pytest.approx(want["rest"], abs=1e-9), (p, want)
        rests.append(last[1:3])
    assert np.hypot(*np.subtract(*rests)) > 1e-4           # the pressure matters here


def test_slide_on_an_uploaded_family_and_a_single_law_needs_no_pressure(site, fitted):
    c, _ = site
    surf, _, out, _ = fitted
    files = [("gauge", ("cli_family.json", out.read_bytes()))]
    where, msg = slide_error(c, {"law": "upload", **SLIDE}, files)
    assert where == FIELD and "50 MPa to 800 MPa" in msg
    jid = job(c, c.post("/motion/slide", data={"law": "upload", **SLIDE, FIELD: "1e8"},
                        files=files))                 # between two members: interpolated
    want = cli("slide", out, "--pressure", "1e8", "--u0", "0.5", "--angle", "30",
               "--dt", "1e-4")
    last = c.get(f"/jobs/{jid}/files/path.csv").text.strip().splitlines()[-1].split(",")
    assert [float(x) for x in last[1:3]] == pytest.approx(want["rest"], abs=1e-9)
    shown = c.get(f"/jobs/{jid}").text                 # the pressure said on its page
    assert "gauge file cli_family.json at p = 100 MPa" in shown
    assert re.search(r'id="law-family-pressure">.*interpolated in ln p between its laws at '
                     r'50 MPa and 200 MPa', shown)
    assert "_p100MPa_" in c.get(f"/jobs/{jid}/files/path.csv").headers["content-disposition"]
    one = job(c, c.post("/law", data={"source": surf, "law": "star", "directions": "72",
                                      "pressure": f"{surf}:0"}))
    job(c, c.post("/motion/slide", data={"law": f"job:{one}", **SLIDE}))
    where, msg = slide_error(c, {"law": f"job:{one}", **SLIDE, FIELD: "1e8"})
    assert where == FIELD and "one law, not a law family" in msg
