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


@pytest.mark.parametrize("u0", [(0.03, 0.0, 2.0), (0.004, -0.002, 0.05), (0.5, 0.2, 1.0)])
def test_slide_and_spin_stop_times_are_where_the_motion_stays_below_the_threshold(u0):
    """BodyResult's slide (spin) stop time: from then on |v| (rho |omega|, rho = sqrt(I/m))
    stays below STOP_FRACTION of |v0| + rho |omega0| + g dt, and the step before was above
    -- read off the recorded states (every step), a body of 4 kg (m != 1), slow starts
    (a velocity scale below 1) included."""
    import numpy as np

    from asperity.dynamics.body import STOP_FRACTION, simulate_body
    fp = fpm.disc(0.05, contact_points=64)
    m, dt = 4.0, 2e-4
    inertia = m * fp.inertia_per_mass
    res = simulate_body(fp.points, fp.weights, coulomb_law(0.4), mass=m, inertia=inertia,
                        u0=u0, dt=dt)
    assert res.ok and res.rest
    rho = math.sqrt(inertia / m)
    thr = STOP_FRACTION * (math.hypot(u0[0], u0[1]) + rho * abs(u0[2]) + G * dt)
    for stop, speed in ((res.slide_stop_time, np.hypot(res.u[:, 0], res.u[:, 1])),
                        (res.spin_stop_time, rho * np.abs(res.u[:, 2]))):
        assert stop is not None and 0 < stop <= res.stop_time + 1e-12
        after = res.t >= stop - 1e-12
        assert np.all(speed[after] <= thr) and speed[~after][-1] > thr
