"""Hostile input to the texture room (issue 11, classes 2, 4, 5, 6): wedge and spring
numbers outside their physical ranges refused in one line by the library (the CLI says the
same), the spring model scale-free (a 1e-300 m wedge once gave mu_b+ = 444200), requests
too long for the spring kernels refused before any work, Ctrl-C honoured between kernel
pieces (the pieces give the result of one piece, bit for bit), and the public API of the
room fed None, text, NaN, inf and wrong shapes.

The lists BAD_FLAGS, BAD_FILE_VALUES (class 2), EXTREME_BUT_VALID (class 2, accepted with
finite results), RESOURCES (class 4) and BAD_API (class 6) hold the inputs of each class,
so their lengths are the counts the issue asks for."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run
from hostile import SURF, assert_finite_output, assert_refused, cli, interrupt
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import asperity as A
from asperity import progress
from asperity.errors import InputError, ResourceError
from asperity.friction.derive import derive, to_json
from asperity.texture import spring_runs
from asperity.texture.closed_form import compute_wedge_axis_closed_form
from asperity.texture.spring_model import MAX_UPDATES, SpringModel
from asperity.texture.springs import simulate_loading_curve, simulate_reservoir, simulate_sliding
from asperity.texture.wedges import GaussianWedgeTexture, WedgeTexture, texture_from_dict

WEDGE = ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2"]
SPRINGS = [*WEDGE, "--method", "springs"]
TEX = WedgeTexture(30, 10, 0.1, 0.2)
CLOSED = compute_wedge_axis_closed_form(TEX.alpha, TEX.beta, 0.1, 0.2)

# ----------------------------------------------------------------------------- class 2

#: (flags, words of the one-line message)
BAD_FLAGS = [
    (["--height", "1e-30"], "--height must be in [1e-10, 100] m, got 1e-30"),  # the issue's
    (["--height", "1e-300"], "--height must be in [1e-10, 100] m"),
    (["--height", "5e-324"], "--height must be in"), (["--height", "0"], "--height must be in"),
    (["--height=-1e-6"], "--height must be in"), (["--height", "1e300"], "--height must be"),
    (["--height", "inf"], "--height must be a finite"), (["--height", "nan"], "got NaN"),
    (["--alpha", "5e-324"], "--alpha must be at least 1e-06 deg"),
    (["--alpha", "90"], "--alpha must be in (0, 90)"), (["--beta", "inf"], "--beta must be"),
    (["--mu-alpha", "1e300"], "--mu-alpha must be in [0, 100]"),
    (["--mu-beta", "nan"], "--mu-beta must be in"),
    (["--k-n", "5e-324"], "--k-n must be in [1e-06, 1e+12] N/m"),
    (["--k-n", "1e300"], "--k-n must be in"), (["--k-n", "0"], "--k-n must be in"),
    (["--k-n=-1e3"], "--k-n must be in"), (["--k-n", "nan"], "--k-n must be in"),
    (["--k-f", "5e-324"], "--k-f must be in [1e-06, 1e+12] N/m or inf (rigid springs)"),
    (["--k-f", "1e300"], "--k-f must be in"), (["--k-f", "0"], "--k-f must be in"),
    (["--k-f=-inf"], "--k-f must be in"), (["--k-f", "nan"], "got NaN"),
    (["--k-f", "1e11", "--k-n", "1e-5"], "--k-f / --k-n must be in [1e-06, 1e+12], got 1e+16"),
    (["--k-f", "1e-6"], "--k-f / --k-n must be in [1e-06, 1e+12], got 1e-09"),
    (["--density", "5e-324"], "density must be in [1, 1e+20] springs/m^2"),
    (["--density", "1e300"], "density must be in"), (["--density", "inf"], "density must be"),
    (["--preload", "1e300"], "preload must be in [-1e+06, 1e+06] N"),
    (["--preload=-inf"], "preload must be a finite"),
    (["--preload=-1"], "preload must exceed -0.001 N (rest level"),
    (["--n-springs", "0"], "--n-springs must be a whole number in [1, 1000000]"),
    (["--n-springs", "10000000"], "--n-springs must be a whole number"),
    (["--steps-per-period", "0"], "--steps-per-period must be a whole number"),
    (["--steps-per-period", "1000000000"], "--steps-per-period must be a whole number"),
    (["--alpha", "89.99", "--mu-alpha", "0"],          # a wall 3e-5 of the pitch wide
     "8000 samples per pitch are too few for this texture (a face too narrow for its force"),
    (["--alpha", "89.9999999", "--mu-alpha", "0"], "use the closed form (--method closed-form)"),
    (["--preload=-9.99e-4"], "raise steps_per_period (--steps-per-period) to"),
]


@pytest.mark.parametrize("flags,msg", BAD_FLAGS, ids=lambda x: " ".join(x) if isinstance(x, list) else "")
def test_derive_springs_flags_with_absurd_numbers(capsys, flags, msg):
    code, out, err = run(capsys, "derive", *SPRINGS, *flags, "--json")
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


TEXTURE_FILE = ('[texture]\nkind = "wedge"\nalpha_deg = 30.0\nbeta_deg = 10.0\nmu_alpha = 0.1\n'
                'mu_beta = 0.2\nheight = 5e-6\n[springs]\nk_n = 1e3\nk_f = 1e7\n')
#: (table, key, TOML value, words of the message): a value edited into TEXTURE_FILE
BAD_FILE_VALUES = [
    ("springs", "k_nn", "1e3", "unknown key springs.k_nn; allowed: k_n, k_f"),
    ("springs", "k_f", '"1e7"', "springs.k_f must be a number, got '1e7' (text)"),
    ("springs", "k_f", '"soft"', "springs.k_f must be a number"),
    ("springs", "k_f", "5e-324", "springs.k_f must be in [1e-06, 1e+12] N/m or inf"),
    ("springs", "k_n", "1e-300", "springs.k_n must be in [1e-06, 1e+12] N/m"),
    ("springs", "k_n", "true", "springs.k_n must be a number, got True (a boolean)"),
    ("springs", "density", "nan", "springs.density must be in [1, 1e+20]"),
    ("springs", "preload", "inf", "springs.preload must be a finite number"),
    ("springs", "n_springs", "1e7", "springs.n_springs must be a whole number in [1, 1000000]"),
    ("springs", "steps_per_period", "2.5", "springs.steps_per_period must be a whole number"),
    ("texture", "height", "1e-300", "texture.height must be in [1e-10, 100] m"),
    ("texture", "alpha_deg", "5e-324", "texture.alpha_deg must be at least 1e-06 deg"),
    ("texture", "kind", "[1]", "texture.kind must be one of gaussian-wedge, wedge, got [1]"),
    ("texture", "mu_beta", '"0.2"', "texture.mu_beta must be a number, got '0.2' (text)"),
]


def _edit(text: str, table: str, key: str, value: str) -> str:
    lines, section, done = [], None, False
    for line in text.splitlines():
        if line.startswith("["):
            section = line.strip("[]")
        elif section == table and line.split("=")[0].strip() == key:
            line, done = f"{key} = {value}", True
        lines.append(line)
    if not done:
        i = lines.index(f"[{table}]") + 1
        lines.insert(i, f"{key} = {value}")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("table,key,value,msg", BAD_FILE_VALUES,
                         ids=[f"{t}.{k}={v}" for t, k, v, _ in BAD_FILE_VALUES])
def test_texture_file_values_refused_whatever_the_method(capsys, tmp_path, table, key, value,
                                                         msg):
    f = tmp_path / "t.toml"
    f.write_text(_edit(TEXTURE_FILE, table, key, value))
    for method in ("closed-form", "springs"):       # a wrong [springs] table is wrong anyway
        code, out, err = run(capsys, "derive", f, "--method", method, "--directions", "8")
        assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


#: (flags, tolerance): accepted at the edges of the ranges; finite JSON, every mu between
#: 0 and the steepest climb's H(mu_alpha, alpha) (no average force ratio can exceed it), and
#: mu_a+, mu_a-, mu_b within the tolerance (absolute) of the closed form, None: a regime
#: the closed form does not describe (k_f = k_n: the tips are dragged over the wedges)
EXTREME_BUT_VALID = [
    (["--height", "1e-10", "--k-f", "1e7"], 1e-3),
    (["--height", "100", "--k-f", "1e7"], 1e-3),
    (["--k-n", "1e-6", "--k-f", "1e-2"], 1e-3),       # forces of 1e-16 N: no underflow
    (["--k-n", "1e12", "--k-f", "1e12"], None),
    (["--k-n", "1e12"], 1e-3), (["--density", "1"], 1e-3), (["--density", "1e20"], 1e-3),
    (["--preload", "1e6"], 1e-3),                      # rest level 1e3 m below 1 um wedges
    (["--preload", "-9e-4"], 2e-3),                    # only the top 10 % of a wedge touches
    (["--mu-alpha", "5e-324", "--mu-beta", "0"], 1e-3),
    (["--k-f", "1e12", "--k-n", "1"], 1e-3),           # k_f/k_n = 1e12, the largest
    (["--alpha", "1e-6", "--k-f", "1e7"], 1e-3),       # a face 1e-6 deg steep
    (["--alpha", "89.99", "--mu-alpha", "0", "--steps-per-period", "6000000"], 2e-3),  # a wall
]


@pytest.mark.parametrize("flags,tol", EXTREME_BUT_VALID, ids=lambda x: " ".join(x) if isinstance(x, list) else "")
def test_extreme_but_valid_numbers_give_finite_plausible_friction(capsys, flags, tol):
    argv = dict(zip(SPRINGS[::2], SPRINGS[1::2]))
    argv.update(zip(flags[::2], flags[1::2]))
    code, out, err = run(capsys, "derive", *[f"{k}={v}" for k, v in argv.items()],
                         "--directions", "8", "--json")
    assert code == 0, err
    assert_finite_output(out)
    d = json.loads(out)
    t = d["texture"]
    a, b = math.radians(t["alpha_deg"]), math.radians(t["beta_deg"])
    top = max(A.compute_H(t["mu_alpha"], a), A.compute_H(t["mu_beta"], b))
    mu = [d[k] for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus")]
    assert all(isinstance(x, float) and -1e-3 <= x <= top for x in mu), (mu, top)
    if tol is not None:
        ref = compute_wedge_axis_closed_form(a, b, t["mu_alpha"], t["mu_beta"])
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus"):
            assert d[k] == pytest.approx(ref[k], abs=tol), (k, d[k], ref[k])


@settings(max_examples=15, deadline=None)
@given(i=st.integers(-13, 26), j=st.integers(-29, 29), ratio=st.floats(2.0, 6.0),
       rest=st.floats(-3.0, 0.5))
def test_the_spring_model_is_scale_free(i, j, ratio, rest):
    """The kernels work in units of h and k_n h, so scaling h (1.2e-10 to 67 m) and k_n
    (1e-6 to 1e12 N/m) by powers of two at fixed k_f/k_n and preload/(k_n h) gives the same
    friction bit for bit (a 1e-300 m wedge once gave mu = 444200 from underflowing squares)."""
    h, k_n = TEX.height * 2.0 ** i, 1e3 * 2.0 ** j
    assume(abs(rest) * k_n * h <= 1e6 and k_n * 10 ** ratio <= 1e12)    # within the ranges
    psi = math.radians(37.0)
    ref = simulate_sliding(TEX, psi, SpringModel(k_n=1e3, k_f=1e3 * 10 ** ratio,
                                                 preload=-rest * 1e3 * TEX.height,
                                                 steps_per_period=2000))
    r = simulate_sliding(WedgeTexture(30, 10, 0.1, 0.2, height=h), psi,
                         SpringModel(k_n=k_n, k_f=k_n * 10 ** ratio, preload=-rest * k_n * h,
                                     steps_per_period=2000))
    np.testing.assert_array_equal(r.p, ref.p)
    assert r.normal_stress == ref.normal_stress * 2.0 ** (i + j)


@pytest.mark.parametrize("height", [1e-10, 3e-7, 1e-3, 100.0])
def test_rigid_springs_give_the_same_friction_at_every_height(height):
    """Any other scaling changes p by round-off only (rigid springs: no stick-slip path)."""
    psi = np.radians([0.0, 37.0, 90.0, 200.0])
    ref = simulate_reservoir(TEX, psi, SpringModel(preload=0.3e-3))
    r = simulate_reservoir(WedgeTexture(30, 10, 0.1, 0.2, height=height), psi,
                           SpringModel(preload=0.3e-3 * height / TEX.height))
    np.testing.assert_allclose(r.p, ref.p, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("deg", [180.0, 135.0, 225.0])
def test_a_tip_on_the_node_between_two_periods(deg):
    """Sliding towards -t_a, tips reach the node between two periods of the profile; it was
    computed from each side with a different rounding, a tip on it sat one rounding past
    its face's end and the kernel divided by zero (SystemError from the compiled code)."""
    tex = WedgeTexture(17.247954291507053, 19.05983806751716, 0.0, 0.2370101285940039,
                       height=0.00020259735937663115)
    model = SpringModel(k_n=1.7485729865146236e-05, k_f=5.5439149985106436e-05,
                        preload=8.785157296942389e-09, n_springs=8, steps_per_period=2000)
    r = simulate_sliding(tex, math.radians(deg), model)
    top = max(A.compute_H(tex.mu_alpha, tex.alpha), A.compute_H(tex.mu_beta, tex.beta))
    assert np.all(np.isfinite(r.p)) and not r.locked
    assert 0.0 < r.tangential and np.hypot(*r.p) <= top, (r.p, top)    # resists, bounded


