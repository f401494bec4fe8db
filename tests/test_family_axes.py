"""Family summaries list their members' axis coefficients along one common axis (issue 19).

Each member of a law family finds its own principal direction t_a, an axis in [0, 180) deg;
the shipped ridge scan (ridges across x) at 1, 3, 10, 30 MPa on E* = 1 GPa has its t_a at
177.9, 179.1, 179.9 and 0.5 deg: the last points the other way, and read member by member
its mu_a+ and mu_a- are exchanged.  Side by side (derive's family summary, fit's family
summary, a study's load-dependence table) every member is read along the reference
direction, the axial mean of the t_a: checked here against each member's per-direction
friction T(psi) at that direction and its opposite (an independent reading), against a
reference found here by brute force, for continuity over the pressures, and with the map
turned half a turn (mu_a+ and mu_a- exchanged)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.friction.family import derive_family, family_json, family_text, summary_rows
from asperity.laws.family import GaugeFamily
from asperity.laws.family_report import family_summary, format_family
from asperity.laws.fitting import fit_derivation
from asperity.study.run import run_study_file
from asperity.surface.contact_facets import ElasticContact, elastic_facets
from asperity.surface.readers import read_surface

ROOT = Path(__file__).resolve().parents[1]
RIDGES = ROOT / "surfaces" / "scan-ridges.txt"
PRESSURES = (1e6, 3e6, 1e7, 3e7)
ELASTIC = ElasticContact(1e9, PRESSURES)
AX = {"mu_a_plus": 0.0, "mu_a_minus": 180.0, "mu_b_plus": 90.0, "mu_b_minus": 270.0}


def family(z):
    hm = read_surface(RIDGES)
    hm = type(hm)(z, hm.dx, hm.dy, "ridges")
    return derive_family(list(elastic_facets(hm, ELASTIC, mu=0.15)), ELASTIC)


@pytest.fixture(scope="module")
def ridges():
    z = read_surface(RIDGES).heights
    return family(z), family(z[::-1, ::-1].copy())


def axial_mean_by_search(degrees) -> float:
    """The axis phi in [0, 180) nearest to all the axes: least sum of sin^2(t_i - phi),
    found on a 0.001 deg grid (not the doubled-angle formula of the code)."""
    phi = np.arange(0.0, 180.0, 0.001)
    cost = sum(np.sin(np.radians(t - phi)) ** 2 for t in degrees)
    return float(phi[np.argmin(cost)])


def T_at(d, deg: float) -> float:
    """A member's tangential friction at ``deg`` read off its per-direction T(psi)."""
    psi = np.degrees(d.reservoir.psi)
    T = d.reservoir.tangential
    return float(np.interp(deg % 360.0, np.r_[psi, psi[0] + 360.0], np.r_[T, T[0]]))


def straddles(degrees) -> bool:
    return any(t > 90.0 for t in degrees) and any(t < 90.0 for t in degrees)


def test_the_ridge_family_straddles_0_180_and_reads_along_the_common_axis(ridges):
    fam = ridges[0]
    own = [d.principal_direction_deg for d in fam.members]
    assert straddles(own), f"the ridge family's t_a no longer straddle 0/180 deg: {own}"
    rows, ref = summary_rows(fam)
    assert ref == pytest.approx(axial_mean_by_search(own), abs=2e-3)
    for r, d in zip(rows, fam.members):
        assert r["principal_direction_deg"] == d.principal_direction_deg   # its own, kept
        for k, off in AX.items():     # mu_a: ~0.02 apart, mu_b: up to 0.005 apart
            assert r[k] == pytest.approx(T_at(d, ref + off), abs=5e-4 if "_a_" in k else 1e-3)
    mu_p = [r["mu_a_plus"] for r in rows]
    mu_m = [r["mu_a_minus"] for r in rows]
    assert all(p - m > 0.015 for p, m in zip(mu_p, mu_m))       # one sign at every load
    assert max(abs(np.diff(mu_p))) < 0.005 and max(abs(np.diff(mu_m))) < 0.005
    assert [r["axes_reversed"] for r in rows] == [
        abs((t - ref + 180.0) % 360.0 - 180.0) > 90.0 for t in own]
    # the members' full derivations are left as derived: the last one's own mu_a+ is the
    # smaller, along its own t_a at 0.5 deg
    last = family_json(fam)["members"][-1]
    assert last["mu_a_plus"] == pytest.approx(T_at(fam.members[-1], own[-1]), abs=5e-4)
    assert last["mu_a_plus"] < last["mu_a_minus"]


def test_derive_family_json_and_text_say_the_reference(ridges):
    fam = ridges[0]
    obj = family_json(fam)
    rows, ref = summary_rows(fam)
    assert obj["reference_direction_deg"] == ref and obj["summary"] == rows
    text = family_text(fam)
    assert f"reference direction {ref:.2f} deg" in text
    turned = [line for line in text.splitlines() if line.rstrip().endswith("(turned)")]
    assert len(turned) == sum(r["axes_reversed"] for r in rows) >= 1
    assert f"{rows[-1]['mu_a_plus']:.6f}" in turned[-1]


