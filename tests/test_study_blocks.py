"""The block path of risk studies (asperity.study.blocks) against the per-case path, the
reference: whole blocks of two-node cases (closed form) and of cases whose texture, friction,
assembly numbers and loading vary, with every output equal case by case (discrete outputs
identically, numbers to 1e-12 of their scale); bad values in a block named per case exactly
as the per-case path names them while the good cases are answered; the store's solved_by
column; a SIGKILL mid-study loses at most the blocks in flight and the rerun stores every
case once."""
from __future__ import annotations

import math
import signal
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hostile import package_env

from asperity.study.blocks import BlockResult, plan
from asperity.study.cases import run_batch, run_case
from asperity.study.spec import load_study

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"

TWO_NODE = """
[study]
kind = "monte-carlo"
samples = 400
seed = 11
assembly = "SURF/two-node-spec.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 20.0, high = 200.0 }
"loading.dT_min" = { distribution = "uniform", low = -30.0, high = 10.0 }
"assembly.N" = { distribution = "lognormal", median = 100.0, sigma = 0.3 }
"assembly.alpha_T" = { distribution = "uniform", low = -2e-5, high = 3e-5 }
"friction.mu_plus" = { distribution = "uniform", low = 0.05, high = 0.3 }
"loading.cycles" = { distribution = "lognormal", median = 1e3, sigma = 3.0 }
"loading.tolerance" = { distribution = "lognormal", median = 1e-4, sigma = 2.0 }
"""
FORCES = """
[study]
kind = "latin-hypercube"
samples = 300
seed = 12
assembly = "ASM"
[parameters]
"loading.force_min" = { distribution = "uniform", low = -30.0, high = 30.0 }
"loading.force_max" = { distribution = "uniform", low = -30.0, high = 45.0 }
"loading.dT_max" = { distribution = "uniform", low = 0.0, high = 150.0 }
"assembly.k_t" = { distribution = "lognormal", median = 5e5, sigma = 1.0 }
"""
TEXTURE = """
[study]
kind = "monte-carlo"
samples = 300
seed = 13
texture = "SURF/wedge-asymmetric.toml"
assembly = "SURF/two-node-spec.toml"
[parameters]
"texture.alpha_deg" = { distribution = "normal", mean = 30.0, sd = 8.0 }
"texture.mu_alpha" = { distribution = "uniform", low = 0.05, high = 0.3 }
"loading.dT_max" = { distribution = "uniform", low = 20.0, high = 200.0 }
"""
STRIP = """
[study]
kind = "monte-carlo"
samples = 150
seed = 15
assembly = "SURF/bushing-strip.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 0.5, high = 6.0 }
"loading.dT_min" = { distribution = "uniform", low = -2.5, high = 0.4 }
"assembly.E" = { distribution = "lognormal", median = 1.1e11, sigma = 0.2 }
"""
BAD = """
[study]
kind = "monte-carlo"
samples = 200
seed = 14
assembly = "SURF/two-node-spec.toml"
[parameters]
"assembly.N" = { distribution = "normal", mean = 20.0, sd = 40.0 }
"loading.dT_max" = { distribution = "normal", mean = 3000.0, sd = 1500.0 }
"friction.mu_plus" = { distribution = "normal", mean = 0.2, sd = 0.1 }
"""


def study(tmp_path: Path, body: str, name: str = "s.toml"):
    asm = tmp_path / "forces.toml"
    asm.write_text((SURF / "two-node-spec.toml").read_text().replace(
        "dT_max = 125.0", "dT_max = 125.0\nforce_min = 0.0\nforce_max = 10.0\n"
                          "force_at = \"start\""))
    p = tmp_path / name
    p.write_text(body.replace("SURF", str(SURF)).replace("ASM", str(asm)))
    return load_study(p)


def per_case(st) -> list:
    X, names = st.matrix(), st.parameter_names
    return [run_case(st.spec, {n: float(v) for n, v in zip(names, X[i])})
            for i in range(st.n_cases)]


def assert_same(block, ref, scale_of=lambda out: 1e-9):
    assert isinstance(block, BlockResult)
    for (cid, status, msg, _, out), (s2, m2, _, o2) in zip(block, ref):
        assert (status, msg) == (s2, m2), cid
        assert set(out) - {"solved_by"} == set(o2) - {"solved_by"}, cid
        for k, v in o2.items():
            w = out[k]
            if k == "solved_by" or not isinstance(v, float) or not isinstance(w, float):
                assert w == v or k == "solved_by", (cid, k, w, v)
                continue
            scale = abs(v) if k in ("mu_plus", "mu_minus", "dT_c_K", "margin") else \
                max(abs(v), scale_of(o2))
            assert abs(w - v) <= 1e-12 * scale, (cid, k, w, v)


@pytest.mark.parametrize("body", [TWO_NODE, FORCES, TEXTURE, STRIP],
                         ids=["two-node", "forces", "texture", "strip"])
