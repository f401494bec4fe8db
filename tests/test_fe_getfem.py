"""The GetFEM runs of issue 27 (item 5): the law written as GWFL (``law --gwfl``) against
the law itself, a plan-view plate dragged in 24 directions against p(psi), the strip as a
2D plane-stress body against the slider chain (drift per cycle, elastic limit against the
shear-lag closed form, which end slips first), invariances that catch sign and unit bugs,
and the bad input.  The GetFEM tests skip, with the reason, when /usr/bin/python3 cannot
import getfem (apt-get install python3-getfem)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run

from asperity import derive, fit_derivation, write_gauge
from asperity.fe.checks import drag_check
from asperity.fe.getfem_runner import getfem_status
from asperity.fe.gwfl import gwfl_text, parse_gwfl
from asperity.laws.sets import TruncatedEllipse
from asperity.laws.walker_leine import associated
from asperity.microslip.closed_forms import strip_dT_c
from asperity.texture.wedges import WedgeTexture

_OK, _WHY = getfem_status()
needs_getfem = pytest.mark.skipif(not _OK, reason=f"GetFEM unavailable: {_WHY}")

#: a slender strip (h / l = 1/50, k_t h / G = 0.05): the chain's assumptions hold
SLENDER = {"h": 2e-3, "E": 1e11, "p": 5e6, "l": 0.1, "k_t": 1e12, "alpha_T": 1e-5, "n": 401,
           "nu": 0.3}


@pytest.fixture(scope="module")
def star():
    """The star law of surfaces/wedge-asymmetric.toml (alpha 30, beta 10, mu 0.1 / 0.2)."""
    return fit_derivation(derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360), "star")


def ellipse():
    """Antoni et al.'s figure 7 truncated ellipse (asymmetric along both axes), as a
    gauge law (a fitted ellipse's GaugeLaw with its law replaced)."""
    from dataclasses import replace
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=90)
    return replace(fit_derivation(d, "truncated-ellipse"),
                   law=associated(TruncatedEllipse(0.2, 0.08, 0.12, 0.15)))


def _eval(expr: str, t):
    return eval(expr, {"pos_part": lambda x: np.maximum(x, 0.0),
                       "Heaviside": lambda x: (x >= 0).astype(float), "t": t})


def _strip(tmp_path, name="strip", mu=(0.2, 0.1), dT=(0.0, 30.0), **kw):
    a = {**SLENDER, **kw}
    body = "\n".join(f"{k} = {v!r}" for k, v in a.items())
    path = tmp_path / f"{name}.toml"
    path.write_text(f'[assembly]\nmodel = "strip"\n{body}\n[friction]\nmu_plus = {mu[0]!r}\n'
                    f"mu_minus = {mu[1]!r}\n[loading]\ndT_min = {dT[0]!r}\n"
                    f"dT_max = {dT[1]!r}\n")
    return path


def _fe(capsys, path, *extra):
    code, out, err = run(capsys, "risk", path, "--fe", "getfem", *extra, "--json")
    assert code == 0, err
    return json.loads(out)


# ------------------------------------------------------------------ the law as GWFL text

@pytest.mark.parametrize("which", ["star", "ellipse"])
def test_gwfl_table_is_the_law_within_1e4_with_its_derivative(which, star):
    gl = star if which == "star" else ellipse()
    law = parse_gwfl(gwfl_text(gl, which))
    psi = np.linspace(-math.pi, math.pi, 7201)
    ref = np.asarray(gl.force(psi).p)
    for k, (name, f, df) in enumerate(law["functions"]):
        got = _eval(f, psi)
        assert np.abs(got - ref[:, k]).max() <= 1e-4, f"{name} is not the law within 1e-4"
        h = 1e-7
        mid = 0.5 * (psi[1:] + psi[:-1])
        fd = (_eval(f, mid + h) - _eval(f, mid - h)) / (2 * h)
        assert np.allclose(_eval(df, mid), fd, rtol=1e-5, atol=1e-6), f"{name}' is not f's slope"


def test_gwfl_strip_limits_are_the_law_along_x(star):
    macros = dict(parse_gwfl(gwfl_text(star, "star"))["macros"])
    p = star.force(np.array([0.0, math.pi])).p
    mup, mum = p[0, 0], -p[1, 0]
    assert mup != pytest.approx(mum, rel=1e-3), "the wedge must be asymmetric along x"
    # clamp(ttr, -mu- p, mu+ p) evaluated from the text: below, inside and above
    for ttr, want in ((-5.0, -mum), (0.01, 0.01), (5.0, mup)):
        tx = eval(macros["asp_tx"], {"pos_part": lambda x: max(x, 0.0),
                                     "asp_ttr": ttr, "asp_p": 1.0})
        assert tx == pytest.approx(-want, rel=1e-12), "asp_tx is minus the clamped trial"


