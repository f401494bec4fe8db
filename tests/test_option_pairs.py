"""Pairwise combinations of the new commands' options (issue 25, item 5, pattern d: options
never combined -- a force with a texture angle, a loose tolerance with a hardness cap).

For each command a covering array (tests/pairwise.py: every pair of levels of any two
options in some row, a few rows instead of the product) runs through the real parser
in-process, and each row is checked against an invariant or a reference, never only "it
runs": the contact's force balance and cap, E* from the materials, the JSON against the
Python API (load_elastic, derive, derive_family, fit_derivation, slide_body,
GaugeFamily.at, solve_contact on a window's crop), the body's motion turned into the law's
frame, the written files against the API's.  Small maps (32 x 24 pixels), coarse steps."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run
from lays import lay
from pairwise import covering_array, ids, pairs_of

import asperity as A
from asperity.dynamics.body_api import make_body
from asperity.dynamics.moreau import Force
from asperity.laws.export import abaqus_block, polar_table
from asperity.laws.summary import summary

E, P = 1e9, 1e7
PIXELS = {"square": (1e-6, 1e-6), "oblong": (1e-6, 0.6e-6)}
MATERIALS = {"elastic": (["--elastic", E], E),
             "nu=0.5": (["--materials", 7.5e8, 0.5], 7.5e8 / 0.75),
             "two bodies": (["--materials", 2e9, 0.3, 3e9, 0.25],
                            1 / ((1 - 0.09) / 2e9 + (1 - 0.0625) / 3e9))}


def cli(capsys, *argv):
    code, out, err = run(capsys, *argv)
    assert code == 0, err
    return json.loads(out)


def finite(obj) -> bool:
    """No NaN or infinity anywhere in a JSON object (json.dumps would write them)."""
    try:
        json.dumps(obj, allow_nan=False)
        return True
    except ValueError:
        return False


@pytest.fixture(scope="module")
def scans(tmp_path_factory):
    """A 32 x 24 asymmetric map with two undefined pixels, in m and in um, per pixel shape:
    {(pixels, unit): (path, heights in m, (dx, dy) in m)}."""
    d = tmp_path_factory.mktemp("pairs")
    out = {}
    for name, (dx, dy) in PIXELS.items():
        z = lay(32, 24, dx, dy, angle_deg=120.0, seed=4, height=1e-6)
        z[3, 17] = z[25, 2] = np.nan
        for unit, k in (("m", 1.0), ("um", 1e6)):
            path = d / f"{name}-{unit}.npy"
            np.save(path, z * k)
            out[name, unit] = (path, z, (dx, dy))
    return out


def flags(unit, dx, dy, k=1.0):
    return ["--unit", unit, "--pixel-size", dx * k, dy * k]


# ---- the generator itself -----------------------------------------------------------------

def test_the_covering_array_covers_every_allowed_pair_in_few_rows():
    factors = {"a": [0, 1, 2], "b": ["x", "y"], "c": [True, False], "d": [1, 2, 3, 4],
               "e": ["p", "q"]}

    def allowed(r):
        return not (r["a"] == 2 and r["b"] == "y")
    rows = covering_array(factors, allowed)
    assert rows == covering_array(factors, allowed)              # the same on every run
    assert all(allowed(r) for r in rows)
    lv = {k: list(v) for k, v in factors.items()}
    got = set().union(*(pairs_of(tuple(lv[k].index(r[k]) for k in factors)) for r in rows))
    import itertools
    want = set()
    for full in itertools.product(*lv.values()):
        r = dict(zip(factors, full))
        if allowed(r):
            want |= pairs_of(tuple(lv[k].index(r[k]) for k in factors))
    assert got == want and ((0, 2), (1, 1)) not in want          # (a=2, b=y) never required
    assert 12 <= len(rows) <= 16 < 3 * 2 * 2 * 4 * 2             # 4 x 3 pairs at least


# ---- asperity contact ------------------------------------------------------------------------

CONTACT = covering_array({
    "boundary": ["periodic", "free"], "hardness": [None, "cap"], "tol": [1e-8, 1e-4],
    "modulus": list(MATERIALS), "pixels": list(PIXELS), "detrend": ["slope", "none"],
    "unit": ["m", "um"], "save": [False, True]})


@pytest.mark.parametrize("row", CONTACT, ids=ids(CONTACT))
def test_contact_option_pairs(row, scans, capsys, tmp_path):
    path, z, (dx, dy) = scans[row["pixels"], row["unit"]]
    k = 1e6 if row["unit"] == "um" else 1.0
    defined = np.isfinite(z).sum()
    H = 6 * P * z.size / defined if row["hardness"] else None
    mod, E_star = MATERIALS[row["modulus"]]
    argv = ["contact", path, *flags(row["unit"], dx, dy, k), "--detrend", row["detrend"],
            *mod, "--pressure", P, "--boundary", row["boundary"], "--tol", row["tol"], "--json"]
    if H:
        argv += ["--hardness", H]
    saved = tmp_path / "p.npy"
    if row["save"]:
        argv += ["--save-pressure", saved]
    d = cli(capsys, *argv)
    assert finite(d) and d["converged"] and d["residual"] < row["tol"]
    assert d["E_star_Pa"] == pytest.approx(E_star, rel=1e-14)
    assert d["pressure_Pa"] == pytest.approx(P, rel=1e-9)                # force balance
    assert d["texture"]["pixel_size_m"] == pytest.approx([dx, dy], rel=1e-12)
    assert d["full_contact"] == (d["area_fraction"] == 1.0)
    if H:
        assert d["hardness_Pa"] == H and d["max_pressure_Pa"] <= H * (1 + 1e-12)
        assert d["plastic_fraction"] > 0                                 # the cap bites
    else:
        assert d["hardness_Pa"] is None and d["plastic_fraction"] == 0
    ec = A.ElasticContact(E_star, P, boundary=row["boundary"], hardness=H, tol=row["tol"])
    ref = A.load_elastic(path, ec, unit=row["unit"], pixel_size=[dx * k, dy * k],
                         detrend=row["detrend"])[0].elastic
    assert d["area_fraction"] == ref["area_fraction"] and d["iterations"] == ref["iterations"]
    for key in ("max_pressure_Pa", "mean_gap_m", "plastic_fraction"):
        assert d[key] == pytest.approx(ref[key], rel=1e-12, abs=1e-300), key
    if row["save"]:
        p = np.load(saved)
        assert p.shape == z.shape and np.array_equal(np.isnan(p), np.isnan(z))
        assert np.nansum(p) * dx * dy == pytest.approx(P * z.size * dx * dy, rel=1e-9)
        assert np.nanmin(p) >= 0 and (H is None or np.nanmax(p) <= H * (1 + 1e-12))


# ---- asperity slide --body -----------------------------------------------------------------

BODY = covering_array({
    "body": ["disc", "ring", "rectangle"], "law": ["coulomb", "ellipse"], "omega0": [0.0, 15.0],
    "texture": [0.0, 130.0], "load": ["none", "constant", "sine"],
    "profile": ["uniform", "linear"], "points": [16, 48]},
    allowed=lambda r: not (r["body"] == "ring" and r["profile"] == "linear"))
BODY_DT, U0, ANGLE = 1e-3, 0.5, 40.0


def body_case(row):
    """(command-line flags, law, make_body keywords, Force or None, t_end)."""
    argv, kw = ["--body", row["body"], "--contact-points", row["points"]], {}
    if row["body"] == "rectangle":
        argv += ["--size", 0.06, 0.03]
        kw["size"] = (0.06, 0.03)
    else:
        argv += ["--radius", 0.05]
        kw["radius"] = 0.05
    if row["profile"] == "linear":
        argv += ["--pressure-profile", "linear", "--centre-of-pressure", 0.004, -0.002]
        kw.update(pressure_profile="linear", centre_of_pressure=(0.004, -0.002))
    if row["law"] == "coulomb":
        argv += ["--law", "coulomb", "--mu1", 0.3]
        law = A.coulomb_law(0.3)
    else:
        argv += ["--law", "ellipse", "--mu1", 0.3, "--mu2", 0.2]
        law = A.ellipse_law(0.3, 0.2)
    force, t_end = None, None
    if row["load"] == "constant":
        argv += ["--force", 4.0, -1.5, "--torque", 0.02, "--t-end", 0.3]
        force, t_end = Force(constant=(4.0, -1.5, 0.02)), 0.3
    elif row["load"] == "sine":
        argv += ["--force-amplitude", 5.0, 2.0, 0.03, "--waveform", "sine", "--period", 0.1,
                 "--t-end", 0.3]
        force, t_end = Force(amplitude=(5.0, 2.0, 0.03), period=0.1, waveform="sine"), 0.3
    return argv, law, kw, force, t_end


def rot(deg):
    a = math.radians(deg)
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


@pytest.mark.parametrize("row", BODY, ids=ids(BODY))
def test_slide_body_option_pairs(row, capsys):
    argv, law, kw, force, t_end = body_case(row)
    d = cli(capsys, "slide", *argv, "--u0", U0, "--angle", ANGLE, "--omega0", row["omega0"],
            "--texture-angle", row["texture"], "--dt", BODY_DT, "--json")
    body = make_body(row["body"], contact_points=row["points"], **kw)
    lib = A.slide_body(law, body, U0, ANGLE, row["omega0"], dt=BODY_DT, t_end=t_end,
                       force=force, texture_angle_deg=row["texture"])
    assert json.loads(json.dumps(lib.summary)) == d, "the JSON is not the Python API's"
    assert d["status"] == "ok" and finite(d)
    r = lib.result
    if force is None:                       # rests exactly, never gains energy
        assert d["rest"] is not None and np.all(r.u_final == 0.0)
        assert np.all(np.diff(r.energy) <= 1e-12 * r.energy[0])
    else:
        assert d["rest"] is None and d["load"] is not None
    # the same problem turned into the law's frame: footprint, launch and load turned by
    # minus the texture angle, the law unturned -> the trajectory turned
    fp, R = body.footprint, rot(-row["texture"])
    a = math.radians(ANGLE)
    v = R @ np.array([U0 * math.cos(a), U0 * math.sin(a)])
    turned = None if force is None else Force(
        constant=(*(R @ force.constant[:2]), force.constant[2]),
        amplitude=(*(R @ force.amplitude[:2]), force.amplitude[2]),
        period=force.period, waveform=force.waveform)
    b = A.simulate_body(fp.points @ R.T, fp.weights, law, mass=body.mass, inertia=body.inertia,
                        u0=(*v, row["omega0"]), dt=BODY_DT, t_end=r.t[-1] if force else None,
                        force=turned)
    assert b.ok and abs(b.steps - r.steps) <= 1      # a stop on the margin's other side
    scale = max(1e-3, float(np.abs(r.q[:, :2]).max()))
    slack = abs(b.steps - r.steps) * BODY_DT * float(np.abs(r.u[:, :2]).max())
    np.testing.assert_allclose(r.q_final[:2] @ R.T, b.q_final[:2], rtol=0,
                               atol=1e-9 * scale + slack)
    spin = abs(b.steps - r.steps) * BODY_DT * float(np.abs(r.u[:, 2]).max())
    assert r.q_final[2] == pytest.approx(b.q_final[2], abs=1e-9 + spin)


# ---- asperity law FAMILY --pressure ---------------------------------------------------------

@pytest.fixture(scope="module")
def families(tmp_path_factory):
    """A star and an ellipse family of three members whose t_a cross 0/180 deg: files."""
    from dataclasses import replace

    from asperity.surface.topography import HeightMap
    d = tmp_path_factory.mktemp("families")
    out = {}
    ps = (1e6, 1e7, 1e8)
    for kind in ("star", "truncated-ellipse"):
        laws = [A.fit_derivation(A.derive(HeightMap(lay(32, 24, 1e-6, 0.6e-6, angle_deg=a,
                                                        seed=1, height=h), 1e-6, 0.6e-6),
                                          n_directions=48), kind)
                for a, h in ((170.0, 2e-6), (178.0, 2.6e-6), (12.0, 3.4e-6))]
        src = laws[0].source
        fam = A.GaugeFamily(ps, tuple(replace(gl, source={**src, "elastic_contact": {
            "area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": E, "boundary": "free", "hardness_Pa": None,
            "iterations": 9, "residual": 1e-9, "converged": True}}) for gl, p in zip(laws, ps)))
        path = d / f"{kind}.json"
        A.write_gauge(path, fam)
        out[kind] = (path, A.read_gauge(path))
    return out


LAW = covering_array({"kind": ["star", "truncated-ellipse"],
                      "pressure": ["first", "between", "last"],
                      "psi": [None, 0.0, 135.0, 360.0], "export": [None, "csv", "abaqus"]})
PRESSURE = {"first": 1e6, "between": 3e7, "last": 1e8}


@pytest.mark.parametrize("row", LAW, ids=ids(LAW))
def test_law_pressure_option_pairs(row, families, capsys, tmp_path):
    path, fam = families[row["kind"]]
    p = PRESSURE[row["pressure"]]
    argv = ["law", path, "--pressure", p, "--json"]
    if row["psi"] is not None:
        argv += ["--psi", row["psi"]]
    out = tmp_path / ("t.csv" if row["export"] == "csv" else "t.inp")
    if row["export"]:
        argv += [f"--{row['export']}", out]
    d = cli(capsys, *argv)
    gl = fam.at(p)
    assert d["family_pressure"]["pressure_Pa"] == p
    assert d["family_pressure"]["interpolated"] == (row["pressure"] == "between")
    if row["psi"] is None:
        want = json.loads(json.dumps(summary(gl)))
        assert {k: d[k] for k in want} == want
    else:
        f = gl.force(np.array([math.radians(row["psi"])]))
        assert d["p"] == pytest.approx(list(f.p[0]), rel=1e-12, abs=1e-15)
        assert d["tangential"] == pytest.approx(float(f.tangential[0]), rel=1e-12)
    if row["export"] == "csv":
        assert out.read_text() == polar_table(gl, 360)
    elif row["export"] == "abaqus":
        assert out.read_text() == abaqus_block(gl)


# ---- asperity derive / fit --elastic ---------------------------------------------------------

ELASTIC = covering_array({
    "command": ["derive", "fit"], "boundary": ["periodic", "free"], "hardness": [None, "cap"],
    "pressures": [1, 2], "pixels": list(PIXELS), "law": ["star", "truncated-ellipse"],
    "mu": [None, 0.2]}, allowed=lambda r: r["command"] == "fit" or r["law"] == "star")
N_DIR = 24
PHI = np.linspace(0, 2 * math.pi, 97)


@pytest.mark.parametrize("row", ELASTIC, ids=ids(ELASTIC))
def test_derive_and_fit_elastic_option_pairs(row, scans, capsys, tmp_path):
    path, _, (dx, dy) = scans[row["pixels"], "m"]
    ps = (P,) if row["pressures"] == 1 else (P, 4 * P)
    H = 8 * ps[-1] if row["hardness"] else None
    argv = [row["command"], path, *flags("m", dx, dy), "--elastic", E, "--pressure", *ps,
            "--boundary", row["boundary"], "--directions", N_DIR, "--json"]
    if H:
        argv += ["--hardness", H]
    if row["mu"] is not None:
        argv += ["--mu", row["mu"]]
    gauge = tmp_path / "law.json"
    if row["command"] == "fit":
        argv += ["--law", "ellipse" if row["law"] == "truncated-ellipse" else "star",
                 "-o", gauge]
    d = cli(capsys, *argv)
    assert finite(d)
    ec = A.ElasticContact(E, ps if len(ps) > 1 else P, boundary=row["boundary"], hardness=H)
    surfaces = A.load_elastic(path, ec, unit="m", pixel_size=[dx, dy], mu=row["mu"])
    members = [A.derive(s, n_directions=N_DIR) for s in surfaces]
    for s, p in zip(surfaces, ps):
        c = s.elastic
        assert c["pressure_Pa"] == pytest.approx(p, rel=1e-9)            # force balance
        assert H is None or (c["max_pressure_Pa"] <= H * (1 + 1e-12) and c["hardness_Pa"] == H)
    if row["command"] == "derive":
        got = [d] if len(ps) == 1 else d["members"]
        assert len(got) == len(ps)
        for m, s, ref in zip(got, surfaces, members):
            assert m["elastic_contact"] == json.loads(json.dumps(s.elastic))
            p = np.array([x["p"] for x in m["directions"]])
            np.testing.assert_allclose(p, ref.reservoir.p, rtol=0, atol=1e-14)
        return
    back = A.read_gauge(gauge)
    laws = [A.fit_derivation(m, row["law"]) for m in members]
    if len(ps) == 1:
        assert not isinstance(back, A.GaugeFamily)
        np.testing.assert_allclose(back.force(PHI).p, laws[0].force(PHI).p, rtol=0, atol=1e-12)
        return
    assert isinstance(back, A.GaugeFamily) and back.pressures == ps
    for k, (mine, ref) in enumerate(zip(back.members, laws)):
        np.testing.assert_allclose(mine.force(PHI).p, ref.force(PHI).p, rtol=0, atol=1e-12)
        assert d["members"][k]["contact"]["hardness_Pa"] == H
    mid = math.sqrt(ps[0] * ps[1])                 # between members, as the file says
    assert back.at(mid).kind == row["law"]


# ---- asperity contact --window -----------------------------------------------------------------

WINDOWS = covering_array({
    "placement": ["grid", "random"], "windows": [1, 3], "size": [16, "short side"],
    "pixels": list(PIXELS), "boundary": ["free", "periodic"], "hardness": [None, "cap"]})


@pytest.mark.parametrize("row", WINDOWS, ids=ids(WINDOWS))
def test_contact_window_option_pairs(row, scans, capsys):
    path, z, (dx, dy) = scans[row["pixels"], "m"]
    nx, ny = z.shape
    w = 16 if row["size"] == 16 else min(nx, ny)
    H = 6 * P * w * w / (w * w - 2) if row["hardness"] else None    # above any window's mean
    argv = ["contact", path, *flags("m", dx, dy), "--detrend", "none", "--elastic", E,
            "--pressure", P, "--boundary", row["boundary"], "--window", w, "--windows",
            row["windows"], "--window-placement", row["placement"], "--json"]
    if H:
        argv += ["--hardness", H]
    d = cli(capsys, *argv)
    assert finite(d) and d["windows"]["used"] == row["windows"] == len(d["per_window"])
    figures = {k: [] for k in ("area_fraction", "max_pressure_Pa", "mean_gap_m")}
    for win in d["per_window"]:
        i0, j0 = win["origin_px"]
        assert 0 <= i0 <= nx - w and 0 <= j0 <= ny - w
        assert win["origin_m"] == pytest.approx([i0 * dx, j0 * dy], rel=1e-12)
        ref = A.solve_contact(z[i0:i0 + w, j0:j0 + w], (dx, dy), E, P,
                              boundary=row["boundary"], hardness=H)
        c = win["elastic_contact"]
        assert abs(c["area_fraction"] - ref.area_fraction) * w * w <= 1.0
        assert c["max_pressure_Pa"] == pytest.approx(ref.max_pressure, rel=1e-9)
        assert c["mean_gap_m"] == pytest.approx(ref.mean_gap, rel=1e-9)
        assert H is None or c["max_pressure_Pa"] <= H * (1 + 1e-12)
        for k, values in figures.items():
            values.append(c[k])
    for k, v in figures.items():
        assert d[k]["mean"] == pytest.approx(float(np.mean(v)), rel=1e-12)
        assert d[k]["min"] == min(v) and d[k]["max"] == max(v)


def test_every_pair_of_each_commands_options_is_run():
    """The arrays above hold every pair (a regression guard on the generator's use)."""
    for rows in (CONTACT, BODY, LAW, ELASTIC, WINDOWS):
        names = list(rows[0])
        seen = {(a, ra[a], b, ra[b]) for ra in rows for a in names for b in names if a < b}
        for a in names:
            for b in names:
                if a < b:
                    for va in {r[a] for r in rows}:
                        for vb in {r[b] for r in rows}:
                            ok = (a, va, b, vb) in seen
                            ring_linear = {va, vb} == {"ring", "linear"}
                            derive_ellipse = {va, vb} == {"derive", "truncated-ellipse"}
                            assert ok or ring_linear or derive_ellipse, (a, va, b, vb)
    assert len(BODY) < 20 and len(CONTACT) < 16
