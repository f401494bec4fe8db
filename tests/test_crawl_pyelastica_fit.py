"""The post-processing of benchmarks/crawl_pyelastica.py on a synthetic run whose answers are
known: a body drawn from a Fourier gait (tests/crawl_reference.py's shape) carried at a
known velocity.  PyElastica itself is not needed (nor installed) here."""
from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from crawl_reference import body_shape

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import crawl_pyelastica as cp

L, T = cp.PARAMETERS["length_m"], cp.PARAMETERS["period_s"]
TERMS = np.array([[1.0, 1.0, 6.5, 1.2], [2.0, 3.0, 0.3, -0.2], [0.0, 1.0, 0.4, 0.0]])
SPEED = 0.2                  # body lengths per period, along +X


def synthetic_run(periods=4, per_period=40, elements=80, heading=0.0):
    """The gait carried at SPEED along ``heading`` (its body frame turned by it)."""
    t = np.arange(periods * per_period + 1) * T / per_period
    turn = np.array([[np.cos(heading), -np.sin(heading)], [np.sin(heading), np.cos(heading)]])
    shapes = [body_shape(TERMS, ti / T, elements + 1)[2] @ turn.T for ti in t]
    com = np.outer(SPEED * L * t / T, turn[:, 0])
    pos = np.array([(c + L * X).T for c, X in zip(com, shapes, strict=True)])  # (S, 2, n + 1)
    return {"t": t, "positions": pos, "com": com,
            "rest_lengths": np.full(elements, L / elements)}


@pytest.mark.parametrize("heading", [0.0, 2.5, -3.0])
def test_speed_per_period_on_the_heading(heading):
    run = synthetic_run(heading=heading)
    per = cp.speeds_per_period(run["t"], run["positions"], run["com"], T, L)
    assert len(per) == 4
    np.testing.assert_allclose(per, SPEED, rtol=1e-3, err_msg="a body carried at 0.2 L / T")


def test_fit_recovers_the_gait():
    fit = cp.fit_gait(synthetic_run(), 2, 3, 3)
    assert fit["window_periods"] == [2, 4]
    assert fit["relative_rms_error"] < 2e-3                 # the chord curvature's h^2
    got = {(t["m"], t["n"]): (t["cos"], t["sin"]) for t in fit["terms"]}
    for m, n, c, s in TERMS:
        assert got[(m, n)] == pytest.approx((c, s), abs=2e-2), f"term m={m}, n={n}"
    others = [abs(c) + abs(s) for (m, n), (c, s) in got.items()
              if not any(m == q[0] and n == q[1] for q in TERMS)]
    assert max(others) < 2e-2


def test_gait_file_reads_back(tmp_path):
    fit = cp.fit_gait(synthetic_run(), 2, 2, 3)
    path = tmp_path / "sub" / "gait.toml"
    cp.write_atomic(path, cp.gait_toml(fit))
    g = tomllib.loads(path.read_text())["gait"]
    assert g["kind"] == "fourier" and g["length"] == L and g["period"] == T
    assert [(t["m"], t["n"], t["cos"], t["sin"]) for t in g["terms"]] == \
        [(t["m"], t["n"], t["cos"], t["sin"]) for t in fit["terms"]]
    assert [p.name for p in path.parent.iterdir()] == ["gait.toml"]   # no temporary left
