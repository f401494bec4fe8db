"""The web page as a new user met it (issue 25, item 6), without a server: the progress of
a job never goes back and its time left does not jump (a real Surface job with an elastic
contact at three pressures, and a 144 s job on a clock of our own), the figures of a
contact (a log axis for small contact fractions, out of contact not white, the axes over
the map, the colour bar of block means said to be one), one number format."""
from __future__ import annotations

import json
import math
import time
from itertools import pairwise
from types import SimpleNamespace

import numpy as np
import pytest

from asperity.web import job_progress as worker
from asperity.web.figures_contact import (
    OUT_OF_CONTACT,
    PRESSURE_COLOURS,
    MapKeeper,
    axes_figure,
    contact_map,
)
from asperity.web.store import clock
from asperity.web.units import choose, fixed, show


class Clock:
    """time.time and time.monotonic of the worker module, moved by hand."""

    def __init__(self):
        self.t = 1000.0

    def time(self):
        return self.t

    def monotonic(self):
        return self.t


@pytest.fixture
def recorded(monkeypatch, tmp_path):
    """(a JobProgress on our clock, the clock, every progress.json it writes)."""
    fake, seen = Clock(), []
    monkeypatch.setattr(worker, "time", fake)
    real = worker.write_text_atomic

    def write(path, text):
        seen.append(json.loads(text))
        real(path, text)
    monkeypatch.setattr(worker, "write_text_atomic", write)
    return worker.JobProgress(tmp_path / "progress.json"), fake, seen


def test_spans_map_each_piece_of_work_into_its_share_and_never_back(recorded):
    bar, now, seen = recorded
    with worker.phase(bar, 0.0, 0.5, "contact"):
        bar.part(0, 2)
        for f in (0.5, 1.0):               # a solve counting its own work from 0 to 1
            now.t += 1
            bar(f)
        bar.part(1, 2)
        now.t += 1
        bar(0.5)
    assert [round(s["fraction"], 6) for s in seen] == [0.0, 0.125, 0.25, 0.375]
    with worker.phase(bar, 0.5, 1.0):
        now.t += 1
        bar(1.0)                           # a last piece: 99 % until the job is done
        now.t += 1
        bar(0.02)                          # a piece without its own share: no step back
    assert [s["fraction"] for s in seen[-2:]] == [0.99, 0.99]
    assert all(a["fraction"] <= b["fraction"] for a, b in pairwise(seen))


def test_a_144_s_job_never_steps_back_and_its_time_left_does_not_jump(recorded):
    """What was seen: 3 % after 100 %, and the time left growing from 7 to 13.6 min for a
    job of 144 s (each contact solve and each derivation counted 0 to 1 on the whole
    bar).  Here three solves of 20 s (half of the bar) and three derivations of 28 s,
    reporting every 0.5 s, as the Surface job with an elastic family does."""
    bar, now, seen = recorded
    with worker.phase(bar, 0.0, 0.5):
        for k in range(3):
            bar.part(k, 3)
            for i in range(1, 41):
                now.t += 0.5
                bar(i / 40)
    with worker.phase(bar, 0.5, 0.95):
        for k in range(3):
            bar.part(k, 3)
            for i in range(1, 57):
                now.t += 0.5
                bar(i / 56)
    fr = [s["fraction"] for s in seen]
    assert all(a <= b for a, b in pairwise(fr)) and max(fr) < 1.0
    left = [(s["updated"], s["left_s"]) for s in seen if s["left_s"] is not None]
    assert left and left[0][0] - 1000.0 <= 3.0
    for (t0, a), (t1, b) in pairwise(left):
        assert b <= a + 0.25 * (t1 - t0) + 1e-9, (t0, a, b)      # no jump upwards
    truth = [(t, 144.0 - (t - 1000.0)) for t, _ in left]
    late = [(t, v) for (t, v), (_, w) in zip(left, truth) if w < 120]
    assert all(abs(v - w) <= 0.35 * 144.0 for (_, v), (_, w) in zip(late, truth[-len(late):]))


def test_the_elastic_surface_job_fills_the_bar_in_order(recorded, tmp_path, monkeypatch):
    """The real task: a wedge pressed at three pressures, then derived at each; every
    piece reports 0 to 1 of its own work (the solver, derive): on the bar they follow."""
    from asperity.web.tasks_contact import derive_task
    _, now, seen = recorded
    monkeypatch.setattr(worker, "PROGRESS_EVERY", 0.0)
    calls = []

    class Spy(worker.JobProgress):
        def __call__(self, fraction, label=None):
            calls.append(fraction)
            now.t += 0.01
            super().__call__(fraction, label)
    ctx = {"job_dir": tmp_path, "uploads": tmp_path, "jobs": tmp_path, "names": {}}
    params = {"source": {"kind": "wedge", "alpha_deg": 30.0, "beta_deg": 10.0,
                         "mu_alpha": 0.1, "mu_beta": 0.2}, "directions": 72,
              "elastic": {"E_star": 1e9, "pressures": [1e6, 1e7, 5e7], "boundary": None,
                          "hardness": None}}
    with Spy(tmp_path / "progress.json") as bar:
        out = derive_task(params, ctx, bar)
    assert out["family"]["pressures_Pa"] == [1e6, 1e7, 5e7]
    assert any(b < a for a, b in pairwise(calls))      # the pieces restart at 0 ...
    fr = [s["fraction"] for s in seen]
    assert all(a <= b for a, b in pairwise(fr)), fr        # ... the bar does not
    assert fr[-1] >= 0.9 and max(fr) < 1.0
    labels = [s["label"] for s in seen]
    assert labels.index("elastic contact solved at pressure 3 of 3") < \
        labels.index("sliding directions") < \
        labels.index("sliding directions at pressure 3 of 3")


