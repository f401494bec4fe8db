"""The web page as a hostile visitor meets it, through a real ``asperity serve`` on
127.0.0.1 (issue 18, sections 1 and 10): a study (or the assembly it names) that names a
file outside the files uploaded with it -- for every key and every form of name -- is
refused with a 4xx and one line naming the key, runs no job and shows nothing of the
file; a Host header that only begins with "localhost" is refused; the upload limit holds
for a body sent in many small chunks; a job's files are served only if the job declared
them; a wrong token cookie is refused; a study job re-run after a restart resumes only on
the same inputs.  (Symbolic links cannot be uploaded: the resolver's tests with links
pointing out are in test_study_inputs.py.)"""
from __future__ import annotations

import html
import json
import re
import select
import socket
import sqlite3
import time
import warnings
from pathlib import Path

import pytest

pytest.importorskip("fastapi")
httpx = pytest.importorskip("httpx")
with warnings.catch_warnings():      # starlette 1.x would rather have httpx2; httpx works
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient  # noqa: E402
from web_server import ROOT, served  # noqa: E402

from asperity.web.app import create_app  # noqa: E402
from asperity.web.settings import make_settings, prepare_data_dir  # noqa: E402

SURF = ROOT / "surfaces"
OUTSIDE = "on this page a study may only name files uploaded with it"
MARKER = "SECRET-3f9c2a-not-for-visitors"
LIMIT_MB = 0.25


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    yield from served(tmp_path_factory.mktemp("web-security") / "data", "--workers", "1",
                      "--max-upload", str(LIMIT_MB))


@pytest.fixture(scope="module")
def outside(tmp_path_factory):
    """A folder outside the server's data folder with a file of every kind the study
    keys name, each holding the marker."""
    d = tmp_path_factory.mktemp("outside")
    for name in ("secret.toml", "secret.json", "secret.x3p", "secret.stl"):
        (d / name).write_text(f'name = "{MARKER}"\n')
    return d


def data_dir(server) -> Path:
    return Path(server.proc.args[server.proc.args.index("--data-dir") + 1])