def test_a_block_equals_the_per_case_path_case_by_case(tmp_path, body):
    st = study(tmp_path, body)
    assert plan(st.spec, st.parameter_names) is None
    X = st.matrix()
    block = run_batch(st.spec, st.parameter_names, np.arange(st.n_cases), X)
    ref = per_case(st)
    # the displacement scale of a case: alpha_T l0 dT ~ 1e-4 m here
    assert_same(block, ref, lambda o: 1e-4)
    by = [o.get("solved_by") for *_, o in block]
    verdicts = {o["verdict"] for *_, o in ref if "verdict" in o}
    if body is STRIP:             # shakedown below dT_c in closed form, the rest exact
        assert 0.2 * st.n_cases <= by.count("closed-form") <= 0.8 * st.n_cases
        assert verdicts >= {"shakedown", "alternating-slip"}
    else:
        assert by.count("closed-form") >= 0.9 * st.n_cases
        assert verdicts >= {"shakedown", "ratchet"}


def test_bad_values_in_a_block_are_named_per_case_and_the_others_answered(tmp_path):
    st = study(tmp_path, BAD)
    X = st.matrix()
    block = run_batch(st.spec, st.parameter_names, np.arange(st.n_cases), X)
    ref = per_case(st)
    assert_same(block, ref, lambda o: 1e-4)
    failed = [m for _, s, m, *_ in block if s == "failed"]
    assert 20 <= len(failed) <= 180                # some of each, one line each
    assert any("assembly.N must be in" in m for m in failed)
    assert any("dT_max must be in" in m for m in failed)
    assert all("\n" not in m for m in failed)


def test_studies_the_block_path_does_not_take_run_per_case(tmp_path):
    st = study(tmp_path, TWO_NODE.replace('"loading.dT_max"', '"assembly.contact_area" = '
                                         '{ distribution = "uniform", low = 1e-4, high = '
                                         '2e-4 }\n"loading.dT_max"'))
    assert plan(st.spec, st.parameter_names) == "assembly.contact_area varies"
    res = run_batch(st.spec, st.parameter_names, np.arange(20), st.matrix()[:20])
    assert isinstance(res, list) and {o["solved_by"] for *_, o in res} == {"exact"}


def test_a_study_stores_which_path_solved_each_case(tmp_path):
    from asperity.study.run import run_study_file
    p = tmp_path / "s.toml"
    p.write_text(TWO_NODE.replace("SURF", str(SURF)).replace("samples = 400",
                                                             "samples = 3000"))
    s = run_study_file(p, tmp_path / "out", workers=0)
    # loading.cycles below 1 (its lognormal's tail) is refused, one line a case
    assert s["completed"] + s["failed"] == 3000 and s["failed"] < 100
    con = sqlite3.connect(tmp_path / "out" / "study.sqlite")
    by = dict(con.execute("SELECT solved_by, COUNT(*) FROM cases WHERE status = 'ok' "
                          "GROUP BY solved_by"))
    msgs = {m for (m,) in con.execute("SELECT message FROM cases WHERE status != 'ok'")}
    con.close()
    assert by.get("closed-form", 0) >= 2700 and sum(by.values()) == s["completed"]
    assert s["solved_by"] == by
    assert all("loading.cycles must be in [1, 1e+15]" in m for m in msgs), msgs


@pytest.mark.slow
def test_sigkill_during_blocks_then_rerun_stores_every_case_once(tmp_path):
    p = tmp_path / "s.toml"
    n = 300_000
    p.write_text(TWO_NODE.replace("SURF", str(SURF)).replace("samples = 400",
                                                             f"samples = {n}"))
    out = tmp_path / "out"
    argv = [sys.executable, "-m", "asperity", "study", str(p), "-o", str(out), "--workers",
            "0", "--batch-size", "5000", "-q"]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            env=package_env())
    from test_study_engine import count, wait_for
    wait_for(lambda: count(out) >= 10_000 or proc.poll() is not None, timeout=300)
    assert proc.poll() is None, proc.communicate()
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    n_killed = count(out)
    assert 10_000 <= n_killed < n and n_killed % 5000 == 0      # whole blocks only
    from asperity.study.run import run_study_file
    s = run_study_file(p, out, workers=0)
    assert s["run"]["ran"] == n - n_killed and s["completed"] + s["failed"] == n
    con = sqlite3.connect(out / "study.sqlite")
    ids = [r[0] for r in con.execute("SELECT case_id FROM cases ORDER BY case_id")]
    sample = con.execute("SELECT case_id, verdict, drift_per_cycle_m FROM cases WHERE "
                         "case_id % 997 = 0 ORDER BY case_id").fetchall()
    con.close()
    assert ids == list(range(n))
    st = load_study(p)
    X, names = st.matrix(), st.parameter_names
    for cid, verdict, drift in sample:
        _, _, _, o = run_case(st.spec, {k: float(v) for k, v in zip(names, X[cid])})
        assert o.get("verdict") == verdict
        assert (drift is None) == (o.get("drift_per_cycle_m") is None)
        assert drift is None or math.isclose(drift, o["drift_per_cycle_m"], rel_tol=1e-12,
                                             abs_tol=1e-16)


