"""Every field of every form of ``asperity serve`` with hostile values: a 4xx with one line
next to the field, the form back with what was typed and the uploads kept, never a 500,
never a traceback in the server's log.

The forms are found in the pages' HTML (:mod:`web_forms`: crawled from the home page), so
a field added later is walked without a new test.  Each form is filled with its own
defaults (plus the few in :data:`QUICK` that keep its jobs short, and the example files
in :func:`examples` for its file fields); then, for each field in turn (the fieldsets
that show it switched on), each value of :data:`HOSTILE` is sent with the others valid.
"""
from __future__ import annotations

import collections
import json
import logging
import os
import re
import socket
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message=".*httpx2.*")
    from fastapi.testclient import TestClient  # noqa: E402
from web_forms import UPLOAD_ID, Page, activate, active  # noqa: E402
from web_server import ROOT, Server, wait_for  # noqa: E402

from asperity.web.app import create_app  # noqa: E402
from asperity.web.settings import make_settings, prepare_data_dir  # noqa: E402

SURFACES = ROOT / "surfaces"
HOSTILE = {"text": "abc", "empty": "", "NaN": "NaN", "nan": "nan", "inf": "inf",
           "-inf": "-inf", "1e999": "1e999", "-1e999": "-1e999", "negative": "-1",
           "zero": "0", "1e308": "1e308", "10**30": str(10 ** 30), "2.5": "2.5"}
#: what a file field gets instead: no file, a file of garbage, an empty file
FILE_HOSTILE = {"empty": None, "text": b"abc\x00\xff not a surface\n", "zero": b""}
#: values never to be accepted in a text field (a number field or not)
NEVER = ("NaN", "nan", "inf", "-inf", "1e999", "-1e999")
#: whole-number fields: 2.5 and the huge values are refused too
WHOLE = ("directions", "despike_window", "strip_n", "workers", "contact_points", "c_points",
         "c_periods", "c_steps")
#: defaults that keep the walker's jobs short (a field not named here keeps the page's)
QUICK = {"directions": "8", "strip_n": "11", "unit": "um", "pixel_size": "1", "r_unit": "um",
         "contact_points": "8", "dt": "1e-3", "t_end": "0.2",
         # a softer support: the wedge's plane-strain solve needs far fewer nodes per wedge
         # (the accepted Surface jobs took 2/3 of this walk at the default E*)
         "E_star": "1e9",
         # a short crawl (the Motion page's crawl form)
         "c_points": "16", "c_periods": "2"}
#: refusals that are physical outcomes of several fields together: shown above the form
UNPLACED = ("the margin ", "the texture self-locks", "wedge.stl gives no friction")
#: words of a message that are neither the page's nor the user's: a key of the command line
#: or of a file (``pixel_size``, ``assembly.h``)
KEY = re.compile(r"[A-Za-z][A-Za-z0-9]*(?:[._][A-Za-z0-9]+)+")
STUDY = """name = "tiny"
[study]
kind = "grid"
stages = ["derive"]
texture = "wedge-asymmetric.toml"
directions = 8
[parameters]
"texture.alpha_deg" = { values = [20.0, 30.0] }
"""

BODY = """name = "coin"
[body]
shape = "disc"
radius = 0.01
mass = 0.005
contact_points = 8
"""


def examples(tmp) -> dict:
    """Valid files for the file fields (field name -> [(file name, bytes)]); a field not
    named here is sent without a file unless it is the one being tried."""
    x = np.arange(24) * 1.0
    z = np.add.outer(np.zeros(24), 0.4 * (x % 6) - 0.06 * (x % 6) ** 2)   # ridges, um
    text = "\n".join(" ".join(f"{v:.4f}" for v in row) for row in z) + "\n"
    from asperity import WedgeTexture, derive, fit_derivation, write_gauge
    write_gauge(tmp / "gauge.json", fit_derivation(derive(WedgeTexture(
        alpha_deg=30.0, beta_deg=10.0, mu_alpha=0.1, mu_beta=0.2), n_directions=16)))
    return {"file": [("ridges.txt", text.encode())],
            "gauge": [("gauge.json", (tmp / "gauge.json").read_bytes())],
            "c_gauge": [("gauge.json", (tmp / "gauge.json").read_bytes())],
            "c_texture_file": [("wedge-asymmetric.toml",
                                (SURFACES / "wedge-asymmetric.toml").read_bytes())],
            "texture_file": [("wedge.stl", (SURFACES / "wedge-30-10.stl").read_bytes())],
            "study": [("tiny.toml", STUDY.encode())],
            "body_file": [("coin.toml", BODY.encode())],
            "companions": [("wedge-asymmetric.toml",
                            (SURFACES / "wedge-asymmetric.toml").read_bytes())]}


