"""How well a sampled footprint reproduces the closed forms of a uniformly loaded disc or ring
sliding and spinning on isotropic Coulomb friction (SPEC.md 8): the check that chose
:data:`asperity.bodies.footprint.DEFAULT_CONTACT_POINTS`
(``python benchmarks/footprint_quadrature.py``)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .footprint import Footprint

# ----------------------------------------------------------------------------- checks of a sampling

def coulomb_wrench(fp: Footprint, eps: float, R: float | None = None,
                   direction: float = 0.0) -> tuple[np.ndarray, float]:
    """Friction force (2,) and torque of footprint ``fp`` on isotropic Coulomb friction
    (mu = 1, unit load) sliding at v = eps R along ``direction`` (rad) while spinning at
    omega = 1 rad/s (eps = inf: a pure slide at unit speed), torque in units of R.  A point
    at rest carries no force.  The closed forms give, for a disc, force -f(eps) along the
    velocity and torque -m(eps)."""
    R = fp.radius if R is None else R
    r = fp.points
    if math.isinf(eps):
        u = np.tile([math.cos(direction), math.sin(direction)], (r.shape[0], 1))
    else:
        u = eps * R * np.array([math.cos(direction), math.sin(direction)]) + \
            np.column_stack([-r[:, 1], r[:, 0]])
    s = np.hypot(u[:, 0], u[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.where(s[:, None] > 0, u / s[:, None], 0.0)
    F = -(fp.weights[:, None] * d).sum(axis=0)
    T = -float(np.sum(fp.weights * (r[:, 0] * d[:, 1] - r[:, 1] * d[:, 0]))) / R
    return F, T



#: the eps of the error table (issue 20): pure spin, slow slide, the disc's terminal ratio,
#: the instantaneous centre on the rim, fast slides
TABLE_EPS = (0.0, 0.1, 0.653, 1.0, 3.0, 100.0)


def sampling_errors(fp: Footprint, eps_values, directions: int = 48) -> list[dict]:
    """Worst relative errors of a disc's or ring's sampled Coulomb force (as a vector:
    |F + f e_v| / f) and torque (|T + m| / m) against the closed forms, over ``directions``
    velocity directions, for each eps (at eps = 0 the force's magnitude itself, the exact
    force being zero)."""
    from .closed_forms import footprint_f_m
    if fp.kind not in ("disc", "ring"):
        raise InputError(f"sampling_errors: a disc or ring footprint, got a {fp.kind}")
    R = fp.radius
    r = fp.points / R
    d = 2.0 * math.pi * np.arange(directions) / directions
    ev = np.column_stack([np.cos(d), np.sin(d)])                   # (k, 2)
    out = []
    for eps in eps_values:
        f, m = footprint_f_m(fp.kind, float(eps))
        if math.isinf(eps):
            u = np.broadcast_to(ev[:, None, :], (directions, r.shape[0], 2))
        else:
            u = eps * ev[:, None, :] + np.column_stack([-r[:, 1], r[:, 0]])[None]
        s = np.hypot(u[..., 0], u[..., 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            un = np.where(s[..., None] > 0, u / s[..., None], 0.0)
        F = np.einsum("j,kjc->kc", fp.weights, un)
        T = np.einsum("j,kj->k", fp.weights, r[:, 0] * un[..., 1] - r[:, 1] * un[..., 0])
        ef = np.hypot(*(F - f * ev).T).max() / (f if f > 0 else 1.0)
        em = np.abs(T - m).max() / (m if m > 0 else 1.0)
        out.append({"eps": float(eps), "force": float(ef), "torque": float(em)})
    return out
