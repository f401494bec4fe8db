"""FRIC as Abaqus/Standard drives it (issue 27, item 4): the harness's implicit driver
re-passes the start-of-increment TAU and STATEV at every Newton iteration and keeps only
the converged iteration's outputs. Checked here on any FRIC with the project's PROPS
(PROPS(1) = k, texture on the main surface): LM = 2 returns at once, iterations leave no
trace, the Newton solve of a spring-driven point converges quadratically (and would not
with a wrong tangent), and the seed's two-node assembly gives `asperity risk`'s drift per
cycle to 1e-6 of alpha_T l0 dT_range."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_json
from fe_builds import library, needs_gfortran
from fe_models import fric_of, spring_driven_point, two_node_cycles
from fe_standin import coulomb_fric

from asperity.fe.fortran_harness import call_fric

pytestmark = needs_gfortran
SURF = Path(__file__).resolve().parent.parent / "surfaces"
MU_PLUS, MU_MINUS = 0.2, 0.1
KT = 5.0e5


@pytest.fixture(scope="module", params=["stand-in", "generated"])
def fric_lib(request):
    """The hand-written Coulomb FRIC, and the FRIC generated from the componentwise law
    mu_f = mu+ along +x, mu_b = mu- along -x (mu_t = 0.15 across)."""
    if request.param == "stand-in":
        return library(coulomb_fric(MU_PLUS, MU_MINUS))
    from asperity.fe.abaqus_fric import routine_source
    from asperity.laws.componentwise import componentwise_gauge
    gl = componentwise_gauge(mu_f=MU_PLUS, mu_b=MU_MINUS, mu_t=0.15)
    return library(routine_source(gl, "fric"))


PROPS = np.array([KT, 0.0, 1.0])


@pytest.mark.parametrize("nfdir", [1, 2])
def test_lm_2_returns_at_once(fric_lib, nfdir):
    """An open point (LM = 2 on entry): nothing is read or written, every output keeps
    its sentinel."""
    tau0, sv0 = np.full(nfdir, 3.5), np.full(4, -2.0)
    out = call_fric(fric_lib, lm=2, tau=tau0, statev=sv0, dgam=np.full(nfdir, 1e-3),
                    press=1e6, props=PROPS, nfdir=nfdir, sentinel=np.nan)
    assert out.lm == 2
    assert out.tau.tolist() == tau0.tolist() and out.statev.tolist() == sv0.tolist()
    assert np.isnan(out.ddtddg).all() and np.isnan(out.ddtddp).all()
    assert np.isnan(out.dslip).all() and math.isnan(out.sfd)


def test_iterations_leave_no_trace(fric_lib):
    """The converged state of an increment does not depend on the iterations that led to
    it: another first guess (other iterations, other trial slips) commits exactly what one
    call with the increment's final DGAM on the start values gives, stick and slip alike."""
    fric = fric_of(fric_lib, PROPS, 2)
    w = np.array([[2e-6, 1e-6], [9e-6, -4e-6], [3e-6, 8e-6], [20e-6, 8e-6], [40e-6, 9e-6]])
    a = spring_driven_point(fric, w, ks=2e5, press=10.0)
    b = spring_driven_point(fric, w, ks=2e5, press=10.0, guess=lambda u, w: w)
    assert [len(r.residuals) for r in b] != [len(r.residuals) for r in a]
    tau, sv, u = np.zeros(2), np.zeros(4), np.zeros(2)
    slid = []
    for ra, rb in zip(a, b):
        assert rb.u == pytest.approx(ra.u, abs=1e-15)
        one = call_fric(fric_lib, lm=0, tau=tau, statev=sv, dgam=rb.u - u, press=10.0,
                        props=PROPS, nfdir=2)
        assert rb.state.tau[0] == pytest.approx(one.tau, abs=1e-12)
        assert ra.state.tau[0] == pytest.approx(one.tau, abs=1e-12)
        assert rb.state.statev[0].tolist() == one.statev.tolist()
        slid.append(np.linalg.norm(one.dslip) > 1e-9 * np.linalg.norm(rb.u - u))
        tau, sv, u = rb.state.tau[0], rb.state.statev[0], rb.u
    assert any(slid) and not all(slid)


def newton_orders(residuals):
    """Estimated orders log(e_{k+1}/e_k) / log(e_k/e_{k-1}) while e is well above round-off."""
    e = [x for x in residuals if x > 1e-11]
    return [math.log(e[i + 1] / e[i]) / math.log(e[i] / e[i - 1]) for i in range(1, len(e) - 1)]


def test_spring_driven_point_converges_quadratically(fric_lib):
    """A point pulled far into sliding in one increment by an anisotropic spring (so the
    sliding direction is found by the iterations): the consistent tangent gives quadratic
    convergence (order ~2); the elastic tangent in its place gives order ~1."""
    fric = fric_of(fric_lib, PROPS, 2)
    w = np.array([[4e-5, 3e-5]])
    ks = np.array([[3e5, 1.5e5], [1.5e5, 1e5]])
    res = spring_driven_point(fric, w, ks=ks, press=40.0)[0]
    tau, u = res.state.tau[0], res.u
    assert np.linalg.norm(tau - KT * u) > 0.1 * np.linalg.norm(tau)         # it slides
    orders = newton_orders(res.residuals)
    assert len(res.residuals) <= 6, res.residuals
    assert len(res.residuals) <= 3 or max(orders) > 1.8, res.residuals

    def elastic_tangent(**kw):
        out = fric(**kw)
        out.ddtddg = KT * np.eye(2, order="F")
        return out
    slow = spring_driven_point(elastic_tangent, w, ks=ks, press=40.0, max_iter=200)[0]
    assert len(slow.residuals) > len(res.residuals) + 3
    assert max(newton_orders(slow.residuals)) < 1.3


