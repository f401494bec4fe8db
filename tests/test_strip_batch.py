"""The discrete strip's closed forms over a block (asperity.microslip.strip_batch): its
elastic limit against the chain's (elastic_limit, a linear solve) and the continuum's
(closed_forms.strip_dT_c) as the nodes grow, and the shakedown test against the exact
solver case by case (every stored field), with the cases at the limit left to it."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.microslip.assembly import assembly_from_dict
from asperity.microslip.batch import assess_batch
from asperity.microslip.chains import elastic_limit, strip_chain
from asperity.microslip.closed_forms import strip_dT_c
from asperity.microslip.friction import Friction
from asperity.microslip.risk import assess_assembly
from asperity.microslip.strip_batch import strip_dT_c_block, strip_shakedown


def strips(seed: int, m: int):
    rng = np.random.default_rng(seed)
    p = {"h": 10 ** rng.uniform(-4, -2, m), "E": 10 ** rng.uniform(9, 12, m),
         "p": 10 ** rng.uniform(4, 8, m), "l": 10 ** rng.uniform(-3, 0, m),
         "k_t": 10 ** rng.uniform(10, 15, m),
         "alpha_T": rng.choice([-1.0, 1.0], m) * 10 ** rng.uniform(-6, -4, m)}
    return p, rng.uniform(0.05, 0.4, m), rng.uniform(0.05, 0.4, m)


@pytest.mark.parametrize("n", [2, 3, 10, 201, 20_001])
def test_elastic_limit_equals_the_chains_linear_solve(n):
    p, mp, mm = strips(n, 60)
    got = strip_dT_c_block({**p, "n": n}, mp, mm)
    checked = 0
    for c in range(60):
        try:
            chain = strip_chain(*(p[k][c] for k in ("h", "E", "p", "l", "k_t", "alpha_T")),
                                n, mp[c], mm[c])
        except Exception:          # noqa: BLE001, S112 - a chain beyond the stiffness ratio
            continue
        assert got[c] == pytest.approx(elastic_limit(chain), rel=1e-12), c
        checked += 1
    assert checked >= 20


def test_elastic_limit_tends_to_the_continuum_and_is_inf_when_self_locking():
    p = {"h": 2.5e-3, "E": 1.1e11, "p": 5e6, "l": 0.04, "k_t": 1e13, "alpha_T": -6e-6}
    cont = strip_dT_c(*(p[k] for k in ("h", "E", "p", "l", "k_t")), 0.2, 0.1, p["alpha_T"])
    errs = [abs(strip_dT_c_block({k: [v] for k, v in p.items()} | {"n": n}, [0.2], [0.1])[0]
                / cont - 1) for n in (11, 101, 1001)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-4          # converges, O(dx^2)
    assert errs[1] / errs[2] == pytest.approx(100.0, rel=0.05)
    inf = strip_dT_c_block({k: [v] for k, v in p.items()} | {"n": 201}, [math.inf], [math.inf])
    assert math.isinf(inf[0])


def test_shakedown_cases_equal_the_exact_solver_and_the_rest_are_left_to_it():
    p, mp, mm = strips(7, 200)
    n = 51
    dT_c = strip_dT_c_block({**p, "n": n}, mp, mm)
    rng = np.random.default_rng(8)
    lo = rng.uniform(-1.2, 0.5, 200) * dT_c
    hi = lo + rng.uniform(0.0, 1.5, 200) * dT_c
    dT = np.column_stack([lo, hi, lo])
    F = np.zeros((200, 3))
    F[:10, 1] = 1.0                        # a force: never a closed-form shakedown
    cycles = 10 ** rng.uniform(0, 6, 200)
    r = strip_shakedown({**p, "n": n}, mp, mm, dT, F, cycles=cycles)
    e = assess_batch("strip", {**p, "n": n}, mp, mm, dT, F, substeps=1, force_at="uniform",
                     cycles=cycles, tolerance=np.full(200, np.nan))
    closed = np.flatnonzero(r["code"] == 0)
    assert 30 <= closed.size <= 170 and not np.any(r["code"][:10] == 0)
    for c in closed:
        assert e["code"][c] == 0 and e["verdict"][c] == 0, c          # shakedown
        for key in ("stabilised_at", "extrapolated", "verdict"):
            assert r[key][c] == e[key][c], (c, key)
        assert r["dT_c"][c] == pytest.approx(e["dT_c"][c], rel=1e-12)
        assert r["margin"][c] == pytest.approx(e["margin"][c], rel=1e-12)
        scale = abs(p["alpha_T"][c]) * p["l"][c] * np.abs(dT[c]).max()
        for key in ("drift_per_cycle", "drift_after_cycles"):
            assert abs(r[key][c] - e[key][c]) <= 1e-12 * scale, (c, key)
        assert math.isnan(r["cycles_to_tolerance"][c])
    # every case left to the exact solver slips (or has a force), none shakes down unseen
    reach = np.abs(dT).max(axis=1)
    left = np.flatnonzero(r["code"] == 2)
    assert np.all((reach[left] >= dT_c[left] * (1 - 1e-9)) | (np.arange(200)[left] < 10))


def test_one_shakedown_case_against_assess_assembly():
    """The bushing cooled and heated by less than its elastic limit, through the public
    per-case path."""
    data = {"assembly": {"model": "strip", "h": 2.5e-3, "E": 1.1e11, "p": 5e6, "l": 0.04,
                         "k_t": 1e13, "alpha_T": 6e-6, "n": 201},
            "loading": {"dT_min": -1.0, "dT_max": 2.0, "tolerance": 1e-6}}
    asm = assembly_from_dict(data, "x.toml")
    ref = assess_assembly(asm, Friction(0.19, 0.2, "explicit"), cycles=1e6)
    p = {k: [v] for k, v in data["assembly"].items() if k not in ("model", "n")} | {"n": 201}
    r = strip_shakedown(p, [0.19], [0.2], [[-1.0, 2.0, -1.0]], [[0.0, 0.0, 0.0]],
                        cycles=[1e6])
    assert r["code"][0] == 0 and ref["verdict"] == "shakedown"
    assert r["stabilised_at"][0] == ref["stabilised_at_cycle"]
    assert r["dT_c"][0] == pytest.approx(ref["dT_c_K"], rel=1e-12)
    assert abs(r["drift_after_cycles"][0] - ref["drift_after_cycles_m"]) <= 1e-20
    assert ref["cycles_to_tolerance"] is None


@pytest.mark.parametrize("rel", [0.0, 4e-13, 9e-13, 1.5e-12, 4e-12, 1e-6])
def test_nearly_equal_coefficients_are_made_equal_as_the_chain_does(rel):
    """mu+ and mu- within 1e-12 of each other (relative) are one coefficient, as in
    strip_chain; the block's mu_minus, dT_c and margin follow the chain's."""
    p = {"h": 2.5e-3, "E": 1.1e11, "p": 5e6, "l": 0.04, "k_t": 1e13, "alpha_T": 6e-6}
    for mu in (0.02, 0.2, 2.0):
        mp, mm = mu, mu * (1 - rel)
        r = strip_shakedown({k: [v] for k, v in p.items()} | {"n": 201}, [mp], [mm],
                            [[0.0, 0.1, 0.0]], [[0.0, 0.0, 0.0]], cycles=[100.0])
        chain = strip_chain(*p.values(), 201, mp, mm)
        assert r["code"][0] == 0
        assert (r["mu_plus"][0], r["mu_minus"][0]) == (chain.mu_plus, chain.mu_minus)
        assert r["dT_c"][0] == pytest.approx(elastic_limit(chain), rel=1e-12)