def test_the_page_counts_the_workers_estimate_down():
    rec = {"status": "running", "started_at": 1000.0}
    told = {"fraction": 0.4, "left_s": 60.0, "updated": 1030.0}
    assert clock(rec, told, now=1030.0)["left_s"] == 60.0
    assert clock(rec, told, now=1050.0)["left_s"] == pytest.approx(40.0)
    assert clock(rec, told, now=1095.0)["left_s"] is None           # spent: no guess
    assert clock(rec, {**told, "left_s": None}, now=1040.0)["left_s"] is None
    old = {"fraction": 0.25}                                          # an older worker's
    assert clock(rec, old, now=1040.0)["left_s"] == pytest.approx(120.0)


def test_small_contact_fractions_go_on_a_log_axis():
    rows = [{"pressure_Pa": p, "p_over_E_star": p / 1e11, "area_fraction": a,
             "mu_a_plus": 0.1, "mu_a_minus": 0.12} for p, a in ((1e6, 1e-4), (1e7, 1e-3),
                                                              (5e7, 2e-2))]
    small = axes_figure(rows, 1e11)["layout"]["yaxis2"]
    assert small["type"] == "log" and "range" not in small
    big = axes_figure([{**r, "area_fraction": 0.3 + 0.2 * k} for k, r in enumerate(rows)],
                      1e11)["layout"]["yaxis2"]
    assert big.get("type") != "log" and big["range"] == [0, 1.05]
    assert axes_figure(rows, 1e11)["layout"]["xaxis"]["title"]["text"] == \
        "nominal pressure p (MPa)"                       # 1 to 50 MPa, not 0.001 GPa


def solved(p: np.ndarray, pressure: float = 1e7, pixel=(0.5e-6, 0.5e-6)):
    return SimpleNamespace(pressure=p, pixel_size=pixel, pressure_asked=pressure)


def test_the_contact_map_spans_the_map_and_out_of_contact_is_not_white():
    rng = np.random.default_rng(2)
    p = np.where(rng.random((128, 64)) < 0.7, 0.0, rng.random((128, 64)) * 3e8)
    keep = MapKeeper(1)
    keep(solved(p))
    fig = contact_map(keep.maps, 1e11)
    heat = fig["data"][0]
    assert heat["colorscale"] == PRESSURE_COLOURS and heat["zmin"] == 0.0
    zero = PRESSURE_COLOURS[0][1]
    assert zero == OUT_OF_CONTACT and zero.lower() not in ("#fff", "#ffffff", "white")
    assert fig["layout"]["plot_bgcolor"] != zero
    assert PRESSURE_COLOURS[1][0] <= 1e-3                 # only p = 0 is drawn so
    lay = fig["layout"]
    assert lay["xaxis"]["range"] == [0.0, pytest.approx(64.0)]    # 128 x 0.5 um
    assert lay["yaxis"]["range"] == [0.0, pytest.approx(32.0)]
    assert lay["xaxis"]["constrain"] == lay["yaxis"]["constrain"] == "domain"
    assert heat["colorbar"]["title"]["text"] == "pressure (MPa)"   # every pixel shown


def test_a_map_of_block_means_says_so_and_gives_the_pixel_maximum():
    rng = np.random.default_rng(3)
    p = rng.random((600, 300)) * 1e8
    p[100, 100] = 8.68e8                                  # one pixel far above its block
    keep = MapKeeper(1)
    keep(solved(p, 5e7))
    assert keep.maps[0]["map"].shape == (200, 100) and keep.maps[0]["top"] == 8.68e8
    bar = contact_map(keep.maps, 1e11)["data"][0]["colorbar"]["title"]["text"]
    assert bar.startswith("block means (MPa)") and "pixel max 868 MPa" in bar
    top = float(np.nanmax(keep.maps[0]["map"]))
    assert top < 0.5 * 8.68e8                             # what the colour bar tops at


def test_one_number_format():
    assert show(5e7, choose([5e7, 9.5e10], "Pa", smallest=True)) == "50 MPa"
    assert show(5e7, choose([5e7, 9.5e10], "Pa")) == "0.05 GPa"    # the old choice
    assert [fixed(x) for x in (0.2506408, 8.011e-05, 1.0, 0.0)] == \
        ["0.2506", "0.00008011", "1.000", "0"]
    assert all("e" not in fixed(10.0 ** -k) for k in range(1, 10))
    assert math.isclose(float(fixed(3.16228e-4)), 3.162e-4)


def test_the_page_bar_waits_for_done_to_show_100_percent(tmp_path):
    """The page as the server draws it at first: 99 % at most while running."""
    bar = worker.JobProgress(tmp_path / "progress.json")
    bar(1.0, "last piece")
    time.sleep(0.01)
    bar.write(bar.top, "last piece")
    assert json.loads((tmp_path / "progress.json").read_text())["fraction"] == 0.99
