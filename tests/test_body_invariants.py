"""Bounds of the body solver that any correct solver keeps, checked without running one:
the rest horizon (the time by which a body with no external force is surely at rest) is
at least the exact stopping time of a uniformly loaded disc's pure slide (v0 / (mu g)) and
pure spin (3 R omega0 / (4 mu g)), for friction coefficients below and above 1."""
from __future__ import annotations

import math

import pytest

from asperity import coulomb_law
from asperity.bodies import footprint as fpm
from asperity.dynamics.body import rest_horizon

G = 9.81


@pytest.mark.parametrize("mu", [0.3, 1.0, 3.0])
@pytest.mark.parametrize("g", [G, 1.62])
def test_rest_horizon_bounds_the_closed_form_stopping_times(mu, g):
    R, m = 0.05, 2.0
    fp = fpm.disc(R, contact_points=256)
    inertia = m * fp.inertia_per_mass
    law = coulomb_law(mu)
    v0, w0 = 1.3, 40.0
    slide = rest_horizon(fp.points, fp.weights, law, m, inertia, (v0, 0.0, 0.0), g)
    spin = rest_horizon(fp.points, fp.weights, law, m, inertia, (0.0, 0.0, w0), g)
    t_slide, t_spin = v0 / (mu * g), 3 * R * w0 / (4 * mu * g)
    assert t_slide <= slide < 20 * t_slide
    assert t_spin <= spin < 20 * t_spin
    # both at once stop no later than the bound of the combined speed
    both = rest_horizon(fp.points, fp.weights, law, m, inertia, (v0, 0.0, w0), g)
    assert both == pytest.approx(math.hypot(slide, spin), rel=1e-12)