# ----------------------------------------------------------------------------- class 4

#: (argv of derive, words of the message, API or CLI) requests refused before any work
RESOURCES = [
    ([*SPRINGS, "--n-springs", "1000000", "--steps-per-period", "100000000"],
     "needs 7.2e+09 spring-tip updates, at most 5e+09; lower n_springs or steps_per_period "
     "(--n-springs, --steps-per-period) or the number of directions (--directions)"),
    ([*SPRINGS, "--directions", "100000", "--k-f", "1e7"],
     "(elastic springs, 100000 directions) needs 1.73e+09 spring-tip updates"),
    ([*SPRINGS, "--k-f", "1e-3"], "wedge pitches; raise k_f/k_n (--k-f, --k-n)"),
    ([*SPRINGS, "--k-f", "1e7", "--preload", "1e3", "--height", "1e-9"],
     "the run-in of 20 elastic slip lengths"),
    ([*SPRINGS, "--steps-per-period", "100000000", "--n-springs", "1", "--k-f", "1e7"],
     "lower n_springs or steps_per_period"),
    ([SURF / "gaussian-wedges.toml", "--method", "springs", "--steps-per-period", "10000000"],
     "100 wedges) needs more than"),
]


@pytest.mark.parametrize("argv,msg", RESOURCES, ids=range(len(RESOURCES)))
def test_requests_too_long_for_the_spring_kernels_refused_at_once(capsys, argv, msg):
    code, out, err = run(capsys, "derive", *argv, "--json")
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


