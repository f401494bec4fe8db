"""The gait optimiser (issue 26, item 5) against the tube limit's closed form.

With mu_t / mu_f large the body slides along its own track: U = J0(x) / k body lengths per
period with x = A / (2 pi k) (the tangent angle's amplitude), and the cost of transport is
mu_f / J0(x) (every point slides the track's length L / k a period against mu_f m g; the
centre moves J0(x) L / k).  So:

* at fixed k, U falls with A (J0 falls on [0, 3.83]): the fastest A is the box's lowest;
* at fixed A, dU/dk = (x J1(x) - J0(x)) / k^2: the fastest k is interior, x* J1(x*) =
  J0(x*) (x* = 1.2558), k* = A / (2 pi x*) -- if that k lies in the box and its gait does
  not cross itself;
* the cheapest gait has the least x = A / (2 pi k): A lowest, k high; its cost tends to
  mu_f.  So the fastest and the cheapest gaits differ (k low against k high).
"""
from __future__ import annotations

import json
import math

import pytest
from cli_run import run
from scipy.optimize import brentq
from scipy.special import j0, j1

from asperity.crawling.design import optimise_gait
from asperity.crawling.solver import coefficient_law
from asperity.errors import InputError

MU = 0.01
TUBE = coefficient_law(MU, MU, 1000 * MU, "associated")        # mu_t / mu_f = 1000
X_STAR = brentq(lambda x: x * j1(x) - j0(x), 0.5, 2.0)


def tube_speed(A, k):
    return j0(A / (2 * math.pi * k)) / k


def test_waves_alone_finds_the_interior_tube_optimum():
    r = optimise_gait(TUBE, params=("waves",), amplitude=7.0)
    k_star = 7.0 / (2 * math.pi * X_STAR)                     # 0.8872
    assert r.optimum["amplitude"] == 7.0 and r.fixed == {"amplitude": 7.0}
    assert r.optimum["waves"] == pytest.approx(k_star, rel=1e-2)
    assert r.speed == pytest.approx(tube_speed(7.0, k_star), rel=5e-4)
    assert r.speed > max(r.grid["objective"])                  # beyond the grid's best
    assert r.converged and r.infeasible == 0


def test_both_in_a_box_with_self_crossing_gaits():
    """A in [4, 8], k in [0.3, 2]: A = 4 (the box's lowest) and k = 4 / (2 pi x*) = 0.507,
    inside the box; at high A and low k the body curls onto itself (infeasible)."""
    r = optimise_gait(TUBE, bounds={"A": (4.0, 8.0), "k": (0.3, 2.0)})
    k_star = 4.0 / (2 * math.pi * X_STAR)
    assert r.infeasible > 0
    assert r.optimum["amplitude"] == pytest.approx(4.0, abs=0.02)
    assert r.optimum["waves"] == pytest.approx(k_star, rel=1.5e-2)
    assert r.speed == pytest.approx(tube_speed(4.0, k_star), rel=2e-3)


def test_fastest_and_cheapest_gaits_differ():
    fast = optimise_gait(TUBE, grid=5)
    cheap = optimise_gait(TUBE, grid=5, objective="cost")
    # fastest: the corner A = 0.5, k = 0.5 (U = 2 J0(1 / 2 pi) = 1.987)
    assert fast.optimum["amplitude"] == pytest.approx(0.5, abs=0.01)
    assert fast.optimum["waves"] == pytest.approx(0.5, abs=0.01)
    assert fast.speed == pytest.approx(tube_speed(0.5, 0.5), rel=3e-3)
    # cheapest: A lowest, the cost near its floor mu_f, far from the fastest gait's k
    assert cheap.optimum["amplitude"] == pytest.approx(0.5, abs=0.05)
    assert cheap.optimum["waves"] > 1.0
    assert MU < cheap.cost < 1.003 * MU
    assert cheap.cost < fast.cost and cheap.speed < fast.speed


def test_infeasible_everywhere_is_one_line():
    with pytest.raises(InputError, match="no gait of the grid is feasible"):
        optimise_gait(TUBE, grid=3, bounds={"amplitude": (13.0, 14.0), "waves": (0.5, 0.55)})
    # tail-ward on every gait (mu_t < mu_f): nothing moves head-ward, no cost to minimise
    with pytest.raises(InputError, match="cost"):
        optimise_gait(mu_f=0.2, mu_b=0.2, mu_t=0.1, rule="associated", grid=3,
                      objective="cost", bounds={"A": (4, 6), "k": (1, 1.5)})


