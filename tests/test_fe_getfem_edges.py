"""Edges of the GetFEM hand-off that tests/test_fe_getfem.py does not reach (issue 27, the
mutation campaign's survivors): the GWFL table from any start and with knots on the cut at
+-pi, GetFEM missing from an interpreter that exists, a run past its timeout, and the
numbers of ``risk --fe getfem``'s text and explanation against the JSON and the closed
forms.  The GetFEM runs skip, with the reason, when /usr/bin/python3 cannot import getfem."""
from __future__ import annotations

import json
import math
import os
import re
import stat
import sys
import time

import numpy as np
import pytest
from cli_run import run

from asperity.fe.getfem_runner import GetfemFailed, getfem_status
from asperity.fe.gwfl import piecewise_linear

_OK, _WHY = getfem_status()
needs_getfem = pytest.mark.skipif(not _OK, reason=f"GetFEM unavailable: {_WHY}")

#: the slender strip of test_fe_getfem.py (h / l = 1/50)
SLENDER = {"h": 2e-3, "E": 1e11, "p": 5e6, "l": 0.1, "k_t": 1e12, "alpha_T": 1e-5, "n": 401}
TWO_PI = 2.0 * math.pi


def _strip(tmp_path, name, mu=(0.2, 0.1), nu=0.3, **kw):
    """A strip assembly file (``nu=None``: the file gives no Poisson's ratio)."""
    a = {**SLENDER, **kw, **({} if nu is None else {"nu": nu})}
    body = "\n".join(f"{k} = {v!r}" for k, v in a.items())
    path = tmp_path / f"{name}.toml"
    path.write_text(f'[assembly]\nmodel = "strip"\n{body}\n[friction]\nmu_plus = {mu[0]!r}\n'
                    f"mu_minus = {mu[1]!r}\n[loading]\ndT_min = 0.0\ndT_max = 30.0\n")
    return path


def _fe(capsys, path, *extra):
    code, out, err = run(capsys, "risk", path, "--fe", "getfem", "--fe-mesh", "80", *extra)
    assert code == 0, err
    return out


def _fake_python(tmp_path, body: str):
    """An executable standing in for GetFEM's interpreter."""
    exe = tmp_path / "python-stand-in"
    exe.write_text(f"#!/bin/sh\n{body}\n")
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    return exe


def _eval(expr: str, t):
    return eval(expr, {"pos_part": lambda x: np.maximum(x, 0.0),
                       "Heaviside": lambda x: (x >= 0).astype(float), "t": t})


# ------------------------------------------------------- the table as GWFL, any knots

_RNG = np.random.default_rng(27)
_ANY = np.sort(_RNG.uniform(0.3, 0.3 + TWO_PI, 9))       # one turn, no knot on +-pi


@pytest.mark.parametrize("psi", [
    _ANY,                                                 # starts anywhere
    np.roll(_ANY, 4) - TWO_PI,                            # listed from another knot, a turn off
    np.array([-math.pi, -2.0, -0.4, 0.0, 1.1, 2.9]),      # a knot on -pi
    np.array([-2.0, -0.4, 0.0, 1.1, 2.9, math.pi]),       # on +pi (the same point)
    np.array([-math.pi - 4.5e-16, -0.4, 1.1, 2.9]),       # a rounding below -pi
    np.array([0.5]),                                      # one knot: a constant
], ids=["any-start", "rolled", "on-minus-pi", "on-plus-pi", "below-minus-pi", "one-knot"])
def test_piecewise_linear_is_the_periodic_interpolation_of_its_knots(psi):
    """f(t) is the periodic linear interpolation through the knots (wherever the turn starts
    and whichever knot sits on the cut at +-pi), finite, with f' its slope."""
    f = np.cos(3.0 * psi) + 0.3 * psi.size
    expr, dexpr = piecewise_linear(psi, f)
    t = np.linspace(-math.pi, math.pi, 4001)
    ref = np.interp(np.mod(t, TWO_PI), np.mod(psi, TWO_PI), f, period=TWO_PI)
    got = _eval(expr, t)
    assert np.all(np.isfinite(got)) and np.abs(got - ref).max() <= 1e-9
    assert _eval(expr, np.array([-math.pi]))[0] == pytest.approx(_eval(expr, np.array(
        [math.pi]))[0], abs=1e-9), "not periodic: f(-pi) != f(pi)"
    knots = np.mod(psi, TWO_PI)
    mid = t[np.all(np.abs(np.mod(t[:, None] - knots[None, :] + math.pi, TWO_PI) - math.pi)
                   > 1e-3, axis=1)]
    h = 1e-7
    fd = (_eval(expr, mid + h) - _eval(expr, mid - h)) / (2 * h)
    assert np.allclose(_eval(dexpr, mid), fd, rtol=1e-5, atol=1e-6), "f' is not f's slope"


