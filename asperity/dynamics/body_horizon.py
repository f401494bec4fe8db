"""How long a body launched without a load can take to come to rest: the horizon of a run
"until rest" of :func:`asperity.dynamics.body.simulate_body` (issue 25: the horizon must be
an honest bound, and a run too long to compute is refused saying why)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..laws.planar import PlanarLaw
from .moreau import LIMITS, MAX_STEPS

#: safety factor of the horizon used when t_end is None (see :func:`rest_horizon`)
HORIZON_FACTOR = 1.5


def slip_ratio(points, weights, rho: float) -> float:
    """kappa = min over rigid velocities u = (v, omega) of sum_i w_i |gamma_i| / |u|_*, with
    |u|_* = sqrt(|v|^2 + rho^2 omega^2): the least mean slip per unit of motion.

    A rigid velocity with omega != 0 is a rotation about a point p (the instantaneous
    centre, v = omega p^perp), so the ratio is f(p) = sum_i w_i |r_i - p| / sqrt(|p|^2 +
    rho^2); a translation is the limit |p| -> inf (f = 1).  f is minimised over the plane:
    the centre of mass, the points themselves (f has its kinks there) and a polar grid of
    p out to 1e3 times the footprint's size, then Nelder-Mead from the best five, on at
    most 4096 of the points (spread evenly through the list); the value returned is f on
    every point at the best centre found.  0 iff the points all coincide."""
    from scipy.optimize import minimize
    p = np.asarray(points, dtype=float)
    w = np.asarray(weights, dtype=float)

    def f_all(c, pp=p, ww=w):
        return float(ww @ np.hypot(pp[:, 0] - c[0], pp[:, 1] - c[1])) / math.hypot(
            math.hypot(c[0], c[1]), rho)

    sub = np.unique(np.linspace(0, len(p) - 1, min(len(p), 4096)).astype(int))
    ps, ws = p[sub], w[sub] / w[sub].sum()
    size = float(np.hypot(p[:, 0], p[:, 1]).max()) + rho
    ang = np.linspace(0.0, 2 * math.pi, 48, endpoint=False)
    rad = size * np.geomspace(1e-3, 1e3, 40)
    grid = np.concatenate([np.zeros((1, 2)), ps[np.linspace(0, len(ps) - 1,
                                                             min(len(ps), 256)).astype(int)],
                           (rad[:, None, None] * np.stack([np.cos(ang), np.sin(ang)], -1)
                            [None]).reshape(-1, 2)])
    vals = np.empty(len(grid))
    for k in range(0, len(grid), 256):
        g = grid[k:k + 256]
        d = np.hypot(ps[None, :, 0] - g[:, None, 0], ps[None, :, 1] - g[:, None, 1])
        vals[k:k + 256] = (d @ ws) / np.hypot(np.hypot(g[:, 0], g[:, 1]), rho)
    best = min(1.0, f_all(grid[0]))
    for k in np.argsort(vals)[:5]:
        r = minimize(f_all, grid[k], args=(ps, ws), method="Nelder-Mead",
                     options=dict(xatol=1e-9 * size, fatol=1e-12, maxiter=400))
        best = min(best, f_all(r.x), f_all(grid[k]))
    return best


def rest_time(points, weights, law: PlanarLaw, mass: float, inertia: float, u0, g: float,
              dt: float) -> float:
    """The end time of a run until rest: HORIZON_FACTOR times :func:`rest_horizon`, plus 10
    steps.  Refused in one line, with the reason, when that takes more steps than a run
    may (t_end / dt times the contact points / 16 above MAX_STEPS)."""
    h = rest_horizon(points, weights, law, mass, inertia, u0, g)
    t = HORIZON_FACTOR * h + 10 * dt
    n = len(points)
    if t <= LIMITS["t_end"][1] and t / dt * max(1.0, n / 16.0) <= MAX_STEPS:
        return t
    span = float(np.ptp(np.asarray(points), axis=0).max())
    why = ""
    if slip_ratio(points, weights, math.sqrt(inertia / mass)) < 1e-2:
        why = (f" (its contact points span only {span:.3g} m, so little friction torque "
               "stops its spin)")
    raise InputError(f"t_end must be given: this body may need up to {t:.3g} s to come to "
                     f"rest ({t / dt:.3g} steps of dt = {dt:g} s for {n} contact points, "
                     f"beyond the limit of {MAX_STEPS:.0e} / (points / 16)){why}; give t_end to "
                     "follow part of the motion, or raise dt")


def rest_horizon(points, weights, law: PlanarLaw, mass: float, inertia: float, u0, g: float
                 ) -> float:
    """A time by which a body with no external force is surely at rest.

    With |u|_* = sqrt(v^2 + (I/m) omega^2) the friction power is at least
    m g mu_min sum_i w_i |gamma_i| >= m g mu_min kappa |u|_* (kappa: :func:`slip_ratio`,
    halved here for the search's misses), so d|u|_*/dt <= -g mu_min kappa and the body
    stops before |u0|_* / (g mu_min kappa)."""
    u0 = np.asarray(u0, dtype=float)
    rho2 = inertia / mass
    kappa = 0.5 * slip_ratio(points, weights, math.sqrt(rho2))
    speed = math.sqrt(u0[0] ** 2 + u0[1] ** 2 + rho2 * u0[2] ** 2)
    if speed == 0.0:
        return 0.0
    return speed / (g * law.min_tangential() * kappa)