def test_law_gwfl_command_writes_the_file_and_refuses_a_family(tmp_path, capsys, star):
    g = tmp_path / "star.json"
    write_gauge(g, star)
    out = tmp_path / "star.gwfl"
    code, _, err = run(capsys, "law", g, "--gwfl", out)
    assert code == 0, err
    text = out.read_text()
    assert "asp_s0" in text and "asp_du" in text and "Pa" in text
    assert parse_gwfl(text) == parse_gwfl(gwfl_text(star, "x"))
    missing = tmp_path / "nope" / "x.gwfl"
    code, _, err = run(capsys, "law", g, "--gwfl", missing)
    assert code == 1 and len(err.strip().splitlines()) == 1 and not missing.exists()


# --------------------------------------------------------------------- GetFEM runs

@needs_getfem
@pytest.mark.parametrize("which", ["star", "ellipse"])
def test_plate_dragged_in_24_directions_pulls_the_law(which, star, tmp_path, capsys):
    gl = star if which == "star" else ellipse()
    text = None
    if which == "star":                        # through the command line's file
        g, f = tmp_path / "s.json", tmp_path / "s.gwfl"
        write_gauge(g, gl)
        assert run(capsys, "law", g, "--gwfl", f)[0] == 0
        text = f.read_text()
    r = drag_check(gl, 24, gwfl_text=text)
    assert len(r["rows"]) == 24
    assert r["max_relative_error"] <= 5e-3, "pull force per unit normal load != p(psi)"
    for row in r["rows"]:                      # the plate slides as a whole, along the drag
        assert row["slip_spread"] < 1e-3
        assert np.allclose(row["fe"], row["friction_integral"], rtol=1e-6, atol=1e-9)
    # an asymmetric law: the pull along 0 and 180 deg differ
    assert abs(r["rows"][0]["fe"][0] + r["rows"][12]["fe"][0]) > 0.005


@needs_getfem
def test_slender_strip_drifts_as_the_chain(tmp_path, capsys):
    out = _fe(capsys, _strip(tmp_path))
    fe = out["fe"]
    assert h_over_l() <= 1 / 20
    assert out["drift_per_cycle_m"] < 0, "mu+ > mu-: the chain creeps towards -x"
    assert fe["drift_per_cycle_m"] == pytest.approx(out["drift_per_cycle_m"], rel=0.05)
    # the gap is the shear through the height: the corrected chain is within 1 %
    assert fe["drift_per_cycle_m"] == pytest.approx(
        fe["chain_shear_corrected"]["drift_per_cycle_m"], rel=0.01)
    assert fe["elements"] == fe["elements_along_l"] * fe["elements_through_h"]
    assert fe["elements_along_l"] == 200 and fe["elements_through_h"] >= 2
    assert fe["seconds"] > 0 and fe["increments"] > 0


def h_over_l():
    return SLENDER["h"] / SLENDER["l"]


@needs_getfem
def test_equal_coefficients_give_no_fe_drift(tmp_path, capsys):
    fe = _fe(capsys, _strip(tmp_path, mu=(0.15, 0.15)), "--fe-mesh", "80")["fe"]
    scale = SLENDER["alpha_T"] * SLENDER["l"] * 30.0
    assert abs(fe["drift_per_cycle_m"]) < 1e-9 * scale


@needs_getfem
def test_swapping_the_coefficients_flips_the_fe_drift(tmp_path, capsys):
    a = _fe(capsys, _strip(tmp_path, "a", mu=(0.2, 0.1)), "--fe-mesh", "80")["fe"]
    b = _fe(capsys, _strip(tmp_path, "b", mu=(0.1, 0.2)), "--fe-mesh", "80")["fe"]
    assert a["drift_per_cycle_m"] < 0 < b["drift_per_cycle_m"]
    assert b["drift_per_cycle_m"] == pytest.approx(-a["drift_per_cycle_m"], rel=1e-6, abs=0)


