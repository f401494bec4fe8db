"""The web page as a new user met it (issue 25, item 6), over HTTP: t_a said for what it is
and the direction of largest friction named apart (on the page and in derive's text), the
plastic share of a contact with a hardness, both pressures of a verdict that solves an
elastic Surface result again, the reference terminal ratio of the body slid (none where
there is none), the Law page's pressures of each result marked with it, the drift led by
the cycles to tolerance with what its extrapolation ignores, one number format, articles,
a single member's download name with its pressure.  Figures and progress without a server
in ``test_web_clarity_units.py``; what needs a browser in ``test_web_clarity_browser.py``."""
from __future__ import annotations

import html
import json
import re
import time
import warnings

import numpy as np
import pytest

pytest.importorskip("fastapi")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient
from test_web_contact import bumps
from web_server import ROOT

from asperity.web.app import create_app
from asperity.web.settings import make_settings, prepare_data_dir

SURFACES = ROOT / "surfaces"
#: the SPEC wedge (SPEC.md section 2: mu_a+ = 0.185697, mu_a- = 0.193238)
WEDGE = {"source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
         "mu_beta": "0.2", "contact": "all-faces", "method": "closed-form", "directions": "72"}
#: the bumps map of test_web_contact on the Surface page, with an elastic contact
MAP = {"source": "file", "unit": "um", "pixel_size": "0.5", "mu": "0.15", "directions": "72",
       "load": "elastic", "E_star": "1e11"}
STRIP = {"model": "strip", "strip_h": "2.5e-3", "strip_E": "1.1e11", "strip_p": "5e7",
         "strip_l": "0.04", "strip_k_t": "1e13", "strip_alpha_T": "6e-6", "strip_n": "21",
         "dT_min": "0", "dT_max": "120"}
SLIDE = {"law": "coulomb", "mu1": "0.2", "u0": "0.3", "angle_deg": "30", "mass": "1",
         "g": "9.81", "dt": "1e-3", "omega0": "10", "contact_points": "64"}


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    settings = make_settings(data_dir=tmp_path_factory.mktemp("web-clarity"), workers=1)
    prepare_data_dir(settings.data_dir)
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                    follow_redirects=False) as c:
        yield c


def job(client, r, timeout: float = 240.0) -> str:
    """The id of the job a form started, once done."""
    assert r.status_code == 303, (r.status_code, r.text[:400])
    jid = r.headers["location"].rsplit("/", 1)[-1]
    t0 = time.monotonic()
    while (st := client.get(f"/api/jobs/{jid}").json())["status"] in ("queued", "running"):
        assert time.monotonic() - t0 < timeout, st
        time.sleep(0.1)
    assert st["status"] == "done", st
    return jid


def cell(page: str, cid: str) -> str:
    """The text of the element of id ``cid`` (up to its own closing tag)."""
    m = re.search(rf'<(\w+)[^>]*\bid="{cid}"[^>]*>(.*?)</\1>', page, re.DOTALL)
    assert m, cid
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", m.group(2))).split())


@pytest.fixture(scope="module")
def bumps_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("clarity-map") / "bumps.txt"
    np.savetxt(path, bumps(), fmt="%.6f")
    return path


@pytest.fixture(scope="module")
def hard(client, bumps_file):
    """The bumps map at 2e8 Pa with a hardness of 6e8 Pa (a third of it at the hardness)."""
    return job(client, client.post("/surface", data={**MAP, "pressure": "2e8",
                                                     "hardness": "6e8"},
                                   files={"file": ("bumps.txt", bumps_file.read_bytes())}))


def largest(directions) -> tuple[float, float]:
    best = max((d for d in directions if d["tangential"] is not None),
               key=lambda d: d["tangential"])
    return best["psi_deg"] % 360.0, best["tangential"]


def test_the_wedge_has_t_a_at_0_and_its_largest_friction_against_it(client):
    """The SPEC wedge rubs most backwards: T(180 deg) = mu_a- = 0.193238 (closed form), the
    largest of its directions, while t_a stays the wedge's axis."""
    page = page_of(client, "/surface", WEDGE)
    assert cell(page, "principal_direction") == "0.00"
    assert cell(page, "largest-friction") == "0.193238" == cell(page, "mu_a_minus")
    assert float(cell(page, "largest-friction-deg")) == pytest.approx(180.0)
    assert "largest friction" not in cell(page, "t_a-words")
    from asperity import WedgeTexture, derive
    from asperity.friction.derive import format_text
    text = format_text(derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=72))
    assert "largest friction: T = 0.193238, sliding at psi = 180.0 deg from +t_a" in text
    assert "principal direction t_a (largest friction" not in text
    law = page_of(client, "/law", {**WEDGE, "source": "wedge", "law": "star",
                                   "directions": "360"})      # from the fitted law itself
    assert cell(law, "law-largest-T") == "0.193238"
    assert float(cell(law, "law-largest-deg")) == pytest.approx(180.0)


def test_a_scan_names_its_largest_friction_and_its_plastic_share(client, hard):
    page = client.get(f"/jobs/{hard}").text
    got = json.loads(client.get(f"/jobs/{hard}/files/derive.json").content)
    psi, top = largest(got["directions"])
    assert float(cell(page, "largest-friction")) == pytest.approx(top, abs=5e-7)
    assert float(cell(page, "largest-friction-deg")) == pytest.approx(psi, abs=0.05)
    words = cell(page, "t_a-words")
    assert "principal axis" in words and "direction of largest friction" not in words
    off = (psi - got["principal_direction_deg"]) % 180.0
    assert ("not along t_a" in cell(page, "largest-friction-words")) == (1 < off < 179)
    # the hardness caps the pressure over a third of the map: its share on the card, as
    # derive's text gives it
    share = got["elastic_contact"]["plastic_fraction"]
    assert 0.05 < share < 1
    shares = re.findall(r'class="plastic-share">([0-9.]+) % of the surface<', page)
    assert shares == [f"{100 * share:.3g}"]           # the figure of derive's text
    assert float(shares[0]) == pytest.approx(100 * share, rel=2e-3)
    assert 'id="plastic-explained"' in page