class Records(logging.Handler):
    """Every log record of WARNING and above (the server's log in-process)."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.records: list[logging.LogRecord] = []

    def emit(self, record):
        self.records.append(record)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    folder = tmp_path_factory.mktemp("web-forms")
    settings = make_settings(data_dir=folder / "data", workers=2)
    prepare_data_dir(settings.data_dir)
    rec = Records()
    logging.getLogger().addHandler(rec)
    try:
        with TestClient(create_app(settings), base_url="http://127.0.0.1:8765",
                        follow_redirects=False) as client:
            yield client, examples(folder), rec
    finally:
        logging.getLogger().removeHandler(rec)


def crawl(client) -> list:
    """The forms of every page the home page links to (the job pages aside)."""
    seen, forms = set(), {}
    todo = ["/"]
    while todo:
        path = todo.pop(0)
        if path in seen:
            continue
        seen.add(path)
        page = Page(client.get(path).text)
        for f in page.forms:
            if f.method == "post" and f.fields:
                forms.setdefault(f.key, f)
        if path == "/":
            todo += [h for h in page.links if h.startswith("/") and not
                     h.startswith(("/jobs/", "/static/", "/api/"))]
    return list(forms.values())


def base_values(form, target) -> dict:
    values = {f.name: QUICK.get(f.name, f.value) for f in form.fields if f.kind != "file"}
    return activate(form, target, values)


def files_for(form, values, ex, target=None, hostile=None) -> list:
    out = []
    for f in form.fields:
        if f.kind != "file":
            continue
        if f is target:
            if hostile is not None:
                name = (ex.get(f.name) or [("x.txt", b"")])[0][0]
                out.append((f.name, (name, hostile)))
        elif f.name in ex and active(f, values):
            out += [(f.name, item) for item in ex[f.name]]
    return out


def outcome(client, form, target, values, files) -> tuple[str, str]:
    """(outcome, detail) of one submission: refused (a 4xx with its line at the field,
    the form kept), accepted (a job: stopped at once if it still runs), or a defect."""
    try:
        r = client.post(form.action, data=values, files=files or None)
    except Exception as exc:          # escaped the app: a server would log a traceback
        return "escaped", f"{type(exc).__name__}: {exc}"[:200]
    if r.status_code == 303:                     # a job: its end, or stopped after 20 s
        jid = r.headers["location"].rsplit("/", 1)[-1]
        t0 = time.monotonic()
        while (st := client.get(f"/api/jobs/{jid}").json())["status"] in ("queued", "running"):
            if time.monotonic() - t0 > 20:
                client.post(f"/jobs/{jid}/cancel")
                return "accepted", "still running after 20 s: stopped"
            time.sleep(0.05)
        if st["status"] != "failed":
            return "accepted", st["status"]
        r = client.get(f"/jobs/{jid}")            # refused by the job: its form again
    if not 400 <= r.status_code < 500:
        return f"status {r.status_code}", r.text[:200]
    return refusal_problems(r, form, target, values, files)


def refusal_problems(r, form, target, values, files) -> tuple[str, str]:
    if "Traceback" in r.text:
        return "traceback", ""
    page = Page(r.text)
    if len(page.page_errors) != 1:
        return "no one-line message", f"{page.page_errors}"
    msg = page.page_errors[0]
    if not msg or len(msg) > 400:
        return "no one-line message", msg
    again = [f for f in page.forms if f.key == form.key]
    if not again:
        return "form not shown again", msg
    form2 = again[0]
    toml = " ".join(d.decode("latin-1") for _, (n, d) in files if n.endswith(".toml"))
    names = " ".join(n for _, (n, _) in files)
    foreign = [w for w in KEY.findall(msg) if w not in form.page_text and w not in names
               and not all(re.search(rf"\b{p}\b", toml) for p in re.split(r"[._]", w))]
    if foreign:
        return "not the page's words", f"{foreign}: {msg}"
    others = sum(len(f.errors) for f in page.forms)
    unplaced = not form2.errors and msg.startswith(UNPLACED)
    if target.kind != "hidden" and not unplaced:
        here = form2.by_name(target.name)[0]
        if len(form2.errors) != 1 or others != 1 or form2.errors[0][1] != msg:
            return "line not at the field", f"{msg} (errors at {form2.errors})"
        if form2.errors[0][0] != here.label and here.label_text not in msg:
            return "line not at the field", f"{msg} (at another field)"
    for f in form2.fields:
        sent = values.get(f.name)
        if f.kind in ("hidden", "file") or sent is None:
            continue
        if f.kind == "select" and sent not in f.options:
            continue
        if f.value != sent:
            return "typed value lost", f"{f.name}: {sent!r} -> {f.value!r} ({msg})"
    stored = [name for field, (name, data) in files if data]
    kept = [f.value for f in form2.fields if f.kind == "hidden" and UPLOAD_ID.match(f.value)]
    if len(kept) < len(stored):
        return "upload lost", f"{stored} -> {kept} ({msg})"
    return ("refused, above the form" if unplaced else "refused"), msg


def kept_resubmission(client, form, target, values, refused_page) -> tuple[str, str]:
    """The form as it came back (its kept uploads, the target field set right again),
    sent without choosing any file: it must be accepted."""
    form2 = [f for f in Page(refused_page).forms if f.key == form.key][0]
    data = {f.name: f.value for f in form2.fields if f.kind not in ("file", "select")}
    data.update({f.name: f.value for f in form2.fields if f.kind == "select"})
    data[target.name] = values[target.name]
    r = client.post(form.action, data=data)
    return ("accepted", "") if r.status_code == 303 else (f"status {r.status_code}", r.text[:300])


def test_whole_number_fields_refuse_non_numbers_at_the_field(site):
    """The issue's 500s first, quickly: inf, nan, 1e999, 2.5 and 10^30 in each whole-number
    field are a 400 with the field's line, the value kept (the walker below tries all)."""
    client, ex, logs = site
    first_record = len(logs.records)
    forms = crawl(client)
    for name in WHOLE:
        form = next(f for f in forms if f.by_name(name))
        target = form.by_name(name)[0]
        for label in ("inf", "nan", "1e999", "2.5", "10**30"):
            values = {**base_values(form, target), name: HOSTILE[label]}
            files = files_for(form, values, ex)
            what, detail = outcome(client, form, target, values, files)
            assert what == "refused", (form.action, name, label, what, detail)
            assert "whole number" in detail and "got" in detail, detail
    assert not [r for r in logs.records[first_record:]
                if r.exc_info or "internal error" in r.getMessage()]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    s = Server(tmp_path_factory.mktemp("web-forms-server"), "--workers", "1")
    try:
        wait_for(lambda: any("data folder" in line for line in s.err), 30)   # start-up said
        yield s
    finally:
        s.stop()