@needs_getfem
def test_fe_drift_scales_with_lengths_and_not_with_stresses(tmp_path, capsys):
    base = _fe(capsys, _strip(tmp_path, "a"), "--fe-mesh", "80")["fe"]["drift_per_cycle_m"]
    s, c = 10.0, 7.0           # lengths x s (bed stiffness / s), stresses x c
    scaled = _strip(tmp_path, "b", h=SLENDER["h"] * s, l=SLENDER["l"] * s,
                    k_t=SLENDER["k_t"] * c / s, E=SLENDER["E"] * c, p=SLENDER["p"] * c)
    d = _fe(capsys, scaled, "--fe-mesh", "80")["fe"]["drift_per_cycle_m"]
    assert d == pytest.approx(s * base, rel=1e-6, abs=0)


@needs_getfem
@pytest.mark.parametrize("alpha_T", [1e-5, -1e-5])
def test_fe_elastic_limit_is_the_shear_lag_closed_form(alpha_T, tmp_path, capsys):
    """SPEC.md 5: on heating the end moving towards -x (x = 0 if alpha_T > 0) slips first,
    at mu- p; the FE dT_c is the closed form with the bed in series with the height's
    shear (and within 3 % of it with k_t alone, this strip being slender)."""
    fe = _fe(capsys, _strip(tmp_path, alpha_T=alpha_T), "--fe-mesh", "200")["fe"]
    a = SLENDER
    kt_eff = fe["chain_shear_corrected"]["k_t_eff_Pa_per_m"]
    G = a["E"] / (2 * (1 + a["nu"]))
    assert kt_eff == pytest.approx(a["k_t"] / (1 + a["k_t"] * a["h"] / (3 * G)), rel=1e-12)
    closed = strip_dT_c(a["h"], a["E"], a["p"], a["l"], kt_eff, 0.2, 0.1, alpha_T)
    assert fe["elastic_limit_shear_corrected_K"] == pytest.approx(closed, rel=1e-12)
    assert fe["elastic_limit_K"] == pytest.approx(closed, rel=5e-3)
    assert fe["elastic_limit_K"] == pytest.approx(fe["elastic_limit_closed_form_K"], rel=0.03)
    assert fe["first_slip_towards"] == "-x"
    assert fe["first_slip_x_m"] == (0.0 if alpha_T > 0 else pytest.approx(a["l"]))


# -------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("argv, words", [
    (["--fe", "abaqus"], "--fe must be getfem"),
    (["--fe", "getfem", "--fe-mesh", "2"], "--fe-mesh"),
    (["--fe", "getfem", "--fe-mesh", "1e9"], "--fe-mesh"),
    (["--fe-mesh", "100"], "give --fe getfem"),
])
def test_bad_fe_flags_one_line(argv, words, tmp_path, capsys):
    plot = tmp_path / "r.png"
    code, _out, err = run(capsys, "risk", _strip(tmp_path), *argv, "--plot", plot)
    assert code == 1 and words in err and len(err.strip().splitlines()) == 1
    assert not plot.exists() and "Traceback" not in err


def test_fe_on_a_two_node_assembly_is_refused(tmp_path, capsys):
    from pathlib import Path
    two = Path(__file__).parents[1] / "surfaces" / "two-node-spec.toml"
    code, _, err = run(capsys, "risk", two, "--fe", "getfem")
    assert code == 1 and "strip" in err and len(err.strip().splitlines()) == 1