def test_a_profile_too_large_for_memory_refused_before_it_is_drawn(monkeypatch):
    from asperity import resources
    monkeypatch.setattr(resources, "available_memory", lambda: 2 << 30)
    g = GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 3e-7, n_wedges=10_000_000)
    with pytest.raises(ResourceError, match="a profile of 10000000 wedges needs about .* GB.*"
                                            "use fewer wedges"):
        g.profile()
    with pytest.raises(ResourceError, match="loading curve of 100000000 steps.*lower n_steps"):
        simulate_loading_curve(TEX, 0.0, SpringModel(k_f=1e6), n_steps=100_000_000)


def test_the_issue_examples_through_the_real_command(tmp_path):
    png = tmp_path / "old.png"
    png.write_bytes(b"old picture")
    assert_refused(cli("derive", *WEDGE, "--height", "1e-30", "--method", "springs", "--json"),
                   contains="--height must be in [1e-10, 100] m, got 1e-30")
    assert_refused(cli("derive", *SPRINGS, "--n-springs", "1000000", "--steps-per-period",
                       "100000000", "--plot", png), contains="at most 5e+09")
    assert png.read_bytes() == b"old picture"


def test_long_spring_simulations_report_progress(monkeypatch):
    seen = []
    monkeypatch.setattr(progress, "report", lambda f, label=None: seen.append((f, label)))
    monkeypatch.setattr(spring_runs, "UPDATES_PER_PIECE", {"rigid": 500, "elastic": 500})
    simulate_reservoir(TEX, np.radians([0.0, 45.0, 200.0]), SpringModel(k_f=1e7))
    fractions = [f for f, _ in seen]
    assert len(seen) > 20 and all(label == "spring simulation" for _, label in seen)
    assert fractions == sorted(fractions) and 0.9 < fractions[-1] <= 1.0


