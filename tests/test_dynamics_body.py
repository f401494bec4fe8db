"""The rigid-body solver (asperity.dynamics.body): a footprint of N contact points that slides,
spins and sticks as one body (issue 20; SPEC.md sections 4 and 8)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.dynamics.body import simulate_body
from asperity.dynamics.moreau import Force
from asperity.errors import InputError
from asperity.laws.planar import coulomb_law, ellipse_law


def disc_points(R, rings=8, sectors=32):
    """Midpoint polar rings of a uniformly loaded disc: weights = cell areas / disc area."""
    r = (np.arange(rings) + 0.5) / rings * R
    th = (np.arange(sectors) + 0.5) / sectors * 2 * math.pi
    rr, tt = np.meshgrid(r, th, indexing="ij")
    pts = np.column_stack([(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel()])
    w = rr.ravel()
    return pts, w / w.sum()


def test_constant_wrench_inside_limit_set_sticks_bit_for_bit():
    pts, w = disc_points(0.1, 4, 16)
    f = Force(constant=(0.5, -0.3, 0.01))                   # |F| = 0.58 N < mu m g = 2.9 N
    r = simulate_body(pts, w, coulomb_law(0.3), mass=1.0, inertia=0.005, q0=(0.2, 0.1, 0.3),
                      dt=1e-3, t_end=0.2, force=f)
    assert r.ok
    assert np.all(r.u == 0.0)
    assert np.all(r.q == np.array([0.2, 0.1, 0.3]))


def test_bad_input_is_one_line():
    pts, w = disc_points(0.1, 2, 8)
    law = coulomb_law(0.3)
    kw = dict(mass=1.0, inertia=0.005, u0=(1.0, 0.0, 0.0), dt=1e-3)
    for bad in (dict(points=pts[:, :1]), dict(weights=w[:-1]), dict(weights=-w),
                dict(weights=2 * w), dict(u0=(math.nan, 0, 0)), dict(u0=(0, 0, math.inf)),
                dict(inertia=0.0), dict(dt=0.0), dict(dt=2.0), dict(t_end=-1.0)):
        args = dict(points=pts, weights=w, law=law, **kw)
        args.update(bad)
        with pytest.raises(InputError) as e:
            simulate_body(args.pop("points"), args.pop("weights"), args.pop("law"), **args)
        assert "\n" not in str(e.value)