def test_fe_without_getfem_says_how_to_install(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("ASPERITY_GETFEM_PYTHON", str(tmp_path / "no-python"))
    plot = tmp_path / "r.png"
    code, _, err = run(capsys, "risk", _strip(tmp_path), "--fe", "getfem", "--plot", plot)
    assert code == 1 and "apt-get install python3-getfem" in err
    assert len(err.strip().splitlines()) == 1 and not plot.exists()


def test_gwfl_of_a_family_needs_a_pressure_and_takes_the_member_there(tmp_path, capsys):
    from law_families import four_members
    fam = four_members()
    g, out = tmp_path / "fam.json", tmp_path / "fam.gwfl"
    write_gauge(g, fam)
    code, _, err = run(capsys, "law", g, "--gwfl", out)
    assert code == 1 and "--pressure" in err and not out.exists()
    assert len(err.strip().splitlines()) == 1
    code, _, err = run(capsys, "law", g, "--pressure", fam.pressures[1], "--gwfl", out)
    assert code == 0, err
    member = fam.members[1]
    assert parse_gwfl(out.read_text()) == parse_gwfl(gwfl_text(member, "member"))


def test_gwfl_over_the_gauge_file_itself_is_refused(tmp_path, capsys, star):
    g = tmp_path / "star.json"
    write_gauge(g, star)
    before = g.read_text()
    code, _, err = run(capsys, "law", g, "--gwfl", g)
    assert code == 1 and len(err.strip().splitlines()) == 1 and g.read_text() == before


@needs_getfem
def test_the_getfem_child_dies_with_its_parent(tmp_path):
    """SIGKILL the asperity process mid-run: its GetFEM child (a /usr/bin/python3) goes too."""
    import os
    import signal
    import subprocess
    import sys
    import time
    from pathlib import Path

    from asperity.lifeline import children_of
    root = Path(__file__).resolve().parents[1]
    asm = _strip(tmp_path, dT=(0.0, 60.0), n=201)
    parent = subprocess.Popen([sys.executable, "-m", "asperity", "risk", str(asm), "--fe",
                               "getfem", "--fe-mesh", "2500", "-q"], cwd=root,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        child = None
        for _ in range(400):                               # up to 40 s to start GetFEM
            kids = [k for k in children_of(parent.pid) if _is_getfem(k)]
            if kids:
                child = kids[0]
                break
            assert parent.poll() is None, "the run ended before GetFEM started"
            time.sleep(0.1)
        assert child is not None, "no GetFEM child seen"
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        for _ in range(50):
            if _gone(child):
                break
            time.sleep(0.1)
        assert _gone(child), "the GetFEM child outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait()


def _is_getfem(pid) -> bool:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return b"getfem_script.py" in fh.read()
    except OSError:
        return False


def _gone(pid) -> bool:
    """No such process, or a zombie (dead, waiting for its new parent to reap it)."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        return True



@needs_getfem
def test_a_tangential_force_history_drifts_as_in_the_chain(tmp_path, capsys):
    """The same history as the chain: a force 0 -> -30 kN/m in phase with the heating,
    spread over the length or on an end face (force_at); the three drift differently, in
    the same order in both models."""
    fe, chain = {}, {}
    for at in ("uniform", "start", "end"):
        path = _strip(tmp_path, at)
        path.write_text(path.read_text()
                        + f'force_min = 0.0\nforce_max = -3e4\nforce_at = "{at}"\n')
        out = _fe(capsys, path, "--fe-mesh", "200")
        assert out["verdict"] == "ratchet"
        f = out["fe"]
        fe[at], chain[at] = f["drift_per_cycle_m"], out["drift_per_cycle_m"]
        assert fe[at] == pytest.approx(chain[at], rel=0.05)
        assert fe[at] == pytest.approx(f["chain_shear_corrected"]["drift_per_cycle_m"],
                                       rel=0.01)
    assert sorted(fe, key=fe.get) == sorted(chain, key=chain.get)
    assert min(abs(fe[a] / fe[b] - 1) for a in fe for b in fe if a != b) > 0.1


@needs_getfem
def test_fe_displacement_is_the_mean_of_the_contact_face(tmp_path):
    """The assembly's displacement (as the chain's: weighted by contact length) is the
    trapezoidal mean of the bottom face's u(x) over its length."""
    from asperity.fe.strip import run_strip_fe
    from asperity.microslip.assembly import load_assembly
    fe = run_strip_fe(load_assembly(_strip(tmp_path)), 0.2, 0.1, mesh=40)
    x, u = np.asarray(fe["_profile"]["x_m"]), np.asarray(fe["_profile"]["u_m"])
    assert x.size == 41 and x[0] == 0.0 and x[-1] == pytest.approx(SLENDER["l"])
    mean = float(np.sum(0.5 * (u[1:] + u[:-1]) * np.diff(x))) / SLENDER["l"]
    assert fe["mean_u_m"][-1] == pytest.approx(mean, rel=1e-12, abs=0)


def test_fe_is_not_run_when_the_assembly_slides_off(tmp_path, capsys):
    path = _strip(tmp_path)
    path.write_text(path.read_text() + "force = 1.2e5\n")     # beyond mu+ p l = 1e5 N/m
    code, out, err = run(capsys, "risk", path, "--fe", "getfem")
    assert code == 0, err
    assert "slides off" in out.lower() and "FE (GetFEM): not run" in out
    obj = json.loads(run(capsys, "risk", path, "--fe", "getfem", "--json")[1])
    assert obj["verdict"] == "slides-off" and "skipped" in obj["fe"]