# ----------------------------------------------------------------------------- class 5

PIECES = {
    "rigid": (TEX, math.radians(30.0), SpringModel()),
    "elastic with run-in": (TEX, math.radians(37.0), SpringModel(k_f=1e5)),
    "elastic along the ridges": (TEX, math.radians(90.0), SpringModel(k_f=1e8)),
    "self-locking": (WedgeTexture(80, 10, 0.3, 0.1), 0.0, SpringModel(k_f=1e6)),
    "gaussian, rest level above the base": (
        GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.3e-6, n_wedges=5, seed=3), 2.0,
        SpringModel(k_f=1e8, preload=-0.8e-3, steps_per_period=2000)),
}


@pytest.mark.parametrize("case", list(PIECES))
def test_pieces_give_the_same_result_bit_for_bit(monkeypatch, case):
    tex, psi, model = PIECES[case]
    whole = simulate_sliding(tex, psi, model)
    calls = []
    monkeypatch.setattr(progress, "report", lambda f, label=None: calls.append(f))
    monkeypatch.setattr(spring_runs, "SPRINGS_PER_PIECE", 5)
    monkeypatch.setattr(spring_runs, "UPDATES_PER_PIECE", {"rigid": 37, "elastic": 23})
    pieces = simulate_sliding(tex, psi, model)
    assert len(calls) > 50
    np.testing.assert_array_equal(pieces.p, whole.p)
    for name in ("tangential", "lateral", "normal_stress", "locked", "locked_face",
                 "n_springs", "n_steps", "sliding_fraction", "set_valued"):
        assert getattr(pieces, name) == getattr(whole, name), name
    assert whole.locked == (case == "self-locking")


