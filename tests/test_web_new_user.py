"""The web page as a new user meets it (issue 18, section 8): an x3p written in another
unit than it states has a way forward on the page; a result that self-locks says what
happened and what to do, the max-slope hint first, and shows no number that means
nothing; one load share on a page, with its definition."""
from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest

pytest.importorskip("fastapi")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient  # noqa: E402
from surface_files import write_x3p  # noqa: E402
from web_forms import Page  # noqa: E402
from web_server import ROOT  # noqa: E402

from asperity.web.app import create_app  # noqa: E402
from asperity.web.settings import make_settings, prepare_data_dir  # noqa: E402

MU = 0.1
SPIKE_UM = 300.0


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    settings = make_settings(data_dir=tmp_path_factory.mktemp("web-new-user"), workers=1)
    prepare_data_dir(settings.data_dir)
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                    follow_redirects=False) as c:
        yield c


def done(client, r, timeout: float = 120.0):
    """The page a form's answer leads to, once its job has finished."""
    import time
    if r.status_code != 303:
        return r
    jid = r.headers["location"].rsplit("/", 1)[-1]
    t0 = time.monotonic()
    while client.get(f"/api/jobs/{jid}").json()["status"] in ("queued", "running"):
        assert time.monotonic() - t0 < timeout
        time.sleep(0.1)
    return client.get(f"/jobs/{jid}")


def form_of(page, form_id):
    return [f for f in Page(page.text).forms if f.id == form_id][0]


def test_an_x3p_in_micrometres_has_a_way_forward(client, tmp_path):
    x = np.arange(40.0)
    raw = np.add.outer(0.4 * (x % 8) - 0.05 * (x % 8) ** 2, 0.01 * np.arange(30.0))
    write_x3p(tmp_path / "um.x3p", raw, "D", inc=None, dx=2.0, dy=2.0)
    r = done(client, client.post("/surface", data={"source": "file"}, files={
        "file": ("um.x3p", (tmp_path / "um.x3p").read_bytes())}))
    assert r.status_code == 422
    page = Page(r.text)
    msg = page.page_errors[0]
    assert msg.startswith("um.x3p: the file states a pixel size dx of 2 m, outside "
                          "[1e-12, 1] m: if its numbers are not in metres, give the length "
                          "unit"), msg
    assert not re.search(r"pixel_size|height_scale|--\w", msg)      # the page's words
    form = form_of(r, "file-form")
    unit = form.by_name("unit")[0]
    assert [lbl for lbl, _ in form.errors] == [unit.label]            # next to the unit
    assert '<fieldset class="attention" id="units">' in r.text
    kept = [f.value for f in form.fields if f.name == "upload"]
    assert len(kept) == 1
    for extra, dx_um in (({"unit": "um"}, 2.0), ({"unit": "um", "pixel_size": "0.5"}, 0.5)):
        ok = done(client, client.post("/surface", data={"source": "file", "upload": kept[0],
                                                        "directions": "16", **extra}))
        assert ok.status_code == 200, Page(ok.text).page_errors
        res = client.get(f"/api/jobs/{ok.url.path.rsplit('/', 1)[-1]}/result").json()
        assert res["derive"]["texture"]["pixel_size_m"] == pytest.approx([dx_um * 1e-6] * 2,
                                                                     rel=1e-12)
        assert math.isfinite(res["derive"]["mu_a_plus"])


def spike_map() -> np.ndarray:
    """Ridges (um) with one spike: its six facets are too steep to climb at mu = 0.1 and
    face every direction, so the map self-locks in every direction."""
    x = np.arange(24) * 1.0
    z = np.add.outer(np.zeros(24), 0.4 * (x % 6) - 0.06 * (x % 6) ** 2)
    z[12, 12] += SPIKE_UM
    return z


def steep_share(z_um: np.ndarray, limit_deg: float) -> float:
    """Share of the load on the facets steeper than ``limit_deg``, independently: two
    triangles per pixel cell (equal projected areas, uniform load), the mean facet slope
    removed (detrend "slope"), slope angle atan |gradient|."""
    z = z_um * 1e-6
    h = 1e-6
    a, b, c, d = z[:-1, :-1], z[:-1, 1:], z[1:, :-1], z[1:, 1:]
    # rows y, columns x; triangles (a, b, d) and (a, c, d)
    g1 = np.stack([(b - a) / h, (d - b) / h], -1).reshape(-1, 2)
    g2 = np.stack([(d - c) / h, (c - a) / h], -1).reshape(-1, 2)
    g = np.concatenate([g1, g2])
    g = g - g.mean(axis=0)
    steep = np.degrees(np.arctan(np.hypot(g[:, 0], g[:, 1]))) > limit_deg
    return steep.sum() / g.shape[0]