def test_a_half_turned_map_exchanges_mu_plus_and_minus(ridges):
    a, b = (summary_rows(f) for f in ridges)
    assert b[1] == pytest.approx(a[1], abs=1e-6)             # the same axes
    for ra, rb in zip(a[0], b[0]):
        assert rb["principal_direction_deg"] == pytest.approx(ra["principal_direction_deg"],
                                                              abs=1e-6)
        for k, opp in (("mu_a_plus", "mu_a_minus"), ("mu_b_plus", "mu_b_minus")):
            assert rb[k] == pytest.approx(ra[opp], rel=1e-6)
            assert rb[opp] == pytest.approx(ra[k], rel=1e-6)
        assert abs(ra["mu_a_plus"] - ra["mu_a_minus"]) > 0.015    # not trivially equal


def test_fit_family_reads_every_law_along_the_common_axis(ridges):
    fam = ridges[0]
    gf = GaugeFamily(fam.pressures, tuple(fit_derivation(d, "star") for d in fam.members))
    own = [gl.principal_direction_deg for gl in gf.members]
    assert straddles(own), own
    s = family_summary(gf)
    ref = s["family"]["reference_direction_deg"]
    assert ref == pytest.approx(axial_mean_by_search(own), abs=2e-3)
    for m, gl in zip(s["members"], gf.members):
        assert m["principal_direction_deg"] == gl.principal_direction_deg
        t = gl.force(np.radians(ref + np.array(list(AX.values())))).tangential
        for k, v in zip(AX, t):       # the law's own friction at the common axis
            assert m["axes"][k] == pytest.approx(v, abs=5e-4 if "_a_" in k else 1.5e-3), k
    mu = [(m["axes"]["mu_a_plus"], m["axes"]["mu_a_minus"]) for m in s["members"]]
    assert all(p - q > 0.015 for p, q in mu)
    text = format_family(gf)
    assert f"reference direction {ref:.2f} deg" in text and "(turned)" in text


LIBRARY = """
[study]
kind = "files"
files = ["*.npy"]
unit = "m"
pixel_size = 1.0e-6
mu = 0.15
stages = ["derive"]
directions = 72

[contact]
E_star = 1.0e9

[parameters]
"contact.pressure" = { values = [1.0e6, 3.0e6, 1.0e7, 3.0e7] }
"""


def test_study_load_dependence_reads_each_file_along_its_common_axis(tmp_path, capsys):
    z = read_surface(RIDGES).heights
    np.save(tmp_path / "a.npy", z)
    np.save(tmp_path / "b.npy", z[::-1, ::-1].copy())     # the same scan half-turned
    np.save(tmp_path / "c.npy", z.T.copy())               # ridges along x: t_a near 90 deg
    (tmp_path / "s.toml").write_text(LIBRARY)
    s = run_study_file(tmp_path / "s.toml", tmp_path / "out", workers=0, plot=True)
    rows = s["load_dependence"]
    by = {n: [r for r in rows if Path(r["file"]).name == n] for n in ("a.npy", "b.npy",
                                                                      "c.npy")}
    assert [r["pressure_Pa"] for r in by["a.npy"]] == pytest.approx(PRESSURES, rel=1e-9)
    own = [r["principal_direction_deg"] for r in by["a.npy"]]
    assert straddles(own), own
    ref = axial_mean_by_search(own)
    for r, p in zip(by["a.npy"], PRESSURES):
        assert r["reference_direction_deg"] == pytest.approx(ref, abs=2e-3)
        one = run_json(capsys, "derive", r["file"], "--unit", "m", "--pixel-size", "1e-6",
                       "--mu", "0.15", "--elastic", "1e9", "--pressure",
                       repr(p))
        T = {round(d["psi_deg"], 6) % 360.0: d["tangential"] for d in one["directions"]}
        psi = np.array(sorted(T))
        Tv = np.array([T[p] for p in psi])
        for k, off in (("mu_a_plus", 0.0), ("mu_a_minus", 180.0)):
            want = np.interp((ref + off) % 360.0, np.r_[psi, psi[0] + 360.0], np.r_[Tv, Tv[0]])
            assert r[k] == pytest.approx(want, abs=5e-4), (r["pressure_Pa"], k)
    for ra, rb in zip(by["a.npy"], by["b.npy"]):
        assert rb["mu_a_plus"] == pytest.approx(ra["mu_a_minus"], rel=1e-6)
        assert rb["mu_a_minus"] == pytest.approx(ra["mu_a_plus"], rel=1e-6)
        assert ra["mu_a_plus"] - ra["mu_a_minus"] > 0.015
    own_c = [r["principal_direction_deg"] for r in by["c.npy"]]    # each file its own axis
    assert all(45.0 < t < 135.0 for t in own_c), own_c
    for r in by["c.npy"]:
        assert r["reference_direction_deg"] == pytest.approx(axial_mean_by_search(own_c),
                                                             abs=2e-3)
    code, out, _ = run(capsys, "study", str(tmp_path / "out"))
    assert code == 0 and "axial mean of that file's t_a" in out and "(turned)" in out
    assert (tmp_path / "out" / "load.png").stat().st_size > 1000
    assert math.isfinite(rows[0]["p_over_E_star"])
