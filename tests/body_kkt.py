"""A slow, obviously correct check of every step of the body solver: the optimality
conditions of the step, in NumPy, independent of the kernels' Newton iterations.

A step of the midpoint scheme (asperity.dynamics.body) ends at u_E = (vx, vy, omega) with
M (u_E - u_free) + sum_i W_i P_i = 0, P_i the friction impulse of point i:

* a point that slips (gamma_i = W_i^T u_E != 0) carries P_i = lam_i c(gamma_i / |gamma_i|),
  c the law's sliding force per unit normal load;
* a point that does not slip carries a reaction in lam_i C.  A moving rigid body has at
  most one spot of non-slipping points (two distinct ones would stop it); their summed
  reaction comes from the residual of the others and must lie in lam_group conv C, and
  the torque equation must close;
* a body at rest (u_E = 0) needs b = M u_free in the limit set sum_i lam_i W_i conv C:
  G(d) = sum_i lam_i h(W_i^T d) - b.d >= 0 for every d (checked on many directions: a
  necessary condition).

The force c is taken from the same table the kernel uses for table laws (its
interpolation is the law's discretisation, tested elsewhere) and from the law's closed form
for the ellipse kind, so the check is on the solve, not on the law's sampling.
"""
from __future__ import annotations

import math

import numpy as np

from asperity.dynamics import _body_kernels as K
from asperity.dynamics.body import BodySettings, law_tables, simulate_body


def _force(kind, par, tab, law, psi):
    """(m, 2) sliding force per unit normal load at the slip directions psi."""
    if kind in (K.KIND_ELLIPSE, K.KIND_COMPONENTWISE):
        return law.force(psi)
    n = tab.shape[0] - 1
    x = np.mod(psi, 2 * math.pi) / (2 * math.pi / n)
    k = np.minimum(x.astype(int), n - 1)
    t = (x - k)[:, None]
    return tab[k, :2] + t * (tab[k + 1, :2] - tab[k, :2])


def _hull_points(law, n=7200):
    phi = 2 * math.pi * np.arange(n) / n
    r = law.radial(phi)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi)])


def _support(hull, s):
    """h(s) of the hull of C for the directions s (m, 2) (not unit)."""
    return (s @ hull.T).max(axis=1)


_PHI = 2 * math.pi * np.arange(7200) / 7200
_S = np.column_stack([np.cos(_PHI), np.sin(_PHI)])


def _gauge(h_s, c):
    """Gauge of conv C at c (2,): max over directions s of c.s / h(s) (h_s: h on _S)."""
    return float(np.max((_S @ c) / h_s))


def check_run(points, weights, law, *, mass, inertia, u0, dt, t_end=None, force=None,
              settings=BodySettings(), n_dirs=4000):
    """Run the solver recording every step and check each step's optimality conditions.

    Returns (result, report) with report = dict(worst_residual: largest relative residual of
    a sliding step, worst_gauge: largest gauge of a pivot's reaction, min_margin: least
    G(d) / scale found at a rest step, pivots: steps with a non-slipping spot, steps)."""
    pts = np.asarray(points, dtype=float)
    w = np.asarray(weights, dtype=float)
    res = simulate_body(pts, w, law, mass=mass, inertia=inertia, u0=u0, dt=dt, t_end=t_end,
                        force=force, settings=settings, record_every=1)
    kind, par, tab, _, mu = law_tables(law)
    hull = _hull_points(law)
    h_s = _support(hull, _S)
    md = np.array([mass, mass, inertia])
    lam = w * mass * 9.81 * dt
    scale = mass * 9.81 * dt * mu          # impulse scale
    rep = dict(worst_residual=0.0, worst_gauge=0.0, min_margin=np.inf, pivots=0,
               steps=len(res.t) - 1)
    k = np.arange(n_dirs) + 0.5
    z = 1.0 - 2.0 * k / n_dirs
    ph = math.pi * (1.0 + 5 ** 0.5) * k
    rr = np.sqrt(1.0 - z * z)
    rho = math.sqrt(inertia / mass)
    dirs = np.column_stack([rr * np.cos(ph), rr * np.sin(ph), z / rho])
    S = len(res.t) - 1
    UA, UE = res.u[:-1], res.u[1:]
    tM = res.t[:-1] + 0.5 * dt
    QM = res.q[:-1] + 0.5 * dt * UA
    Fx = np.zeros((S, 3)) if force is None else force(tM)
    UF = UA + dt * Fx / md
    c, s = np.cos(QM[:, 2:3]), np.sin(QM[:, 2:3])
    OX = c * pts[None, :, 0] - s * pts[None, :, 1]
    OY = s * pts[None, :, 0] + c * pts[None, :, 1]
    GX = UE[:, 0:1] - UE[:, 2:3] * OY
    GY = UE[:, 1:2] + UE[:, 2:3] * OX
    moving = (GX != 0.0) | (GY != 0.0)
    CX = np.zeros_like(GX)
    CY = np.zeros_like(GY)
    cf = _force(kind, par, tab, law, np.arctan2(GY[moving], GX[moving]))
    CX[moving] = cf[:, 0]
    CY[moving] = cf[:, 1]
    R = md * (UE - UF)
    R[:, 0] += CX @ lam
    R[:, 1] += CY @ lam
    R[:, 2] += (OX * CY - OY * CX) @ lam
    rest = ~UE.any(axis=1)
    slide = moving.all(axis=1) & ~rest
    unit = scale / math.sqrt(mass)
    if slide.any():
        rep["worst_residual"] = float(np.sqrt((R[slide] ** 2 / md).sum(axis=1)).max()) / unit
    for j in np.flatnonzero(~slide & ~rest):
        # a pivot: the non-slipping points sit at one spot
        stuck = ~moving[j]
        sx, sy = OX[j, stuck], OY[j, stuck]
        assert np.all(sx == sx[0]) and np.all(sy == sy[0]), \
            f"step {j}: non-slipping points at more than one spot while the body moves"
        lg = lam[stuck].sum()
        cg = -R[j, :2] / lg
        torque = R[j, 2] + lg * (sx[0] * cg[1] - sy[0] * cg[0])
        rep["worst_residual"] = max(rep["worst_residual"],
                                    abs(torque) / math.sqrt(inertia) / unit)
        rep["worst_gauge"] = max(rep["worst_gauge"], _gauge(h_s, cg))
        rep["pivots"] += 1
    for j in np.flatnonzero(rest):
        if not UA[j].any() and not Fx[j].any():
            continue
        # stick of the body: G(d) >= 0 on many directions, and on the pivots about points
        b = md * UF[j]
        ox, oy = OX[j], OY[j]
        piv = np.column_stack([oy, -ox, np.ones_like(ox)])[:: max(1, len(ox) // 200)]
        d = np.vstack([dirs, piv, -piv])
        gx = d[:, 0:1] - d[:, 2:3] * oy[None, :]
        gy = d[:, 1:2] + d[:, 2:3] * ox[None, :]
        # h(gamma) = |gamma| h(unit gamma), h interpolated on the 7200 directions
        ang = np.mod(np.arctan2(gy, gx), 2 * math.pi)
        h = np.hypot(gx, gy) * np.interp(ang, np.append(_PHI, 2 * math.pi),
                                         np.append(h_s, h_s[0]))
        G = h @ lam - d @ b
        dn = np.sqrt((d * d * md).sum(axis=1))
        rep["min_margin"] = min(rep["min_margin"], float(np.min(G / dn)) / unit)
    return res, rep