@pytest.mark.parametrize("kw,match", [
    ({"params": ("speed",)}, "unknown parameter"),
    ({"params": ()}, "params"),
    ({"bounds": {"A": (3.0, 1.0)}}, "low 3 must be below high 1"),
    ({"bounds": {"A": (1.0, 101.0)}}, r"bounds.amplitude high must be in \[0, 100\]"),
    ({"bounds": {"waves": (0.0, 2.0)}}, r"bounds.waves low"),
    ({"params": ("amplitude",), "bounds": {"k": (1.0, 2.0)}}, "waves is not optimised"),
    ({"objective": "slow"}, "objective"),
    ({"grid": 2}, "grid"),
])
def test_bad_arguments_refused(kw, match):
    with pytest.raises(InputError, match=match):
        optimise_gait(TUBE, **kw)


def test_command_json_plot_and_the_crawl_at_the_optimum(capsys, tmp_path):
    png = tmp_path / "design.png"
    code, out, err = run(capsys, "crawl", "--mu-f", MU, "--mu-b", MU, "--mu-t", 1000 * MU,
                         "--rule", "associated", "--quasi-static", "--optimise", "k",
                         "--amplitude", 7, "--optimise-grid", 5, "--points", 100,
                         "--json", "--plot", png)
    assert code == 0, err
    obj = json.loads(out)
    o = obj["optimum"]
    assert o["params"] == ["waves"] and o["objective"] == "speed" and o["rule"] == "associated"
    assert obj["gait"]["waves"] == o["waves"] and obj["gait"]["amplitude"] == 7.0
    assert obj["points"] == 100 and o["search_points"] == 60
    # the crawl at the optimum (100 points, 200 steps) and the search's (60, 100) agree
    assert obj["speed_body_lengths_per_period"] == pytest.approx(
        o["search_speed_body_lengths_per_period"], rel=1e-3)
    assert o["evaluations"] > 5 and o["seconds"] > 0
    assert png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("argv,msg", [
    (["--optimise", "speed"], "--optimise: unknown parameter 'speed'"),
    (["--optimise", "A", "--bounds", "A=3:1"], "--bounds amplitude: low 3 must be below"),
    (["--optimise", "A", "--bounds", "A=-1:2"], "--bounds amplitude low must be in [0, 100]"),
    (["--optimise", "A", "--bounds", "k=1:2"], "--bounds waves: waves is not optimised"),
    (["--optimise", "A", "--bounds", "A=1"], "--bounds: 'A=1' must be NAME=LOW:HIGH"),
    (["--optimise", "A", "--bounds", "A=x:2"], "--bounds A low must be a number"),
    (["--optimise", "A", "--amplitude", "3"], "--amplitude does not apply"),
    (["--objective", "cost"], "--objective applies with --optimise only"),
    (["--bounds", "A=1:2"], "--bounds applies with --optimise only"),
    (["--optimise", "A", "--optimise-points", "2"], "--optimise-points must be"),
])
def test_bad_flags_one_line_exit_1(capsys, argv, msg):
    code, out, err = run(capsys, "crawl", "--mu-f", 0.1, "--mu-b", 0.15, "--mu-t", 0.2,
                         "--quasi-static", *argv)
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and msg in err and "Traceback" not in err


def test_bounds_reach_the_gaits_own_range_and_no_further():
    """Bounds may go to the gait's range, amplitude [0, 100] and waves (0, 20], ends
    included where the gait takes them; one step past is refused naming the range."""
    from asperity.crawling.design import check_bounds
    from asperity.errors import InputError
    got = check_bounds({"A": (0.0, 100.0), "k": (1e-9, 20.0)}, ("amplitude", "waves"))
    assert got == {"amplitude": (0.0, 100.0), "waves": (1e-9, 20.0)}
    with pytest.raises(InputError, match=r"bounds.waves high must be in \(0, 20\]"):
        check_bounds({"k": (1.0, 20.000001)}, ("waves",))
    with pytest.raises(InputError, match=r"bounds.waves low must be in \(0, 20\]"):
        check_bounds({"k": (0.0, 2.0)}, ("waves",))