def test_piecewise_linear_does_not_depend_on_where_the_list_starts():
    f = np.sin(_ANY) + 0.1 * _ANY
    t = np.linspace(-math.pi, math.pi, 997)
    base = _eval(piecewise_linear(_ANY, f)[0], t)
    for k in range(1, _ANY.size):
        psi = np.roll(_ANY, k) + TWO_PI * (k % 3 - 1)
        got = _eval(piecewise_linear(psi, np.roll(f, k))[0], t)
        assert np.abs(got - base).max() <= 1e-9, f"listed from knot {k}: another function"


# ------------------------------------------------------------- GetFEM not there, or slow

def test_getfem_missing_from_an_existing_interpreter_says_how_to_install(tmp_path, capsys,
                                                                          monkeypatch):
    """An interpreter that runs but cannot import getfem (here: Python without its site
    packages): one line naming the import error and the install command, exit 1."""
    exe = _fake_python(tmp_path, f'exec "{sys.executable}" -S "$@"')
    monkeypatch.setenv("ASPERITY_GETFEM_PYTHON", str(exe))
    plot = tmp_path / "r.png"
    code, _, err = run(capsys, "risk", _strip(tmp_path, "s"), "--fe", "getfem", "--plot", plot)
    assert code == 1 and len(err.strip().splitlines()) == 1 and not plot.exists()
    assert "apt-get install python3-getfem" in err and "No module named 'getfem'" in err
    ok, why = getfem_status()
    assert not ok and "apt-get install python3-getfem" in why and "\n" not in why


@pytest.mark.parametrize("status", [3, 1])
def test_a_getfem_child_that_fails_is_a_failure_whatever_it_printed(status, tmp_path, capsys,
                                                                     monkeypatch):
    """A child that exits non-zero (a crash after its output) is not believed, even when its
    last line looks like a result: one line with the exit status, exit 1, nothing written."""
    exe = _fake_python(tmp_path, f"cat > /dev/null\necho '{{\"getfem\": \"9.9\", "
                                 f"\"drift_per_cycle_m\": 0.0}}'\nexit {status}")
    monkeypatch.setenv("ASPERITY_GETFEM_PYTHON", str(exe))
    ok, why = getfem_status()
    assert not ok and f"exit status {status}" in why and "\n" not in why
    plot = tmp_path / "r.png"
    code, out, err = run(capsys, "risk", _strip(tmp_path, "s"), "--fe", "getfem", "--plot", plot,
                         "--json")
    assert code == 1 and len(err.strip().splitlines()) == 1 and f"exit status {status}" in err
    assert out == "" and not plot.exists()


