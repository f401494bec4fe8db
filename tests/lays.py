"""Asymmetric fixtures and the plane's isometries for the metamorphic tests.

The maps have no mirror symmetry along either axis (an asymmetric sawtooth across a lay
turned by ``angle_deg``, a second sawtooth along it with the other asymmetry, a smooth
random part), so that a transposition, a mirror or a quarter turn done wrong changes the
numbers; :func:`separable` maps (z = A(x) + B(y)) have planar cells, whose two triangles
share one gradient, so that even a mirror or a quarter turn -- which exchange the
cells' diagonals -- maps their facets exactly."""
from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.friction.faces import compute_faces_reservoir

#: the axis coefficients and their directions from t_a, deg
AXES = {"mu_a_plus": 0.0, "mu_a_minus": 180.0, "mu_b_plus": 90.0, "mu_b_minus": 270.0}
#: what each isometry does to a height map z[i, j] (axis 0 along x) and its pixel sides,
#: and Q, the map of the plane: a direction s of the old map is Q s on the new one
ISOMETRIES = {
    "transpose": (lambda z: z.T, True, np.array([[0.0, 1.0], [1.0, 0.0]])),
    "mirror-x": (lambda z: z[::-1, :], False, np.array([[-1.0, 0.0], [0.0, 1.0]])),
    "mirror-y": (lambda z: z[:, ::-1], False, np.array([[1.0, 0.0], [0.0, -1.0]])),
    "quarter-turn": (lambda z: np.rot90(z), True, np.array([[0.0, -1.0], [1.0, 0.0]])),
    "half-turn": (lambda z: z[::-1, ::-1], False, -np.eye(2)),
}


def isometry(name, z, dx, dy):
    """(heights, dx, dy, Q) of map ``z`` of pixel sides (dx, dy) after isometry ``name``."""
    f, swap, Q = ISOMETRIES[name]
    return np.ascontiguousarray(f(z)), (dy if swap else dx), (dx if swap else dy), Q


def saw(f, rise):
    """An asymmetric sawtooth of period 1 and height 1: up over ``rise`` of the period."""
    f = np.mod(f, 1.0)
    return np.where(f < rise, f / rise, (1.0 - f) / (1.0 - rise))


def lay(nx, ny, dx, dy, angle_deg=95.0, seed=0, height=2e-6, period=8e-6):
    """Ridges across ``angle_deg`` (from x): an asymmetric sawtooth (up over 70 % of the
    period), a sawtooth along the ridges (up over 20 % of 1.4 periods, half the height)
    and a smooth random part (0.1 of the height), m."""
    x = np.arange(nx)[:, None] * dx
    y = np.arange(ny)[None, :] * dy
    a = math.radians(angle_deg)
    u = x * math.cos(a) + y * math.sin(a)
    v = -x * math.sin(a) + y * math.cos(a)
    rng = np.random.default_rng(seed)
    ph = rng.uniform(0, 2 * math.pi, 4)
    smooth = (np.sin(2 * math.pi * x / (1.7 * period) + ph[0])
              * np.cos(2 * math.pi * y / (1.3 * period) + ph[1])
              + 0.5 * np.sin(2 * math.pi * (x + 2 * y) / (2.3 * period) + ph[2]))
    return height * (saw(u / period + ph[3], 0.7) + 0.5 * saw(v / (1.4 * period), 0.2)
                     + 0.1 * smooth)


def separable(nx, ny, dx, dy, height=2e-6, period=8e-6):
    """z = A(x) + B(y): an asymmetric sawtooth along x (up over 75 %) and one along y (up
    over 30 %, 0.6 of the height), periods not multiples of the pixels."""
    x = np.arange(nx)[:, None] * dx
    y = np.arange(ny)[None, :] * dy
    return height * (saw(x / period + 0.13, 0.75) + 0.6 * saw(y / (0.9 * period) + 0.41, 0.3))


def angle_deg(v) -> float:
    return math.degrees(math.atan2(v[1], v[0]))


