"""A form's refusal writes its pressures as the pages write them (issue 25, item 6: one
number format): ``50 MPa to 800 MPa``, not ``5e+07 to 8e+08 Pa``; a range in the unit of
its smallest, as a column of pressures.  The rewriting itself, the library's refusals
brought back to a form (``page_words``), and the Surface form's own refusals over HTTP."""
from __future__ import annotations

import warnings

import pytest

pytest.importorskip("fastapi")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient
from web_forms import Page

from asperity.web.app import create_app
from asperity.web.labels import page_pressures
from asperity.web.settings import make_settings, prepare_data_dir
from asperity.web.units import choose, show
from asperity.web.words import page_words


@pytest.mark.parametrize("said, shown", [
    ("the law is a family over the pressures 5e+07 to 8e+08 Pa; give it (got 4.9e+07 Pa)",
     "the law is a family over the pressures 50 MPa to 800 MPa; give it (got 49 MPa)"),
    ("pressure 4.9e+07 Pa is outside the law family's pressures [5e+07, 8e+08] Pa: refit",
     "pressure 49 MPa is outside the law family's pressures [50 MPa, 800 MPa]: refit"),
    ("between the members at 1e+07 and 2e+07 Pa is not valid",
     "between the members at 10 MPa and 20 MPa is not valid"),
    ("pressures 50000 to 2e+06 Pa", "pressures 50 kPa to 2000 kPa"),
    ("the materials give E* = 1.15e+11 Pa, outside", "the materials give E* = 115 GPa, outside"),
    # the unit of the smallest would need an exponent for the largest: kept as it was
    ("E* (Pa) must be in [1, 1e+13] Pa, got 1e+14", "E* (Pa) must be in [1, 1e+13] Pa, got 1e+14"),
    ("pressures 50000 to 1e+09 Pa", "pressures 50000 to 1e+09 Pa"),
    ("k_t (Pa/m) must be in [1000, 1e+20] Pa/m", "k_t (Pa/m) must be in [1000, 1e+20] Pa/m"),
    ("pressure must be in (0, inf) Pa, got -5", "pressure must be in (0, inf) Pa, got -5"),
    ("p = 0 Pa", "p = 0 Pa"),
    ("a 1e+400 Pa load", "a 1e+400 Pa load"),
])
def test_pressures_are_written_as_the_pages_write_them(said, shown):
    assert page_pressures(said) == shown


def test_a_range_takes_the_unit_of_its_smallest_as_a_page_column():
    lo, hi = 5e7, 8e8
    u = choose([lo, hi], "Pa", smallest=True)
    assert page_pressures(f"{lo:g} to {hi:g} Pa") == f"{show(lo, u)} to {show(hi, u)}"


def test_the_library_refusals_brought_back_to_a_form():
    msg, _ = page_words("gauge holds a law family over the pressures 5e+07 to 8e+08 Pa: take "
                        "its law at the contact pressure first", "risk", {})
    assert "50 MPa to 800 MPa" in msg and "e+0" not in msg


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    settings = make_settings(data_dir=tmp_path_factory.mktemp("web-refusals"), workers=1)
    prepare_data_dir(settings.data_dir)
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                    follow_redirects=False) as c:
        yield c


#: the SPEC wedge on the Surface page, weighted by an elastic contact
ELASTIC = {"source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
           "mu_beta": "0.2", "contact": "all-faces", "method": "closed-form",
           "directions": "72", "load": "elastic", "E_star": "1e11"}


@pytest.mark.parametrize("fields, field, words", [
    ({"pressure": "5e7", "hardness": "2e7"}, "hardness",
     "hardness (Pa) must be above the pressure (50 MPa), got 20 MPa"),
    ({"p_min": "1e8", "p_max": "1e6", "p_count": "3"}, "p_max",
     "pressures to (Pa) must be above pressures from (Pa) (100 MPa), got 1 MPa"),
])
def test_the_surface_form_refuses_in_the_pages_units(client, fields, field, words):
    r = client.post("/surface", data={**ELASTIC, **fields})
    assert r.status_code == 400, r.text[:300]
    page = Page(r.text)
    assert page.page_errors == [words], page.page_errors
    form = next(f for f in page.forms if f.errors)
    assert form.errors == [(form.by_name(field)[0].label, words)]
