"""The body benchmark's measurements say what they measured: the best of two runs is the
faster one (a failed run never wins), and ``sliding_at_end`` is false for a point mass that
stopped within the slide time, true for one still moving (no timing asserted)."""
from __future__ import annotations

from asperity import coulomb_law
from asperity.dynamics import body_bench as bb


def test_best_of_two_is_the_faster_and_never_a_failed_run():
    slow, fast, failed = {"steps_per_second": 1e3}, {"steps_per_second": 2e3}, {"error": "x"}
    assert bb._best(slow, fast) is fast and bb._best(fast, slow) is fast
    assert bb._best(fast, failed) is fast and bb._best(failed, slow) is slow


def test_sliding_at_end_tells_a_stopped_point_mass_from_a_moving_one():
    # V0 = 10 m/s: mu = 3 stops it after 0.34 s of the 1 s slide, mu = 0.3 does not
    assert bb.point_mass_rate(coulomb_law(3.0), 0.01)["sliding_at_end"] is False
    assert bb.point_mass_rate(coulomb_law(0.3), 0.01)["sliding_at_end"] is True
