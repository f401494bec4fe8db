"""``asperity serve`` at the HTTP level: every bad request is a 4xx with a one-line message
and the server stays up; uploads are size-limited and stored under generated names; a
client's path is never opened; a non-loopback address needs --allow-remote and then the
token; jobs survive a restart."""
from __future__ import annotations

import json
import re
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
with warnings.catch_warnings():      # starlette 1.x would rather have httpx2; httpx works
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient  # noqa: E402
from web_server import ROOT, SHARED, Server  # noqa: E402

from asperity.web.app import create_app  # noqa: E402
from asperity.web.settings import make_settings, prepare_data_dir  # noqa: E402

BASE = "http://127.0.0.1:8765"
SURFACES = ROOT / "surfaces"
WEDGE = {"source": "wedge", "alpha_deg": "30", "beta_deg": "10", "mu_alpha": "0.1",
         "mu_beta": "0.2", "contact": "all-faces", "method": "closed-form",
         "directions": "72"}


def client_for(folder: Path, **kw) -> TestClient:
    settings = make_settings(data_dir=folder, workers=kw.pop("workers", 1), **kw)
    prepare_data_dir(settings.data_dir)
    return TestClient(create_app(settings), base_url=BASE, follow_redirects=False)


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with client_for(tmp_path_factory.mktemp("web-http"), max_upload_mb=0.25) as c:
        yield c


def error_line(resp) -> str:
    """The page's one-line message (and no traceback anywhere)."""
    assert "Traceback" not in resp.text
    if resp.headers["content-type"].startswith("application/json"):
        msg = resp.json()["error"]
    else:
        m = re.search(r'<p class="error" id="error" role="alert">(.*?)</p>', resp.text, re.S)
        assert m, resp.text[:500]
        msg = m.group(1)
    assert "\n" not in msg and 0 < len(msg) <= 400, msg
    return msg


def finished(client: TestClient, resp, timeout: float = 60.0):
    """The final page of a form's job (polling its status while it runs)."""
    if resp.status_code != 303:
        return resp
    return job_page(client, resp.headers["location"].rsplit("/", 1)[-1], timeout)


