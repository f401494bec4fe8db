"""Hostile input to the Moreau solver and the planar laws (issue 11, classes 2, 4, 5, 6):
absurd numbers refused with their physical range, work and memory estimated before a run,
Ctrl-C honoured (the kernel runs in pieces, with the same result as one
piece, bit for bit), and the public API raising one-line InputErrors."""
from __future__ import annotations

import math

import numpy as np
import pytest
from cli_run import run
from hostile import assert_refused, cli, interrupt

from asperity.dynamics import moreau as M
from asperity.dynamics import references as R
from asperity.errors import InputError, ResourceError
from asperity.laws import planar as L

BASE = ["--mu1", "0.3", "--u0", "1", "--angle", "30"]

FLAGS = [
    (["--dt", "5e-324"], "--dt must be in [1e-09, 1] s"),
    (["--dt", "1e-10"], "--dt must be in [1e-09, 1] s"),
    (["--dt", "nan"], "--dt must be in"), (["--dt", "inf"], "--dt must be a finite number"),
    (["--dt=-1e-3"], "--dt must be in"),
    (["--g", "5e-324"], "--g must be in [1e-06, 10000]"), (["--g", "1e300"], "--g must be in"),
    (["--mass", "1e-300"], "--mass must be in [1e-09, 1e+09] kg"),
    (["--mass", "inf"], "--mass must be a finite number"),
    (["--tol", "inf"], "--tol must be a finite number"), (["--tol", "0"], "--tol must be in"),
    (["--tol", "1e-300"], "--tol must be in [1e-15, 0.001]"),
    (["--max-iterations", "0"], "--max-iterations"),
    (["--max-iterations", "1000000000000"], "--max-iterations"),
    (["--t-end", "-1"], "--t-end must be in"), (["--t-end", "inf"], "--t-end must be a finite"),
    (["--t-end", "1e6", "--dt", "1e-3"], "at most 5e+08: raise --dt or lower --t-end"),
]
REPLACING = [
    (["--mu1", "5e-324"], "--mu1 must be in [1e-06, 100]"),
    (["--mu1", "1e300"], "--mu1 must be in [1e-06, 100]"),
    (["--mu1", "inf"], "--mu1 must be a finite number"),
    (["--mu1", "0.3", "--mu2", "nan"], "--mu2 must be in"),
    (["--u0", "inf"], "--u0 must be a finite number"), (["--u0", "1e308"], "--u0 must be in"),
    (["--angle", "inf"], "--angle must be a finite"), (["--angle", "1e308"], "--angle must be in"),
]