def test_loading_curve_pieces_give_the_same_curve_bit_for_bit(monkeypatch):
    tex, model = WedgeTexture(5, 5, 0.1, 0.1), SpringModel(k_f=1e7, preload=2e-3)
    whole = simulate_loading_curve(tex, 0.3, model, n_steps=300)
    monkeypatch.setattr(spring_runs, "SPRINGS_PER_PIECE", 7)
    monkeypatch.setattr(spring_runs, "UPDATES_PER_PIECE", {"rigid": 37, "elastic": 50})
    pieces = simulate_loading_curve(tex, 0.3, model, n_steps=300)
    for name in ("displacement", "tangential_stress", "lateral_stress", "normal_stress",
                 "sliding_fraction"):
        np.testing.assert_array_equal(getattr(pieces, name), getattr(whole, name), name)
    assert (pieces.k_t_measured, pieces.mu_steady) == (whole.k_t_measured, whole.mu_steady)


def test_ctrl_c_between_two_pieces_stops_the_simulation(monkeypatch):
    """KeyboardInterrupt (what Python raises on SIGINT once a kernel piece returns) ends
    the run at once: no further piece is computed."""
    calls = []

    def report(fraction, label=None):
        calls.append(fraction)
        if len(calls) == 3:
            raise KeyboardInterrupt
    monkeypatch.setattr(progress, "report", report)
    monkeypatch.setattr(spring_runs, "UPDATES_PER_PIECE", {"rigid": 500, "elastic": 500})
    with pytest.raises(KeyboardInterrupt):
        simulate_reservoir(TEX, np.radians([10.0, 20.0]), SpringModel(k_f=1e7))
    assert len(calls) == 3 and calls[-1] < 0.1


