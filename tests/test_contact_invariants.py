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
