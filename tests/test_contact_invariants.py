"""Invariants of the elastic contact solver that any correct solver keeps: a load curve of
one pressure, with the defaults, is the single solve with the defaults; (more below)."""
from __future__ import annotations

import numpy as np
import pytest

from asperity.contact import solve_contact, solve_load_curve
from asperity.contact.bench import self_affine

E = 1e11


def scan(n=40, m=56, dx=1e-6, dy=1.5e-6, seed=3):
    """A rough map with non-square pixels, heights away from zero."""
    return self_affine(n, m, dx=dx, dy=dy, seed=seed) + 3e-5, (dx, dy)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_load_curve_of_one_pressure_with_the_defaults_is_the_single_solve(boundary):
    z, px = scan()
    p = 0.003 * E
    (curve,) = solve_load_curve(z, px, E, [p], boundary=boundary)
    single = solve_contact(z, px, E, p, boundary=boundary)
    assert curve.converged and single.converged
    assert curve.pressure_asked == p and curve.pixel_size == single.pixel_size
    np.testing.assert_allclose(curve.pressure, single.pressure, rtol=0,
                               atol=1e-9 * single.max_pressure)
    assert curve.iterations == single.iterations
    assert curve.mean_pressure == pytest.approx(p, rel=1e-8)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
@pytest.mark.parametrize("shape", [(12, 10), (9, 7)], ids=["even", "odd"])
def test_self_compliance_is_the_operators_diagonal(boundary, shape):
    """HalfSpace.self_compliance, the displacement of a pixel under unit pressure on it
    alone, is K's diagonal: apply K to a unit pressure at any pixel and read it there."""
    from asperity.contact.elastic import HalfSpace
    space = HalfSpace(shape, 1e-6, 2.5e-6, E, boundary)
    for i, j in ((0, 0), (shape[0] // 2, shape[1] - 1), (3, 2)):
        p = np.zeros(shape)
        p[i, j] = 1.0
        u = space.apply(p, np.empty(shape))
        assert u[i, j] == pytest.approx(space.self_compliance, rel=1e-10, abs=0)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_memory_refusal_counts_every_pixel(boundary, monkeypatch):
    """The solve plans its bytes a pixel times the pixels: 10 % less free memory than that
    is refused in one line before any work, 10 % more is solved."""
    from asperity import resources
    from asperity.contact import elastic
    from asperity.errors import ResourceError
    z, px = scan()
    need = elastic.BYTES_PER_PIXEL[boundary] * z.size
    monkeypatch.setattr(resources, "available_memory",
                        lambda: int(0.9 * need / resources.MEMORY_SHARE))
    with pytest.raises(ResourceError, match=f"{z.shape[0]} x {z.shape[1]} pixels"):
        solve_contact(z, px, E, 0.003 * E, boundary=boundary)
    monkeypatch.setattr(resources, "available_memory",
                        lambda: int(1.1 * need / resources.MEMORY_SHARE))
    assert solve_contact(z, px, E, 0.003 * E, boundary=boundary).converged


def test_bearing_area_fill_keeps_the_load_under_the_cap():
    """The plastic solve's fill: the contact pixels at H and the rest of the load on the
    most penetrating pixels out of contact (smallest u - h), the load exact, nothing
    above H, nothing on undefined pixels (on the flat views the solver passes)."""
    from asperity.contact.loads import fill
    rng = np.random.default_rng(4)
    shape, H = (1200,), 2.0
    h = rng.normal(size=shape)
    h[rng.random(shape) < 0.1] = np.nan
    u = rng.normal(size=shape)
    p = np.where(rng.random(shape) < 0.05, rng.uniform(0.1, H, shape), 0.0)
    p[np.isnan(h)] = 0.0
    on = p > 0
    for extra in (0.5, 7.25, 100.0):
        load = H * (on.sum() + extra)
        q = p.copy()
        fill(q, u, h, load, H)
        assert q.sum() == pytest.approx(load, rel=1e-12)
        assert q.max() <= H and q.min() >= 0.0 and not q[np.isnan(h)].any()
        assert np.all(q[on] == H)
        k = int(np.ceil(extra))
        g = np.where(~on & ~np.isnan(h), u - h, np.inf)
        assert set(np.flatnonzero((q > 0) & ~on)) == set(np.argsort(g, kind="stable")[:k])


@pytest.mark.parametrize("boundary", ["periodic", "free"])
@pytest.mark.parametrize("ratio,outer", [(None, False), (1.6, False), (1.6, True)],
                         ids=["elastic", "capped", "capped-outer-loop"])
def test_gap_is_displacement_minus_heights_plus_approach(boundary, ratio, outer, monkeypatch):
    """g = u - h + d (the result's displacement and approach): zero on the contact
    pixels, positive off them, and the mean gap its mean over the defined pixels; with a
    cap, no pressure above it -- also when the plastic set comes from the outer loop
    (forced: the capped single iteration given one iteration to converge)."""
    from asperity.contact import solver
    if outer:
        monkeypatch.setattr(solver, "PLASTIC_FIRST_TRY", 1)
    z, px = scan()
    p = 0.003 * E
    res = solve_contact(z, px, E, p, boundary=boundary,
                        hardness=None if ratio is None else ratio * p)
    assert res.converged and (ratio is None or res.plastic_fraction > 0)
    g = res.displacement - z + res.approach
    span = np.ptp(z)
    off = ~res.contact
    np.testing.assert_allclose(res.gap[off], g[off], rtol=0, atol=1e-9 * span)
    assert np.all(res.gap[res.contact] == 0.0) and res.gap[off].min() > -1e-9 * span
    assert res.mean_gap == pytest.approx(res.gap.mean(), rel=1e-12, abs=0)
    if ratio is not None:
        assert np.nanmax(res.pressure) <= ratio * p * (1 + 1e-12)


@pytest.mark.parametrize("args,field", [
    ((0.0, 0.3), "E1"), ((-5e9, 0.3), "E1"), ((-0.5, 0.3), "E1"), ((1e9, -1.0), "nu1"),
    ((1e9, 0.51), "nu1"), ((1e9, 0.3, 0.0, 0.3), "E2"), ((1e9, 0.3, 1e9, 0.6), "nu2"),
    ((1e9, 0.3, 1e9, None), "E2 and nu2 together")])
def test_effective_modulus_takes_only_physical_materials(args, field):
    """E > 0 and -1 < nu <= 0.5 (the edge nu = 0.5, incompressible, is allowed: E* =
    E / 0.75 on a rigid counterface); anything else is one line naming the field."""
    from asperity.contact.solver import effective_modulus
    from asperity.errors import InputError
    assert effective_modulus(3e9, 0.5) == pytest.approx(4e9, rel=1e-14)
    with pytest.raises(InputError) as e:
        effective_modulus(*args)
    assert field in str(e.value) and "\n" not in str(e.value)


@pytest.mark.parametrize("E1,E2", [(0.5, None), (1e-3, 2e-3), (7e11, 0.25)])
def test_effective_modulus_is_the_closed_form_over_the_whole_open_range(E1, E2):
    """Any E > 0, however soft (below 1 Pa too: the range is open at 0, not at 1 Pa), gives
    1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2."""
    from asperity.contact.solver import effective_modulus
    nu1, nu2 = 0.3, 0.45
    if E2 is None:
        assert effective_modulus(E1, nu1) == pytest.approx(E1 / (1 - nu1 ** 2), rel=1e-14)
    else:
        want = 1 / ((1 - nu1 ** 2) / E1 + (1 - nu2 ** 2) / E2)
        assert effective_modulus(E1, nu1, E2, nu2) == pytest.approx(want, rel=1e-14)


@pytest.mark.parametrize("shape", [(1, 6), (6, 1), (1, 1)])
def test_a_map_one_pixel_thin_along_either_side_is_refused_in_one_line(shape):
    from asperity.errors import InputError
    with pytest.raises(InputError, match="at least 2 x 2 pixels") as e:
        solve_contact(np.zeros(shape), 1e-6, 1e9, 1e6)
    assert "\n" not in str(e.value)


def test_the_hardness_must_exceed_the_mean_pressure_over_the_defined_pixels():
    """13 of 16 pixels defined: the defined pixels carry p * 16 / 13 on average, so a cap
    just below that (here above p and within 1 Pa of the mean) cannot carry the load and is
    refused naming the field; just above it is a solve whose pressure stays at the cap."""
    from asperity.errors import InputError
    z = np.add.outer(np.arange(4.0), np.arange(4.0)) * 1e-7
    z[0, :3] = np.nan
    p = 3.0
    mean = p * 16 / 13
    with pytest.raises(InputError, match="hardness") as e:
        solve_contact(z, 1e-6, 1e6, p, hardness=mean * (1 - 1e-9))
    assert "\n" not in str(e.value)
    res = solve_contact(z, 1e-6, 1e6, p, hardness=mean * 1.5)
    assert np.nanmax(res.pressure) <= mean * 1.5 * (1 + 1e-12)


@pytest.mark.parametrize("boundary", ["free", "periodic"])
@pytest.mark.parametrize("plateau", ["one pixel", "2 x 2"])
def test_complementarity_of_a_fully_plastic_plateau_and_of_a_pixel_through_the_half_space(
        boundary, plateau):
    """A plateau of k pixels loaded with exactly k H: every contact pixel at the cap, none
    free (0 < p < H), so the rigid approach comes from the plastic pixels alone.  The
    solve's answer satisfies the complementarity the iteration stops on (.gaps), in the
    iteration's unit of length; the same state with one pixel out of contact lifted half
    the height range above the plateau (it would cut through the half-space) does not."""
    from asperity.contact import _pk_kernels as K
    from asperity.contact import elastic, gaps
    n, dx, E, H = 16, 1e-6, 1e9, 2e7
    z = np.zeros((n, n))
    top = (slice(7, 8), slice(7, 8)) if plateau == "one pixel" else (slice(7, 9), slice(7, 9))
    z[top] = 1e-6
    k = int(np.count_nonzero(z))
    P = H * k / n ** 2
    res = solve_contact(z, dx, E, P, boundary=boundary, hardness=H)
    assert res.converged and np.all(res.pressure[top] == H) and res.contact.sum() == k
    space = elastic.HalfSpace(z.shape, dx, dx, E, boundary)
    L = gaps.reference_length(space, z, P)
    h = (z - z.max()) / L
    p, u = res.pressure / L, np.empty_like(h)

    def holds(heights):
        return gaps.complementary(K, space, p, u, heights, H / L, 1, 1e-6, P / L)
    assert holds(h)
    lifted = h.copy()
    lifted[0, 0] = 0.5 * (h.max() - h.min())
    assert not holds(lifted)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_unloading_from_a_capped_solution_lands_on_the_cold_answer_as_fast(boundary):
    """A capped load curve going down: started from the solution at twice the load, whose
    pixels at the cap alone carry about twice the new load, the solve scales every pixel
    down (none can stay fixed at H) and lands on the cold solve's answer in no more
    iterations than the cold solve, give or take half (measured: 12 against 14)."""
    x = np.linspace(0, 2 * np.pi, 32, endpoint=False)
    z = 1e-6 * (np.sin(x)[:, None] * np.cos(2 * x)[None, :] + 0.3 * np.cos(3 * x)[:, None]
                + 0.2 * np.sin(5 * x + 1)[None, :])
    E, H, p = 1e9, 6e7, 2e7
    heavy = solve_contact(z, 1e-6, E, 2 * p, boundary=boundary, hardness=H)
    assert np.count_nonzero(heavy.pressure >= H) * H > 1.5 * p * z.size
    cold = solve_contact(z, 1e-6, E, p, boundary=boundary, hardness=H)
    warm = solve_contact(z, 1e-6, E, p, boundary=boundary, hardness=H, initial=heavy.pressure)
    assert np.abs(warm.pressure - cold.pressure).max() < 1e-6 * H
    assert warm.iterations <= 1.5 * cold.iterations, (warm.iterations, cold.iterations)


@pytest.mark.parametrize("boundary", ["free", "periodic"])
def test_the_reference_length_is_the_height_range_or_the_nominal_displacement(boundary):
    """The length the complementarity is measured against (.gaps) is the height range, or,
    when larger, the displacement of one pixel under the nominal pressure alone: a closed
    form, the same for the heights shifted by any constant (the datum is arbitrary) and
    blind to undefined pixels."""
    from asperity.contact import elastic, gaps
    z, (dx, dy) = scan(12, 10)
    space = elastic.HalfSpace(z.shape, dx, dy, E, boundary)
    span = float(z.max() - z.min())
    light = 1e-3 * span / space.self_compliance
    heavy = 1e3 * span / space.self_compliance
    holed = z.copy()
    holed[0, 0] = np.nan
    for shift in (0.0, -z.max(), -z.min(), 1.0, -7e-3):
        assert gaps.reference_length(space, z + shift, light) == pytest.approx(span, rel=1e-9)
        assert gaps.reference_length(space, z + shift, heavy) == pytest.approx(
            heavy * space.self_compliance, rel=1e-12)
        assert gaps.reference_length(space, holed + shift, light) == pytest.approx(
            float(np.nanmax(holed) - np.nanmin(holed)), rel=1e-9)


@pytest.mark.parametrize("cap", [1.5, 3.0])
def test_a_capped_solve_in_other_units_is_the_same_solve(cap):
    """Lengths times 1e5 (heights and pixels: the same slopes) and E* 1 Pa instead of 1e11
    with the same p / E* and H / p: the same contact problem, whose pressures scale with E*
    and whose gaps scale with the lengths.  The solve works in units of its own (every
    number near 1, whatever the scale), so it is also the same iteration: the pressure
    field in units of E* agrees, and the iteration counts differ by rounding only (a step
    that mixes a pressure with a pure number, e.g. a load sum starting at 1, would see it at
    one scale and not at the other)."""
    z, (dx, dy) = scan()
    k, E1 = 1e5, 1.0
    p = 0.003 * E
    base = solve_contact(z, (dx, dy), E, p, hardness=cap * p)
    other = solve_contact(z * k, (dx * k, dy * k), E1, p / E * E1, hardness=cap * p / E * E1)
    assert base.converged and other.converged
    np.testing.assert_allclose(other.pressure / E1, base.pressure / E, rtol=0,
                               atol=1e-6 * base.max_pressure / E)
    assert abs(other.area_fraction - base.area_fraction) <= 1.0 / z.size    # a pixel
    assert abs(other.iterations - base.iterations) <= max(3, 0.25 * base.iterations)
