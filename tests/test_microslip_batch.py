"""The block solver ``assess_batch`` (issue 28, item 1) against the per-case reference
``assess_assembly``: random blocks of two-node and strip cases over every verdict, lead-ins,
signed alpha_T, constant and in-phase forces, the force at the start or end, self-locking
sides, tolerances reached while marching and after, short lives; every stored field equal
(displacements to 1e-12 of the case's displacement scale), and the cases the block leaves
to the per-case path (code 2) refused or failed there."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from asperity.errors import AsperityError
from asperity.microslip import _batch_kernels as BK
from asperity.microslip.assembly import assembly_from_dict
from asperity.microslip.batch import NOT_HANDLED, PARAMS, assess_batch
from asperity.microslip.chains import TOL
from asperity.microslip.closed_forms import two_node_drift_per_cycle
from asperity.microslip.friction import Friction
from asperity.microslip.limits import ASYMMETRY, MARGIN, SAME_FRICTION, STIFFNESS_RATIO
from asperity.microslip.quasi_static import MAX_NODE_UPDATES, load_scale
from asperity.microslip.risk import assess_assembly
from asperity.microslip.verdict import VERDICTS

SURF = Path(__file__).resolve().parents[1] / "surfaces"
MAX_MARCHED = 12


def block(model, par, mup, mum, dT, F, *, substeps=1, force_at="uniform", cycles=None,
          tolerance=None, n=11):
    m = len(mup)
    cycles = np.full(m, 1e6) if cycles is None else np.asarray(cycles, float)
    tolerance = np.full(m, np.nan) if tolerance is None else np.asarray(tolerance, float)
    return {"model": model, "par": {k: np.asarray(v, float) for k, v in par.items()},
            "n": n, "mup": np.asarray(mup, float), "mum": np.asarray(mum, float),
            "dT": np.asarray(dT, float), "F": np.asarray(F, float), "substeps": substeps,
            "force_at": force_at, "cycles": cycles, "tolerance": tolerance}


def run_block(b, **kw):
    params = dict(b["par"], **({"n": b["n"]} if b["model"] == "strip" else {}))
    return assess_batch(b["model"], params, b["mup"], b["mum"], b["dT"], b["F"],
                        substeps=b["substeps"], force_at=b["force_at"], cycles=b["cycles"],
                        tolerance=b["tolerance"], max_marched=MAX_MARCHED, **kw)


def reference(b, j):
    """(the study's stored fields, displacement scale) of case j by the per-case path, or
    (the exception, None)."""
    a = {"model": b["model"], **{k: float(v[j]) for k, v in b["par"].items()}}
    if b["model"] == "strip":
        a["n"] = b["n"]
    tol = b["tolerance"][j]
    data = {"assembly": a, "loading": {"history": [float(x) for x in b["dT"][j]],
                                       "force_history": [float(x) for x in b["F"][j]],
                                       "substeps": b["substeps"], "force_at": b["force_at"]}}
    try:
        asm = assembly_from_dict(data, "case.toml")
        r = assess_assembly(asm, Friction(b["mup"][j], b["mum"][j], "explicit"),
                            cycles=b["cycles"][j], tolerance=None if math.isnan(tol) else tol,
                            max_marched=MAX_MARCHED)
    except AsperityError as exc:
        return exc, None
    return r, load_scale(r["_chain"], asm.loading)


def none(x):
    return None if x is None or not math.isfinite(x) else float(x)


def check_block(b, out=None, allow_not_handled=()):
    """Every case of the block equal to the per-case path; returns the verdicts seen."""
    out = run_block(b) if out is None else out
    seen = []
    for j in range(len(b["mup"])):
        r, scale = reference(b, j)
        code = int(out["code"][j])
        if scale is None:
            assert code == NOT_HANDLED, (j, r, {k: v[j] for k, v in out.items()})
            seen.append(type(r).__name__)
            continue
        if code == NOT_HANDLED:
            assert j in allow_not_handled, (j, r["verdict"])
            seen.append("not handled")
            continue
        v = VERDICTS[int(out["verdict"][j])]
        assert v == r["verdict"] and code == (1 if v == "slides-off" else 0), (j, v, r)
        seen.append(v)
        assert none(out["mu_plus"][j]) == r["mu_plus"] and \
            none(out["mu_minus"][j]) == r["mu_minus"]
        assert none(out["dT_c"][j]) == r["dT_c_K"] and out["margin"][j] == r["margin"], j
        assert none(out["cycles_to_tolerance"][j]) == none(r["cycles_to_tolerance"]), \
            (j, out["cycles_to_tolerance"][j], r["cycles_to_tolerance"])
        st = int(out["stabilised_at"][j])
        assert (None if st < 0 else st) == r["stabilised_at_cycle"], j
        ex = int(out["extrapolated"][j])
        assert (None if ex < 0 else bool(ex)) == r.get("extrapolated"), j
        for key, ref in (("drift_per_cycle", "drift_per_cycle_m"),
                         ("drift_after_cycles", "drift_after_cycles_m")):
            if r[ref] is None:
                assert math.isnan(out[key][j]), (j, key)
            else:
                assert abs(out[key][j] - r[ref]) <= 1e-12 * scale, (j, key, out[key][j], r[ref])
        if v != "slides-off":
            assert out["cycles_marched"][j] == r["cycles_marched"]
    return seen


def two_node_block(rng, m, *, lead=True, force="none", aT_sign=None, same=0.15, locked=0.1):
    """Random two-node cases around the SPEC.md 5 values: margins 0.2-4 (shakedown below
    1, ratchet above with mu+ != mu-, alternating slip with mu+ = mu-)."""
    k = 10 ** rng.uniform(5, 7, m)
    kt = 10 ** rng.uniform(5, 6.5, m)
    N = 10 ** rng.uniform(1, 3, m)
    l0 = rng.uniform(0.02, 0.3, m)
    sign = rng.choice([-1.0, 1.0], m) if aT_sign is None else np.full(m, aT_sign)
    aT = sign * 10 ** rng.uniform(-5.5, -4.5, m)
    mup = rng.uniform(0.1, 0.3, m)
    mum = rng.uniform(0.1, 0.3, m)
    eq = rng.random(m) < same
    mum[eq] = mup[eq] * (1 + rng.uniform(-1, 1, eq.sum()) * 0.5 * SAME_FRICTION)
    lk = rng.random(m) < locked
    mup[lk & (rng.random(m) < 0.5)] = np.inf
    mum[lk & ~np.isinf(mup)] = np.inf
    dTc = np.minimum(mup, mum) * N * (1 / k + 2 / kt) / (np.abs(aT) * l0)
    dTc = np.where(np.isfinite(dTc), dTc, 50.0)
    rng_T = np.minimum(2 * dTc * rng.uniform(0.2, 4.0, m), 3000.0)   # |dT| <= 5000 K
    lo = rng.uniform(-0.5, 0.3, m) * rng_T if lead else np.zeros(m)
    dT = np.column_stack([lo, lo + rng_T, lo])
    cap = 2 * N * np.minimum(np.where(np.isfinite(mup), mup, 10), np.where(np.isfinite(mum),
                                                                           mum, 10))
    if force == "constant":
        F = np.tile(rng.uniform(-0.6, 0.6, m)[:, None] * cap[:, None], (1, 3))
    elif force == "phase":
        f0, f1 = (rng.uniform(-0.5, 0.5, m) * cap for _ in range(2))
        F = np.column_stack([f0, f1, f0])
    elif force == "off":
        F = np.tile((rng.choice([-1, 1], m) * rng.uniform(1.01, 2, m) * cap)[:, None], (1, 3))
    else:
        F = np.zeros((m, 3))
    cycles = np.where(rng.random(m) < 0.25, rng.choice([1.0, 2.0, 2.5, 5.0, 11.0], m),
                      10 ** rng.uniform(3, 8, m))
    drift = np.abs(aT) * l0 * np.maximum(rng_T - 2 * dTc, 0)
    tol = np.where(rng.random(m) < 0.2, np.nan, drift * rng.choice([0.5, 3.0, 1e4], m) + 1e-9)
    par = {"k": k, "l0": l0, "alpha_T": aT, "k_t": kt, "N": N}
    return block("two-node", par, mup, mum, dT, F, cycles=cycles, tolerance=np.where(
        tol > 1e3, np.nan, tol))


def strip_block(rng, m, n=11, *, force="none", lead=True, locked=0.1):
    """Random strips around surfaces/bushing-strip.toml (lam l about 1-6)."""
    h = rng.uniform(1e-3, 4e-3, m)
    E = 10 ** rng.uniform(10.5, 11.5, m)
    ll = rng.uniform(0.01, 0.1, m)
    kt = (rng.uniform(1.0, 6.0, m) / ll) ** 2 * E * h
    p = 10 ** rng.uniform(5.5, 7, m)
    aT = rng.choice([-1.0, 1.0], m) * 10 ** rng.uniform(-5.5, -4.5, m)
    mup = rng.uniform(0.1, 0.3, m)
    mum = rng.uniform(0.1, 0.3, m)
    eq = rng.random(m) < 0.15
    mum[eq] = mup[eq]                       # symmetric: alternating slip, no drift
    lk = rng.random(m) < locked
    mup[lk] = np.inf
    lam = np.sqrt(kt / (E * h))
    dTc = np.minimum(mup, mum) * p * lam / (np.abs(aT) * kt * np.tanh(0.5 * lam * ll))
    rng_T = np.minimum(2 * dTc * rng.uniform(0.3, 8.0, m), 3000.0)
    lo = rng.uniform(-0.5, 0.3, m) * rng_T if lead else np.zeros(m)
    dT = np.column_stack([lo, lo + rng_T, lo])
    cap = p * ll * mum
    if force == "constant":
        F = np.tile(rng.uniform(-0.5, 0.5, m)[:, None] * cap[:, None], (1, 3))
    elif force == "phase":
        f0, f1 = (rng.uniform(-0.4, 0.4, m) * cap for _ in range(2))
        F = np.column_stack([f0, f1, f0])
    else:
        F = np.zeros((m, 3))
    cycles = np.where(rng.random(m) < 0.25, rng.choice([1.0, 3.0, 7.5], m),
                      10 ** rng.uniform(3, 7, m))
    tol = np.where(rng.random(m) < 0.3, np.nan, 10 ** rng.uniform(-8, -3, m))
    par = {"h": h, "E": E, "p": p, "l": ll, "k_t": kt, "alpha_T": aT}
    return block("strip", par, mup, mum, dT, F, cycles=cycles, tolerance=tol, n=n)


# ------------------------------------------------------------------------------ blocks

@pytest.mark.parametrize("force", ["none", "constant", "phase", "off"])
def test_two_node_blocks_equal_the_per_case_path(force):
    rng = np.random.default_rng(["none", "constant", "phase", "off"].index(force))
    b = two_node_block(rng, 60, force=force)
    out = run_block(b)
    seen = set(check_block(b, out))
    ok = out["code"] == 0
    ct, k = out["cycles_to_tolerance"][ok], out["cycles_marched"][ok]
    if force != "off":     # the block covers what it should
        assert (ct <= k).any() and (ct > k).any(), "tolerance reached marching and after"
        assert (out["extrapolated"][ok] == 0).any() and (out["extrapolated"][ok] == 1).any()
        assert (b["dT"][:, 0] < 0).any() and (b["dT"][:, 0] > 0).any()
        assert (b["par"]["alpha_T"] < 0).any() and np.isinf(b["mup"]).any()
    want = {"none": {"shakedown", "ratchet", "alternating-slip"}, "off": {"slides-off"},
            "constant": {"shakedown", "ratchet"}, "phase": {"shakedown", "ratchet"}}[force]
    assert want <= seen, seen


@pytest.mark.parametrize("force_at", ["start", "end"])
def test_two_node_force_at_an_end(force_at):
    b = two_node_block(np.random.default_rng(7), 40, force="phase")
    b["force_at"] = force_at
    assert {"shakedown", "ratchet"} <= set(check_block(b))


def test_self_locking_both_ways_never_slips():
    """mu+ = mu- = inf: dT_c = inf, margin 0, shakedown, whatever the force."""
    b = two_node_block(np.random.default_rng(8), 6, force="phase")
    b["mup"][:] = b["mum"][:] = np.inf
    out = run_block(b)
    assert np.isinf(out["dT_c"]).all() and (out["margin"] == 0).all()
    assert set(check_block(b, out)) == {"shakedown"}


def test_two_node_drift_is_the_closed_form():
    """A ratchet's drift per cycle from the block is SPEC.md 5's -alpha_T l0 (range - 2 dT_c)
    towards the smaller coefficient (an independent check of the block's numbers)."""
    rng = np.random.default_rng(3)
    b = two_node_block(rng, 40, lead=False, locked=0.0, same=0.0)
    b["cycles"][:] = 1e6                          # marched until stabilised
    out = run_block(b)
    p = b["par"]
    for j in range(40):
        want = two_node_drift_per_cycle(p["k"][j], p["k_t"][j], p["N"][j], b["mup"][j],
                                        b["mum"][j], p["alpha_T"][j], p["l0"][j], b["dT"][j, 0],
                                        b["dT"][j, 1])
        scale = abs(p["alpha_T"][j]) * p["l0"][j] * (b["dT"][j, 1] - b["dT"][j, 0])
        assert abs(out["drift_per_cycle"][j] - want) <= 1e-9 * scale, j
        assert out["verdict"][j] == (2 if want else 0)


@pytest.mark.parametrize("force", ["none", "constant", "phase"])
def test_strip_blocks_equal_the_per_case_path(force):
    rng = np.random.default_rng(10 + ["none", "constant", "phase"].index(force))
    b = strip_block(rng, 30, n=11, force=force)
    seen = set(check_block(b))
    assert {"shakedown", "ratchet", "alternating-slip"} <= seen, seen


def test_strip_force_at_the_start_and_a_longer_history():
    """Five breakpoints with two substeps, the force acting on the first node."""
    rng = np.random.default_rng(21)
    b = strip_block(rng, 20, n=8, force="phase")
    lo, hi = b["dT"][:, 0], b["dT"][:, 1]
    b["dT"] = np.column_stack([lo, hi, 0.5 * (lo + hi), hi, lo])
    b["F"] = np.column_stack([b["F"][:, 0], b["F"][:, 1], b["F"][:, 0], b["F"][:, 1],
                              b["F"][:, 0]])
    b["substeps"], b["force_at"] = 2, "start"
    check_block(b)


def test_bushing_strip_of_201_nodes():
    """The study's strip: surfaces/bushing-strip.toml's parameters, dT_max in [90, 140] K,
    mu+/mu- around 0.19."""
    rng = np.random.default_rng(5)
    m = 6
    base = {"h": 2.5e-3, "E": 1.1e11, "p": 5.0e6, "l": 0.04, "k_t": 1.0e13, "alpha_T": 6e-6}
    par = {k: np.full(m, v) for k, v in base.items()}
    dT = np.column_stack([np.zeros(m), rng.uniform(90, 140, m), np.zeros(m)])
    b = block("strip", par, rng.uniform(0.17, 0.21, m), rng.uniform(0.17, 0.21, m), dT,
              np.zeros((m, 3)), cycles=np.full(m, 1e6), tolerance=np.full(m, 1e-4), n=201)
    assert "ratchet" in check_block(b)


def test_a_strip_the_per_case_path_marches_in_pieces():
    """1200 nodes under a force in phase: a cycle of about 3e6 node-passes, which the
    per-case path marches in pieces of 1e6 and the block in one call -- the same state."""
    b = strip_block(np.random.default_rng(77), 3, n=1200, force="phase", locked=0.0)
    b["cycles"][:] = 1e6
    assert {"ratchet", "alternating-slip"} == set(check_block(b))


# ---------------------------------------------------------------- left to the per-case path

def test_cases_beyond_the_solvers_are_left_to_the_per_case_path():
    """Stiffness ratio, asymmetry and margin beyond what the chain solvers resolve: code 2,
    and the per-case path refuses them (check_block asserts it); good cases around them
    are solved."""
    b = two_node_block(np.random.default_rng(9), 8, lead=False, locked=0.0)
    p = b["par"]
    p["k"][1] = p["k_t"][1] * STIFFNESS_RATIO * 2          # elements too stiff
    p["k_t"][2] = p["k"][2] * STIFFNESS_RATIO * 2          # contacts too stiff
    b["mup"][3] = b["mum"][3] * ASYMMETRY * 1.5            # asymmetry
    dTc = min(b["mup"][4], b["mum"][4]) * p["N"][4] * (1 / p["k"][4] + 2 / p["k_t"][4]) / (
        abs(p["alpha_T"][4]) * p["l0"][4])
    b["dT"][4] = [0.0, min(2 * MARGIN * dTc * 1.5, 4999.0), 0.0]
    p["N"][4] = 1e-6
    out = run_block(b)
    assert list(out["code"][1:5]) == [NOT_HANDLED] * 4
    assert np.isnan(out["dT_c"][1:5]).all() and (out["verdict"][1:5] == -1).all()
    check_block(b, out)
    assert (out["code"][[0, 5, 6, 7]] != NOT_HANDLED).all()


def test_a_case_over_the_work_cap_is_left_to_the_per_case_path():
    b = strip_block(np.random.default_rng(4), 4, n=11)
    out = run_block(b, max_case_work=1.0)
    assert (out["code"] == NOT_HANDLED).all()
    check_block(b, out, allow_not_handled=range(4))


def test_kernel_constants_are_the_per_case_paths():
    assert (BK.STABILISED, BK.NO_DRIFT, BK.EVENTS_PER_NODE) == (
        TOL.stabilised, TOL.no_drift, TOL.max_events_per_node)
    assert (BK.STIFFNESS_RATIO, BK.ASYMMETRY, BK.MARGIN, BK.SAME_FRICTION,
            BK.MAX_NODE_UPDATES) == (STIFFNESS_RATIO, ASYMMETRY, MARGIN, SAME_FRICTION,
                                     MAX_NODE_UPDATES)
    assert VERDICTS[BK.SHAKEDOWN:BK.SLIDES_OFF + 1] == (
        "shakedown", "alternating-slip", "ratchet", "slides-off")


def test_numpy_sums_are_numpys():
    rng = np.random.default_rng(2)
    for n in (1, 7, 8, 9, 127, 128, 129, 200, 201, 1000, 4097):
        a = rng.standard_normal(n) * 10 ** rng.uniform(-3, 3, n)
        assert BK.np_sum(a, 0, n) == a.sum()


def test_shapes_and_names_are_checked_in_one_line():
    b = two_node_block(np.random.default_rng(1), 3)
    with pytest.raises(AsperityError, match="model must be one of two-node, strip"):
        assess_batch("three-node", {}, b["mup"], b["mum"], b["dT"], b["F"], substeps=1,
                     force_at="uniform", cycles=b["cycles"], tolerance=b["tolerance"])
    with pytest.raises(AsperityError, match=r"params.N missing"):
        assess_batch("two-node", {k: b["par"][k] for k in PARAMS["two-node"][:4]}, b["mup"],
                     b["mum"], b["dT"], b["F"], substeps=1, force_at="uniform",
                     cycles=b["cycles"], tolerance=b["tolerance"])
    with pytest.raises(AsperityError, match=r"F must be one row of breakpoints per case"):
        assess_batch("two-node", b["par"], b["mup"], b["mum"], b["dT"], b["F"][:, :2],
                     substeps=1, force_at="uniform", cycles=b["cycles"],
                     tolerance=b["tolerance"])


def test_risk_columns_are_what_the_study_stores():
    """risk_columns against study.cases.evaluate (the store's row of a case) on cases with
    explicit finite coefficients (an assembly file's), every verdict but slides-off and a
    slide-off block."""
    from asperity.microslip.batch import risk_columns
    from asperity.study.cases import OUTPUTS, evaluate
    for force in ("none", "off"):
        b = two_node_block(np.random.default_rng(31), 25, force=force, locked=0.0)
        b["par"]["k"][0], b["par"]["k_t"][0] = 1e15, 1e5        # code 2: None
        cols = risk_columns(run_block(b))
        assert set(cols) == {c for c, _ in OUTPUTS["risk"]}
        for j in range(25):
            a = {"model": "two-node", **{k: float(v[j]) for k, v in b["par"].items()}}
            lo = {"history": b["dT"][j].tolist(), "force_history": b["F"][j].tolist()}
            fr = {"mu_plus": float(b["mup"][j]), "mu_minus": float(b["mum"][j])}
            tol = b["tolerance"][j]
            spec = {"stages": ["risk"], "texture": None, "assembly_path": "case.toml",
                    "assembly": {"assembly": a, "friction": fr, "loading": lo},
                    "cycles": float(b["cycles"][j]), "max_marched": MAX_MARCHED,
                    "tolerance": None if math.isnan(tol) else float(tol)}
            row = {k: v[j] for k, v in cols.items()}
            if j == 0:
                assert set(row.values()) == {None}
                with pytest.raises(AsperityError, match="times stiffer"):
                    evaluate(spec, {})
                continue
            want = evaluate(spec, {})
            dT = b["dT"][j]
            scale = abs(b["par"]["alpha_T"][j]) * b["par"]["l0"][j] * max(np.ptp(dT),
                                                                          np.abs(dT).max())
            for k in ("drift_per_cycle_m", "drift_after_cycles_m"):     # load_scale's
                if want[k] is not None:
                    assert abs(row[k] - want[k]) <= 1e-12 * scale, (j, k)
                    row[k] = want[k]
            assert row == want, j


def test_the_work_cap_counts_a_changing_force_per_node_squared():
    """quasi_static.march_cost: a segment whose force changes costs about n^2 node-passes
    (event by event), one whose force is constant about 10 n: with a cap between the two
    the strip under constant force is solved here and the one under a force in phase is
    left to the per-case path."""
    rng = np.random.default_rng(9)
    n = 201
    for force, code in (("constant", {0, 1}), ("phase", {NOT_HANDLED})):
        b = strip_block(rng, 3, n=n, force=force, lead=False, locked=0.0)
        b["cycles"] = np.full(3, 1e6)
        cap = 4.0 * MAX_MARCHED * (10 * 2 * n + 2000)          # constant: ~10 n a segment
        assert 2 * n * n * MAX_MARCHED > cap                      # in phase: ~n^2
        out = run_block(b, max_case_work=cap)
        assert set(out["code"].tolist()) <= code, (force, out["code"])


def test_the_model_is_read_by_value_not_identity():
    """A model name built at run time (read from a file, say) is the same model."""
    b = strip_block(np.random.default_rng(10), 4, n=7)
    name = "".join(["st", "rip"])  # noqa: FLY002 - built at run time, not interned
    params = dict(b["par"], n=7)
    args = (params, b["mup"], b["mum"], b["dT"], b["F"])
    kw = {"substeps": 1, "force_at": "uniform", "cycles": b["cycles"],
          "tolerance": b["tolerance"], "max_marched": MAX_MARCHED}
    a, c = assess_batch(name, *args, **kw), assess_batch("strip", *args, **kw)
    for key in a:
        assert np.array_equal(a[key], c[key], equal_nan=True), key
