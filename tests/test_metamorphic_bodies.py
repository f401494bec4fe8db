"""Metamorphic tests of footprints and the body solver (issue 25, item 5).

The body solver's Newton iteration is being rewritten: these tests use the closed-form
ellipse laws (Coulomb, the asymmetric truncated ellipse) on footprints of tens of points,
with spin, runs of a fraction of a second, and tolerances set by the step equation's
(1e-12 of the impulse scale, summed over the steps), not bit for bit.

* a load along the law's axes under a texture angle, from rest: Newton's closed form
  x = (F/m - mu g) t^2 / 2 along the force, for each of mu_a+, mu_a-, mu_b+, mu_b-;
* the whole problem turned into the law's frame (footprint, velocity, force: the texture
  angle taken off) gives the trajectory turned; mirrored in t_a (y -> -y: mu_b+ <-> mu_b-,
  spin, torque and texture angle negated) the trajectory mirrored;
* origins: a footprint's points or polygon given away from the origin, and a body
  started away from it, change nothing but the positions by the shift; mass, inertia,
  force and torque scaled together change nothing;
* a footprint from a contact solution of oblong pixels: the full contact of a flat map
  (area fraction exactly 1) against its closed-form extent and inertia, a transposed
  contact gives the footprint mirrored in x = y, merged points keep the load's centre.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from lays import assert_same_motion

from asperity.bodies import footprint as F
from asperity.bodies.pressure import from_contact, from_pressure
from asperity.contact import solve_contact
from asperity.dynamics.body import simulate_body
from asperity.dynamics.moreau import Force
from asperity.laws.planar import coulomb_law, truncated_ellipse_law

G = 9.81
MU = (0.3, 0.12, 0.2, 0.25)            # mu_a+, mu_a-, mu_b+, mu_b-: no symmetry
#: an L-shaped plate (m), its corner away from the origin: no symmetry either
L_SHAPE = np.array([[0, 0], [0.06, 0], [0.06, 0.02], [0.025, 0.02], [0.025, 0.05], [0, 0.05]])
DT = 1e-4


def rot(deg: float) -> np.ndarray:
    a = math.radians(deg)
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


@pytest.fixture(scope="module")
def plate():
    return F.polygon(L_SHAPE + [0.7, -0.4], contact_points=64)


def run(fp, law, u0, *, tex=0.0, force=None, t_end=None, mass=1.0, q0=(0.0, 0.0, 0.0),
        inertia=None):
    I = mass * fp.inertia_per_mass if inertia is None else inertia
    r = simulate_body(fp.points, fp.weights, law, mass=mass, inertia=I, u0=u0, q0=q0, dt=DT,
                      t_end=t_end, force=force, texture_angle_deg=tex)
    assert r.ok, r.message
    return r


def scale_of(r) -> float:
    """A length of the motion: the largest distance from the start."""
    return float(np.hypot(*(r.q[:, :2] - r.q[0, :2]).T).max())


# ---- a load under a texture angle, in closed form ----------------------------------------

@pytest.mark.parametrize("tex", [130.0, -35.0])
def test_a_load_along_each_axis_of_a_turned_law_accelerates_as_newton_says(plate, tex):
    """From rest, a force F = 2.5 mu m g along +-t_a or +-t_b of a law turned by the texture
    angle: every point slides along the force (the normal of the ellipse at its axis is the
    axis), the friction is mu m g against it, no torque about the centroid: x(t) = (F/m -
    mu g) t^2 / 2 along the force (the midpoint scheme is exact for it), no turn."""
    law = truncated_ellipse_law(*MU)
    m, T = 2.0, 0.05
    for k, (off, mu) in enumerate(zip((0.0, 180.0, 90.0, 270.0), MU)):
        e = rot(tex + off) @ np.array([1.0, 0.0])
        Fm = 2.5 * mu * m * G
        r = run(plate, law, (0.0, 0.0, 0.0), tex=tex, mass=m, t_end=T,
                force=Force(constant=(*(Fm * e), 0.0)))
        t = r.t[-1]
        want = 0.5 * (Fm / m - mu * G) * t * t * e
        np.testing.assert_allclose(r.q_final[:2], want, rtol=0, atol=1e-9 * np.abs(want).max(),
                                   err_msg=f"axis {k}: the force or the law turned wrong")
        assert abs(r.q_final[2]) < 1e-9 and abs(r.u_final[2]) < 1e-9


# ---- the problem turned or mirrored -----------------------------------------------------

CASES = {"free": {"force": None, "t_end": None},
         "loaded": {"force": (1.5, 2.0, 0.02), "t_end": 0.25}}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("tex", [130.0, -20.0])
def test_turning_the_whole_problem_into_the_laws_frame_turns_the_trajectory(plate, case, tex):
    """Run A: the law's t_a at the texture angle from x.  Run B: the same body, footprint,
    launch and load turned by minus that angle, on the law unturned.  B is A turned."""
    law = truncated_ellipse_law(*MU)
    v, om = np.array([0.8, -0.5]), 15.0
    R = rot(-tex)
    c = CASES[case]
    fa = fb = None
    if c["force"] is not None:
        f = np.array(c["force"][:2])
        fa = Force(constant=(*f, c["force"][2]))
        fb = Force(constant=(*(R @ f), c["force"][2]))
    a = run(plate, law, (*v, om), tex=tex, force=fa, t_end=c["t_end"])
    turned = F.Footprint("polygon", plate.points @ R.T, plate.weights, plate.outline @ R.T,
                         plate.area, None, "uniform", plate.inertia_per_mass)
    b = run(turned, law, (*(R @ v), om), force=fb, t_end=c["t_end"])
    assert_same_motion(a, b, R, f"turned by {-tex} deg")
    if case == "free":
        assert a.stop_time == pytest.approx(b.stop_time, abs=1.5 * DT)
    assert scale_of(a) > 0.05 and abs(a.q_final[2]) > 1.0       # it slid and turned


@pytest.mark.parametrize("case", list(CASES))
def test_mirroring_the_problem_in_t_a_mirrors_the_trajectory(plate, case):
    """y -> -y: the law's mu_b+ and mu_b- exchanged, the footprint, the launch and the load
    mirrored, spin and torque negated, the texture angle too: (x, y, theta) -> (x, -y,
    -theta)."""
    tex = 25.0
    M = np.diag([1.0, -1.0])
    v, om = np.array([0.6, 0.7]), -12.0
    c = CASES[case]
    fa = fb = None
    if c["force"] is not None:
        fx, fy, tz = c["force"]
        fa, fb = Force(constant=(fx, fy, tz)), Force(constant=(fx, -fy, -tz))
    a = run(plate, truncated_ellipse_law(*MU), (*v, om), tex=tex, force=fa, t_end=c["t_end"])
    mirrored = F.Footprint("polygon", plate.points @ M, plate.weights, plate.outline @ M,
                           plate.area, None, "uniform", plate.inertia_per_mass)
    law_m = truncated_ellipse_law(MU[0], MU[1], MU[3], MU[2])
    b = run(mirrored, law_m, (v[0], -v[1], -om), tex=-tex, force=fb, t_end=c["t_end"])
    assert_same_motion(a, b, M, "mirrored in t_a")
    assert abs(a.q_final[1]) > 0.02 and abs(a.q_final[2]) > 0.5


# ---- origins and scales ------------------------------------------------------------------

def test_a_footprint_given_away_from_the_origin_is_the_same_footprint(plate):
    """A polygon, pressure points or a body's start shifted by (X, Y): the footprint is the
    same (centred on its centroid; the shift is recorded), the motion is shifted."""
    here = F.polygon(L_SHAPE, contact_points=64)
    np.testing.assert_allclose(plate.points, here.points, rtol=0, atol=1e-12)
    np.testing.assert_allclose(plate.weights, here.weights, rtol=0, atol=1e-15)
    assert plate.inertia_per_mass == pytest.approx(here.inertia_per_mass, rel=1e-12)
    np.testing.assert_allclose(np.subtract(plate.info["centroid_shift"],
                                           here.info["centroid_shift"]), [0.7, -0.4],
                               atol=1e-12)
    rng = np.random.default_rng(7)
    pts = rng.uniform(0, 0.05, (40, 2))
    p = rng.uniform(0, 1e6, 40)
    p[::5] = 0.0
    a = from_pressure(pts, p)
    b = from_pressure(pts + [-2.3, 4.1], p)
    np.testing.assert_allclose(a.points, b.points, rtol=0, atol=1e-12)
    np.testing.assert_allclose(a.weights, b.weights, rtol=0, atol=1e-15)
    assert a.inertia_per_mass == pytest.approx(b.inertia_per_mass, rel=1e-9)
    law = truncated_ellipse_law(*MU)
    r0 = run(plate, law, (0.5, 0.4, 8.0), tex=70.0)
    r1 = run(plate, law, (0.5, 0.4, 8.0), tex=70.0, q0=(3.0, -5.0, 0.0))
    assert r0.stop_time == pytest.approx(r1.stop_time, abs=1.5 * DT)
    np.testing.assert_allclose(r1.q_final[:2] - [3.0, -5.0], r0.q_final[:2], rtol=0,
                               atol=1e-9 * scale_of(r0))


def test_mass_inertia_and_load_scaled_together_change_nothing(plate):
    law = coulomb_law(0.25)
    f = (0.8, -1.1, 0.015)
    a = run(plate, law, (0.4, 0.3, 10.0), tex=40.0, force=Force(constant=f), t_end=0.2)
    b = run(plate, law, (0.4, 0.3, 10.0), tex=40.0, mass=3.5, t_end=0.2,
            force=Force(constant=tuple(3.5 * x for x in f)))
    np.testing.assert_allclose(a.q, b.q, rtol=0, atol=1e-9 * max(1.0, scale_of(a)))
    # Coulomb is isotropic: the texture angle plays no part, with or without a force
    c = run(plate, law, (0.4, 0.3, 10.0), tex=-110.0, force=Force(constant=f), t_end=0.2)
    np.testing.assert_allclose(a.q, c.q, rtol=0, atol=1e-9 * max(1.0, scale_of(a)))


# ---- footprints from a contact solution ----------------------------------------------------

DX, DY = 2.0e-4, 0.5e-4


def test_the_full_contact_of_a_flat_map_of_oblong_pixels_is_the_rectangle(capsys):
    """A flat map pressed on a free half-space: every pixel in contact (area fraction
    exactly 1, the edges carrying most: a flat punch); every pixel kept, the footprint
    spans (nx - 1) dx x (ny - 1) dy about its centre, its area is nx ny dx dy and its
    lamina inertia dx^2 (nx^2 - 1)/12 + dy^2 (ny^2 - 1)/12."""
    nx, ny = 24, 40
    res = solve_contact(np.zeros((nx, ny)), (DX, DY), 1e9, 1e6, boundary="free")
    assert res.area_fraction == 1.0 and res.full_contact
    fp = from_contact(res, contact_points=nx * ny)
    assert fp.n == nx * ny
    lo, hi = fp.points.min(axis=0), fp.points.max(axis=0)
    np.testing.assert_allclose(hi - lo, [(nx - 1) * DX, (ny - 1) * DY], rtol=1e-12)
    np.testing.assert_allclose(lo + hi, [0.0, 0.0], atol=1e-12 * DX)     # centred
    assert fp.info["contact_area_m2"] == pytest.approx(nx * ny * DX * DY, rel=1e-12)
    J = DX ** 2 * (nx ** 2 - 1) / 12 + DY ** 2 * (ny ** 2 - 1) / 12
    assert fp.inertia_per_mass == pytest.approx(J, rel=1e-12)
    np.testing.assert_allclose(fp.info["centroid_shift"], [(nx - 1) * DX / 2,
                                                           (ny - 1) * DY / 2], rtol=1e-12)
    np.testing.assert_allclose(fp.centre_of_pressure, [0.0, 0.0], atol=1e-9 * DX)


def test_a_transposed_contact_gives_the_footprint_mirrored_in_x_equals_y():
    """An off-centre paraboloid bottom on oblong pixels, and its transposed map with the
    pixel sides exchanged: the footprint's points, weights and inertia are the same with x
    and y exchanged, merged or not; merged points keep the load and its centre."""
    nx, ny = 40, 56
    x = (np.arange(nx) - 13.3)[:, None] * DX
    y = (np.arange(ny) - 31.7)[None, :] * DY
    z = -(x * x / 0.9 + y * y / 0.2)                       # radii 0.45 m and 0.1 m
    a = solve_contact(z, (DX, DY), 1e9, 2e5, boundary="free", tol=1e-11)
    b = solve_contact(z.T, (DY, DX), 1e9, 2e5, boundary="free", tol=1e-11)
    assert 0.05 < a.area_fraction < 0.6
    n_in = int(a.contact.sum())
    for n in (n_in, 64):
        fa, fb = from_contact(a, contact_points=n), from_contact(b, contact_points=n)
        swapped = fb.points[:, ::-1]
        near = np.hypot(*(fa.points[:, None, :] - swapped[None, :, :]).transpose(2, 0, 1))
        k = near.argmin(axis=1)                          # each point of a among b's
        assert fa.n == fb.n and np.unique(k).size == fa.n
        assert near[np.arange(fa.n), k].max() < 1e-9 * DX, "footprint not mirrored in x = y"
        np.testing.assert_allclose(fb.weights[k], fa.weights, rtol=1e-6, atol=0)
        assert fb.inertia_per_mass == pytest.approx(fa.inertia_per_mass, rel=1e-9)
        np.testing.assert_allclose(fb.info["centroid_shift"][::-1],
                                   fa.info["centroid_shift"], rtol=1e-9)
    # the load's centre in the map's frame: pixel (i, j) at (i dx, j dy)
    i, j = np.nonzero(a.pressure > 0)
    w = a.pressure[i, j]
    centre = np.array([w @ (i * DX), w @ (j * DY)]) / w.sum()
    for n in (n_in, 64):
        fp = from_contact(a, contact_points=n)
        np.testing.assert_allclose(fp.centre_of_pressure + fp.info["centroid_shift"],
                                   centre, rtol=0, atol=1e-9 * DX)
    # Hertz: an elliptic patch, longer along x by about (R_x / R_y)^(2/3) (Johnson,
    # Contact Mechanics 4.2: within a few % at this ratio) -- a footprint squeezed along
    # y by dy / dx would be 4 times longer
    spread = fa.weights @ fa.points ** 2 - (fa.weights @ fa.points) ** 2
    assert math.sqrt(spread[0] / spread[1]) == pytest.approx(4.5 ** (2 / 3), rel=0.1)