def test_a_real_server_logs_no_traceback_for_hostile_numbers(server):
    """The values of the issue through uvicorn: a 400 with the field's line, nothing but
    the start-up lines in the server's log (stderr)."""
    import httpx
    before = len(server.err)
    with httpx.Client(base_url=server.base, timeout=60) as c:
        for name, value in (("directions", "inf"), ("directions", "1e999"),
                            ("directions", "nan"), ("alpha_deg", "1e999")):
            r = c.post("/surface", data={"source": "wedge", "alpha_deg": "30",
                                         "beta_deg": "10", "mu_alpha": "0.1",
                                         "mu_beta": "0.2", "directions": "72", name: value})
            assert r.status_code == 400, (name, value, r.text[:300])
            form = [f for f in Page(r.text).forms if f.id == "wedge-form"][0]
            assert len(form.errors) == 1 and form.by_name(name)[0].value == value
    assert server.alive()
    assert server.err[before:] == [], "".join(server.err[before:])     # not a word


def test_a_client_gone_mid_upload_logs_nothing(server):
    """A raw socket sends the head and half of a multipart body, then closes: the server
    stays up, says nothing in its log, and keeps no half upload."""
    host, port = server.base.split("//", 1)[1].split(":")
    body = (b"--XyZ\r\nContent-Disposition: form-data; name=\"source\"\r\n\r\nfile\r\n"
            b"--XyZ\r\nContent-Disposition: form-data; name=\"file\"; filename=\"m.txt\"\r\n"
            b"Content-Type: text/plain\r\n\r\n" + b"1 2 3 4\n" * 4000)
    before = len(server.err)
    for _ in range(3):
        with socket.create_connection((host, int(port)), timeout=10) as sock:
            sock.sendall(b"POST /surface HTTP/1.1\r\nHost: " + f"{host}:{port}".encode() +
                         b"\r\nContent-Type: multipart/form-data; boundary=XyZ\r\n"
                         b"Content-Length: " + str(2 * len(body)).encode() + b"\r\n\r\n" + body)
            time.sleep(0.3)
    import httpx
    time.sleep(1.0)
    assert httpx.get(server.base + "/", timeout=30).status_code == 200
    assert server.err[before:] == [], "".join(server.err[before:])     # not a word
    assert not [p for p in (server_dir(server) / "uploads").iterdir()
                if p.name.startswith(("m", ".")) or p.suffix == ".part"]


def server_dir(server) -> Path:
    return Path(server.proc.args[server.proc.args.index("--data-dir") + 1])