@pytest.mark.slow
def test_ctrl_c_stops_a_long_spring_simulation(tmp_path):
    png = tmp_path / "reservoir.png"
    status, err = interrupt("derive", SURF / "wedge-asymmetric.toml", "--method", "springs",
                            "--directions", "4000", "--plot", png)
    assert status == 130 and "interrupted" in err and "Traceback" not in err, err
    assert err.count("\n") == 1, err
    assert not list(tmp_path.iterdir())


# ----------------------------------------------------------------------------- class 6

nan = float("nan")
BAD_API = {
    "WedgeTexture(None)": lambda: WedgeTexture(None, 10, 0.1, 0.2),
    "WedgeTexture('30')": lambda: WedgeTexture("30", 10, 0.1, 0.2),
    "WedgeTexture(beta nan)": lambda: WedgeTexture(30, nan, 0.1, 0.2),
    "WedgeTexture(alpha 5e-324)": lambda: WedgeTexture(5e-324, 10, 0.1, 0.2),
    "WedgeTexture(mu -0.1)": lambda: WedgeTexture(30, 10, -0.1, 0.2),
    "WedgeTexture(height array)": lambda: WedgeTexture(30, 10, 0.1, 0.2, np.array([1e-6])),
    "WedgeTexture(height 1e-300)": lambda: WedgeTexture(30, 10, 0.1, 0.2, height=1e-300),
    "WedgeTexture(height inf)": lambda: WedgeTexture(30, 10, 0.1, 0.2, height=math.inf),
    "Gaussian(std > 3 mean)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 4e-6),
    "Gaussian(n_wedges 0)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.0, 0),
    "Gaussian(n_wedges '5')": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.0, "5"),
    "Gaussian(seed -1)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.0, seed=-1),
    "Gaussian(mean_gap nan)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.0,
                                                           mean_gap=nan),
    "Gaussian(mean_gap 1 m)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, 1e-6, 0.0,
                                                           mean_gap=1.0),
    "Gaussian(height_mean None)": lambda: GaussianWedgeTexture(30, 10, 0.1, 0.2, None, 0.0),
    "compute_H(-1, nan)": lambda: A.compute_H(-1, nan),
    "compute_H(0.1, nan)": lambda: A.compute_H(0.1, nan),
    "compute_H(None, 0.1)": lambda: A.compute_H(None, 0.1),
    "compute_H('0.1', 0.1)": lambda: A.compute_H("0.1", 0.1),
    "compute_H(x, y shapes)": lambda: A.compute_H([0.1, 0.2], [0.1, 0.2, 0.3]),
    "compute_H(0.1, pi/2)": lambda: A.compute_H(0.1, math.pi / 2),
    "compute_H(x nan in array)": lambda: A.compute_H(np.array([[0.1, nan]]), 0.1),
    "compute_H(y degrees)": lambda: A.compute_H(0.1, [10.0, 30.0]),
    "closed_form(alpha nan)": lambda: compute_wedge_axis_closed_form(nan, 0.2, 0.1, 0.2),
    "closed_form(alpha 30 rad)": lambda: compute_wedge_axis_closed_form(30.0, 0.2, 0.1, 0.2),
    "closed_form(mu None)": lambda: compute_wedge_axis_closed_form(0.5, 0.2, None, 0.2),
    "compute_axis_coefficients(None)": lambda: A.compute_axis_coefficients(None),
    "compute_axis_coefficients(contact)": lambda: A.compute_axis_coefficients(TEX, "lee"),
    "SpringModel(k_n None)": lambda: SpringModel(k_n=None),
    "SpringModel(k_f soft)": lambda: SpringModel(k_f="soft"),
    "SpringModel(k_f nan)": lambda: SpringModel(k_f=nan),
    "SpringModel(k_n 5e-324)": lambda: SpringModel(k_n=5e-324),
    "SpringModel(density 1e300)": lambda: SpringModel(density=1e300),
    "SpringModel(preload inf)": lambda: SpringModel(preload=math.inf),
    "SpringModel(n_springs 0.5)": lambda: SpringModel(n_springs=0.5),
    "SpringModel(n_springs True)": lambda: SpringModel(n_springs=True),
    "SpringModel(k_f/k_n 1e16)": lambda: SpringModel(k_n=1e-5, k_f=1e11),
    "SpringModel.from_dict(None)": lambda: SpringModel.from_dict(None),
    "SpringModel.from_dict(k_nn)": lambda: SpringModel.from_dict({"k_nn": 1.0}),
    "SpringModel.from_dict(k_f text)": lambda: SpringModel.from_dict({"k_f": "1e7"}),
    "simulate_sliding(None)": lambda: simulate_sliding(None, 0.0),
    "simulate_sliding(class)": lambda: simulate_sliding(WedgeTexture, 0.0),
    "simulate_sliding(surface)": lambda: simulate_sliding("wedge-asymmetric.toml", 0.0),
    "simulate_sliding(psi nan)": lambda: simulate_sliding(TEX, nan),
    "simulate_sliding(psi text)": lambda: simulate_sliding(TEX, "0"),
    "simulate_sliding(psi 1e300)": lambda: simulate_sliding(TEX, 1e300),
    "simulate_sliding(model None)": lambda: simulate_sliding(TEX, 0.0, None),
    "simulate_sliding(contact None)": lambda: simulate_sliding(TEX, 0.0, contact=None),
    "simulate_sliding(rest level)": lambda: simulate_sliding(TEX, 0.0, SpringModel(preload=-1)),
    "simulate_sliding(work)": lambda: simulate_sliding(TEX, 0.3, SpringModel(
        k_f=1e7, n_springs=10_000, steps_per_period=100_000_000)),
    "simulate_reservoir(None)": lambda: simulate_reservoir(TEX, None),
    "simulate_reservoir(text)": lambda: simulate_reservoir(TEX, "0 90"),
    "simulate_reservoir(2-D)": lambda: simulate_reservoir(TEX, [[0.0, 1.0]]),
    "simulate_reservoir([])": lambda: simulate_reservoir(TEX, []),
    "simulate_reservoir([nan])": lambda: simulate_reservoir(TEX, [0.0, nan]),
    "simulate_reservoir(model)": lambda: simulate_reservoir(TEX, [0.0], "rigid"),
    "simulate_reservoir(2e6 directions)": lambda: simulate_reservoir(TEX, np.zeros(2_000_000)),
    "simulate_loading_curve(rigid)": lambda: simulate_loading_curve(TEX, 0.0, SpringModel()),
    "simulate_loading_curve(distance -1)": lambda: simulate_loading_curve(
        TEX, 0.0, SpringModel(k_f=1e6), distance=-1.0),
    "simulate_loading_curve(distance inf)": lambda: simulate_loading_curve(
        TEX, 0.0, SpringModel(k_f=1e6), distance=math.inf),
    "simulate_loading_curve(distance 1e300)": lambda: simulate_loading_curve(
        TEX, 0.0, SpringModel(k_f=1e6), distance=1e300),
    "simulate_loading_curve(n_steps 1)": lambda: simulate_loading_curve(
        TEX, 0.0, SpringModel(k_f=1e6), n_steps=1),
    "simulate_loading_curve(n_steps '2000')": lambda: simulate_loading_curve(
        TEX, 0.0, SpringModel(k_f=1e6), n_steps="2000"),
    "simulate_loading_curve(model None)": lambda: simulate_loading_curve(TEX, 0.0, None),
    "derive(springs, model text)": lambda: derive(TEX, method="springs", model="fast"),
    "load_texture(None)": lambda: A.load_texture(None),
    "load_texture(123)": lambda: A.load_texture(123),
    "load_texture(bytes)": lambda: A.load_texture(b"t.toml"),
    "load_texture(missing)": lambda: A.load_texture("missing-texture.toml"),
    "texture_from_dict(None)": lambda: texture_from_dict(None),
    "texture_from_dict(kind [1])": lambda: texture_from_dict({"kind": [1]}),
    "texture_from_dict(no angles)": lambda: texture_from_dict({"kind": "wedge"}),
}


