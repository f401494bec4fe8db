"""Closed forms and reference solutions beside the Moreau solver (SPEC.md 4).

:func:`coulomb_stop_time`, :func:`coulomb_stop_distance` (isotropic Coulomb),
:func:`ratchet_drift_square` (a block under a zero-mean square-wave force on an asymmetric
law); :func:`reference_path` integrates the sliding-phase ODE with scipy's solve_ivp at
tight tolerances and :func:`path_error` measures a solver path against it.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_instance, check_range
from ..laws.planar import PlanarLaw
from .moreau import LIMITS, Result


def _common(u0, mu, g):
    return (check_range("u0", u0, *LIMITS["u0"], unit="m/s"),
            check_range("mu", mu, *LIMITS["mu"]), check_range("g", g, *LIMITS["g"], unit="m/s^2"))


def coulomb_stop_time(u0: float, mu: float, g: float = 9.81) -> float:
    """Stop time u0 / (mu g) of a point mass with isotropic (or on-axis) Coulomb friction."""
    u0, mu, g = _common(u0, mu, g)
    return u0 / (mu * g)


def coulomb_stop_distance(u0: float, mu: float, g: float = 9.81) -> float:
    """Stop distance u0^2 / (2 mu g)."""
    u0, mu, g = _common(u0, mu, g)
    return u0 * u0 / (2.0 * mu * g)


def ratchet_drift_square(F0: float, mass: float, period: float, mu_plus: float,
                         mu_minus: float, g: float = 9.81) -> float:
    """Drift per cycle of a block on an asymmetric law under a zero-mean square-wave force.

    The force is ``f(t) = +F0`` in the first half period, ``-F0`` in the second; the
    block starts at rest with the ``+F0`` half.  A closed form beside the Moreau solver.

    Parameters
    ----------
    F0 : float
        Force amplitude, N, in [0, 1e12].
    mass : float
        kg, in [1e-9, 1e9].
    period : float
        Period of the square wave, s, in [1e-9, 1e9].
    mu_plus : float
        Coefficient resisting motion towards +t_a, in [1e-6, 100].
    mu_minus : float
        Coefficient resisting motion towards -t_a, in [1e-6, 100].
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4]; default 9.81.

    Returns
    -------
    float
        Drift per cycle, m, along +t_a (negative: towards -t_a); 0 when ``F0`` is below
        both slip thresholds.

    Raises
    ------
    InputError
        If a number is out of range, or ``F0`` exceeds both thresholds ``mu_plus m g`` and
        ``mu_minus m g`` (the block slips both ways: no closed form here).

    See Also
    --------
    asperity.truncated_ellipse_law : an asymmetric law.
    asperity.simulate_microslip : ratcheting of an assembly under thermal cycles.

    Notes
    -----
    With ``mu_minus m g < F0 <= mu_plus m g`` the block sticks while pushed towards +t_a
    and slides when pulled towards -t_a.  Every cycle it sticks through the first half; in
    the second it accelerates at ``a1 = F0/m - mu_minus g`` for ``tau = period/2``,
    reaching ``v1 = a1 tau`` after ``a1 tau^2 / 2``; in the next ``+F0`` half it
    decelerates at ``a2 = F0/m + mu_minus g`` and stops after ``v1 / a2 < tau``, having
    moved ``v1^2 / (2 a2)``, then sticks again.  Drift per cycle:

    .. math:: d = -\\frac{a_1 \\tau^2}{2} \\left(1 + \\frac{a_1}{a_2}\\right)

    Mirror case ``mu_plus m g < F0 <= mu_minus m g``: ``+d`` with ``mu_plus``, the block
    slipping during the ``+F0`` half and stopping in the ``-F0`` half.

    Examples
    --------
    1 kg, 1.5 N, 1 s, mu+ = 0.2 and mu- = 0.1 (thresholds 1.962 and 0.981 N):

    >>> print(f"{asperity.ratchet_drift_square(1.5, 1.0, 1.0, 0.2, 0.1):.6f}")
    -0.078446
    >>> print(f"{asperity.ratchet_drift_square(1.5, 1.0, 1.0, 0.1, 0.2):.6f}")
    0.078446
    >>> asperity.ratchet_drift_square(0.5, 1.0, 1.0, 0.2, 0.1)
    0.0
    """
    F0 = check_range("F0", F0, 0.0, 1e12, unit="N")
    mass = check_range("mass", mass, *LIMITS["mass"], unit="kg")
    period = check_range("period", period, 1e-9, 1e9, unit="s")
    mu_plus = check_range("mu_plus", mu_plus, *LIMITS["mu"])
    mu_minus = check_range("mu_minus", mu_minus, *LIMITS["mu"])
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    tau = 0.5 * period
    lo, hi = mu_minus * mass * g, mu_plus * mass * g
    if F0 <= lo and F0 <= hi:
        return 0.0
    if F0 > lo and F0 > hi:
        raise InputError(f"F0 = {F0:g} N exceeds both slip thresholds ({lo:g}, {hi:g} N): the "
                         "block slips both ways, no closed-form drift")
    mu = mu_minus if F0 > lo else mu_plus
    a1 = F0 / mass - mu * g
    a2 = F0 / mass + mu * g
    d = 0.5 * a1 * tau * tau * (1.0 + a1 / a2)
    return -d if F0 > lo else d


def reference_path(law: PlanarLaw, u0: float, angle_deg: float, g: float = 9.81,
                   rtol: float = 1e-12, atol: float = 1e-14, stop_speed: float = 1e-9,
                   edge_eps: float = 1e-9):
    """Sliding-phase ODE of a point mass, integrated with scipy's solve_ivp (DOP853):
    dx/dt = v,  dv/dt = -g p(angle v)  until |v| = stop_speed u0 (then the remaining
    straight-line distance |v|^2 / (2 g p.s) is added).

    Set-valued directions of D (flat edges, e.g. windward sliding along the ridges) attract
    the motion into a sliding mode: when the velocity direction reaches such an edge normal
    from a side whose lateral force pushes it onward, the path continues straight along it
    (Filippov), decelerating at g p.s with p.s the edge's support value; the velocity direction
    is checked to point into the edge from both sides.

    Returns (t_stop, rest (2,), dense(t) -> (2,) position for 0 <= t, constant after t_stop).
    """
    check_instance("law", law, PlanarLaw)
    u0 = check_range("u0", u0, LIMITS["mu"][0], LIMITS["u0"][1], unit="m/s")
    angle_deg = check_range("angle_deg", angle_deg, -360.0, 360.0, unit="deg")
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    from scipy.integrate import solve_ivp
    a0 = math.radians(angle_deg)
    edges = np.asarray(getattr(law.law.D, "edges", np.empty(0)), dtype=float)

    def p_of(v):
        psi = math.atan2(v[1], v[0])
        return law.force(np.array([psi]))[0]

    def rhs(t, y):
        p = p_of(y[2:])
        return [y[2], y[3], -g * p[0], -g * p[1]]

    def ev_stop(t, y):
        return math.hypot(y[2], y[3]) - stop_speed * u0
    ev_stop.terminal = True
    ev_stop.direction = -1

    def ev_edge(t, y):
        if edges.size == 0:
            return 1.0
        psi = math.atan2(y[3], y[2])
        d = np.mod(psi - edges + math.pi, 2 * math.pi) - math.pi
        return float(np.min(np.abs(d))) - edge_eps
    ev_edge.terminal = True
    ev_edge.direction = -1

    y0 = [0.0, 0.0, u0 * math.cos(a0), u0 * math.sin(a0)]
    segments = []
    t0 = 0.0
    T_scale = u0 / (g * law.min_tangential())
    sol = solve_ivp(rhs, (0.0, 2.0 * T_scale), y0, method="DOP853", rtol=rtol, atol=atol,
                    dense_output=True, events=[ev_stop, ev_edge])
    segments.append((t0, sol.t[-1], sol.sol))
    yend = sol.y[:, -1]
    tend = sol.t[-1]
    if sol.t_events[1].size and not sol.t_events[0].size:
        # sliding mode along the edge normal s_e: no lateral force, so p is the point of C
        # on the ray of s_e (within the edge's fan of forces), deceleration g rho_C(psi_e)
        psi = math.atan2(yend[3], yend[2])
        k = int(np.argmin(np.abs(np.mod(psi - edges + math.pi, 2 * math.pi) - math.pi)))
        pe = edges[k]
        s = np.array([math.cos(pe), math.sin(pe)])
        dec = g * float(law.law.C.radial(np.array([pe]))[0])
        w = math.hypot(yend[2], yend[3])
        x0 = yend[:2].copy()
        te = w / dec
        t_start = tend

        def mode(t, x0=x0, w=w, s=s, dec=dec, t_start=t_start):
            t = np.minimum(np.asarray(t) - t_start, w / dec)
            return x0[:, None] + s[:, None] * (w * t - 0.5 * dec * t * t)
        segments.append((t_start, t_start + te, mode))
        rest = x0 + s * (w * w / (2 * dec))
        t_stop = t_start + te
    else:
        v = yend[2:]
        w = math.hypot(v[0], v[1])
        p = p_of(v)
        dec = g * float(p @ (v / w)) if w > 0 else 1.0
        rest = yend[:2] + (v / w) * (w * w / (2 * dec)) if w > 0 else yend[:2]
        t_stop = tend + (w / dec if w > 0 else 0.0)

    def dense(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((t.size, 2))
        out[:] = rest
        done = t >= t_stop
        for (a, b, f) in segments:
            sel = ~done & (t <= b)
            if sel.any():
                out[sel] = np.asarray(f(np.clip(t[sel], a, b)))[:2].T
                done |= sel
        return out

    return t_stop, rest, dense


def path_error(res: Result, dense) -> float:
    """max over the recorded states of |q(t_n) - q_ref(t_n)| (m)."""
    check_instance("res", res, Result)
    if not callable(dense):
        raise InputError(f"dense must be the function returned by reference_path, got {dense!r}")
    ref = dense(res.t)
    return float(np.max(np.hypot(*(res.q[:, :2] - ref).T)))