def test_a_bug_is_one_line_and_its_traceback_only_with_asperity_debug(tmp_path, monkeypatch):
    """An exception in a page is a 500 with one line; the log has one line, the traceback
    only with ASPERITY_DEBUG=1; nothing escapes the application (a server would print the
    traceback of anything that does)."""
    settings = make_settings(data_dir=tmp_path, workers=1)
    prepare_data_dir(settings.data_dir)
    rec = Records()
    logging.getLogger().addHandler(rec)
    try:
        app = create_app(settings)
        with TestClient(app, base_url="http://127.0.0.1:8765") as client:
            web = app.app.state.web

            def broken(*a, **k):
                raise RuntimeError("planted\nbug")
            monkeypatch.setattr(web.store, "jobs", broken)
            for debug in ("", "1"):
                monkeypatch.setenv("ASPERITY_DEBUG", debug)
                n = len(rec.records)
                r = client.get("/")               # raises here if the exception escaped
                assert r.status_code == 500
                assert Page(r.text).page_errors == [
                    "internal error: RuntimeError: planted bug (please report it)"]
                new = rec.records[n:]
                assert len(new) == 1 and "planted" in new[0].getMessage()
                assert bool(new[0].exc_info) == bool(debug)
    finally:
        logging.getLogger().removeHandler(rec)


def test_every_field_of_every_form_refuses_hostile_values(site):
    client, ex, logs = site
    first_record = len(logs.records)
    forms = crawl(client)
    assert {f.action for f in forms} >= {"/surface", "/law", "/law/open", "/motion/slide",
                                         "/motion/risk", "/studies"}
    names = {f.name for form in forms for f in form.fields}
    assert set(WHOLE) <= names, set(WHOLE) - names      # the list names real fields
    table, seconds = collections.Counter(), collections.Counter()
    defects, accepted, resubmitted, bases = [], collections.defaultdict(list), set(), set()
    for form in forms:
        for target in form.fields:
            if any(not allowed for _, allowed in target.when):
                continue          # no choice on the page shows it (a law family's pressure
                #                   with no family yet: test_web_law_family walks it)
            values = base_values(form, target)
            key = (form.key, tuple(sorted(values.items())))
            if key not in bases:                   # the valid submission is accepted
                bases.add(key)
                base = outcome(client, form, target, values, files_for(form, values, ex))
                assert base[0] == "accepted", (form.action, target.name, base)
            cases = FILE_HOSTILE if target.kind == "file" else HOSTILE
            for label, value in cases.items():
                v = dict(values)
                if target.kind != "file":
                    v[target.name] = value
                files = files_for(form, v, ex, target, value if target.kind == "file" else None)
                t0 = time.monotonic()
                what, detail = outcome(client, form, target, v, files)
                seconds[f"{form.action} {what}"] += time.monotonic() - t0
                table[(label, what)] += 1
                where = f"{form.action}#{form.id} {target.name}={label}"
                if what == "accepted":
                    accepted[target.name].append(label)
                    bad = (target.kind != "select" and label in NEVER) or \
                        (target.name in WHOLE and label in ("2.5", "1e308", "10**30")) or \
                        (label == "text" and target.kind not in ("select", "hidden", "file"))
                    if bad:
                        defects.append(f"{where}: accepted")
                elif not what.startswith("refused"):
                    defects.append(f"{where}: {what}: {detail}")
                elif files and form.key not in resubmitted and target.kind != "file":
                    resubmitted.add(form.key)
                    page = client.post(form.action, data=v, files=files).text
                    res = kept_resubmission(client, form, target, values, page)
                    if res[0] != "accepted":
                        defects.append(f"{where}: the kept uploads do not work: {res}")
    traced = [r.getMessage()[:200] for r in logs.records[first_record:]
              if r.exc_info or "Traceback" in r.getMessage() or "internal error" in
              r.getMessage()]
    report = {"cases": sum(table.values()), "forms": len(forms),
              "fields": sum(len(f.fields) for f in forms),
              "outcomes": {f"{k[0]}: {k[1]}": n for k, n in sorted(table.items())},
              "accepted": dict(accepted), "defects": defects,
              "seconds": {k: round(v, 1) for k, v in seconds.items()}}
    if os.environ.get("ASPERITY_WALK_REPORT"):     # the counts for a closing note
        Path(os.environ["ASPERITY_WALK_REPORT"]).write_text(json.dumps(report, indent=1))
    assert not defects, "\n".join(defects[:40]) + f"\n({len(defects)} defects)"
    assert not traced, traced[:10]
    # the forms whose other fields come with a file: Surface (file), risk (texture), studies
    assert len(resubmitted) >= 3, resubmitted