def job_page(client: TestClient, jid: str, timeout: float = 60.0):
    """The page of job ``jid`` once it has finished."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        st = client.get(f"/api/jobs/{jid}").json()
        if st["status"] not in ("queued", "running"):
            return client.get(f"/jobs/{jid}")
        time.sleep(0.1)
    raise AssertionError(f"job {jid} did not finish")


def test_wedge_form_gives_the_spec_value(client):
    page = finished(client, client.post("/surface", data=WEDGE))
    assert page.status_code == 200
    assert '<td id="mu_a_plus">0.185697</td>' in page.text


def test_non_numeric_form_field_is_400(client):
    r = client.post("/surface", data={**WEDGE, "alpha_deg": "thirty"})
    assert r.status_code == 400
    assert error_line(r) == "alpha (deg) must be a number, got &#39;thirty&#39;"
    assert 'value="thirty"' in r.text                 # the form comes back filled in
    r = client.post("/motion/slide", data={"law": "ellipse", "mu1": "0.2", "mu2": "x",
                                           "u0": "1", "angle_deg": "0"})
    assert r.status_code == 400 and "mu2 must be a number" in error_line(r)


def test_value_out_of_range_is_the_librarys_one_line_in_the_pages_words(client):
    r = client.post("/surface", data={**WEDGE, "alpha_deg": "95"})
    assert r.status_code == 422
    assert error_line(r) == "alpha (deg) must be in (0, 90) deg, got 95"
    assert re.search(r'name="alpha_deg"[^>]*value="95"[^>]*>\s*<small>[^<]*</small>'
                     r'<small class="field-error">alpha \(deg\) must', r.text)


def test_unknown_route_and_method(client):
    r = client.get("/no/such/page")
    assert r.status_code == 404 and error_line(r) == "no page at /no/such/page"
    r = client.delete("/surface")
    assert r.status_code == 405 and "not allowed" in error_line(r)
    r = client.get("/jobs/../../etc/passwd")
    assert r.status_code == 404
    r = client.get("/jobs/20990101-000000-abcdef")
    assert r.status_code == 404 and "no result" in error_line(r)
    r = client.get("/api/jobs/nope")
    assert r.status_code == 404 and r.json()["error"].startswith("no result")


def test_traversal_file_name_is_refused_and_nothing_is_opened(client, tmp_path):
    r = client.post("/surface", data={"source": "file"},
                    files={"file": ("../../etc/passwd", b"root:x:0:0", "text/plain")})
    assert r.status_code == 400
    assert "not a plain file name" in error_line(r)
    for name in ("passwd", "..\\..\\boot.ini", ".hidden"):
        r = client.post("/surface", data={"source": "file"},
                        files={"file": (name, b"1 2\n3 4\n", "text/plain")})
        assert r.status_code == 400, name
        error_line(r)
    r = client.post("/studies", files=[
        ("study", ("s.toml", b'[study]\nkind = "grid"\nassembly = "../../etc/passwd"\n')),
        ("companions", ("a.toml", b"x = 1\n"))])
    assert r.status_code == 400 and "may only name files uploaded with it" in error_line(r)
    r = client.post("/studies", files=[
        ("study", ("s.toml", b'[study]\nkind = "grid"\n')),
        ("companions", ("../a.toml", b"x = 1\n"))])
    assert r.status_code == 400 and "not a plain file name" in error_line(r)


@pytest.mark.skipif(not SHARED.is_dir(), reason=f"measured surfaces not found in {SHARED} "
                                                "(../shared/data/surfaces/)")
def test_uploads_get_generated_names(client):
    r = finished(client, client.post("/surface", data={"source": "file"}, files={
        "file": ("matrix-4.txt.gz", (SHARED / "matrix-4.txt.gz").read_bytes())}))
    assert r.status_code == 200 and "matrix-4.txt.gz" in r.text
    folder = Path(client.app.app.state.web.store.uploads_dir)
    names = sorted(p.name for p in folder.iterdir() if not p.name.endswith(".json"))
    assert names and all(re.fullmatch(r"[0-9a-f]{32}(\.[a-z0-9]+){1,2}", n) for n in names)
    assert any(n.endswith(".txt.gz") for n in names)
    assert "uploads" not in r.text.split("<main>")[1].split("<footer>")[0]  # no stored path


def test_malformed_uploads_are_422_with_the_readers_message(client):
    units = {"unit": "um", "pixel_size": "1"}
    cases = [("scan.x3p", b"\x00\x01 not a zip", "not an x3p file", {}),
             ("prose.txt", b"Dear reader,\nthis is no matrix.\n", "prose.txt", units),
             ("mesh.stl", b"solid broken\nfacet normal\n", "mesh.stl", {"unit": "um"}),
             ("texture.toml", b"[texture]\nkind = 'wedge'\nalpha_deg = 'steep'\n",
              "texture.toml", {})]
    for name, data, expect, extra in cases:
        r = finished(client, client.post("/surface", data={"source": "file", **extra},
                                         files={"file": (name, data)}))
        assert 400 <= r.status_code < 500, (name, r.status_code)
        msg = error_line(r)
        assert expect in msg, msg
        assert "/uploads/" not in msg and not re.search(r"[0-9a-f]{32}", msg), msg
    r = client.post("/surface", content=b"--xyz\r\ngarbage", headers={
        "content-type": "multipart/form-data; boundary=xyz"})
    assert 400 <= r.status_code < 500
    error_line(r)
    r = client.post("/surface", data={"source": "file"}, files={"file": ("empty.x3p", b"")})
    assert r.status_code == 400 and "is empty" in error_line(r)


def test_oversized_uploads_are_413(client):
    big = b"0" * (300 * 1024)                          # the limit is 0.25 MB
    r = client.post("/surface", data={"source": "file"}, files={"file": ("big.txt", big)})
    assert r.status_code == 413 and "0.25 MB" in error_line(r)

    def chunks():                                     # no Content-Length: counted as it comes
        for _ in range(40):
            yield b"x" * 10_000
    r = client.post("/surface", content=chunks(),
                    headers={"content-type": "multipart/form-data; boundary=b"})
    assert r.status_code == 413 and "limit" in error_line(r)


def test_a_file_without_units_asks_for_them_and_keeps_the_upload(client, tmp_path):
    z = np.add.outer(np.sin(np.linspace(0, 12, 64)), np.zeros(48))
    path = tmp_path / "map.npy"
    np.save(path, z)
    r = finished(client, client.post("/surface", data={"source": "file"},
                                     files={"file": ("map.npy", path.read_bytes())}))
    assert r.status_code == 422
    assert "unit" in error_line(r)
    assert '<fieldset class="attention" id="units">' in r.text       # the unit fields lit
    kept = re.search(r'name="upload" value="([0-9a-f]{32}\.npy)"', r.text).group(1)
    r = finished(client, client.post("/surface", data={"source": "file", "upload": kept,
                                                         "unit": "um", "pixel_size": "0.5"}))
    assert r.status_code == 200 and 'id="principal_direction">0.00<' in r.text


def test_forged_upload_and_job_ids_are_refused(client):
    r = client.post("/surface", data={"source": "file", "upload": "../../etc/passwd"})
    assert r.status_code == 400 and "no such upload" in error_line(r)
    r = client.post("/law", data={"source": "../../x", "law": "star"})
    assert r.status_code == 400 and "pick one from the list" in error_line(r)
    r = client.get("/jobs/20990101-000000-abcdef/files/job.json")
    assert r.status_code == 404


def test_host_and_origin_checks(client):
    r = client.get("/", headers={"host": "evil.example"})
    assert r.status_code == 403 and "localhost only" in error_line(r)
    r = client.post("/surface", data=WEDGE, headers={"origin": "http://evil.example"})
    assert r.status_code == 403 and "another site" in error_line(r)


def test_the_server_stays_up_and_jobs_list(client):
    r = client.get("/")
    assert r.status_code == 200 and "1. Surface" in r.text
    assert client.get("/jobs").status_code == 200
    assert client.get("/static/plotly.min.js").status_code == 200
    assert client.get("/static/nope.js").status_code == 404


def test_remote_needs_the_token(tmp_path):
    with client_for(tmp_path / "data", host="0.0.0.0", allow_remote=True,
                    token="s3cret-token") as c:
        for path in ("/", "/surface", "/api/jobs/x", "/static/app.js"):
            r = c.get(path)
            assert r.status_code == 401, path
            assert "access token" in error_line(r)
        assert c.get("/?token=wrong").status_code == 401
        r = c.get("/surface?token=s3cret-token")
        assert r.status_code == 303 and r.headers["location"] == "/surface"
        assert "HttpOnly" in r.headers["set-cookie"]
        assert c.get("/surface").status_code == 200               # the cookie now
        c.cookies.clear()
        assert c.get("/", headers={"Authorization": "token s3cret-token"}).status_code == 200
        assert c.get("/", headers={"host": "192.0.2.7:8765",
                                   "Authorization": "token s3cret-token"}).status_code == 200


def test_serve_refuses_a_remote_host_without_allow_remote(capsys):
    from cli_run import run
    code, out, err = run(capsys, "serve", "--host", "0.0.0.0")
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and "--allow-remote" in err
    code, out, err = run(capsys, "serve", "--port", "70000")
    assert code == 1 and "--port" in err


def test_jobs_and_uploads_survive_a_restart(tmp_path):
    folder = tmp_path / "data"
    with client_for(folder) as c:
        done = finished(c, c.post("/surface", data=WEDGE))
        jid = re.search(r'result <a href="/jobs/([0-9-a-f]+)"', done.text).group(1)
    rec = json.loads((folder / "jobs" / jid / "job.json").read_text())
    # a job left running when the server stopped: the next start runs it again
    from asperity.web.store import Store
    store = Store(folder)
    other = store.new_job("derive", {"source": {"kind": "wedge", "alpha_deg": 5.0,
                                                "beta_deg": 5.0, "mu_alpha": 0.1,
                                                "mu_beta": 0.1},
                                     "contact": "all-faces", "directions": 72,
                                     "method": "closed-form", "form": {}}, "left running")
    store.update(other["id"], status="running")
    with client_for(folder) as c:
        r = c.get(f"/jobs/{jid}")
        assert r.status_code == 200 and '<td id="mu_a_plus">0.185697</td>' in r.text
        assert rec["status"] == "done"
        page = job_page(c, other["id"])
        assert '<td id="mu_a_plus">0.100773</td>' in page.text     # SPEC.md 5 deg wedge


def test_a_real_server_with_a_token(tmp_path):
    srv = Server(tmp_path / "data", "--allow-remote", "--workers", "1")
    try:
        import httpx
        assert "?token=" in srv.url
        assert httpx.get(srv.base + "/").status_code == 401
        with httpx.Client(follow_redirects=True) as h:
            assert h.get(srv.url).status_code == 200
            assert h.get(srv.base + "/surface").status_code == 200      # by the cookie
        assert srv.alive()
    finally:
        assert srv.stop() == 0


def test_a_long_job_reports_progress_and_stops_from_its_page(client):
    r = client.post("/motion/slide", data={"law": "coulomb", "mu1": "0.01", "u0": "10",
                                           "angle_deg": "0", "dt": "1e-6"})   # ~1.5e8 steps
    assert r.status_code == 303
    jid = r.headers["location"].rsplit("/", 1)[-1]
    page = client.get(f"/jobs/{jid}")
    assert page.status_code == 200 and 'id="progress-bar"' in page.text
    t0 = time.monotonic()
    while client.get(f"/api/jobs/{jid}").json()["fraction"] <= 0.0:
        assert time.monotonic() - t0 < 60, "no progress reported"
        time.sleep(0.1)
    r = client.post(f"/jobs/{jid}/cancel")
    assert r.status_code == 303
    page = job_page(client, jid)
    assert page.status_code == 200 and "was stopped" in page.text
    assert client.get(f"/api/jobs/{jid}").json()["status"] == "cancelled"
    done = finished(client, client.post("/surface", data=WEDGE))      # a fresh worker
    assert '<td id="mu_a_plus">0.185697</td>' in done.text


def jid_of(page) -> str:
    return re.search(r'result <a href="/jobs/([0-9a-f-]+)"', page.text).group(1)


def test_every_source_of_every_form(client, tmp_path):
    """Surface -> Law -> Motion and risk through the results of the step before, a gauge
    file opened, and each friction source of the risk form."""
    surf = finished(client, client.post("/surface", data={"source": "file", "unit": "um"},
                                        files={"file": ("wedge.stl", (SURFACES /
                                                        "wedge-30-10.stl").read_bytes())}))
    assert surf.status_code == 200
    sid = jid_of(surf)
    law = finished(client, client.post("/law", data={"source": sid, "law": "ellipse",
                                                     "directions": "72"}))
    assert law.status_code == 200, error_line(law)
    assert 'id="law-kind">truncated-ellipse<' in law.text
    lid = jid_of(law)
    gauge = client.get(f"/jobs/{lid}/files/gauge.json")
    assert gauge.status_code == 200 and gauge.json()["format"] == "asperity-gauge"
    opened = finished(client, client.post("/law/open", files={
        "gauge": ("mine.json", gauge.content)}))
    assert opened.status_code == 200 and "gauge file mine.json" in opened.text
    for data, files in (({"law": f"job:{lid}"}, None),
                        ({"law": "upload"}, {"gauge": ("g.json", gauge.content)}),
                        ({"law": "star", "mu1": "0.3", "mu2": "0.2"}, None)):
        r = finished(client, client.post("/motion/slide", data={**data, "u0": "0.5",
                                                                 "angle_deg": "30"},
                                         files=files))
        assert r.status_code == 200 and 'id="deflection"' in r.text, error_line(r)
        assert client.get(f"/jobs/{jid_of(r)}/files/path.csv").text.startswith("t_s,x_m")
    two = {"model": "two-node", "two_k": "1e6", "two_l0": "0.1", "two_alpha_T": "1.2e-5",
           "two_k_t": "5e5", "two_N": "100", "dT_min": "0", "dT_max": "125"}
    asm = (SURFACES / "two-node-spec.toml").read_bytes()
    for data, files, verdict in (
            ({**two, "friction": "mu", "mu_plus": "0.2", "mu_minus": "0.1"}, None, "ratchet"),
            ({**two, "friction": f"job:{sid}"}, None, "ratchet"),
            ({**two, "friction": f"law:{lid}"}, None, "ratchet"),
            ({"friction": "assembly"}, {"assembly_file": ("spec.toml", asm)}, "ratchet")):
        r = finished(client, client.post("/motion/risk", data=data, files=files))
        assert r.status_code == 200, error_line(r)
        assert f'id="verdict">{verdict}<' in r.text
    r = finished(client, client.post("/motion/risk", data={"friction": "assembly"}, files={
        "assembly_file": ("b.toml", (SURFACES / "bushing-strip.toml").read_bytes())}))
    assert r.status_code == 422 and "friction.texture = " in error_line(r)
    assert "may not name other files" in error_line(r)