def listing(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


def alerts(resp) -> list[str]:
    """The page's one-line messages (unescaped)."""
    text = resp.text
    if resp.headers.get("content-type", "").startswith("application/json"):
        return [resp.json().get("error", "")]
    found = re.findall(r'<[^>]*(?:role="alert"|class="error[^"]*")[^>]*>(.*?)</', text, re.S)
    return [html.unescape(m).strip() for m in found]


def post_study(server, study: str, companions: dict[str, str]):
    files = [("study", ("s.toml", study.encode()))]
    files += [("companions", (n, t.encode())) for n, t in companions.items()]
    return httpx.post(server.base + "/studies", files=files, data={"workers": "0"},
                      timeout=60)


def _q(v: str) -> str:
    return json.dumps(v)


def forms(outside: Path, name: str) -> dict[str, str]:
    """Every form of name a visitor can type that points at ``outside/name``."""
    return {"absolute": str(outside / name), "dotdot": f"../../../../../..{outside}/{name}",
            "dotdot-plain": f"../{name}", "tilde": f"~/{name}", "tilde-user": f"~root/{name}",
            "glob": "../*", "absolute-glob": str(outside / "secret.*"),
            "etc-glob": "/etc/host*", "tilde-glob": "~/*"}


ASSEMBLY = (SURF / "bushing-strip.toml").read_text()
_BEFORE, _AFTER = ASSEMBLY.split("[friction]")
GRID = '[parameters]\n"loading.dT_max" = { values = [80.0] }\n'


def hostile(key: str, value: str) -> tuple[str, dict[str, str]]:
    """(study text, companions) naming ``value`` at ``key``."""
    tex = (SURF / "wedge-asymmetric.toml").read_text()
    plain = _BEFORE + "[friction]\nmu_plus = 0.2\nmu_minus = 0.1\n" + \
        _AFTER[_AFTER.index("[loading]"):]
    comp = {"wedge.toml": tex, "asm.toml": plain}
    if key == "study.files":
        return f'[study]\nkind = "files"\nstages = ["derive"]\nfiles = {_q(value)}\n', comp
    if key == "study.files[1]":
        return (f'[study]\nkind = "files"\nstages = ["derive"]\n'
                f'files = ["wedge.toml", {_q(value)}]\n'), comp
    if key == "study.texture":
        return (f'[study]\nkind = "grid"\nassembly = "asm.toml"\ntexture = {_q(value)}\n'
                + GRID), comp
    if key == "study.assembly":
        return f'[study]\nkind = "grid"\nassembly = {_q(value)}\n' + GRID, comp
    k = key.rsplit(".", 1)[1]
    comp["named.toml"] = _BEFORE + f"[friction]\n{k} = {_q(value)}\n" + \
        _AFTER[_AFTER.index("[loading]"):]
    return '[study]\nkind = "grid"\nassembly = "named.toml"\n' + GRID, comp


KEYS = {"study.files": "secret.x3p", "study.files[1]": "secret.toml",
        "study.texture": "secret.toml", "study.assembly": "secret.toml",
        "named.toml: friction.gauge": "secret.json",
        "named.toml: friction.texture": "secret.stl"}


def test_every_file_name_that_leaves_the_upload_is_a_400_naming_the_key(server, outside):
    data = data_dir(server)
    before = listing(data)
    tried = 0
    for key, name in KEYS.items():
        for form, value in forms(outside, name).items():
            study, comp = hostile(key, value)
            r = post_study(server, study, comp)
            tried += 1
            want = f"{key} = {value!r}: {OUTSIDE}"
            lines = [m for m in alerts(r) if key in m]
            assert r.status_code == 400 and lines == [want], (key, form, r.status_code,
                                                              alerts(r))
            assert MARKER not in r.text and "Traceback" not in r.text
    assert tried == len(KEYS) * 9
    assert listing(data) == before, "a refused study left an upload or a job behind"
    assert httpx.get(server.base + "/jobs").status_code == 200 and server.alive()


def test_the_risk_pages_assembly_never_makes_the_server_read_a_file_it_names(server,
                                                                             outside):
    """The Motion and risk page takes an assembly file alone: a gauge or texture it names
    (any form) is refused in one line naming the key when the assembly's own friction is
    asked for, and never read when the form gives the friction."""
    tried = 0
    for key, name in (("gauge", "secret.json"), ("texture", "secret.toml")):
        for form, value in forms(outside, name).items():
            asm = _BEFORE + f"[friction]\n{key} = {_q(value)}\n" + \
                _AFTER[_AFTER.index("[loading]"):]
            files = {"assembly_file": ("b.toml", asm.encode())}
            r = httpx.post(server.base + "/motion/risk", data={"friction": "assembly"},
                           files=files, timeout=60, follow_redirects=True)
            lines = [m for m in alerts(r) if f"friction.{key} = " in m]
            assert r.status_code == 422 and len(lines) == 1, (key, form, alerts(r))
            assert "may not name other files" in lines[0] and MARKER not in r.text
            tried += 1
    assert tried == 2 * 9
    wedge = {"friction": "wedge", "r_alpha_deg": "30", "r_beta_deg": "10",
             "r_mu_alpha": "0.1", "r_mu_beta": "0.2"}
    asm = _BEFORE + f"[friction]\ngauge = {_q(str(outside / 'secret.json'))}\n" + \
        _AFTER[_AFTER.index("[loading]"):]
    r = httpx.post(server.base + "/motion/risk", data=wedge, timeout=60,
                   files={"assembly_file": ("b.toml", asm.encode())})
    jid = wait_done(server, r)
    page = httpx.get(f"{server.base}/jobs/{jid}")
    assert page.status_code == 200 and 'id="verdict"' in page.text, alerts(page)
    out = "".join(p.read_text(errors="replace") for p in
                  (data_dir(server) / "jobs" / jid).rglob("*") if p.is_file())
    assert MARKER not in page.text + out


def wait_done(server, r, timeout=120.0) -> str:
    assert r.status_code == 303, (r.status_code, alerts(r))
    jid = r.headers["location"].rsplit("/", 1)[-1]
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        st = httpx.get(f"{server.base}/api/jobs/{jid}").json()
        if st["status"] not in ("queued", "running"):
            return jid
        time.sleep(0.1)
    raise AssertionError(f"job {jid} did not finish")


def test_a_study_of_uploaded_files_runs_and_its_job_serves_only_what_it_declared(server):
    """The positive control of the confinement (a string pattern of uploaded files runs),
    and the downloads of an existing job: declared files only."""
    tex = (SURF / "wedge-asymmetric.toml").read_text()
    sym = (SURF / "wedge-symmetric-30.toml").read_text()
    r = post_study(server, '[study]\nkind = "files"\nstages = ["derive"]\nfiles = "w*.toml"\n',
                   {"wa.toml": tex, "wb.toml": sym})
    jid = wait_done(server, r)
    page = httpx.get(f"{server.base}/jobs/{jid}")
    assert page.status_code == 200, alerts(page)
    rec = json.loads((data_dir(server) / "jobs" / jid / "job.json").read_text())
    assert rec["status"] == "done" and "cases.csv" in rec["files"]
    csv = httpx.get(f"{server.base}/jobs/{jid}/files/cases.csv")
    assert csv.status_code == 200
    files = [line.split(",")[1] for line in csv.text.splitlines()[1:]]
    assert sorted(files) == ["wa.toml", "wb.toml"], files        # the upload's names only
    job = data_dir(server) / "jobs" / jid
    undeclared = ["job.json", "result.json", "progress.json", "input/s.toml", "input/wa.toml",
                  "study/study.sqlite"]
    for name in undeclared:
        assert (job / name).is_file(), name              # exists, yet is not served
        got = httpx.get(f"{server.base}/jobs/{jid}/files/{name}")
        assert got.status_code == 404 and "Traceback" not in got.text, name
        assert (job / name).read_bytes()[:40] not in got.content, name
    for name in ("../" + jid + "/job.json", "%2e%2e/job.json", "study/../job.json"):
        assert httpx.get(f"{server.base}/jobs/{jid}/files/{name}").status_code in (404, 400)
    for name in rec["files"]:
        assert httpx.get(f"{server.base}/jobs/{jid}/files/{name}").status_code == 200, name


@pytest.mark.parametrize("host", ["localhost.evil.example", "localhost.evil.example:80",
                                  "localhost@evil.example", "127.0.0.1.evil.example",
                                  "localhostevil.example", "evil.example"])
def test_a_host_that_only_begins_like_localhost_is_refused(server, host):
    r = httpx.get(server.base + "/", headers={"host": host})
    assert r.status_code == 403 and any("localhost only" in m for m in alerts(r)), host


def test_loopback_hosts_are_answered(server):
    port = server.base.rsplit(":", 1)[1]
    for host in (f"localhost:{port}", f"127.0.0.1:{port}", "localhost", f"[::1]:{port}"):
        assert httpx.get(server.base + "/", headers={"host": host}).status_code == 200, host


def _multipart(fields: list[tuple[str, str, bytes]]) -> bytes:
    """A multipart/form-data body (boundary ``bnd``) of (field, file name, content)."""
    out = b""
    for field, name, content in fields:
        out += (f'--bnd\r\nContent-Disposition: form-data; name="{field}"; '
                f'filename="{name}"\r\nContent-Type: text/plain\r\n\r\n').encode()
        out += content + b"\r\n"
    return out + b"--bnd--\r\n"


def _chunked_post(base: str, path: str, body: bytes, piece: int) -> tuple[int, bytes]:
    """POST ``body`` in chunks of ``piece`` bytes (Transfer-Encoding: chunked, no
    Content-Length), stopping as soon as the server answers; (status, answer)."""
    host, port = base.split("//", 1)[1].split(":")
    s = socket.create_connection((host, int(port)), timeout=30)
    answer = b""
    try:
        s.sendall((f"POST {path} HTTP/1.1\r\nHost: {host}:{port}\r\nConnection: close\r\n"
                   f"Content-Type: multipart/form-data; boundary=bnd\r\n"
                   f"Transfer-Encoding: chunked\r\n\r\n").encode())
        for at in range(0, len(body), piece):
            if select.select([s], [], [], 0)[0]:        # the server answered: stop sending
                break
            b = body[at:at + piece]
            s.sendall(f"{len(b):x}\r\n".encode() + b + b"\r\n")
        else:
            s.sendall(b"0\r\n\r\n")
    except (BrokenPipeError, ConnectionResetError):
        pass
    try:
        while part := s.recv(65536):
            answer += part
    except ConnectionResetError:
        pass
    finally:
        s.close()
    status = int(answer.split(b" ", 2)[1]) if answer.startswith(b"HTTP/") else 0
    return status, answer


def test_the_upload_limit_counts_every_small_chunk_through_a_real_server(server):
    """Four files of 0.3 times the limit each, sent in 2 kB chunks: each file and each
    chunk is under the limit, the request is not."""
    limit = int(LIMIT_MB * 2**20)
    part = b"# " + b"x" * int(0.3 * limit) + b"\n"
    study = b'[study]\nkind = "grid"\n'
    body = _multipart([("study", "s.toml", study)] +
                      [("companions", f"c{i}.toml", part) for i in range(4)])
    status, answer = _chunked_post(server.base, "/studies", body, 2048)
    assert status == 413, answer[:300]
    assert b"limit of 0.25 MB" in answer and b"Traceback" not in answer
    # under the limit, the same chunked request is read (a form's answer, not a 413)
    body = _multipart([("study", "s.toml", study), ("companions", "c0.toml", part)])
    status, answer = _chunked_post(server.base, "/studies", body, 2048)
    assert status in (400, 422) and b"limit" not in answer, answer[:300]
    assert server.alive()


def test_a_wrong_token_cookie_is_refused(tmp_path):
    """The token's cookie must hold the token: its name alone, or a value that only
    begins like the token, is refused (in-process app: the cookie logic is the same)."""
    settings = make_settings(data_dir=tmp_path / "data", workers=1, host="0.0.0.0",
                             allow_remote=True, token="s3cret-token")
    prepare_data_dir(settings.data_dir)
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                    follow_redirects=False) as c:
        r = c.get("/surface?token=s3cret-token")
        name = r.headers["set-cookie"].split("=", 1)[0]
        c.cookies.clear()
        for value in ("wrong", "", "s3cret-toke", "s3cret-token-and-more", "S3CRET-TOKEN"):
            r = c.get("/surface", headers={"cookie": f"{name}={value}"})
            assert r.status_code == 401 and any("access token" in m for m in alerts(r)), value
        r = c.get("/surface", headers={"cookie": f"other=s3cret-token; {name}=nope"})
        assert r.status_code == 401
        assert c.get("/surface", headers={"cookie": f"{name}=s3cret-token"}).status_code == 200