def test_a_getfem_run_past_its_timeout_is_stopped_in_one_line(tmp_path, monkeypatch):
    """A run that takes longer than its timeout: GetfemFailed in one line (how long, what to
    do), soon after the timeout, and the child process is gone."""
    from asperity.fe.strip import run_strip_fe
    from asperity.microslip.assembly import load_assembly
    pid_file = tmp_path / "pid"
    exe = _fake_python(tmp_path, f'echo $$ > "{pid_file}"\nexec sleep 60')
    monkeypatch.setenv("ASPERITY_GETFEM_PYTHON", str(exe))
    asm = load_assembly(_strip(tmp_path, "s"))
    t0 = time.monotonic()
    with pytest.raises(GetfemFailed) as info:
        run_strip_fe(asm, 0.2, 0.1, mesh=80, timeout=0.5)
    assert time.monotonic() - t0 < 10.0
    msg = str(info.value)
    assert "more than 0.5 s" in msg and "--fe-mesh" in msg and "\n" not in msg
    pid = int(pid_file.read_text())
    try:
        os.kill(pid, 0)
        alive = True
    except ProcessLookupError:
        alive = False
    if alive:
        os.kill(pid, 9)
    assert not alive, "the timed-out child was left running"


# ------------------------------------------ the text and the explanation against the JSON

def _pct(text: str) -> float:
    m = re.search(r"\(([-+0-9.e]+) % apart\)", text)
    assert m, f"no '% apart' in the FE line: {text.splitlines()[0]!r}"
    return float(m.group(1))


@needs_getfem
def test_fe_text_gives_the_gap_of_the_json(tmp_path, capsys):
    """The text's '(x % apart)' is 100 x the JSON's relative difference."""
    path = _strip(tmp_path, "a")
    fe = json.loads(_fe(capsys, path, "--json"))["fe"]
    rel = fe["relative_difference"]
    assert rel is not None and rel > 1e-4
    assert _pct(_fe(capsys, path)) == pytest.approx(100 * rel, rel=5e-3)


@needs_getfem
@pytest.mark.parametrize("s", [0.1, 10.0])
def test_no_drift_in_both_models_is_no_gap_at_any_size(s, tmp_path, capsys):
    """Equal coefficients: neither model drifts (the FE's rounding is within its
    stabilisation test, relative to alpha_T l dT), so the gap is 0, not unknown (null), at
    any size of the strip (lengths x s, bed stiffness / s)."""
    path = _strip(tmp_path, "e", mu=(0.15, 0.15), h=SLENDER["h"] * s, l=SLENDER["l"] * s,
                  k_t=SLENDER["k_t"] / s)
    fe = json.loads(_fe(capsys, path, "--json"))["fe"]
    assert fe["chain_drift_per_cycle_m"] == 0.0
    assert fe["relative_difference"] == 0.0
    assert fe["chain_shear_corrected"]["relative_difference"] == 0.0
    assert _pct(_fe(capsys, path)) == 0.0


@needs_getfem
@pytest.mark.parametrize("nu", [0.3, 0.45, None])
def test_fe_explanation_gives_the_shear_compliance_in_series_with_the_bed(nu, tmp_path,
                                                                          capsys):
    """The explanation's numbers: h/(3G) with G = E / (2 (1 + nu)) (nu the file's, else the
    default 0.3), 1/k_t, and k_t,eff, the two compliances in series."""
    fe = json.loads(_fe(capsys, _strip(tmp_path, "n", nu=nu), "--json"))["fe"]
    assert fe["nu"] == (0.3 if nu is None else nu)
    assert ("default" in fe["nu_from"]) == (nu is None)
    text = fe["explanation"]           # (compliances ~1e-14: approx with abs=0)
    num = r"([0-9.]+(?:e[-+]?[0-9]+)?)"
    shear = float(re.search(rf"h/\(3G\) = {num} m/Pa", text).group(1))
    bed = float(re.search(rf"1/k_t = {num}", text).group(1))
    k_eff = float(re.search(rf"k_t,eff = {num} Pa/m", text).group(1))
    G = SLENDER["E"] / (2.0 * (1.0 + fe["nu"]))
    assert shear == pytest.approx(SLENDER["h"] / (3.0 * G), rel=5e-3, abs=0)
    assert bed == pytest.approx(1.0 / SLENDER["k_t"], rel=5e-3, abs=0)
    assert 1.0 / k_eff == pytest.approx(bed + shear, rel=5e-3, abs=0)
    assert k_eff == pytest.approx(fe["chain_shear_corrected"]["k_t_eff_Pa_per_m"], rel=5e-4)
