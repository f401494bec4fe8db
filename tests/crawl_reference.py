"""An independent quasi-static reference for crawling (issue 26, item 1), for the tests only:
numpy and scipy, written from the model of Hu, Nirody, Scott and Shelley (PNAS 106:10081,
2009) and not from the package's crawl solver.

The model.  A body of length L, uniform weight per unit length (rho g), whose curvature in
its own frame is a Fourier series in s (tail 0 to head L) and t (period T)::

    kappa(s, t) L = sum_j c_j cos 2 pi (m_j s / L + n_j t / T) + d_j sin 2 pi (m_j s / L + n_j t / T)

(the travelling wave kappa L = A cos 2 pi (k s / L + t / T), running from head to tail, is the
single term m = k, n = 1, c = A).  The tangent angle psi = integral of kappa ds (in closed form
for each term, as is its rate d psi / dt), less its mean over s: the body frame's x axis is
the mean tangent angle (Hu et al.), its origin the centre of mass.  The shape X(s, t) and its
rate dX/dt are the cumulative trapezoid integrals of (cos psi, sin psi) and of
psi_t (-sin psi, cos psi) on a uniform grid of ``points`` nodes, less their means.

At each instant the rigid motion (v, Omega), in the body frame, makes the net friction force
and its torque about the centre of mass vanish (quasi-static, no inertia); the friction per
unit length at s is rho g times f(u_hat) in the local frame (t towards the head, n = z x t)
of the point's velocity u = v + Omega z x X + dX/dt, with the ``rule``:

* ``componentwise`` (Hu et al.): f = -(mu_t (u_hat.n) n + mu_{f|b} (u_hat.t) t), mu_f where u.t > 0;
* ``associated``: f = -argmax_{c in C} c.u_hat, C the two half-ellipses of semi-axes mu_f (+t),
  mu_b (-t) and mu_t (+-n): on the half-ellipse (a, b) = (mu_{f|b}, mu_t),
  c = (a^2 u_t, b^2 u_n) / sqrt(a^2 u_t^2 + b^2 u_n^2) (its outward normal is u_hat);
* ``colinear``: f = -r u_hat, r = 1 / sqrt(u_t^2 / a^2 + u_n^2 / b^2) the radius of C along u_hat.

Quadrature: the trapezoid rule on the ``points`` nodes.  Each of the three laws is continuous
in u_hat (the two half-ellipses meet with a common tangent at +-mu_t n), so wherever u does
not vanish along the body the integrands are continuous in s with kinks where u.t changes
sign, and U converges as points^-2 (and steps^-2): observed ratio 4.0 per halving for the
componentwise and associated rules at (1, 1.5, 2).
The non-smooth point is u = 0, where the force is set-valued (any point of -C).  A node with
u = 0 exactly gets f = 0, so the residual is always finite; nothing is regularised.  A body
can pivot, though: the colinear rule turns it about a point of itself at some instants, and a
discrete body then needs one node at rest.  When no root exists, each of the slowest nodes j
is tried at rest: the torque about it fixes Omega (a bracketed scalar root), the net force
fixes its friction, which must lie in w_j (-C) (``stick_instants`` counts such instants).
Across a pivot u_hat turns by pi within one node spacing, so colinear converges only as about
points^-1, unevenly (U at (1, 1.5, 2): 0.04864 at 51 points, 0.04917 at 201, 0.04918 at
3201).

The root.  Friction depends on directions only, so (v, Omega) does not depend on T and in
the body frame depends on the phase t / T alone: the quasi-static motion is periodic from
the first instant (no start-up period to discard).  (v, Omega) at ``steps`` instants of a
period come from scipy.optimize.root (Powell hybrid, then Levenberg-Marquardt), each started
from the previous instant; the residual (net force and torque over rho g L max(mu), L^2) must
fall below ``RESIDUAL_TOL`` or ReferenceFailure names the instant.  The heading theta and the
centre's path are the cumulative trapezoid integrals of Omega and R(theta) v over the period.

    r = reference_speed(7.0, 1.0, 1.0, 1.0, 10.0, "componentwise")
    r["U"]               # centre displacement over a period on the mean heading, in L (head-ward +)
    r["lateral"]         # the displacement across the mean heading, in L
    r["heading_drift"]   # theta(T) - theta(0), rad per period
    r["power_gait"]      # mean of -integral f . dX/dt ds over the period, in rho g L^2 / T
    r["dissipation"]     # mean of -integral f . u ds, same units (equal when the root holds)
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import brentq, root

RULES = ("componentwise", "associated", "colinear")
RESIDUAL_TOL = 1e-10
STICK_CANDIDATES = 4
EXTRA_STARTS = 8


class ReferenceFailure(RuntimeError):
    """The root finder found no rigid motion at some instant."""


def wave_terms(A: float, k: float) -> np.ndarray:
    """The travelling wave kappa L = A cos 2 pi (k s / L + t / T) as Fourier terms (m, n, cos, sin)."""
    return np.array([[k, 1.0, A, 0.0]])


def tangent_angle(terms, sigma, tau):
    """(Psi, Psi_tau): the integral of kappa L over sigma = s / L from 0 and its derivative in
    tau = t / T, for Fourier ``terms`` (K, 4) = (m, n, cos, sin), at sigma (N,), phase tau."""
    m, n, c, d = (np.asarray(terms, float)[:, i][:, None] for i in range(4))
    a = 2 * np.pi * (m * sigma[None, :] + n * tau)       # (K, N)
    b = 2 * np.pi * n * tau                                # (K, 1)
    zero = m == 0.0
    ms = np.where(zero, 1.0, m)
    two_pi_m = 2 * np.pi * ms
    # m != 0: integrals of cos a, sin a over sigma and their tau-derivatives (n / m factors)
    ic = (np.sin(a) - np.sin(b)) / two_pi_m
    is_ = -(np.cos(a) - np.cos(b)) / two_pi_m
    ic_t = n / ms * (np.cos(a) - np.cos(b))
    is_t = n / ms * (np.sin(a) - np.sin(b))
    # m == 0: the term is uniform in sigma, its integral sigma cos b, sigma sin b
    s = sigma[None, :]
    ic = np.where(zero, s * np.cos(b), ic)
    is_ = np.where(zero, s * np.sin(b), is_)
    ic_t = np.where(zero, -2 * np.pi * n * s * np.sin(b), ic_t)
    is_t = np.where(zero, 2 * np.pi * n * s * np.cos(b), is_t)
    return (c * ic + d * is_).sum(0), (c * ic_t + d * is_t).sum(0)


def trapezoid_weights(points: int) -> np.ndarray:
    """Weights of the trapezoid rule on ``points`` uniform nodes of [0, 1] (they sum to 1)."""
    w = np.full(points, 1.0 / (points - 1))
    w[[0, -1]] *= 0.5
    return w


def body_shape(terms, tau, points):
    """The body at phase tau in its own frame (lengths in L, rates per T): psi, psi_tau (N,),
    X, X_tau (N, 2), centre of mass at 0 and mean tangent angle 0."""
    sigma = np.linspace(0.0, 1.0, points)
    w = trapezoid_weights(points)
    Psi, Psi_t = tangent_angle(terms, sigma, tau)
    psi = Psi - w @ Psi
    psi_t = Psi_t - w @ Psi_t
    tang = np.stack([np.cos(psi), np.sin(psi)], 1)
    norm = np.stack([-np.sin(psi), np.cos(psi)], 1)
    X = cumulative_trapezoid(tang, sigma, axis=0, initial=0.0)
    Xt = cumulative_trapezoid(psi_t[:, None] * norm, sigma, axis=0, initial=0.0)
    return psi, psi_t, X - w @ X, Xt - w @ Xt


def friction(ut, un, rule, mu_f, mu_b, mu_t):
    """(f_t, f_n): friction per unit weight in the local frame for velocity components
    (ut, un) along the tangent (head-ward) and the normal; zero where u = 0 exactly."""
    speed = np.hypot(ut, un)
    moving = speed > 0.0
    safe = np.where(moving, speed, 1.0)
    et, en = np.where(moving, ut / safe, 0.0), np.where(moving, un / safe, 0.0)
    a = np.where(et >= 0.0, mu_f, mu_b)
    b = mu_t
    if rule == "componentwise":
        ft, fn = -a * et, -b * en
    elif rule == "associated":
        q = np.sqrt((a * et) ** 2 + (b * en) ** 2)
        q = np.where(moving, q, 1.0)
        ft, fn = -a * a * et / q, -b * b * en / q
    elif rule == "colinear":
        r = 1.0 / np.sqrt(np.where(moving, (et / a) ** 2 + (en / b) ** 2, 1.0))
        ft, fn = -r * et, -r * en
    else:
        raise ValueError(f"rule must be one of {', '.join(RULES)}, got {rule!r}")
    return np.where(moving, ft, 0.0), np.where(moving, fn, 0.0)


class Instant:
    """The body at one phase: its shape and the friction of a rigid motion x = (vx, vy, Omega)."""

    def __init__(self, terms, tau, points, coefficients, rule):
        self.psi, _, self.X, self.Xt = body_shape(terms, tau, points)
        self.w = trapezoid_weights(points)
        self.t = np.stack([np.cos(self.psi), np.sin(self.psi)], 1)
        self.n = np.stack([-self.t[:, 1], self.t[:, 0]], 1)
        self.coefficients, self.rule = coefficients, rule
        self.scale = max(coefficients)

    def velocity(self, x):
        vx, vy, om = x
        return np.stack([vx - om * self.X[:, 1], vy + om * self.X[:, 0]], 1) + self.Xt

    def force(self, x, stick=None):
        """(N, 2) friction per unit weight at every node for the rigid motion x; ``stick``
        (j, f_j): node j is at rest and its friction f_j (a point of its set)."""
        u = self.velocity(x)
        ut = np.einsum("ij,ij->i", u, self.t)
        un = np.einsum("ij,ij->i", u, self.n)
        ft, fn = friction(ut, un, self.rule, *self.coefficients)
        f = ft[:, None] * self.t + fn[:, None] * self.n
        if stick is not None:
            f[stick[0]] = stick[1]
        return f

    def residual(self, x, stick=None):
        """Net force and torque about the centre over (rho g L max mu) and (rho g L^2 max mu)."""
        f = self.force(x, stick)
        F = self.w @ f
        M = self.w @ (self.X[:, 0] * f[:, 1] - self.X[:, 1] * f[:, 0])
        return np.array([F[0], F[1], M]) / self.scale

    def powers(self, x, stick=None):
        """(gait power, dissipation) per unit weight: -int f . dX/dt ds and -int f . u ds."""
        f = self.force(x, stick)
        u = self.velocity(x)
        if stick is not None:
            u[stick[0]] = 0.0
        return (-self.w @ np.einsum("ij,ij->i", f, self.Xt),
                -self.w @ np.einsum("ij,ij->i", f, u))


def solve_instant(inst: Instant, start):
    """The rigid motion of one instant, from ``start`` (then from rest and EXTRA_STARTS fixed
    random starts, each by two methods); if no root, the motion with one node at rest
    (:func:`solve_stick`).  Returns (x, stick): stick None or (node, its friction)."""
    best, best_res = None, np.inf
    rng = np.random.default_rng(0)                       # the same extra starts every call
    extra = [rng.normal(size=3) * (0.5, 0.5, 3.0) for _ in range(EXTRA_STARTS)]
    for x0 in [np.asarray(start, float), np.zeros(3)] + extra:
        for method in ("hybr", "lm"):
            sol = root(inst.residual, x0, method=method, tol=1e-14)
            res = np.max(np.abs(inst.residual(sol.x)))
            if res < best_res:
                best, best_res = sol.x, res
            if best_res < RESIDUAL_TOL:
                return best, None
    speed = np.hypot(*inst.velocity(best).T)
    for j in np.argsort(speed)[:STICK_CANDIDATES]:
        found = solve_stick(inst, int(j), best[2])
        if found is not None:
            return found
    raise ReferenceFailure(f"no rigid motion: residual {best_res:.3g} > {RESIDUAL_TOL:g} "
                           f"and no node can stick")


def stick_motion(inst: Instant, j: int, om: float) -> np.ndarray:
    """The rigid motion turning at om about node j with node j at rest (u_j = 0)."""
    X, Xt = inst.X[j], inst.Xt[j]
    return np.array([om * X[1] - Xt[0], -om * X[0] - Xt[1], om])


def stick_torque(inst: Instant, j: int, om: float) -> float:
    """Torque about node j of the other nodes' friction, node j at rest, over max mu."""
    f = inst.force(stick_motion(inst, j, om))
    f[j] = 0.0
    arm = inst.X - inst.X[j]
    return float(inst.w @ (arm[:, 0] * f[:, 1] - arm[:, 1] * f[:, 0])) / inst.scale


