"""Invariants of sampled footprints that hold for any footprint, whatever its sampling rule:
a pure slide's Coulomb friction is the whole load opposite the velocity, acting at the
centre of pressure; a pure spin's torque is the load-weighted mean distance from the spin
centre; a point at rest (on the instantaneous centre) carries no force."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.bodies import accuracy as fpa
from asperity.bodies import footprint as fpm


def cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


@pytest.mark.parametrize("make", [
    lambda: fpm.disc(0.05, contact_points=300, profile="linear",
                     centre_of_pressure=(0.01, -0.004)),
    lambda: fpm.rectangle(0.08, 0.02, contact_points=200, profile="linear",
                          centre_of_pressure=(-0.005, 0.001)),
    lambda: fpm.ring(0.03, contact_points=17),
], ids=["linear-disc", "linear-rectangle", "ring"])
@pytest.mark.parametrize("direction", [0.0, 0.7, 2.5, -2.0])
def test_pure_slide_is_the_load_opposite_the_velocity_at_the_centre_of_pressure(make, direction):
    fp, R = make(), 0.04
    F, T = fpa.coulomb_wrench(fp, math.inf, R, direction)
    e = np.array([math.cos(direction), math.sin(direction)])
    np.testing.assert_allclose(F, -e, rtol=0, atol=1e-12)
    c = fp.centre_of_pressure
    assert np.hypot(*c) > 0 or fp.kind == "ring"
    assert T == pytest.approx(cross(c, -e) / R, rel=1e-9, abs=1e-14)


def test_pure_spin_torque_is_the_mean_distance_and_a_point_at_rest_carries_nothing():
    """eps = 0 about the centroid: every point's friction is perpendicular to its radius,
    so T = -sum w |r| / R exactly; a point on the spin centre is at rest and adds no force
    (not a NaN from 0 / 0)."""
    R = 0.02
    k = 12
    phi = 2 * math.pi * np.arange(k) / k
    pts = np.vstack([[0.0, 0.0], R * np.column_stack([np.cos(phi), np.sin(phi)])])
    w0 = 0.25
    w = np.r_[w0, np.full(k, (1 - w0) / k)]
    fp = fpm.Footprint("ring", pts, w, pts[1:], 0.0, R, "uniform", R * R)
    F, T = fpa.coulomb_wrench(fp, 0.0, R, 0.3)
    assert np.all(np.isfinite(F)) and np.hypot(*F) < 1e-12
    assert T == pytest.approx(-(1 - w0), rel=1e-12)
    # against the ring's closed forms m(0) = 1, f(0) = 0: the centre point's share is missing
    (err,) = fpa.sampling_errors(fp, [0.0], directions=8)
    assert math.isfinite(err["force"]) and err["force"] < 1e-12
    assert err["torque"] == pytest.approx(w0, rel=1e-12)


@pytest.mark.parametrize("kind", ["disc", "ring"])
def test_pressure_on_a_disc_or_ring_keeps_load_and_centre_and_takes_its_rim(kind):
    """A pressure given on a disc's (ring's) points: each point's share is its pressure
    (equal cells), so the centre of pressure is sum p x / sum p; points on the rim belong
    to the body, a point 1e-3 R outside does not."""
    from asperity.bodies import pressure as fpp
    from asperity.errors import InputError
    R = 0.02
    shape = fpm.disc(R, contact_points=64) if kind == "disc" else fpm.ring(R, contact_points=8)
    phi = np.linspace(0, 2 * math.pi, 24, endpoint=False)
    rim = R * np.column_stack([np.cos(phi), np.sin(phi)])
    pts = np.vstack([rim, 0.5 * rim, [[0.0, 0.0]]]) if kind == "disc" else rim
    p = 1e5 * (1.0 + 0.6 * pts[:, 0] / R - 0.3 * pts[:, 1] / R)
    fp = fpp.from_pressure(pts, p, shape=shape)
    assert fp.kind == kind and fp.n == len(pts)
    np.testing.assert_allclose(fp.weights, p / p.sum(), rtol=1e-12)
    np.testing.assert_allclose(fp.centre_of_pressure, p @ pts / p.sum(), rtol=1e-12)
    out = np.vstack([pts, [[R * 1.001, 0.0]]])
    with pytest.raises(InputError, match=f"outside the body's {kind}"):
        fpp.from_pressure(out, np.r_[p, 1e5], shape=shape)