def test_two_node_assembly_drifts_as_asperity_risk(fric_lib, capsys):
    """SPEC.md section 5's two-node bar with FRIC at both nodes (NFDIR = 1, PRESS = N per
    unit area, PROPS(1) = k_t, the support textured): the drift per stabilised cycle is
    `asperity risk`'s to 1e-6 of alpha_T l0 dT_range."""
    risk = run_json(capsys, "risk", SURF / "two-node-spec.toml")
    a = risk["assembly"]
    lo, hi = risk["loading"]["history_K"][0], max(risk["loading"]["history_K"])
    assert (risk["mu_plus"], risk["mu_minus"]) == (MU_PLUS, MU_MINUS)
    fric = fric_of(fric_lib, np.array([a["k_t"], 0.0, 1.0]), 1)
    ends, iters = two_node_cycles(fric, k=a["k"], l0=a["l0"], alpha_T=a["alpha_T"],
                                  k_t=a["k_t"], N=a["N"], dT_min=lo, dT_max=hi)
    drift = np.diff(ends)[1:]                       # from the second cycle on
    scale = a["alpha_T"] * a["l0"] * (hi - lo)
    assert drift == pytest.approx(np.full(drift.size, risk["drift_per_cycle_m"]),
                                  abs=1e-6 * scale)
    assert risk["drift_per_cycle_m"] < -0.1 * scale
    assert max(iters) <= 6


def _pulled(fric, lm0: int, w, ks: float = 2e5, press: float = 40.0):
    """One increment of a point pulled by a spring to w, its committed LM being lm0."""
    from asperity.fe.implicit_driver import ContactState, newton_increment
    state = ContactState.fresh(1, 2, 4)
    state.lm[:] = lm0
    return newton_increment(fric, state, np.zeros(2), np.eye(2)[None], [press],
                            lambda x: (ks * (x - w), ks * np.eye(2)))


def test_an_open_point_is_frictionless_and_a_closed_one_is_not(fric_lib):
    """A point open at the previous increment (LM = 2 committed): FRIC returns at once and
    the driver takes the point as frictionless, so the spring alone sets u = w, TAU stays 0
    and LM 2. The same point closed (LM = 0) holds the spring back by TAU / ks."""
    fric = fric_of(fric_lib, PROPS, 2)
    w = np.array([3e-5, -1e-5])
    res = _pulled(fric, 2, w)
    assert res.u == pytest.approx(w, abs=1e-18)
    assert res.state.tau[0].tolist() == [0.0, 0.0] and res.state.lm.tolist() == [2]
    assert [x.tolist() for x in res.lm_seen] == [[2]] * len(res.residuals)
    closed = _pulled(fric, 0, w)
    tau = closed.state.tau[0]
    assert closed.state.lm.tolist() == [0] and np.linalg.norm(tau) > 1.0
    assert closed.u == pytest.approx(w - tau / 2e5, abs=1e-12)


def test_lagrange_stick_is_refused_by_the_driver():
    """PROPS(1) = 0 makes the generated FRIC ask for Lagrange-multiplier stick (LM = 1),
    which the driver does not model: it says so instead of using the outputs."""
    from asperity.fe.abaqus_fric import routine_source
    from asperity.fe.implicit_driver import NotConverged
    from asperity.laws.componentwise import componentwise_gauge
    gl = componentwise_gauge(mu_f=MU_PLUS, mu_b=MU_MINUS, mu_t=0.15)
    fric = fric_of(library(routine_source(gl, "fric")), np.array([0.0, 0.0, 1.0]), 2)
    assert fric(lm=0, tau=np.zeros(2), statev=np.zeros(4), dgam=np.array([1e-6, 0.0]),
                press=40.0).lm == 1
    with pytest.raises(NotConverged, match="LM = 1"):
        _pulled(fric, 0, np.array([3e-5, -1e-5]))


def test_two_node_drift_does_not_depend_on_the_increments(fric_lib):
    """The law is rate-independent and the thermal load moves monotonically between the
    turning points, so the drift per cycle is the same in 4 or 9 increments each way (to
    1e-9 of alpha_T l0 dT); each cycle is 2 x steps increments."""
    bar = {"k": 1e6, "l0": 0.1, "alpha_T": 1.2e-5, "k_t": 5e5, "N": 100.0, "dT_min": 0.0,
           "dT_max": 125.0}                               # surfaces/two-node-spec.toml
    fric = fric_of(fric_lib, np.array([bar["k_t"], 0.0, 1.0]), 1)
    drifts = []
    for steps in (4, 9):
        ends, iters = two_node_cycles(fric, cycles=3, steps=steps, **bar)
        assert len(iters) == 3 * 2 * steps
        drifts.append(np.diff(ends)[1:])
    scale = 1.2e-5 * 0.1 * 125.0
    assert abs(drifts[0][0]) > 0.05 * scale
    assert drifts[1] == pytest.approx(drifts[0], abs=1e-9 * scale)