@pytest.mark.parametrize("flags,msg", FLAGS)
def test_slide_flags_with_absurd_numbers(capsys, flags, msg):
    code, out, err = run(capsys, "slide", *BASE, *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


@pytest.mark.parametrize("flags,msg", REPLACING)
def test_slide_law_and_launch_flags_with_absurd_numbers(capsys, flags, msg):
    argv = dict(zip(BASE[::2], BASE[1::2]))
    i = 0
    while i < len(flags):
        argv[flags[i]] = flags[i + 1]
        i += 2
    code, out, err = run(capsys, "slide", *[x for kv in argv.items() for x in kv])
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


def test_a_representative_refusal_through_the_real_command(tmp_path):
    csv = tmp_path / "p.csv"
    csv.write_text("old\n")
    assert_refused(cli("slide", *BASE, "--dt", "5e-324", "--csv", csv), contains="--dt")
    assert csv.read_text() == "old\n"


# ----------------------------------------------------------------------------- pieces, Ctrl-C

def _runs(law, **kw):
    body = kw.pop("body", None) or M.point_mass(law, 2.0)
    return M.simulate(body, kw.pop("u0", [1.0, 0.5][:body.ndof] + [0.3][:body.ndof - 2]),
                      **kw)


@pytest.mark.parametrize("case", ["star slide to rest", "ellipse under a square wave",
                                  "rigid body, two contacts, recorded every 7"])
def test_pieces_give_the_same_result_bit_for_bit(monkeypatch, case):
    if case == "star slide to rest":
        law = L.star_law(0.3, 0.2)
        kw = dict(dt=1e-3, t_end=2.0, halt_at_rest=True)
    elif case == "ellipse under a square wave":
        law = L.truncated_ellipse_law(0.3, 0.2, 0.25, 0.25)
        kw = dict(dt=1e-3, t_end=3.0, force=M.Force(amplitude=(5.0, 1.0), period=0.4,
                                                   waveform="square"))
    else:
        law = L.ellipse_law(0.3, 0.2)
        body = M.Body(mass=1.0, laws=law, inertia=0.01, contacts=[[0.1, 0.0], [-0.1, 0.05]],
                      share=[0.6, 0.4])
        kw = dict(dt=1e-3, t_end=1.5, body=body, record_every=7,
                  force=M.Force(constant=(0.5, 0.0, 0.01)))
    whole = _runs(law, **dict(kw))
    monkeypatch.setattr(M, "STEPS_PER_PIECE", 13)
    pieces = _runs(law, **dict(kw))
    for name in ("t", "q", "u", "q_final", "u_final"):
        np.testing.assert_array_equal(getattr(pieces, name), getattr(whole, name), err_msg=name)
    for name in ("steps", "stop_step", "max_iterations_used", "mean_iterations", "status",
                 "fail_step", "max_residual"):
        assert getattr(pieces, name) == getattr(whole, name), name
    assert whole.steps > 100


@pytest.mark.slow
def test_ctrl_c_stops_a_long_slide(tmp_path):
    out = tmp_path / "path.csv"
    status, err = interrupt("slide", "--law", "star", "--mu1", "0.3", "--mu2", "0.2", "--u0",
                            "1", "--angle", "30", "--t-end", "4000", "--dt", "1e-5", "--csv",
                            out)
    assert status == 130 and "interrupted" in err and "Traceback" not in err, err
    assert err.count("\n") == 1, err
    assert not out.exists() and not list(tmp_path.iterdir())


def test_long_runs_report_progress(monkeypatch):
    from asperity import progress
    seen = []
    monkeypatch.setattr(progress, "report", lambda f, label=None: seen.append((f, label)))
    monkeypatch.setattr(M, "chunks", _chunks_reporting(progress))
    monkeypatch.setattr(M, "STEPS_PER_PIECE", 1000)
    M.slide(L.coulomb_law(0.3), 1.0, 0.0, dt=1e-4)
    assert len(seen) >= 3 and seen[-1][0] == pytest.approx(1.0)
    assert all(label == "Moreau steps" for _, label in seen)


def _chunks_reporting(progress):
    def chunks(total, size, label=None):
        start = 0
        while start < total:
            stop = min(total, start + size)
            yield start, stop
            start = stop
            progress.report(start / total, label)
    return chunks


# ----------------------------------------------------------------------------- API

LAW = L.coulomb_law(0.3)
nan = float("nan")
API = {
    "slide(None)": lambda: M.slide(None, 1.0, 0.0),
    "slide(u0 text)": lambda: M.slide(LAW, "1", 0.0),
    "slide(u0 inf)": lambda: M.slide(LAW, math.inf, 0.0),
    "slide(dt 5e-324)": lambda: M.slide(LAW, 1.0, 0.0, dt=5e-324),
    "slide(g 0)": lambda: M.slide(LAW, 1.0, 0.0, g=0.0),
    "slide(angle nan)": lambda: M.slide(LAW, 1.0, nan),
    "simulate(None)": lambda: M.simulate(None, [1, 0], dt=1e-3, t_end=1),
    "simulate(u0 shape)": lambda: M.simulate(M.point_mass(LAW), [1, 0, 0], dt=1e-3, t_end=1),
    "simulate(u0 nan)": lambda: M.simulate(M.point_mass(LAW), [nan, 0], dt=1e-3, t_end=1),
    "simulate(settings)": lambda: M.simulate(M.point_mass(LAW), [1, 0], dt=1e-3, t_end=1,
                                             settings="fast"),
    "simulate(force)": lambda: M.simulate(M.point_mass(LAW), [1, 0], dt=1e-3, t_end=1,
                                          force=3.0),
    "simulate(steps)": lambda: M.simulate(M.point_mass(LAW), [1, 0], dt=1e-9, t_end=1e3),
    "simulate(records)": lambda: M.simulate(M.point_mass(LAW), [1, 0], dt=1e-6, t_end=400.0),
    "simulate(force_table)": lambda: M.simulate(M.point_mass(LAW), [1, 0], dt=0.1, t_end=1,
                                                force_table=np.zeros((3, 2))),
    "point_mass(None)": lambda: M.point_mass(None),
    "point_mass(mass 0)": lambda: M.point_mass(LAW, 0.0),
    "Body(contacts None)": lambda: M.Body(mass=1.0, laws=LAW, contacts=None),
    "Body(laws text)": lambda: M.Body(mass=1.0, laws="coulomb"),
    "Body(share nan)": lambda: M.Body(mass=1.0, laws=LAW, share=[nan]),
    "Body(inertia 1e300)": lambda: M.Body(mass=1.0, laws=LAW, inertia=1e300,
                                          contacts=[[0.1, 0.0], [-0.1, 0.0]]),
    "Force(waveform)": lambda: M.Force(waveform="triangle"),
    "Force(waveform list)": lambda: M.Force(waveform=["square"]),
    "Force(period 0)": lambda: M.Force(period=0.0),
    "Force(amplitude text)": lambda: M.Force(amplitude="big"),
    "Force(constant 1e300)": lambda: M.Force(constant=(1e300, 0.0)),
    "Settings(tol inf)": lambda: M.Settings(tol=math.inf),
    "Settings(relax 2)": lambda: M.Settings(relax=2.0),
    "deflection_deg(nan)": lambda: M.deflection_deg(nan, (1.0, 0.0)),
    "deflection_deg(rest None)": lambda: M.deflection_deg(0.0, None),
    "deflection_deg(rest nan)": lambda: M.deflection_deg(0.0, (nan, 1.0)),
    "ratchet(F0 nan)": lambda: R.ratchet_drift_square(nan, 1.0, 1.0, 0.3, 0.2),
    "ratchet(period -1)": lambda: R.ratchet_drift_square(2.5, 1.0, -1.0, 0.3, 0.2),
    "ratchet(mass text)": lambda: R.ratchet_drift_square(2.5, "1", 1.0, 0.3, 0.2),
    "ratchet(mu 5e-324)": lambda: R.ratchet_drift_square(2.5, 1.0, 1.0, 5e-324, 0.2),
    "coulomb_stop_time(-1)": lambda: R.coulomb_stop_time(-1.0, 0.3),
    "coulomb_stop_distance(mu 0)": lambda: R.coulomb_stop_distance(1.0, 0.0),
    "reference_path(None)": lambda: R.reference_path(None, 1.0, 0.0),
    "reference_path(u0 0)": lambda: R.reference_path(LAW, 0.0, 0.0),
    "path_error(None)": lambda: R.path_error(None, None),
    "coulomb_law('0.3')": lambda: L.coulomb_law("0.3"),
    "coulomb_law(0)": lambda: L.coulomb_law(0.0),
    "ellipse_law(1e300)": lambda: L.ellipse_law(0.3, 1e300),
    "truncated_ellipse_law(None)": lambda: L.truncated_ellipse_law(None, 0.1, 0.1, 0.1),
    "truncated_ellipse_law(theta)": lambda: L.truncated_ellipse_law(0.1, 0.1, 0.1, 0.1, "0"),
    "collinear_law(C text)": lambda: L.collinear_law(C="ellipse"),
    "collinear_law()": lambda: L.collinear_law(),
    "star_law(5e-324)": lambda: L.star_law(5e-324, 0.2),
    "windward_star_law(alpha 95)": lambda: L.windward_star_law(95.0),
    "from_gauge(None)": lambda: L.from_gauge(None),
    "from_gauge(missing)": lambda: L.from_gauge("missing-gauge.json"),
    "PlanarLaw(law None)": lambda: L.PlanarLaw("x", None),
    "prox_interval(nan)": lambda: L.prox_interval([nan], 0.2, 0.3),
    "prox_interval(mu text)": lambda: L.prox_interval([0.1], "0.2", 0.3),
    "prox_interval(normal < 0)": lambda: L.prox_interval([0.1], 0.2, 0.3, -1.0),
    "prox_set(None)": lambda: L.prox_set(None, [[0.1, 0.0]]),
    "prox_set(which)": lambda: L.prox_set(LAW, [[0.1, 0.0]], which="E"),
    "prox_set(x nan)": lambda: L.prox_set(LAW, [[nan, 0.0]]),
    "prox_set(normal 0)": lambda: L.prox_set(LAW, [[0.1, 0.0]], normal=0.0),
    "law_point(x shape)": lambda: L.law_point(LAW, [[0.1, 0.0, 3.0]]),
    "kernel_radial(nan)": lambda: L.kernel_radial(LAW, nan),
}


@pytest.mark.parametrize("name", list(API))
def test_public_api_raises_one_line_input_errors(monkeypatch, name):
    if name == "simulate(records)":       # 4e8 recorded states, 16 GB: beyond a 2 GB machine
        from asperity import resources
        monkeypatch.setattr(resources, "available_memory", lambda: 2 << 30)
    with pytest.raises(InputError) as exc:
        API[name]()
    assert "\n" not in str(exc.value) and str(exc.value)
    if name in ("simulate(steps)", "simulate(records)"):
        assert isinstance(exc.value, ResourceError)
