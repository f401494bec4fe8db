"""Hostile input to the microslip room (issue 11, classes 2-6): assembly files with wrong
types and structure, extreme numbers, requests too large for the machine, Ctrl-C during
the chain kernels, and the Python API fed None, text, NaN and wrong shapes.  Every bad
input ends in one InputError line (exit 1 on the command line); accepted input gives
finite results.  Class 8 (signed alpha_T, the verdict) is in test_microslip_verdict.py.

The lists BAD_TYPES, BAD_NUMBERS, BAD_FLAGS, RESOURCES and BAD_API hold the bad inputs of
each class, so their lengths are the counts the issue asks for."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from cli_run import run
from hostile import SURF, assert_finite_output, assert_refused, cli, interrupt, limit_memory
from hypothesis import given, settings
from hypothesis import strategies as st

import asperity as A
from asperity.errors import InputError, ResourceError
from asperity.microslip import dynamic, limits, pacing
from asperity.microslip import quasi_static as qs
from asperity.microslip.chains import (
    Chain,
    MicroslipTolerances,
    elastic_limit,
    strip_chain,
    two_node_chain,
)
from asperity.microslip.closed_forms import strip_dT_c, two_node_drift_per_cycle, two_node_dT_c
from asperity.microslip.loading import Loading

TWO = {"assembly": {"model": '"two-node"', "k": "1e6", "l0": "0.1", "alpha_T": "1.2e-5",
                    "k_t": "5e5", "N": "100.0"},
       "friction": {"mu_plus": "0.2", "mu_minus": "0.1"},
       "loading": {"dT_min": "0.0", "dT_max": "125.0"}}
STRIP = {"assembly": {"model": '"strip"', "h": "2.5e-3", "E": "1.1e11", "p": "5e6", "l": "0.04",
                      "k_t": "1e13", "alpha_T": "6e-6", "n": "21"},
         "friction": {"mu_plus": "0.2", "mu_minus": "0.1"},
         "loading": {"dT_min": "0.0", "dT_max": "40.0"}}


def toml(base=TWO, edits=(), top=""):
    """An assembly file: ``base`` with edits (table, key, TOML value or None to drop; key
    None drops the table), ``top`` prepended (top-level keys)."""
    tables = {t: dict(kv) for t, kv in base.items()}
    for t, k, v in edits:
        if k is None:
            tables.pop(t, None)
        elif v is None:
            tables[t].pop(k, None)
        else:
            tables.setdefault(t, {})[k] = v
    body = "".join(f"[{t}]\n" + "".join(f"{k} = {v}\n" for k, v in kv.items())
                   for t, kv in tables.items())
    return top + body


def history(values):
    return [("loading", "dT_min", None), ("loading", "dT_max", None),
            ("loading", "history", values)]


# ------------------------------------------------------------- class 3: types, structure

BAD_TYPES = [
    ("mu_plus text", toml(TWO, [("friction", "mu_plus", '"0.2"')]), "friction.mu_plus must be a number"),
    ("mu_minus boolean", toml(TWO, [("friction", "mu_minus", "true")]), "friction.mu_minus must be a number"),
    ("alpha_T text", toml(TWO, [("assembly", "alpha_T", '"1e-5"')]), "assembly.alpha_T must be a number"),
    ("k a list", toml(TWO, [("assembly", "k", "[1e6]")]), "assembly.k must be a number"),
    ("N a table", toml(TWO, [("assembly", "N", "{ a = 1 }")]), "assembly.N must be a number"),
    ("E text", toml(STRIP, [("assembly", "E", '"1.1e11"')]), "assembly.E must be a number"),
    ("force_history booleans", toml(TWO, history("[0, 50, 0]") + [
        ("loading", "force_history", "[true, false, true]")]), "loading.force_history[0] must be a number"),
    ("history list of lists", toml(TWO, history("[[0, 1], [1, 0]]")), "loading.history[0] must be a number"),
    ("history nested deep", toml(TWO, history("[0, " + "[" * 200 + "1" + "]" * 200 + ", 0]")),
     "loading.history[1] must be a number"),
    ("history text", toml(TWO, history('"0, 50, 0"')), "loading.history must be a list"),
    ("history with text", toml(TWO, history('[0, "50", 0]')), "loading.history[1] must be a number"),
    ("history too long", toml(TWO, history("[" + ", ".join(["0.0", "1.0"] * 5001) + ", 0.0]")),
     "loading.history has 10003 points, at most 10000"),
    ("history one point", toml(TWO, history("[0]")), "loading.history must have 2 to 10000 points"),
    ("history empty", toml(TWO, history("[]")), "loading.history must have 2 to 10000 points"),
    ("force_history text", toml(TWO, history("[0, 50, 0]") + [("loading", "force_history", '"1"')]),
     "loading.force_history must be a list"),
    ("force_history short", toml(TWO, history("[0, 50, 0]") + [("loading", "force_history", "[0, 1]")]),
     "as many points as loading.history"),
    ("force text", toml(TWO, [("loading", "force", '"1"')]), "loading.force must be a number"),
    ("force_min list", toml(TWO, [("loading", "force_min", "[0]")]), "loading.force_min must be a number"),
    ("substeps fraction", toml(TWO, [("loading", "substeps", "2.5")]), "loading.substeps must be a whole number"),
    ("substeps text", toml(TWO, [("loading", "substeps", '"2"')]), "loading.substeps must be a whole number"),
    ("substeps boolean", toml(TWO, [("loading", "substeps", "true")]), "loading.substeps must be a whole number"),
    ("cycles text", toml(TWO, [("loading", "cycles", '"1e6"')]), "loading.cycles must be a number"),
    ("tolerance list", toml(TWO, [("loading", "tolerance", "[1e-4]")]), "loading.tolerance must be a number"),
    ("force_at number", toml(TWO, [("loading", "force_at", "3")]), "loading.force_at must be one of uniform, start, end"),
    ("force_at unknown", toml(TWO, [("loading", "force_at", '"middle"')]), "loading.force_at must be one of"),
    ("dT_min boolean", toml(TWO, [("loading", "dT_min", "true")]), "loading.dT_min must be a number"),
    ("model a list", toml(TWO, [("assembly", "model", "[1]")]), "assembly.model must be one of strip, two-node"),
    ("model unknown", toml(TWO, [("assembly", "model", '"beam"')]), "assembly.model must be one of"),
    ("n fraction", toml(STRIP, [("assembly", "n", "20.5")]), "assembly.n must be a whole number"),
    ("n text", toml(STRIP, [("assembly", "n", '"21"')]), "assembly.n must be a whole number"),
    ("assembly not a table", toml(TWO, [("assembly", None, None)], top="assembly = 5\n"), "assembly must be a table"),
    ("loading not a table", toml(TWO, [("loading", None, None)], top="loading = [1, 2]\n"), "loading must be a table"),
    ("friction not a table", toml(TWO, [("friction", None, None)], top='friction = "x"\n'), "friction must be a table"),
    ("unknown key in assembly", toml(TWO, [("assembly", "color", "1")]), "unknown key assembly.color"),
    ("unknown key in loading", toml(TWO, [("loading", "dT_mx", "3")]), "unknown key loading.dT_mx"),
    ("unknown key in friction", toml(TWO, [("friction", "mu", "0.2")]), "unknown key friction.mu"),
    ("unknown top-level key", toml(TWO, top="asembly = 1\n"), "unknown key 'asembly'"),
    ("textured a number", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                     ("friction", "texture", '"wedge.toml"'), ("friction", "textured", "1")]),
     "friction.textured must be one of support, part"),
    ("contact unknown", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                   ("friction", "texture", '"wedge.toml"'), ("friction", "contact", '"rigid"')]),
     "friction.contact must be one of all-faces, windward"),
    ("gauge a number", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                  ("friction", "gauge", "5")]), "friction.gauge must be a file name"),
    ("texture a list", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                  ("friction", "texture", "[]")]), "friction.texture must be a file name"),
    ("slip axis text", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                  ("friction", "texture", '"w.toml"'), ("friction", "slip_axis_deg", '"0"')]),
     "friction.slip_axis_deg must be a number"),
    ("name a number", toml(TWO, top="name = 5\n"), "name must be text"),
    ("description a list", toml(TWO, top="description = []\n"), "description must be text"),
]


@pytest.mark.parametrize("name,text,msg", BAD_TYPES, ids=[c[0] for c in BAD_TYPES])
def test_bad_types_and_structure_one_line(tmp_path, name, text, msg):
    p = tmp_path / "a.toml"
    p.write_text(text)
    with pytest.raises(InputError) as exc:
        A.load_assembly(p)
    assert msg in str(exc.value) and "\n" not in str(exc.value), str(exc.value)


@pytest.mark.parametrize("k", [0, 1, 6, 11, 30, 36])
def test_types_through_the_real_command(tmp_path, k):
    _, text, msg = BAD_TYPES[k]
    p = tmp_path / "a.toml"
    p.write_text(text)
    assert_refused(cli("risk", p), contains=msg)


# ------------------------------------------------------------- class 2: extreme numbers

POSITIVE = ["0", "-1", "5e-324", "1e-300", "1e308", "inf", "nan"]
NUMBER_CASES = (
    [(TWO, "assembly", k, v) for k in ("k", "l0", "k_t", "N") for v in POSITIVE]
    + [(STRIP, "assembly", k, v) for k in ("h", "E", "p", "l", "k_t") for v in POSITIVE]
    + [(TWO, "assembly", "alpha_T", v) for v in ("0", "5e-324", "-5e-324", "1e-300", "1e308",
                                                 "-1e308", "inf", "nan")]
    + [(TWO, "friction", k, v) for k in ("mu_plus", "mu_minus")
       for v in ("0", "-0.1", "5e-324", "1e308", "inf", "nan", "1000")]
    + [(TWO, "loading", k, v) for k in ("dT_min", "dT_max")
       for v in ("1e308", "-1e308", "inf", "-inf", "nan", "6000")]
    + [(TWO, "loading", "force", v) for v in ("1e308", "-inf", "nan", "1e13")]
    + [(TWO, "loading", "substeps", v) for v in ("0", "-1", "1000000", "1e308", "inf", "nan")]
    + [(TWO, "loading", "cycles", v) for v in ("0", "0.5", "1e16", "inf", "nan", "-1")]
    + [(TWO, "loading", "tolerance", v) for v in ("0", "-1e-4", "5e-324", "1e-300", "1e308",
                                                   "inf", "nan")]
    + [(STRIP, "assembly", "n", v) for v in ("1", "0", "-5", "10000000", "2000000")])
BAD_NUMBERS = [(f"{t}.{k} = {v}", toml(b, [(t, k, v)]), f"{t}.{k} must be")
               for b, t, k, v in NUMBER_CASES] + [
    ("history nan", toml(TWO, history("[0, nan, 0]")), "loading.history[1] must be in [-5000, 5000] K"),
    ("history 1e308", toml(TWO, history("[0, 1e308, 0]")), "loading.history[1] must be in"),
    ("force_history inf", toml(TWO, history("[0, 5, 0]") + [("loading", "force_history", "[0, inf, 0]")]),
     "loading.force_history[1] must be a finite number in [-1e+12, 1e+12]"),
    ("force_max 1e20", toml(TWO, [("loading", "force_min", "0"), ("loading", "force_max", "1e20")]),
     "loading.force_max must be in"),
    ("dT_min > dT_max", toml(TWO, [("loading", "dT_min", "500")]), "dT_min <= dT_max"),
    ("slip axis 1e308", toml(TWO, [("friction", "mu_plus", None), ("friction", "mu_minus", None),
                                   ("friction", "texture", '"w.toml"'), ("friction", "slip_axis_deg", "1e308")]),
     "friction.slip_axis_deg must be in [-360, 360]"),
    ("history x substeps > 1e7 points", toml(TWO, history("[" + ", ".join(["0.0", "9.0"] * 2500)
                                                          + ", 0.0]") + [("loading", "substeps", "5000")]),
     "load points per cycle, at most 1e+07; lower loading.substeps"),
]
#: combinations beyond what the model resolves (each field in range)
BAD_COMBINATIONS = [
    ("bar 1e18 x stiffer than contacts", toml(TWO, [("assembly", "k", "1e15"), ("assembly", "k_t", "1e-3")]),
     "elements are 1e+18 times stiffer than its contacts"),
    ("contacts 1e18 x stiffer", toml(TWO, [("assembly", "k", "1e-3"), ("assembly", "k_t", "1e15")]),
     "contacts are 1e+18 times stiffer"),
    ("strip E h tiny on a stiff bed", toml(STRIP, [("assembly", "E", "1e4"), ("assembly", "h", "1e-7"),
                                                   ("assembly", "k_t", "1e20")]), "times stiffer"),
    ("friction asymmetry 1e4", toml(TWO, [("friction", "mu_plus", "10"), ("friction", "mu_minus", "1e-3")]),
     "mu_plus / mu_minus = 1e+04"),
    ("margin 1e6", toml(TWO, [("assembly", "N", "1e-3")]), "margin dT range / (2 dT_c) = 1.5e+05"),
]


@pytest.mark.parametrize("name,text,msg", BAD_NUMBERS + BAD_COMBINATIONS,
                         ids=[c[0] for c in BAD_NUMBERS + BAD_COMBINATIONS])
def test_extreme_numbers_refused_with_the_range(tmp_path, capsys, name, text, msg):
    p = tmp_path / "a.toml"
    p.write_text(text)
    code, out, err = run(capsys, "risk", p, "--json")
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert msg in err, err


BAD_FLAGS = ([["--cycles", v] for v in ("0", "-1", "nan", "inf", "1e16", "5e-324")]
             + [["--tolerance", v] for v in ("0", "-1", "nan", "inf", "5e-324", "1e300")]
             + [["--max-marched", v] for v in ("1", "0", "1e7", "2.5", "abc", "inf")]
             + [["--dynamic", v] for v in ("99", "0", "1e8", "1.5", "abc", "nan")])


@pytest.mark.parametrize("flags", BAD_FLAGS, ids=[" ".join(f) for f in BAD_FLAGS])
def test_extreme_flags_refused(capsys, flags):
    code, out, err = run(capsys, "risk", SURF / "two-node-spec.toml", *flags)
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert f"{flags[0]} must be" in err


@pytest.mark.parametrize("flag", ["--slip-axis", "--cycles", "--tolerance"])
def test_flags_refused_through_the_real_command(flag):
    assert_refused(cli("risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip.toml",
                       flag, "nan"), contains=f"{flag} must be")


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda x: 10.0 ** x)


@settings(max_examples=120, deadline=None)
@given(k=log_uniform(*limits.TWO_NODE["k"][:2]), kt=log_uniform(*limits.TWO_NODE["k_t"][:2]),
       N=log_uniform(*limits.TWO_NODE["N"][:2]), l0=log_uniform(*limits.TWO_NODE["l0"][:2]),
       aT=log_uniform(*limits.ALPHA_T), sign=st.sampled_from([1, -1]),
       mup=log_uniform(1e-3, 10), mum=log_uniform(1e-3, 10), rng=st.floats(0, 5000))
def test_any_two_node_in_range_is_exact_or_refused(k, kt, N, l0, aT, sign, mup, mum, rng):
    """In the documented ranges an assembly is either refused in one line or its dT_c and
    drift per cycle are the closed forms of SPEC.md 5 and every number is finite."""
    try:
        c = two_node_chain(k, l0, sign * aT, kt, N, mup, mum)
        out = A.assess(c, Loading.cycles_between(0.0, rng), 1e6, 1e-4)
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    out.pop("_result")
    json.dumps(out, allow_nan=False)
    # the tridiagonal solve loses the digits of the stiffness ratio (at most 1e9)
    rel = 1e-12 + 10 * max(k / kt, kt / k) * 2.2e-16
    assert out["dT_c_K"] == pytest.approx(two_node_dT_c(k, kt, N, mup, mum, sign * aT, l0), rel=rel)
    want = two_node_drift_per_cycle(k, kt, N, mup, mum, sign * aT, l0, 0.0, rng)
    assert out["drift_per_cycle_m"] == pytest.approx(want, rel=1e-9 + 1e4 * rel,
                                                     abs=1e-12 * abs(aT) * l0 * rng)


# ------------------------------------------------------------- class 4: resources

def big_strip(n, substeps, extra=()):
    return toml(STRIP, [("assembly", "n", str(n)), ("loading", "substeps", str(substeps)), *extra])


RESOURCES = [
    ("substeps 1e5 on a 1e4-node strip", big_strip(10_000, 100_000), [], "loading.substeps"),
    ("--max-marched 1e6 on a large march", big_strip(20_000, 2000), ["--max-marched", "1e6"],
     "--max-marched"),
    ("--dynamic 1e7 on a 1e4-node strip", big_strip(10_000, 1), ["--dynamic", "1e7"], "--dynamic"),
    ("--dynamic 1e6 on a 1e5-node strip", big_strip(100_000, 1), ["--dynamic", "1e6"], "--dynamic"),
]


@pytest.mark.parametrize("name,text,flags,lower", RESOURCES, ids=[c[0] for c in RESOURCES])
def test_too_large_requests_refused_before_starting(tmp_path, name, text, flags, lower):
    p = tmp_path / "big.toml"
    p.write_text(text)
    status, out, err = cli("risk", p, *flags, timeout=60, preexec_fn=limit_memory(2 << 30))
    assert_refused((status, out, err), contains=lower)
    # a work limit or, under this 2 GB address-space limit, the memory estimate
    assert ("at most" in err) if "dynamic" in name else ("at most" in err or "memory" in err)


def test_api_refuses_what_cannot_fit():
    c = two_node_chain(1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1)
    with pytest.raises(ResourceError, match="memory"):
        A.simulate_microslip(c, Loading.cycles_between(0, 100), 10**8, until_stable=False)
    s = strip_chain(2.5e-3, 1.1e11, 5e6, 0.04, 1e13, 6e-6, 10_000, 0.2, 0.1)
    with pytest.raises(ResourceError, match="steps per segment"):
        dynamic.simulate_dynamic(s, Loading.cycles_between(0, 40), 3, steps_per_segment=10**7)


def test_long_work_reports_progress(monkeypatch):
    from asperity import progress

    class Tty:
        text = ""

        def isatty(self):
            return True

        def write(self, s):
            Tty.text += s

        def flush(self):
            pass
    monkeypatch.setattr(progress, "QUIET_SECONDS", 0.0)
    c = strip_chain(2.5e-3, 1.1e11, 5e6, 0.04, 1e13, 6e-6, 41, 0.2, 0.1)
    with progress.progress_bar("risk", stream=Tty()):
        A.simulate_microslip(c, Loading.cycles_between(0, 40, substeps=50), 3)
        dynamic.simulate_dynamic(c, Loading.cycles_between(0, 40), 1, steps_per_segment=1000)
    assert "quasi-static cycles" in Tty.text and "Moreau time steps" in Tty.text
    assert "100.0 %" in Tty.text


# ------------------------------------------------------------- class 5: interrupts

@pytest.mark.slow
def test_ctrl_c_during_the_dynamic_strip(tmp_path):
    png = tmp_path / "out.png"
    png.write_bytes(b"precious")
    status, err = interrupt("risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip.toml",
                            "--dynamic", "10000000", "--plot", png)
    assert status == 130 and "interrupted" in err and err.count("\n") == 1, err
    assert png.read_bytes() == b"precious"


@pytest.mark.slow
def test_ctrl_c_during_a_long_quasi_static_march(tmp_path):
    p = tmp_path / "big.toml"
    p.write_text(big_strip(20_000, 2000))      # with 3 cycles at most: about 40 s of work
    status, err = interrupt("risk", p, "--max-marched", "3")
    assert status == 130 and err.count("\n") == 1 and "Traceback" not in err, (status, err)


def test_pieces_give_the_result_of_one_piece(monkeypatch):
    c = strip_chain(2e-3, 2e11, 1e6, 0.1, (3.54 / 0.1) ** 2 * 4e8, 1.2e-5, 31, 0.2, 0.1)
    L = Loading(np.array([0, 5, -2, 7, 0.0]) * elastic_limit(c), np.array([0, 3, -4, 1, 0.0]), 7)

    def both():
        return (qs.simulate(c, L, 5, until_stable=False, record_nodes=[0, 9, 30]),
                dynamic.simulate_dynamic(c, L, 2, steps_per_segment=1500, record_nodes=[3]))
    monkeypatch.setattr(pacing, "TARGET_SECONDS", 1e9)
    monkeypatch.setattr(qs, "PIECE_NODE_UPDATES", 10**12)
    monkeypatch.setattr(dynamic, "PIECE_NODE_STEPS", 10**12)
    one = both()
    monkeypatch.setattr(pacing, "TARGET_SECONDS", 1e-12)      # one load point / step a piece
    monkeypatch.setattr(qs, "PIECE_NODE_UPDATES", 1)
    monkeypatch.setattr(dynamic, "PIECE_NODE_STEPS", 1)
    many = both()
    for a, b in zip(one, many):
        assert np.array_equal(a.u_end, b.u_end) and np.array_equal(a.trace["u"], b.trace["u"])
        assert a.drift_per_cycle == b.drift_per_cycle and a.q_end.tolist() == b.q_end.tolist()


# ------------------------------------------------------------- class 6: Python API

def _two():
    return two_node_chain(1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1)


def _L():
    return Loading.cycles_between(0.0, 125.0)


def _asm():
    return A.load_assembly(SURF / "two-node-spec.toml")


def _mild():
    return A.load_assembly(SURF / "bushing-strip-mild.toml")


def _chain(**kw):
    c = _two()
    args = {"kind": "x", "x": c.x, "kb": c.kb, "le": c.le, "kt": c.kt, "cp": c.cp, "cm": c.cm,
            "fw": c.fw, "weight": c.weight, "alpha_T": c.alpha_T, "mu_plus": 0.2,
            "mu_minus": 0.1, "params": c.params}
    args.update(kw)
    return Chain(**args)


NAN = float("nan")
BAD_API = [
    ("two_node_chain k None", lambda: two_node_chain(None, .1, 1e-5, 5e5, 100, .2, .1), "k must be a number"),
    ("two_node_chain N text", lambda: two_node_chain(1e6, .1, 1e-5, 5e5, "100", .2, .1), "N must be a number"),
    ("two_node_chain l0 NaN", lambda: two_node_chain(1e6, NAN, 1e-5, 5e5, 100, .2, .1), "l0 must be in"),
    ("two_node_chain k array", lambda: two_node_chain(np.ones(2), .1, 1e-5, 5e5, 100, .2, .1), "k must be a number"),
    ("two_node_chain mu None", lambda: two_node_chain(1e6, .1, 1e-5, 5e5, 100, None, .1), "mu_plus must be a number"),
    ("strip_chain n None", lambda: strip_chain(1e-3, 1e11, 1e6, .1, 1e13, 1e-5, None, .2, .1), "n must be a whole number"),
    ("strip_chain n 2.5", lambda: strip_chain(1e-3, 1e11, 1e6, .1, 1e13, 1e-5, 2.5, .2, .1), "n must be a whole number"),
    ("strip_chain E inf", lambda: strip_chain(1e-3, math.inf, 1e6, .1, 1e13, 1e-5, 5, .2, .1), "E must be a finite"),
    ("Chain kb too short", lambda: _chain(kb=np.ones(0)), "chain.kb must have shape"),
    ("Chain kt negative", lambda: _chain(kt=np.array([1.0, -1.0])), "chain.kt must be > 0"),
    ("Chain cp NaN", lambda: _chain(cp=np.array([NAN, 1.0])), "chain.cp must be finite or +inf"),
    ("Chain x 2-D", lambda: _chain(x=np.zeros((2, 2))), "chain.x must have"),
    ("Chain weights", lambda: _chain(weight=np.array([0.5, 0.6])), "must each sum to 1"),
    ("Chain kind None", lambda: _chain(kind=None), "chain.kind must be text"),
    ("Loading None", lambda: Loading(None, 0.0), "loading.history must be a list of numbers"),
    ("Loading text", lambda: Loading("0 1 0", 0.0), "loading.history must be a list"),
    ("Loading 2-D", lambda: Loading([[0, 1], [1, 0]], 0.0), "loading.history[0] must be a number"),
    ("Loading NaN", lambda: Loading([0, NAN, 0], 0.0), "loading.history[1] must be in"),
    ("Loading F 2-D", lambda: Loading([0, 1, 0], np.zeros((3, 1))), "loading.force_history must be a flat list"),
    ("Loading F length", lambda: Loading([0, 1, 0], [0, 1]), "as many points"),
    ("Loading substeps None", lambda: Loading([0, 1, 0], 0.0, None), "loading.substeps must be a whole number"),
    ("cycles_between None", lambda: Loading.cycles_between(None, 1), "dT_min must be a number"),
    ("cycles_between text", lambda: Loading.cycles_between("0", 1), "dT_min must be a number"),
    ("cycles_between force", lambda: Loading.cycles_between(0, 1, force_min="x"), "force_min must be a number"),
    ("simulate chain None", lambda: A.simulate_microslip(None, _L()), "chain must be a slider chain"),
    ("simulate chain text", lambda: A.simulate_microslip("chain", _L()), "chain must be a slider chain"),
    ("simulate loading None", lambda: A.simulate_microslip(_two(), None), "loading must be a Loading"),
    ("simulate cycles None", lambda: A.simulate_microslip(_two(), _L(), None), "cycles must be a whole number"),
    ("simulate cycles NaN", lambda: A.simulate_microslip(_two(), _L(), NAN), "cycles must be a whole number"),
    ("simulate cycles 0", lambda: A.simulate_microslip(_two(), _L(), 0), "cycles must be a whole number in"),
    ("record_nodes 1e12", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[10**12]), "record_nodes must be whole numbers in [0, 1]"),
    ("record_nodes -1", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[-1]), "record_nodes must be whole numbers in [0, 1]"),
    ("record_nodes 1.5", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[1.5]), "record_nodes must be whole numbers"),
    ("record_nodes NaN", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[NAN]), "record_nodes must be whole numbers"),
    ("record_nodes 10**30", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[10**30]), "record_nodes must be"),
    ("record_nodes 2-D", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[[0]]), "record_nodes must be a flat list"),
    ("record_nodes text", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes="0"), "record_nodes must be a list"),
    ("record_nodes boolean", lambda: A.simulate_microslip(_two(), _L(), 3, record_nodes=[True]), "record_nodes must be node indices"),
    ("until_stable text", lambda: A.simulate_microslip(_two(), _L(), 3, until_stable="yes"), "until_stable must be True or False"),
    ("tol a number", lambda: A.simulate_microslip(_two(), _L(), 3, tol=1e-3), "tol must be a MicroslipTolerances"),
    ("tolerances negative iterations", lambda: MicroslipTolerances(max_events_per_node=-1), "tol.max_events_per_node must be"),
    ("tolerances NaN", lambda: MicroslipTolerances(stabilised=NAN), "tol.stabilised must be in"),
    ("tolerances r factor 2", lambda: MicroslipTolerances(prox_r_factor=2.0), "tol.prox_r_factor must be in (0, 2)"),
    ("long_life cycles None", lambda: A.long_life(_two(), _L(), None), "cycles must be a number"),
    ("long_life max_marched 1", lambda: A.long_life(_two(), _L(), 10, max_marched=1), "max_marched must be a whole number in"),
    ("assess tolerance NaN", lambda: A.assess(_two(), _L(), 1e6, NAN), "tolerance must be in"),
    ("assess tolerance text", lambda: A.assess(_two(), _L(), 1e6, "1"), "tolerance must be a number"),
    ("assess dT_c text", lambda: A.assess(_two(), _L(), dT_c_closed_form="x"), "dT_c_closed_form must be a number"),
    ("assess chain None", lambda: A.assess(None, _L()), "chain must be a slider chain"),
    ("dynamic steps 5", lambda: dynamic.simulate_dynamic(_two(), _L(), 1, steps_per_segment=5), "steps_per_segment must be"),
    ("dynamic record 1e12", lambda: dynamic.simulate_dynamic(_two(), _L(), 1, record_nodes=[10**12]), "record_nodes must be whole numbers"),
    ("dynamic record_points 0", lambda: dynamic.simulate_dynamic(_two(), _L(), 1, record_points=0), "record_points must be"),
    ("load_assembly None", lambda: A.load_assembly(None), "an assembly file must be a path"),
    ("load_assembly number", lambda: A.load_assembly(5), "an assembly file must be a path"),
    ("load_assembly empty", lambda: A.load_assembly(""), "an assembly file must be a path"),
    ("assembly_friction None", lambda: A.assembly_friction(None), "asm must be a parsed assembly"),
    ("assembly_friction texture text", lambda: A.assembly_friction(_asm(), "wedge.toml"), "texture must be a wedge texture or a surface"),
    ("assembly_friction contact", lambda: A.assembly_friction(_mild(), contact="rigid"), "contact must be one of"),
    ("assembly_friction axis NaN", lambda: A.assembly_friction(_mild(), slip_axis_deg=NAN), "slip_axis_deg must be in"),
    ("assembly_friction textured", lambda: A.assembly_friction(_mild(), textured="both"), "textured must be one of"),
    ("assess_assembly None", lambda: A.assess_assembly(None, None), "asm must be a parsed assembly"),
    ("assess_assembly friction None", lambda: A.assess_assembly(_asm(), None), "friction must be a Friction"),
    ("assess_assembly cycles NaN", lambda: A.assess_assembly(_asm(), A.assembly_friction(_asm()), cycles=NAN), "cycles must be in"),
    ("assess_assembly dynamic text", lambda: A.assess_assembly(_asm(), A.assembly_friction(_asm()), dynamic_steps="x"), "dynamic_steps must be a whole number"),
    ("risk_map asm None", lambda: A.risk_map(None, None, None), "asm must be a parsed assembly"),
    ("risk_map axis None", lambda: A.risk_map(_mild(), None, ("beta", [5, 10])), "risk map axis x must be"),
    ("risk_map unknown parameter", lambda: A.risk_map(_mild(), ("gamma", [5, 10]), ("beta", [5, 10])), "map parameter must be one of"),
    ("risk_map NaN value", lambda: A.risk_map(_mild(), ("alpha", [NAN, 10]), ("beta", [5, 10])), "risk map alpha values must be finite"),
    ("risk_map 2-D values", lambda: A.risk_map(_mild(), ("alpha", [[5, 10]]), ("beta", [5, 10])), "risk map alpha values must have"),
    ("risk_map 300 values", lambda: A.risk_map(_mild(), ("alpha", np.linspace(5, 40, 300)), ("beta", [5, 10])), "at most 200"),
    ("risk_map texture text", lambda: A.risk_map(_mild(), ("alpha", [5, 10]), ("beta", [5, 10]), "w"), "texture must be a wedge texture"),
    ("elastic_limit None", lambda: elastic_limit(None), "chain must be a Chain"),
    ("elastic_limit sign 0", lambda: elastic_limit(_two(), 0), "sign must be 1 (heating) or -1"),
    ("two_node_dT_c None", lambda: two_node_dT_c(None, 5e5, 100, .2, .1, 1e-5, .1), "k must be a number"),
    ("two_node_dT_c alpha 0", lambda: two_node_dT_c(1e6, 5e5, 100, .2, .1, 0.0, .1), "alpha_T must be in"),
    ("two_node_drift dT NaN", lambda: two_node_drift_per_cycle(1e6, 5e5, 100, .2, .1, 1e-5, .1, 0, NAN), "dT_max must be in"),
    ("two_node_drift dT reversed", lambda: two_node_drift_per_cycle(1e6, 5e5, 100, .2, .1, 1e-5, .1, 9, 1), "dT_min <= dT_max"),
    ("strip_dT_c text", lambda: strip_dT_c(1e-3, "1e11", 1e6, .1, 1e13, .2, .1, 1e-5), "E must be a number"),
]


@pytest.mark.parametrize("name,call,msg", BAD_API, ids=[c[0] for c in BAD_API])
def test_python_api_validates_like_the_command(name, call, msg):
    with pytest.raises(InputError) as exc:
        call()
    text = str(exc.value)
    assert msg in text and "\n" not in text, text


def test_out_of_range_record_node_cannot_crash_the_interpreter():
    code = ("import asperity as A\n"
            "c = A.two_node_chain(1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1)\n"
            "L = A.Loading.cycles_between(0.0, 125.0)\n"
            "for r in ([10**12], [-10**12], [2], [2**63 - 1]):\n"
            "    try:\n        A.simulate_microslip(c, L, 3, record_nodes=r)\n"
            "    except A.InputError as e:\n        print('refused')\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                       check=False)
    assert p.returncode == 0 and p.stdout.split() == ["refused"] * 4, (p.returncode, p.stderr)


def test_accepted_extremes_give_finite_output(capsys, tmp_path):
    """Corners of the ranges that the solvers resolve: every printed number finite."""
    cases = [toml(TWO, [("assembly", "alpha_T", "-1e-3"), ("loading", "dT_min", "-5000"),
                        ("loading", "dT_max", "5000"), ("assembly", "N", "1e9")]),
             toml(STRIP, [("assembly", "alpha_T", "-1e-9"), ("assembly", "n", "2")]),
             toml(TWO, [("loading", "force_min", "-19.9"), ("loading", "force_max", "39.9"),
                        ("loading", "tolerance", "1e3"), ("loading", "cycles", "1e15")])]
    for text in cases:
        p = tmp_path / "a.toml"
        p.write_text(text)
        for extra in ([], ["--json"]):
            code, out, err = run(capsys, "risk", p, *extra)
            assert code == 0, err
            assert_finite_output(out)


@pytest.mark.parametrize("k,kt,N,l0,aT,mup,mum,rng", [
    (10.0 ** 6.375, 1e15, 1.0, 1.0, 1e-9, 1.0, 1.000000005872572, 1110.0),   # hypothesis: half
    (1.0, 1.0, 1.0, 10.0, 0.001, 1.0, 1.000000005872572, 593.0),   # the drift; no convergence
    (30413.639716874168, 11534291441183.266, 6890.052007564204, 162.1133547581583,  # fuzzed:
     -4.430981027573224e-05, 0.0013138742332858165, 0.001314010515681902, 123.9962765009478),
])                                               # stiff contacts, margin 1500: no drift at all
def test_nearly_symmetric_friction_is_resolved(k, kt, N, l0, aT, mup, mum, rng):
    """Pairs the Newton solver once could not resolve (half the drift, no convergence, no
    drift at all; they were refused): the two-node model ratchets for any mu+ != mu- (the
    weaker slider caps the bar force, the other never slips), so the drift is the closed
    form's, towards the smaller coefficient, to rounding; 2e-12 apart the pair is told
    apart; equal but for rounding (1e-15) it is the symmetric case, no drift."""
    scale = abs(aT) * l0 * rng
    for a, b in ((mup, mum), (mum, mup), (mup, mup * (1 + 2e-12)), (mup, mup * (1 + 1e-15))):
        out = A.assess(two_node_chain(k, l0, aT, kt, N, a, b), Loading.cycles_between(0.0, rng),
                       1e6, 1e-4)
        want = two_node_drift_per_cycle(k, kt, N, a, b, aT, l0, 0.0, rng)
        assert abs(out["drift_per_cycle_m"] - want) <= 1e-12 * scale, (a, b, out, want)
        if b == mup * (1 + 1e-15):
            assert want == 0.0 and out["drift_per_cycle_m"] == 0.0
        elif out["margin"] > 1.0:
            assert np.sign(out["drift_per_cycle_m"]) == np.sign(b - a) != 0.0