def solve_stick(inst: Instant, j: int, om0: float):
    """Node j at rest, its friction anywhere in its set w_j (-C) (the set-valued law at u = 0):
    the torque about it fixes Omega (a bracketed scalar root), the net force fixes its friction.
    Returns (x, (j, f_j)) if that friction lies in the set, else None."""
    def g(om):
        return stick_torque(inst, j, om)
    lo, hi, step = om0, om0, max(1.0, abs(om0)) * 1e-3
    glo = ghi = g(om0)
    while glo * ghi > 0.0 and step < 1e6:
        lo, hi, step = lo - step, hi + step, 2 * step
        glo, ghi = g(lo), g(hi)
    if glo * ghi > 0.0:
        return None
    om = brentq(g, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    x = stick_motion(inst, j, om)
    f = inst.force(x)
    f[j] = 0.0
    fj = -(inst.w @ f) / inst.w[j]                      # per unit weight, world of the body frame
    ct, cn = -fj @ inst.t[j], -fj @ inst.n[j]            # c = -f_j must lie in C
    mu_f, mu_b, mu_t = inst.coefficients
    a = mu_f if ct >= 0.0 else mu_b
    if (ct / a) ** 2 + (cn / mu_t) ** 2 > 1.0 + 1e-9:
        return None
    return x, (j, fj)


def check_arguments(terms, coefficients, rule, points, steps):
    if rule not in RULES:
        raise ValueError(f"rule must be one of {', '.join(RULES)}, got {rule!r}")
    if not all(np.isfinite(c) and c > 0 for c in coefficients):
        raise ValueError(f"mu_f, mu_b, mu_t must be finite and > 0, got {coefficients}")
    if points < 3 or steps < 4:
        raise ValueError(f"points >= 3 and steps >= 4, got {points}, {steps}")
    if not np.all(np.isfinite(terms)):
        raise ValueError("gait terms must be finite")


def reference_speed(A: float, k: float, mu_f: float, mu_b: float, mu_t: float, rule: str,
                    points: int = 401, steps: int = 200, terms=None) -> dict:
    """Quasi-static crawl over one period of the travelling wave (A, k) or of Fourier
    ``terms`` (rows m, n, cos, sin; A and k ignored when given).  Returns U, lateral
    (body lengths per period), heading_drift (rad per period), power_gait and dissipation
    (period means, rho g L^2 / T), the largest residual, rule, points and steps."""
    terms = wave_terms(A, k) if terms is None else np.atleast_2d(np.asarray(terms, float))
    coefficients = (float(mu_f), float(mu_b), float(mu_t))
    check_arguments(terms, coefficients, rule, points, steps)
    taus = np.arange(steps) / steps
    motion = np.zeros((steps, 3))
    power = np.zeros((steps, 2))
    worst, sticks = 0.0, 0
    x = np.zeros(3)
    for j, tau in enumerate(taus):
        inst = Instant(terms, tau, points, coefficients, rule)
        try:
            x, stick = solve_instant(inst, x)
        except ReferenceFailure as exc:
            raise ReferenceFailure(f"t/T = {tau:.4f}: {exc}") from None
        worst = max(worst, float(np.max(np.abs(inst.residual(x, stick)))))
        sticks += stick is not None
        motion[j] = x
        power[j] = inst.powers(x, stick)
    out = integrate_period(motion, power, worst, rule, points, steps)
    out["stick_instants"] = sticks
    return out


def integrate_period(motion, power, worst, rule, points, steps) -> dict:
    """Heading and centre path over the period from (v, Omega) at the steps (periodic)."""
    closed = np.vstack([motion, motion[:1]])             # phase 1 is phase 0
    tau = np.linspace(0.0, 1.0, steps + 1)
    theta = cumulative_trapezoid(closed[:, 2], tau, initial=0.0)
    c, s = np.cos(theta), np.sin(theta)
    world = np.stack([c * closed[:, 0] - s * closed[:, 1], s * closed[:, 0] + c * closed[:, 1]], 1)
    disp = np.trapezoid(world, tau, axis=0) if hasattr(np, "trapezoid") else np.trapz(world, tau, axis=0)
    mean_heading = np.mean(theta[:-1])                   # periodic mean of the heading
    head = np.array([np.cos(mean_heading), np.sin(mean_heading)])
    side = np.array([-head[1], head[0]])
    return {"U": float(disp @ head), "lateral": float(disp @ side),
            "heading_drift": float(theta[-1] - theta[0]),
            "power_gait": float(np.mean(power[:, 0])), "dissipation": float(np.mean(power[:, 1])),
            "residual": worst, "rule": rule, "points": points, "steps": steps}
