"""Assembly physics limits (issue 11, class 8): a signed expansion coefficient alpha_T
against the closed forms and an exact mirror symmetry, and the verdict that tells
shakedown (no slip after the first cycles) from alternating slip (slip every cycle, no
drift) on cases whose regime is known from SPEC.md or from an independent calculation."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.errors import InputError
from asperity.microslip.assembly import load_assembly
from asperity.microslip.chains import elastic_limit, strip_chain, two_node_chain
from asperity.microslip.closed_forms import strip_dT_c, two_node_drift_per_cycle, two_node_dT_c
from asperity.microslip.loading import Loading
from asperity.microslip.quasi_static import simulate
from asperity.microslip.verdict import VERDICTS, assess

K, KT, N, AT, L0 = 1e6, 5e5, 100.0, 1.2e-5, 0.1          # SPEC.md 5 two-node values
H, E, P, LS = 2e-3, 2e11, 1e6, 0.1                        # a strip, lam l set per test


def two_node(aT=AT, mup=0.2, mum=0.1):
    return two_node_chain(K, L0, aT, KT, N, mup, mum)


def strip(lam_l, n, aT=AT, mup=0.2, mum=0.1):
    return strip_chain(H, E, P, LS, (lam_l / LS) ** 2 * E * H, aT, n, mup, mum)


# ----------------------------------------------------------------------- signed alpha_T

@pytest.mark.parametrize("aT", [-1.2e-5, -1e-9, -1e-3, 3e-7])
def test_signed_alpha_T_is_accepted_everywhere(aT, tmp_path):
    assert two_node(aT).alpha_T == aT and strip(3.54, 11, aT).alpha_T == aT
    assert two_node_dT_c(K, KT, N, 0.2, 0.1, aT, L0) > 0
    p = tmp_path / "a.toml"
    p.write_text(f"[assembly]\nmodel = 'two-node'\nk = 1e6\nl0 = 0.1\nalpha_T = {aT!r}\n"
                 "k_t = 5e5\nN = 100.0\n[friction]\nmu_plus = 0.2\nmu_minus = 0.1\n"
                 "[loading]\ndT_min = 0\ndT_max = 50\n")
    assert load_assembly(p).params["alpha_T"] == aT


@pytest.mark.parametrize("aT", [0.0, -0.0, 5e-324, -1e-10, 2e-3, -1e308])
def test_alpha_T_zero_tiny_or_huge_is_refused(aT):
    with pytest.raises(InputError, match=r"alpha_T must be in \[-0\.001, -1e-09\] or "
                                         r"\[1e-09, 0\.001\] 1/K"):
        two_node(aT)


@pytest.mark.parametrize("mup,mum", [(0.2, 0.1), (0.1, 0.3), (0.25, 0.25)])
def test_elastic_limit_depends_on_the_size_of_alpha_T_only(mup, mum):
    want = min(mup, mum) * N * (1 / K + 2 / KT) / (AT * L0)           # SPEC.md 5 by hand
    for aT in (AT, -AT):
        assert two_node_dT_c(K, KT, N, mup, mum, aT, L0) == pytest.approx(want, rel=1e-14)
        for sign in (1, -1):
            assert elastic_limit(two_node(aT, mup, mum), sign) == pytest.approx(want, rel=1e-12)


def test_strip_elastic_limit_with_negative_alpha_converges_to_shear_lag():
    kts = (3.54 / LS) ** 2 * E * H
    exact = strip_dT_c(H, E, P, LS, kts, 0.2, 0.1, -AT)
    assert exact == strip_dT_c(H, E, P, LS, kts, 0.2, 0.1, AT) > 0
    err = [elastic_limit(strip(3.54, n, -AT)) / exact - 1 for n in (201, 801)]
    assert abs(err[1]) < 3e-6 and err[0] / err[1] == pytest.approx(16, rel=1e-4), err  # 1.5e-5


@pytest.mark.parametrize("aT", [AT, -AT])
@pytest.mark.parametrize("mup,mum", [(0.2, 0.1), (0.1, 0.2)])
@pytest.mark.parametrize("margin", [0.6, 1.5, 4.0])
def test_two_node_drift_matches_the_signed_closed_form(aT, mup, mum, margin):
    """-|alpha_T| l0 (range - 2 dT_c) towards the smaller coefficient: the drift does NOT
    change direction with the sign of alpha_T (only which end slips first does)."""
    dTc = two_node_dT_c(K, KT, N, mup, mum, aT, L0)
    r = simulate(two_node(aT, mup, mum), Loading.cycles_between(0.0, 2 * margin * dTc), 8)
    by_hand = (-1 if mup > mum else 1) * abs(aT) * L0 * max(0.0, 2 * margin * dTc - 2 * dTc)
    want = two_node_drift_per_cycle(K, KT, N, mup, mum, aT, L0, 0.0, 2 * margin * dTc)
    assert want == pytest.approx(by_hand, rel=1e-12, abs=1e-18)
    assert r.drift_per_cycle == pytest.approx(want, rel=1e-9, abs=1e-15)


@pytest.mark.parametrize("at", ["uniform", "start"])
def test_turning_alpha_T_is_mirroring_the_chain(at):
    """u -> u mirrored end for end when alpha_T changes sign (exact symmetry of the chain
    equations), the force moving to the mirrored node: node by node, every cycle."""
    n = 31
    a, b = strip(3.54, n, AT), strip(3.54, n, -AT)
    if at == "start":
        from dataclasses import replace
        fw = np.zeros(n)
        fw[0] = 1.0
        a, b = replace(a, fw=fw), replace(b, fw=fw[::-1].copy())
    dTc = elastic_limit(a)
    L = Loading(np.array([0, 9, -2, 6, 0.0]) * dTc, np.array([0, 1, -1, 0.5, 0]) * 0.3 * a.cm.sum())
    ra = simulate(a, L, 6, until_stable=False, record_nodes=np.arange(n))
    rb = simulate(b, L, 6, until_stable=False, record_nodes=np.arange(n))
    scale = np.abs(ra.u_end).max()
    assert scale > 0
    np.testing.assert_allclose(rb.u_end, ra.u_end[:, ::-1], rtol=0, atol=1e-9 * scale,
                               err_msg="alpha_T -> -alpha_T is the mirror image")
    np.testing.assert_allclose(rb.trace["u"], ra.trace["u"][:, ::-1], rtol=0, atol=1e-9 * scale)
    assert rb.drift_per_cycle == pytest.approx(ra.drift_per_cycle, rel=1e-9, abs=1e-18)
    # heating from the stress-free state: with alpha_T > 0 the x = 0 end moves towards -x,
    # with alpha_T < 0 the x = l end does
    j = int(np.argmax(ra.trace["dT"]))
    assert ra.trace["u"][j, 0] < 0 and rb.trace["u"][j, -1] < 0


# ----------------------------------------------------------------------- the verdict

def elastic_stroke(chain, rng):
    """Stroke of node 0 over a cycle of range ``rng`` if every contact sticks: a dense
    solve of (K_bar + diag(k_t)) u = thermal load, independent of the kernels."""
    n = chain.n
    A = np.diag(chain.kt.astype(float))
    f = np.zeros(n)
    for e in range(n - 1):
        k = chain.kb[e]
        A[e, e] += k
        A[e + 1, e + 1] += k
        A[e, e + 1] -= k
        A[e + 1, e] -= k
        th = k * chain.alpha_T * chain.le[e]
        f[e] -= th
        f[e + 1] += th
    return abs(np.linalg.solve(A, f)[0]) * rng


def last_cycle_stroke(r):
    t = r.trace["t"]
    sel = t > r.cycles_run - 1 - 1e-12
    u0 = r.trace["u"][sel, 0]
    return float(u0.max() - u0.min())


#: (name, chain, margin, verdict) with the regime known independently
KNOWN = [
    ("two-node below dT_c: never slips", lambda: two_node(), 0.45, "shakedown"),
    ("two-node, slips in the first cycle only", lambda: two_node(), 0.9, "shakedown"),
    ("two-node, mu+ = mu-: slips both ways every cycle", lambda: two_node(AT, .15, .15), 3.0,
     "alternating-slip"),
    ("two-node, margin 1.5 (SPEC.md)", lambda: two_node(), 1.5, "ratchet"),
    ("two-node, alpha_T < 0, margin 1.5", lambda: two_node(-AT), 1.5, "ratchet"),
    ("strip lam l = 10, margin 0.9", lambda: strip(10, 201), 0.9, "shakedown"),
    ("strip lam l = 10, margin 1.6 (SPEC.md: ends fret)", lambda: strip(10, 201), 1.6,
     "alternating-slip"),
    ("strip lam l = 10, alpha_T < 0, margin 1.6", lambda: strip(10, 201, -AT), 1.6,
     "alternating-slip"),
    ("strip lam l = 3.5, mu+/mu- = 1.6, margin 3.05 (SPEC.md)",
     lambda: strip(3.5, 201, AT, .16, .1), 3.05, "alternating-slip"),
    ("strip lam l = 3.5, mu+/mu- = 1.6, margin 3.1 (SPEC.md)",
     lambda: strip(3.5, 201, AT, .16, .1), 3.1, "ratchet"),
    ("strip, alpha_T < 0, margin 3.1", lambda: strip(3.5, 201, -AT, .16, .1), 3.1, "ratchet"),
]


@pytest.mark.parametrize("name,make,margin,verdict", KNOWN, ids=[k[0] for k in KNOWN])
def test_verdict_on_cases_of_known_regime(name, make, margin, verdict):
    chain = make()
    rng = 2 * margin * elastic_limit(chain)
    L = Loading.cycles_between(0.0, rng)
    out = assess(chain, L, 1e6)
    assert out["verdict"] == verdict, (name, out["regime"])
    r = out["_result"]
    stroke, el = last_cycle_stroke(r), elastic_stroke(chain, rng)
    if verdict == "shakedown":
        # the stabilised cycle is elastic: node 0 moves exactly as if every contact stuck
        assert stroke == pytest.approx(el, rel=1e-8), "shakedown: no slip in the cycle"
        assert out["drift_per_cycle_m"] == 0.0
        slipped_once = margin > 0.5
        assert (abs(r.mean_u[1]) > 1e-3 * el) == slipped_once, "slip in the first cycle"
    elif verdict == "alternating-slip":
        assert stroke > el * (1 + 1e-3), "alternating slip: node 0 slips every cycle"
        assert out["drift_per_cycle_m"] == 0.0 and out["drift_direction"] == "none"
        assert abs(r.mean_u[-1] - r.mean_u[-2]) < 1e-9 * el
    else:
        assert out["drift_per_cycle_m"] < 0 and out["drift_direction"] == "-x"


def test_verdict_in_text_json_and_map(capsys, tmp_path):
    from pathlib import Path
    surf = Path(__file__).resolve().parents[1] / "surfaces"
    d = run_json(capsys, "risk", surf / "wedge-asymmetric.toml", surf / "bushing-strip-mild.toml")
    assert d["verdict"] == "alternating-slip" and d["drift_per_cycle_m"] == 0
    code, out, _ = run(capsys, "risk", surf / "bushing-strip-mild.toml")
    assert code == 0 and "verdict: ALTERNATING SLIP" in out and "fretting" in out
    a = tmp_path / "cool.toml"
    a.write_text((surf / "two-node-spec.toml").read_text().replace("dT_max = 125.0", "dT_max = 75"))
    d = run_json(capsys, "risk", a)
    assert d["verdict"] == "shakedown" and d["margin"] == pytest.approx(0.9)
    code, out, _ = run(capsys, "risk", a)
    assert "verdict: SHAKEDOWN -- no slip after the first cycles" in out
    m = run_json(capsys, "risk", surf / "wedge-asymmetric.toml", surf / "bushing-strip-mild.toml",
                 "--map", "alpha=5:40:3", "beta=5:40:3")
    v = {x for row in m["map"]["verdict"] for x in row}
    assert v <= set(VERDICTS) and "alternating-slip" in v
    code, out, _ = run(capsys, "risk", surf / "wedge-asymmetric.toml",
                       surf / "bushing-strip-mild.toml", "--map", "alpha=5:40:3", "beta=5:40:3")
    assert "A = alternating slip" in out and json.dumps(m, allow_nan=False)
    assert math.isfinite(m["cycles"])