def page_of(client, path: str, data: dict, files=None) -> str:
    """The result page of a form's job."""
    return client.get(f"/jobs/{job(client, client.post(path, data=data, files=files))}").text


def test_risk_on_an_elastic_result_states_both_pressures(client, hard):
    r = page_of(client, "/motion/risk", {**STRIP, "friction": f"job:{hard}"})
    said = cell(r, "contact-pressures")
    assert "p = 200 MPa" in said and "p = 50 MPa" in said and "assembly.p" in said
    assert cell(r, "assembly-pressure") == "p = 50 MPa"
    plain = page_of(client, "/motion/risk", {**STRIP, "friction": "wedge", "r_alpha_deg": "30",
                                             "r_beta_deg": "10", "r_mu_alpha": "0.1",
                                             "r_mu_beta": "0.2"})
    assert 'id="contact-pressures"' not in plain          # an area-weighted source: none


def test_the_shipped_bushing_leads_with_the_cycles_to_its_tolerance(client):
    """0.27 um a cycle over 1e6 cycles is 0.27 m for a 40 mm strip: the page leads with the
    364 cycles to the 0.1 mm tolerance and says what the extrapolation ignores."""
    r = client.post("/motion/risk", data={"friction": "file"}, files={
        "assembly_file": ("bushing-strip.toml", (SURFACES / "bushing-strip.toml").read_bytes()),
        "texture_file": ("wedge-asymmetric.toml",
                         (SURFACES / "wedge-asymmetric.toml").read_bytes())})
    page = client.get(f"/jobs/{job(client, r)}").text
    assert cell(page, "cycles_to_tolerance") == "364" and cell(page, "tolerance") == "100 um"
    assert page.index('id="cycles_to_tolerance"') < page.index('id="drift-after"')
    after = cell(page, "drift-after")
    assert re.fullmatch(r"274\.\d mm", after), after
    words = cell(page, "drift-after-words")
    assert "ignores" in words and "wear" in words and "more than the part's length (40 mm)" \
        in words
    assert 'id="beyond-length"' in page


def slide(client, **fields) -> str:
    """The words of a slide's result page (its figures' data left out)."""
    page = page_of(client, "/motion/slide", {**SLIDE, **fields})
    return re.sub(r"<script[^>]*>.*?</script>", "", page, flags=re.DOTALL)


def test_each_body_shows_its_own_reference_terminal_ratio(client):
    ring = slide(client, body="ring", radius="0.05")
    assert cell(ring, "terminal-reference").startswith("A thin ring")
    assert cell(ring, "terminal-reference-ratio") == "1" and "0.653" not in ring
    disc = slide(client, body="disc", radius="0.05")
    assert cell(disc, "terminal-reference-ratio") == "0.653" and "thin ring" not in disc
    for other in (slide(client, body="disc", radius="0.05", pressure_profile="hertz"),
                  slide(client, body="rectangle", size_a="0.08", size_b="0.04")):
        assert 'id="terminal-reference"' not in other
        assert "0.653" not in other and "thin ring" not in other


def test_an_ellipse_takes_an(client):
    page = slide(client, law="ellipse", mu2="0.1")
    assert "an ellipse law" in page and "a ellipse" not in page
    from asperity.web.units import article
    assert [article(w) for w in ("ellipse", "star", "uniform", "ring", "outline")] == \
        ["an ellipse", "a star", "a uniform", "a ring", "an outline"]


def test_the_law_page_marks_each_pressure_with_its_result_and_units(client, bumps_file, hard):
    fam = job(client, client.post("/surface", data={**MAP, "pressure": "1e8 3.16228e8 1e9"},
                                  files={"file": ("bumps.txt", bumps_file.read_bytes())}))
    law = client.get(f"/law?source={fam}").text
    options = re.findall(r'<option value="([^"]+)" data-source="([^"]+)"[^>]*>([^<]+)<', law)
    assert {s for _, s, _ in options} == {fam, hard}
    assert all(v.startswith(s + ":") for v, s, _ in options)
    words = {v: t for v, _, t in options}
    assert words[f"{fam}:1"] == "p = 316.2 MPa alone" and words[f"{hard}:0"] == \
        "its only pressure, p = 200 MPa"
    assert "100 MPa to 1000 MPa" in words[f"{fam}:family"]
    assert not re.search(r"\de[+-]?\d", " ".join(words.values()))    # no exponents
    page = client.get(f"/jobs/{fam}").text
    table = page[page.index('id="family-table"'):page.index("</table>", page.index(
        'id="family-table"'))]
    assert "<th>p (MPa)</th>" in table and not re.search(r">\s*[\d.]+e[+-]\d", table)
    # one pressure of the family alone: its download names carry it
    one = job(client, client.post("/law", data={"source": fam, "law": "star",
                                                "directions": "72", "pressure": f"{fam}:1"}))
    for name in ("gauge.json", "law.csv", "law.inp"):
        disp = client.get(f"/jobs/{one}/files/{name}").headers["content-disposition"]
        assert "_p316.2MPa_star" in disp, disp
    note = cell(client.get(f"/jobs/{one}").text, "law-pressure-note")
    assert "p = 316.2 MPa" in note and "e+" not in note