def test_a_restarted_server_resumes_a_study_job_on_the_same_inputs_only(tmp_path):
    """A study job that was running when the server stopped runs again at the next start:
    it resumes its store if its inputs are the same, and is refused in one line naming
    the file if they changed (the study store's fingerprint of the content)."""
    from asperity.web.store import Store
    folder = tmp_path / "data"

    def client():
        settings = make_settings(data_dir=folder, workers=1)
        prepare_data_dir(settings.data_dir)
        return TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                          follow_redirects=False)

    def finished(c, jid):
        t0 = time.monotonic()
        while time.monotonic() - t0 < 120:
            if c.get(f"/api/jobs/{jid}").json()["status"] not in ("queued", "running"):
                return c.get(f"/jobs/{jid}")
            time.sleep(0.1)
        raise AssertionError("job did not finish")

    study = '[study]\nkind = "grid"\nassembly = "asm.toml"\n' + \
        '[parameters]\n"loading.dT_max" = { values = [60.0, 120.0] }\n'
    files = [("study", ("s.toml", study.encode())),
             ("companions", ("asm.toml", (SURF / "bushing-strip.toml").read_bytes())),
             ("companions", ("wedge-asymmetric.toml",
                             (SURF / "wedge-asymmetric.toml").read_bytes()))]
    with client() as c:
        r = c.post("/studies", files=files, data={"workers": "0"})
        jid = r.headers["location"].rsplit("/", 1)[-1]
        assert finished(c, jid).status_code == 200
    job = folder / "jobs" / jid
    rec = json.loads((job / "job.json").read_text())

    def left_running():
        (job / "result.json").unlink()
        Store(folder).update(jid, status="running")

    left_running()                                       # the same inputs: resumed
    with client() as c:
        assert finished(c, jid).status_code == 200
    assert json.loads((job / "result.json").read_text())["summary"]["run"]["ran"] == 0
    con = sqlite3.connect(job / "study" / "study.sqlite")
    assert con.execute("SELECT COUNT(*) FROM cases").fetchone()[0] == 2
    con.close()
    up = next(f["upload"] for f in rec["params"]["companions"]
              if f["name"] == "wedge-asymmetric.toml")
    stored = folder / "uploads" / up
    stored.write_text(stored.read_text().replace("mu_alpha = 0.1", "mu_alpha = 0.11"))
    left_running()                                       # a changed input: refused
    with client() as c:
        page = finished(c, jid)
    msg = [m for m in alerts(page) if "changed since" in m]
    assert page.status_code == 422 and len(msg) == 1, alerts(page)
    assert msg[0].startswith("wedge-asymmetric.toml changed since the study in") and \
        "cannot be resumed" in msg[0] and str(folder) not in msg[0], msg[0]