@pytest.mark.parametrize("name", list(BAD_API))
def test_public_api_raises_one_line_input_errors(name):
    with pytest.raises(InputError) as exc:
        BAD_API[name]()
    assert "\n" not in str(exc.value) and str(exc.value)
    if name in ("simulate_sliding(work)",):
        assert isinstance(exc.value, ResourceError)


def test_gaussian_wedges_with_gaps_below_the_rest_level(capsys):
    """The shipped Gaussian texture (flat gaps below the springs' rest level, which carry
    nothing) passes the sampling check without a warning and gives the closed form."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code, out, err = run(capsys, "derive", SURF / "gaussian-wedges.toml", "--method",
                             "springs", "--directions", "8", "--json")
        assert code == 0, err
        d = json.loads(out)
        assert d["mu_a_plus"] == pytest.approx(CLOSED["mu_a_plus"], abs=1e-3)
        code, out, err = run(capsys, "derive", SURF / "gaussian-wedges.toml", "--method",
                             "springs", "--steps-per-period", "50", "--json")
        assert code == 1 and "50 samples per pitch are too few" in err, err


def test_self_locking_is_reported_never_nan(capsys):
    code, out, err = run(capsys, "derive", SURF / "self-locking.toml", "--method", "springs",
                         "--k-f", "1e6", "--directions", "8", "--json")
    assert code == 0, err
    assert_finite_output(out)
    d = json.loads(out)
    assert d["mu_a_plus"] is None and d["self_locking"][0]["face"] == "alpha"
    r = simulate_sliding(WedgeTexture(80, 10, 0.3, 0.1), 0.0, SpringModel())
    assert r.locked and np.all(np.isinf(r.p)) and r.locked_face == 0


#: values a hand-edited [springs] table or a careless caller may hold in any field
ANY_VALUE = st.one_of(
    st.none(), st.booleans(), st.text(max_size=4), st.integers(-10**6, 10**25),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([5e-324, 1e-300, 1e-6, 1e-3, 1e3, 1e12, 1e300, -1.0, "inf", 0.0]))


@settings(max_examples=60, deadline=None)
@given(key=st.sampled_from(["k_n", "k_f", "density", "preload", "n_springs",
                            "steps_per_period"]), value=ANY_VALUE)
def test_any_spring_value_gives_finite_friction_or_one_error(key, value):
    MAX_UPDATES_SAVED = dict(MAX_UPDATES)
    MAX_UPDATES.update(rigid=2e6, elastic=1e5)       # keep every accepted run short
    try:
        model = SpringModel(**{"n_springs": 8, "steps_per_period": 2000, key: value})
        d = derive(TEX, method="springs", n_directions=8, model=model)
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc)
        return
    finally:
        MAX_UPDATES.update(MAX_UPDATES_SAVED)
    json.dumps(to_json(d), allow_nan=False)          # finite, or null where self-locking