def test_a_result_locked_in_every_direction_says_what_to_do(client, tmp_path):
    np.savetxt(tmp_path / "spike.txt", spike_map(), fmt="%.4f")
    r = done(client, client.post("/surface", data={
        "source": "file", "unit": "um", "pixel_size": "1", "mu": str(MU), "directions": "16"},
        files={"file": ("spike.txt", (tmp_path / "spike.txt").read_bytes())}))
    assert r.status_code == 200, Page(r.text).page_errors
    t = r.text
    box = t[t.index('id="self-locking-help"'):]
    box = box[:box.index("</div>")]
    limit = math.floor(math.degrees(math.atan(1 / MU)) * 100) / 100      # 84.28
    assert "self-locks in every direction" in box
    first = re.search(r"<p[^>]*>(.*?)</p>", box, re.S)
    assert 'id="max-slope-hint"' in first.group(0)                        # the hint first
    assert f"<b>Compute it again with a max slope of {limit:g} deg.</b>" in first.group(1)
    for absent in ('id="to-law"', 'id="to-risk"', 'id="polar"', "smallest dissipation",
                   "0.0000", ">yes<"):
        assert absent not in t, absent
    for cell in ("anisotropy", "principal_direction", "admissible"):
        assert re.search(rf'<td id="{cell}">&ndash;</td>', t), cell
    assert 'id="no-plot"' in t
    # one load share on the page (the text of the command line included), with its
    # definition: the facets steeper than the locking limit, recomputed here
    share = f"{100 * steep_share(spike_map(), limit):.3g}"
    figures = set(re.findall(r"([0-9.]+(?:e-?\d+)?) % of the load", t)) - {"0"}
    assert figures == {share}, figures
    assert re.search(rf'<span id="locking-share">{share} %</span> of the load on the facets '
                     rf"steeper than the locking limit of {limit:g} deg", t)
    assert "load share 0" not in t                     # no bare fractions any more
    # the button computes it again with that max slope (the upload kept): finite friction
    again = form_of(r, "again-max-slope")
    data = {f.name: f.value for f in again.fields}
    assert data["max_slope"] == f"{limit:g}" and data["directions"] == "16"
    ok = done(client, client.post(again.action, data=data))
    assert ok.status_code == 200 and 'id="self-locking-help"' not in ok.text
    assert re.search(r'<td id="mu_a_plus">0\.\d{6}</td>', ok.text)
    assert 'id="to-law"' in ok.text


def test_a_partly_self_locking_wedge_offers_no_law_and_one_share(client):
    """The shipped self-locking texture (alpha 80 deg, mu_alpha 0.3) locks in some
    directions: no fit button (a law needs finite friction everywhere), the risk button
    stays, and its one share is the locking faces' (a wedge has no data quality)."""
    r = done(client, client.post("/surface", data={"source": "file", "directions": "36"},
                                 files={"file": ("self-locking.toml", (
                                     ROOT / "surfaces" / "self-locking.toml").read_bytes())}))
    assert r.status_code == 200, Page(r.text).page_errors
    t = r.text
    n = re.search(r"It self-locks in (\d+) of 36 directions", t)
    assert n and 0 < int(n.group(1)) < 36
    assert 'id="to-law"' not in t and 'id="to-risk"' in t and 'id="polar"' in t
    res = client.get(f"/api/jobs/{r.url.path.rsplit('/', 1)[-1]}/result").json()["derive"]
    # the alpha face's share of the projected area: tan(beta) / (tan(alpha) + tan(beta))
    ta, tb = math.tan(math.radians(80.0)), math.tan(math.radians(10.0))
    assert res["self_locking_load_share"] == pytest.approx(tb / (ta + tb), rel=1e-9)
    share = f"{100 * tb / (ta + tb):.3g}"
    assert set(re.findall(r"([0-9.]+) % of the load", t)) == {share}
