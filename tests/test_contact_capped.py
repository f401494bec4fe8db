"""The capped (elastic-perfectly-plastic) contact solve where it used to stall, and the
solver's numbers at the ends of the float range (issue 25, item 2).

* ``asperity contact surfaces/wedge-asymmetric.toml --elastic 1e9 --pressure 1e7
  --hardness 2e7`` ran 10000 iterations (69 s) without converging while 1.5e7 and 3e7
  converged: a sweep of the hardness through that point on the same profile (512 nodes: one
  in six caps of the sweep stalled), the command itself, and a sweep of caps on a rough
  map; each result checked against the invariants of the capped problem (the load carried,
  no pressure above H, the complementarity with an independent operator) and the
  fully plastic limit (the area at least P / H of the map, hardly more);
* heights around 1e-306 m (a flat map) gave a residual of 3e290; heights times 1e300 an
  OverflowError: the solve is invariant under a change of the length unit (heights and
  pixel together), a map far flatter than the elastic displacement is in full contact at
  the nominal pressure, heights beyond the coordinate range are refused in one line.
"""
from __future__ import annotations

import sys
from functools import cache
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_json
from test_contact_solver import gap_violation as violations

from asperity.contact import solve_contact
from asperity.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from contact_peers import self_affine

WEDGE_FILE = ROOT / "surfaces" / "wedge-asymmetric.toml"
E, P = 1e9, 1e7                                # the issue's command


@cache
def wedge_profile(n: int = 512):
    """The profile of wedge-asymmetric.toml over one period on ``n`` nodes, two columns
    (the plane-strain map ``asperity contact`` solves), and the node spacing."""
    from asperity.texture.wedges import load_texture_file
    prof = load_texture_file(WEDGE_FILE).texture.profile()
    dx = prof.period / n
    z = prof.height(np.arange(n) * dx)
    return np.repeat(z[:, None], 2, axis=1), dx


def check_capped(z, res, pbar, H):
    """The capped problem's invariants and the fully plastic bound."""
    n = np.count_nonzero(np.isfinite(z))
    assert res.converged and res.residual <= 1e-8
    assert np.nanmax(res.pressure) <= H * (1 + 1e-12) and np.nanmin(res.pressure) >= 0.0
    assert np.nansum(res.pressure) == pytest.approx(pbar * z.size, rel=1e-10)   # the load
    assert max(violations(z, res)) < 1e-6
    # at most H per pixel: at least pbar x (map) / H pixels carry the load
    assert res.area_fraction * n * H >= pbar * z.size * (1 - 1e-12)
    assert res.plastic_fraction <= res.area_fraction


# ---- the wedge of the issue --------------------------------------------------------------

SWEEP = sorted({*np.round(np.geomspace(1.2e7, 5e7, 19), -3), 1.5e7, 1.58e7, 1.999e7, 2e7,
                2.001e7, 2.1e7, 3e7, 3.765e7})


def test_hardness_sweep_through_the_stalled_cap_converges():
    """The wedge's profile, caps from 1.2 to 5 times the mean pressure: each solve within
    100 iterations (measured: 4 to 52, mean 19; before, 10 of these 27 caps reached the
    limit: the iteration cycled between contact sets at the plastic zone's edges), the
    invariants held, and the contact essentially plastic (H << E* x slope): the area
    between P / H and P / H + 3 % of the map."""
    z, dx = wedge_profile()
    its = []
    for H in SWEEP:
        res = solve_contact(z, dx, E, P, hardness=H, max_iterations=300, workers=1)
        check_capped(z, res, P, H)
        assert res.area_fraction <= P / H + 0.03, H
        assert res.plastic_fraction >= P / H - 0.03, H
        its.append(res.iterations)
    assert max(its) <= 100, list(zip(SWEEP, its))


def test_the_issue_command_converges(capsys):
    """The command of the issue: converged in a few dozen iterations (measured 48, on the
    4096-node profile the command picks), half the period at H."""
    d = run_json(capsys, "contact", str(WEDGE_FILE), "--elastic", "1e9", "--pressure", "1e7",
                 "--hardness", "2e7", "--max-iterations", "1000")
    assert d["converged"] and d["iterations"] <= 200 and d["residual"] <= 1e-8
    assert d["area_fraction"] == pytest.approx(0.5, abs=0.01)
    assert d["plastic_fraction"] == pytest.approx(0.5, abs=0.01)
    assert d["max_pressure_Pa"] == pytest.approx(2e7, rel=1e-12)


