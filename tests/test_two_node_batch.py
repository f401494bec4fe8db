"""The two-node closed form over a block (asperity.microslip.two_node_batch) against the
reference, the per-case exact solver (assess_assembly), case by case: every verdict, the
lead-in (dT_min != 0), both signs of alpha_T, constant and in-phase forces on every
force_at, substeps, self-locking sides, tolerances reached within the cycles marched and
after, lives shorter than two cycles.  Discrete outputs identical, numbers within 1e-12 of
their scale."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.microslip.assembly import assembly_from_dict
from asperity.microslip.friction import Friction
from asperity.microslip.risk import assess_assembly
from asperity.microslip.two_node_batch import two_node_closed
from asperity.microslip.verdict import VERDICTS


def random_block(seed: int, m: int, forces: str = "mixed"):
    rng = np.random.default_rng(seed)
    k = 10 ** rng.uniform(4, 8, m)
    kt = k * 10 ** rng.uniform(-2, 2, m)
    l0 = 10 ** rng.uniform(-3, 0, m)
    aT = rng.choice([-1, 1], m) * 10 ** rng.uniform(-6, -4, m)
    mp = rng.uniform(0.05, 0.4, m)
    mm = rng.uniform(0.05, 0.4, m)
    same = rng.random(m) < 0.1
    mm[same] = mp[same]
    locked = rng.random(m) < 0.05
    mp[locked] = np.inf
    # N so that dT_c is 5 to 500 K (inside the dT range)
    N = rng.uniform(5, 500, m) * abs(aT) * l0 / (np.minimum(mp, mm) * (1 / k + 2 / kt))
    dTc = np.minimum(mp, mm) * N * (1 / k + 2 / kt) / (abs(aT) * l0)
    kind = {"thermal": np.zeros(m, int), "mixed": rng.integers(0, 3, m)}[forces]
    dmin = np.where(rng.random(m) < 0.5, 0.0, rng.uniform(-1, 1, m) * dTc)
    dmax = dmin + rng.uniform(0, 4, m) * dTc
    cap = 2 * np.minimum(mp, mm) * N
    f0 = np.where(kind > 0, rng.uniform(-1.1, 1.1, m) * cap, 0.0)
    f1 = np.where(kind == 2, rng.uniform(-1.1, 1.1, m) * cap, f0)
    cycles = np.where(rng.random(m) < 0.2, rng.integers(1, 5, m).astype(float),
                      10 ** rng.uniform(0, 7, m))
    tol = np.where(rng.random(m) < 0.5, np.nan, 10 ** rng.uniform(-9, -2, m))
    return {"params": {"k": k, "l0": l0, "alpha_T": aT, "k_t": kt, "N": N},
            "mu_plus": mp, "mu_minus": mm, "dT": np.column_stack([dmin, dmax, dmin]),
            "F": np.column_stack([f0, f1, f0]), "cycles": cycles, "tolerance": tol}


def reference(b: dict, c: int, force_at: str, substeps: int) -> dict:
    p = {k: float(v[c]) for k, v in b["params"].items()}
    lo = {"dT_min": float(b["dT"][c, 0]), "dT_max": float(b["dT"][c, 1]),
          "force_min": float(b["F"][c, 0]), "force_max": float(b["F"][c, 1]),
          "force_at": force_at, "substeps": substeps}
    asm = assembly_from_dict({"assembly": {"model": "two-node", **p}, "loading": lo}, "x.toml")
    tol = b["tolerance"][c]
    return assess_assembly(asm, Friction(float(b["mu_plus"][c]), float(b["mu_minus"][c]),
                                         "explicit"), cycles=float(b["cycles"][c]),
                           tolerance=None if math.isnan(tol) else float(tol))


def compare(b: dict, res: dict, c: int, r: dict) -> list:
    errs = []
    v = VERDICTS[int(res["verdict"][c])]
    if v != r["verdict"]:
        return [("verdict", v, r["verdict"])]
    dmin, dmax = b["dT"][c, 0], b["dT"][c, 1]
    scale = abs(b["params"]["alpha_T"][c]) * b["params"]["l0"][c] * max(
        dmax - dmin, abs(dmin), abs(dmax))
    for key, name in (("mu_plus", "mu_plus"), ("mu_minus", "mu_minus"), ("dT_c_K", "dT_c"),
                      ("margin", "margin")):
        a, x = res[name][c], r[key]
        if x is None:
            if math.isfinite(a) and not (key == "margin" and a == 0.0):
                errs.append((key, a, x))
        elif abs(a - x) > 1e-12 * abs(x):
            errs.append((key, a, x))
    if v == "slides-off":
        return errs
    for key, name in (("drift_per_cycle_m", "drift_per_cycle"),
                      ("drift_after_cycles_m", "drift_after_cycles")):
        a, x = res[name][c], r[key]
        if abs(a - x) > 1e-12 * scale * max(1.0, b["cycles"][c]):
            errs.append((key, a, x))
    st = r["stabilised_at_cycle"]
    if (-1 if st is None else st) != res["stabilised_at"][c]:
        errs.append(("stabilised_at_cycle", res["stabilised_at"][c], st))
    ct, a = r["cycles_to_tolerance"], res["cycles_to_tolerance"][c]
    if not ((ct is None and math.isnan(a)) or (ct is not None and ct == a)):
        errs.append(("cycles_to_tolerance", a, ct))
    if bool(res["extrapolated"][c]) != bool(r["extrapolated"]):
        errs.append(("extrapolated", res["extrapolated"][c], r["extrapolated"]))
    return errs


@pytest.mark.parametrize("seed, force_at, substeps", [(1, "uniform", 1), (2, "start", 1),
                                                     (3, "end", 2), (4, "uniform", 3)])
def test_block_equals_the_exact_solver_case_by_case(seed, force_at, substeps):
    b = random_block(seed, 300)
    kw = {k: b[k] for k in ("cycles", "tolerance")}
    res = two_node_closed(b["params"], b["mu_plus"], b["mu_minus"], b["dT"], b["F"],
                          substeps=substeps, force_at=force_at, **kw)
    seen = set()
    covered = 0
    for c in range(300):
        if res["code"][c] == 2:
            continue
        covered += 1
        r = reference(b, c, force_at, substeps)
        assert compare(b, res, c, r) == [], (c, compare(b, res, c, r))
        seen.add(r["verdict"])
    assert seen == set(VERDICTS)              # every verdict met
    assert covered >= 270                     # the closed form answers nearly every case


def test_not_covered_cases_are_the_ties_and_refusals():
    """A case the block leaves to the exact path is one where mu+ = mu- under no force
    (the split of the slip between the nodes is the march's choice), a refusal, or a
    decision at a threshold: never a case the block could answer."""
    b = random_block(5, 300, "thermal")
    res = two_node_closed(b["params"], b["mu_plus"], b["mu_minus"], b["dT"], b["F"],
                          substeps=1, force_at="uniform", cycles=b["cycles"],
                          tolerance=b["tolerance"])
    left = np.flatnonzero(res["code"] == 2)
    assert left.size > 0
    same = b["mu_plus"] == b["mu_minus"]
    dT_c = (np.minimum(b["mu_plus"], b["mu_minus"]) * b["params"]["N"]
            * (1 / b["params"]["k"] + 2 / b["params"]["k_t"])
            / (abs(b["params"]["alpha_T"]) * b["params"]["l0"]))
    slips = np.abs(b["dT"]).max(axis=1) > dT_c          # a slider slips somewhere
    assert np.all(same[left] & slips[left])               # symmetric sliders that slip
    for c in left[:5]:                                      # the exact path answers them
        assert reference(b, c, "uniform", 1)["verdict"] in VERDICTS


def test_stabilised_drift_is_the_spec_closed_form():
    """SPEC.md 5: above the threshold the drift per cycle is -|alpha_T| l0 (dT range -
    2 dT_c) towards the smaller coefficient, zero below it."""
    from asperity.microslip.closed_forms import two_node_drift_per_cycle
    b = random_block(6, 400, "thermal")
    res = two_node_closed(b["params"], b["mu_plus"], b["mu_minus"], b["dT"], b["F"],
                          substeps=1, force_at="uniform", cycles=np.full(400, 1e6),
                          tolerance=b["tolerance"])
    p = b["params"]
    n = 0
    for c in np.flatnonzero(res["code"] == 0):
        want = two_node_drift_per_cycle(p["k"][c], p["k_t"][c], p["N"][c], b["mu_plus"][c],
                                        b["mu_minus"][c], p["alpha_T"][c], p["l0"][c],
                                        b["dT"][c, 0], b["dT"][c, 1])
        scale = abs(p["alpha_T"][c]) * p["l0"][c] * (b["dT"][c, 1] - b["dT"][c, 0])
        assert abs(res["drift_per_cycle"][c] - want) <= 1e-9 * scale + 1e-8 * scale, c
        n += want != 0.0
    assert n > 100


def test_the_force_crossing_cp_minus_cm_splits_the_slip_between_the_nodes():
    """A force in phase that crosses cp - cm inside a segment: the slider that slips
    changes there (a case built for it, with its drift from the exact solver)."""
    b = random_block(7, 1, "thermal")
    p = b["params"]
    p.update({"k": np.array([1e6]), "k_t": np.array([5e5]), "N": np.array([100.0]),
              "l0": np.array([0.1]), "alpha_T": np.array([1.2e-5])})
    b.update({"mu_plus": np.array([0.2]), "mu_minus": np.array([0.1]),
              "dT": np.array([[0.0, 125.0, 0.0]]), "F": np.array([[0.0, 25.0, 0.0]]),
              "cycles": np.array([1e6]), "tolerance": np.array([1e-3])})
    res = two_node_closed(p, b["mu_plus"], b["mu_minus"], b["dT"], b["F"], substeps=1,
                          force_at="uniform", cycles=b["cycles"], tolerance=b["tolerance"])
    assert res["code"][0] == 0
    r = reference(b, 0, "uniform", 1)
    assert compare(b, res, 0, r) == []
    assert r["verdict"] != "shakedown"            # the sliders slip in every cycle


def spec_block(margins, lead_in=0.0, mp=0.2, mm=0.1, cycles=1e6, tolerance=np.nan):
    """The SPEC.md two-node assembly (dT_c = 41.67 K) at the given margins."""
    m = len(margins)
    one = np.ones(m)
    dT_c = min(mp, mm) * 100.0 * (1 / 1e6 + 2 / 5e5) / (1.2e-5 * 0.1)
    lo = lead_in * one
    hi = lo + 2.0 * dT_c * np.asarray(margins, dtype=float)
    return {"params": {"k": 1e6 * one, "l0": 0.1 * one, "alpha_T": 1.2e-5 * one,
                       "k_t": 5e5 * one, "N": 100.0 * one},
            "mu_plus": mp * one, "mu_minus": mm * one, "dT": np.column_stack([lo, hi, lo]),
            "F": np.zeros((m, 3)), "cycles": cycles * one, "tolerance": tolerance * one}


@pytest.mark.parametrize("lead_in", [0.0, -7.5, 20.0])
def test_margins_at_the_threshold_equal_the_exact_solver_or_are_left_to_it(lead_in):
    """Margins 1 +- 1e-4 ... 1e-12 and exactly 1 (the drift per cycle from 1e-4 of the
    thermal scale down to its rounding, across the no-drift threshold 1e-8): every case the
    closed form answers equals the exact solver, decisions included."""
    deltas = [s * d for d in (1e-4, 1e-6, 1e-7, 1e-8, 2e-8, 7e-9, 5e-9, 1e-9, 1e-10, 1e-12)
              for s in (1, -1)]
    b = spec_block([1.0 + d for d in deltas] + [1.0], lead_in, tolerance=3.0712345678e-3)
    res = two_node_closed(b["params"], b["mu_plus"], b["mu_minus"], b["dT"], b["F"],
                          substeps=1, force_at="uniform", cycles=b["cycles"],
                          tolerance=b["tolerance"])
    answered = 0
    for c in range(len(deltas) + 1):
        r = reference(b, c, "uniform", 1)
        if res["code"][c] == 2:
            continue
        answered += 1
        assert compare(b, res, c, r) == [], (c, compare(b, res, c, r))
    assert answered >= len(deltas) - 2       # the ones at the no-drift threshold left


def test_equal_coefficients_under_thermal_cycles_are_left_to_the_exact_path():
    """mu+ = mu- (or within 1e-12 of each other) and a slip: which node slips is the
    march's choice, so the closed form answers none of them; below dT_c it answers."""
    b = spec_block([0.2, 0.45, 0.6, 1.5, 3.0], mp=0.15, mm=0.15)
    b["mu_minus"] = b["mu_minus"] * (1 + np.array([0, 0, 5e-13, 0, -5e-13]))
    res = two_node_closed(b["params"], b["mu_plus"], b["mu_minus"], b["dT"], b["F"],
                          substeps=1, force_at="uniform", cycles=b["cycles"],
                          tolerance=b["tolerance"])
    assert res["code"].tolist() == [0, 0, 2, 2, 2]
    assert res["mu_minus"][0] == res["mu_plus"][0]
    for c in (0, 1):
        assert compare(b, res, c, reference(b, c, "uniform", 1)) == []


def test_kernel_constants_are_the_limits():
    from asperity.microslip import _two_node_kernels as K
    from asperity.microslip import limits as L
    assert (K.SAME_FRICTION, K.STIFFNESS_RATIO, K.ASYMMETRY, K.MARGIN) == (
        L.SAME_FRICTION, L.STIFFNESS_RATIO, L.ASYMMETRY, L.MARGIN)