def turned(Q, deg: float) -> float:
    """The angle (deg) of direction ``deg`` mapped by Q."""
    a = math.radians(deg)
    return angle_deg(Q @ np.array([math.cos(a), math.sin(a)]))


def axial_gap(a_deg: float, b_deg: float) -> float:
    """Distance of two axes (deg, modulo 180)."""
    return abs(math.remainder(a_deg - b_deg, 180.0))


def mapped_points(p_old, Q):
    """The reservoir points of the mapped surface on the same grid of n directions,
    psi_k = 2 pi k / n: p_new(s_k) = Q p_old(Q^T s_k) (Q^T s_k must be a grid direction)."""
    n = p_old.shape[0]
    psi = 2 * np.pi * np.arange(n) / n
    s = np.column_stack([np.cos(psi), np.sin(psi)])
    back = s @ Q                                   # rows: Q^T s_k
    k = np.rint(np.arctan2(back[:, 1], back[:, 0]) / (2 * np.pi / n)).astype(int) % n
    assert np.allclose(s[k], back, atol=1e-9), "Q must map the grid of directions to itself"
    return p_old[k] @ Q.T


def T_at(d, degrees) -> np.ndarray:
    """T = p . s of derivation d's (weighted) faces at the directions ``degrees``."""
    psi = np.radians(np.asarray(degrees, dtype=float))
    return compute_faces_reservoir(d.texture.faces(), psi, d.contact).tangential


def assert_mapped(a, b, Q, what, atol=1e-9):
    """Derivation b is derivation a's surface mapped by Q: p_b(Q s) = Q p_a(s); t_a of b is
    Q t_a (an axis); each of b's axis coefficients is a's T in the direction Q^T s."""
    scale = np.abs(a.reservoir.p).max()
    np.testing.assert_allclose(b.reservoir.p, mapped_points(a.reservoir.p, Q), rtol=0,
                               atol=atol * scale, err_msg=f"{what}: reservoir not mapped")
    assert axial_gap(turned(Q, a.principal_direction_deg), b.principal_direction_deg) < 1e-6, \
        (what, a.principal_direction_deg, b.principal_direction_deg)
    back = [turned(Q.T, b.principal_direction_deg + off) for off in AXES.values()]
    want = dict(zip(AXES, T_at(a, back)))
    for k in AXES:
        assert b.axes[k] == pytest.approx(want[k], rel=1e-9, abs=1e-12), (what, k)


def assert_same_motion(a, b, Q, what="", rel=1e-9):
    """Body result b is body result a mapped by Q (a turn or a mirror of the plane):
    positions and velocities Q x, angles and spins times det Q, to ``rel`` of the motion's
    size.  A stop decided on the other side of the stick test's margin may shift the
    rest by one step (the last step's displacement): allowed, nothing more."""
    sign = round(float(np.linalg.det(Q)))
    qa, qb = a.q.copy(), b.q.copy()
    qa[:, :2], qa[:, 2] = qa[:, :2] @ Q.T, sign * qa[:, 2]
    ua = a.u.copy()
    ua[:, :2], ua[:, 2] = ua[:, :2] @ Q.T, sign * ua[:, 2]
    assert abs(a.steps - b.steps) <= 1 and a.t.size == a.steps + 1 == qa.shape[0], what
    n = min(qa.shape[0], qb.shape[0]) - 1                 # states before the last
    size = max(float(np.abs(a.q[:, :2] - a.q[0, :2]).max()), 1e-12)
    speed = max(float(np.abs(a.u[:, :2]).max()), 1e-12)
    np.testing.assert_allclose(qb[:n, :2], qa[:n, :2], rtol=0, atol=rel * size,
                               err_msg=f"{what}: positions")
    np.testing.assert_allclose(qb[:n, 2], qa[:n, 2], rtol=0, atol=rel, err_msg=f"{what}: angle")
    np.testing.assert_allclose(b.u[:n, :2], ua[:n, :2], rtol=0, atol=rel * speed,
                               err_msg=f"{what}: velocities")
    last = rel * size + abs(a.steps - b.steps) * a.dt * speed
    assert np.abs(qb[-1, :2] - qa[-1, :2]).max() <= last, what