@cache
def rough(holes: bool):
    z = self_affine(64, 48, dx=1e-6, seed=3)
    if holes:
        z[np.random.default_rng(4).random(z.shape) < 0.05] = np.nan
    return z


@pytest.mark.parametrize("boundary", ["periodic", "free"])
@pytest.mark.parametrize("holes", [False, True])
def test_cap_sweep_on_a_rough_map(boundary, holes):
    """Caps from 1.05 to 8 times the mean pressure over the defined pixels (a cap of 2
    took 718 iterations before: 300 of a stalled single iteration, then the outer loop's
    elastic solves to 1e-8 each): every solve within 60 iterations (measured 8 to 19), the
    invariants held, and the plastic share falling as the cap rises."""
    z = rough(holes)
    pbar = 2.5e8
    mean = pbar * z.size / np.count_nonzero(np.isfinite(z))
    shares = []
    for ratio in (1.05, 1.3, 2.0, 3.0, 5.0, 8.0):
        res = solve_contact(z, 1e-6, 1e11, pbar, boundary=boundary, hardness=ratio * mean,
                            max_iterations=300, workers=1)
        check_capped(z, res, pbar, ratio * mean)
        assert res.iterations <= 60, (ratio, res.iterations)
        shares.append(res.plastic_fraction)
    assert all(a > b for a, b in pairwise(shares)), shares


# ---- the ends of the float range ---------------------------------------------------------

@pytest.mark.parametrize("scale", [1e-306, 1e-300, 1e-200, 1e-20])
def test_a_map_far_flatter_than_the_displacement_is_in_full_contact(scale):
    """Heights of 1e-306 m (and 1e-20 m) under 1 MPa on E* = 1 GPa: far below the
    displacement the pressure causes (1e-9 m), so in full contact at the nominal pressure
    (the residual was 3e290: the complementarity was measured against a height range
    below the displacement's rounding)."""
    z = scale * np.random.default_rng(1).standard_normal((32, 24))
    for boundary in ("periodic", "free"):
        res = solve_contact(z, 1e-6, 1e9, 1e6, boundary=boundary)
        assert res.converged and 0.0 <= res.residual <= 1e-8
        assert res.full_contact and res.area_fraction == 1.0 and res.mean_gap == 0.0
        if boundary == "periodic":                 # p = p_bar + O(E* scale / dx)
            assert np.abs(res.pressure - 1e6).max() <= 1e-6 * 1e6
        assert np.nansum(res.pressure) == pytest.approx(1e6 * z.size, rel=1e-12)
        assert np.isfinite(res.approach) and np.isfinite(res.displacement).all()


@pytest.mark.parametrize("boundary", ["periodic", "free"])
@pytest.mark.parametrize("capped", [False, True])
def test_a_change_of_length_unit_changes_nothing_but_the_lengths(boundary, capped):
    """Heights and pixel size times k (the slopes kept; k from 1e-6 to 1e6, the pixel
    from 1e-12 m to 1 m): the same pressures, contact and plastic set, iterations; the
    gaps, displacements and approach times k (the half-space has no length of its own)."""
    z = rough(True)
    H = 1e9 if capped else None
    ref = solve_contact(z, 1e-6, 1e11, 2.5e8, boundary=boundary, hardness=H, tol=1e-10)
    for k in (1e-6, 1e-3, 1e3, 1e6):
        res = solve_contact(z * k, 1e-6 * k, 1e11, 2.5e8, boundary=boundary, hardness=H,
                            tol=1e-10)
        assert np.array_equal(res.contact, ref.contact)
        assert res.area_fraction == ref.area_fraction
        assert res.plastic_fraction == ref.plastic_fraction
        assert np.nanmax(np.abs(res.pressure - ref.pressure)) <= 1e-9 * ref.max_pressure
        assert res.approach == pytest.approx(k * ref.approach, rel=1e-9)
        assert res.mean_gap == pytest.approx(k * ref.mean_gap, rel=1e-9)
        assert np.nanmax(np.abs(res.gap - k * ref.gap)) <= 1e-9 * k * np.nanmax(ref.gap)
        assert abs(res.iterations - ref.iterations) <= 2


@pytest.mark.parametrize("scale", [1e4, 1e300])
def test_heights_beyond_the_coordinate_range_are_refused_in_one_line(scale):
    z = scale * np.random.default_rng(1).standard_normal((16, 16))
    with pytest.raises(InputError) as exc:
        solve_contact(z, 1e-6, 1e9, 1e6)
    msg = str(exc.value)
    assert msg.startswith("heights must lie within +-1000 m") and "\n" not in msg
