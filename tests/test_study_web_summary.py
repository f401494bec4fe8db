"""The Studies page shows what the summary may claim (issue 18, sections 5 and 10): a study
whose output does not vary names no parameter, a grid's share has no interval (and no
HTTP 500), and a scan library's downloads name each file as the study names it, never
by the server's path."""
from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
from test_web_http import client_for, error_line, job_page  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TWO_NODE = (ROOT / "surfaces" / "two-node-spec.toml").read_bytes()


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with client_for(tmp_path_factory.mktemp("web-study")) as c:
        yield c


def run_study(client, study: str, companions: list[tuple[str, bytes]]):
    r = client.post("/studies", files=[("study", ("s.toml", study.encode())),
                                       *[("companions", c) for c in companions]])
    assert r.status_code == 303, error_line(r)
    jid = r.headers["location"].rsplit("/", 1)[-1]
    page = job_page(client, jid, timeout=120.0)
    assert page.status_code == 200 and 'id="study-text"' in page.text, page.text[:2000]
    return jid, page.text


def test_a_study_whose_output_does_not_vary_names_no_parameter_on_the_page(client):
    _, page = run_study(client, """
[study]
kind = "latin-hypercube"
samples = 20
assembly = "two-node-spec.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 10.0, high = 60.0 }
"assembly.N" = { distribution = "uniform", low = 90.0, high = 110.0 }
""", [("two-node-spec.toml", TWO_NODE)])
    assert "no parameter matters: the output does not vary (drift_per_cycle_m = 0 in every " \
           "case)" in page
    assert "matters most" not in page and "most influential" not in page


def test_a_grid_shows_its_share_without_an_interval(client):
    _, page = run_study(client, """
[study]
kind = "grid"
assembly = "two-node-spec.toml"
[parameters]
"loading.dT_max" = { values = [60.0, 125.0] }
""", [("two-node-spec.toml", TWO_NODE)])
    assert "share of the grid&#39;s cases that ratchet" in page or \
        "share of the grid's cases that ratchet" in page
    assert 'id="p-ratchet">0.5000<' in page and "95 % interval" not in page


def test_a_scan_librarys_downloads_name_the_files_as_uploaded(client, tmp_path):
    rng = np.random.default_rng(2)
    scans = []
    for i in range(2):
        buf = io.BytesIO()
        np.save(buf, rng.normal(size=(20, 20)))
        scans.append((f"scan{i}.npy", buf.getvalue()))
    jid, page = run_study(client, """
[study]
kind = "files"
files = ["scan*.npy"]
unit = "um"
pixel_size = 1.0
mu = 0.1
stages = ["derive"]
""", scans)
    got = client.get(f"/jobs/{jid}/files/cases.csv")
    assert got.status_code == 200
    rows = list(csv.DictReader(io.StringIO(got.text)))
    assert [r["file"] for r in rows] == ["scan0.npy", "scan1.npy"]
    assert all(r["status"] == "ok" and float(r["anisotropy"]) >= 0 for r in rows)
    import pyarrow.parquet as pq
    pq_bytes = client.get(f"/jobs/{jid}/files/cases.parquet").content
    (tmp_path / "c.parquet").write_bytes(pq_bytes)
    assert pq.read_table(tmp_path / "c.parquet").column("file").to_pylist() == \
        ["scan0.npy", "scan1.npy"]