def test_cases_the_closed_form_leaves_go_to_the_exact_block_solver(tmp_path):
    """mu+ = mu- under thermal cycles beyond dT_c (the split of the slip between the nodes
    is the march's choice): the exact block solver answers, as the per-case path does."""
    body = """
[study]
kind = "grid"
assembly = "SURF/two-node-spec.toml"
[parameters]
"friction.mu_plus" = { values = [0.05, 0.1, 0.2] }
"loading.dT_max" = { values = [20.0, 60.0, 100.0, 160.0] }
"""
    st = study(tmp_path, body)
    block = run_batch(st.spec, st.parameter_names, np.arange(st.n_cases), st.matrix())
    assert_same(block, per_case(st), lambda o: 1e-4)
    by = {(round(x[0], 3), x[1]): o["solved_by"] for x, (*_, o) in zip(st.matrix(), block)}
    assert by[(0.1, 160.0)] == "exact" and by[(0.2, 160.0)] == "closed-form"


VARIANTS = {
    # the study's own cycles and tolerance override the file's (the command line's path)
    "study-cycles": ('cycles = 5e4\ntolerance = 2e-5\n', "",
                     ('"loading.dT_max" = { distribution = "uniform", low = 60.0, '
                     'high = 200.0 }')),
    # force_min alone: a constant force (force_max follows it)
    "force-min-only": ("", 'force_min = 5.0\n',
                       ('"loading.force_min" = { distribution = "uniform", low = -25.0, '
                       'high = 35.0 }\n"loading.dT_max" = { distribution = "uniform", '
                       'low = 0.0, high = 150.0 }')),
    # a constant force over a five-point history
    "history-force": ("", 'history = [0.0, 90.0, 30.0, 120.0, 0.0]\nforce = 1.0\n',
                      ('"loading.force" = { distribution = "uniform", low = -30.0, '
                      'high = 30.0 }')),
    # a study's texture replaces the file's explicit coefficients (still checked)
    "texture-over-explicit": ('texture = "SURF/wedge-asymmetric.toml"\n', "",
                              ('"friction.mu_plus" = { distribution = "uniform", low = 0.05, '
                              'high = 0.3 }\n"loading.dT_max" = { distribution = '
                              '"uniform", low = 20.0, high = 200.0 }')),
    # explicit coefficients across the file's limit of 100: above it refused per case
    "mu-beyond-the-file": ("", "", ('"friction.mu_minus" = { distribution = "uniform", '
                                   'low = 50.0, high = 150.0 }\n"assembly.N" = { '
                                   'distribution = "uniform", low = 1.0, high = 2.0 }')),
}


@pytest.mark.parametrize("name", list(VARIANTS))
def test_options_combined_equal_the_per_case_path(tmp_path, name):
    study_extra, loading, params = VARIANTS[name]
    asm = (SURF / "two-node-spec.toml").read_text()
    if "history" in loading:
        asm = asm.replace("dT_min = 0.0\ndT_max = 125.0      # 3 dT_c\n", "")
    asm = asm.replace("[loading]\n", "[loading]\n" + loading)
    (tmp_path / "a.toml").write_text(asm)
    body = (f'[study]\nkind = "monte-carlo"\nsamples = 200\nseed = 21\n{study_extra}'
            f'assembly = "{tmp_path / "a.toml"}"\n[parameters]\n{params}\n')
    st = study(tmp_path, body)
    assert plan(st.spec, st.parameter_names) is None
    block = run_batch(st.spec, st.parameter_names, np.arange(st.n_cases), st.matrix())
    ref = per_case(st)
    assert_same(block, ref, lambda o: 1e-4)
    statuses = {s for _, s, *_ in block}
    assert statuses == ({"ok", "failed"} if name == "mu-beyond-the-file" else {"ok"})


def test_the_study_benchmark_reports_each_models_rates_paths_and_whole_study(monkeypatch):
    """asperity bench --only study on tiny studies: every figure present and consistent
    (no speed asserted: speed targets live in the benchmark's output)."""
    from asperity.study import bench
    from asperity.study.bench import bench_study, format_study
    # this checkout's surfaces/ (a copy of the package, as the mutation runs make, sits apart)
    monkeypatch.setattr(bench, "ROOT", ROOT)
    out = bench_study(workers=2, n_two=400, n_strip=60, n_scans=2, serial_seconds=0.2)
    assert set(out["cases"]) == {"two-node risk", "201-node strip risk",
                                 "derive of a 256^2 scan"}
    for label, r in out["cases"].items():
        assert sum(r["solved_by"].values()) == r["cases"], label
        assert r["minutes_per_1e6_cases"] == pytest.approx(1e6 / r["engine_cases_per_s"] / 60)
        assert r["speedup"] == pytest.approx(r["engine_cases_per_s"] / r["serial_cases_per_s"])
        assert 0 < r["loop_s"] < r["study_s"] and r["startup_s"] > 0
    assert out["cases"]["two-node risk"]["solved_by"] == {"closed-form": 400}
    assert out["cases"]["derive of a 256^2 scan"]["serial_cases_per_s"] == \
        out["cases"]["derive of a 256^2 scan"]["per_case_cases_per_s"]
    text = format_study(out)
    assert "solved by: closed-form 400" in text and "a 1e6-case study" in text
