"""Numba kernels of the crawl solver (physics in :mod:`asperity.crawling.solver`).

A step of a crawling body is a step of the rigid-body solver (:mod:`asperity.dynamics`)
whose contact points carry rows: point i slips at W_i^T u + R(theta) v_i (v_i its velocity
in the body frame, the gait's) and its law is turned by its own angle (the body's tangent
there for a texture on the body; the texture's angle for one on the ground).  The unknowns
stay the three rigid velocities u = (vx, vy, omega); the Newton solve with its kink cases
(a point that sticks exactly: a rotation about it; one that slides slowly: polar
coordinates of its slip) is the body solver's ``_slide``.

The gait is periodic: its body-frame kinematics are tabulated once a period (``P`` steps,
dt = T / P) at the steps' mid times (positions r, velocities v, tangent angles) and at
their ends (inertia and internal spin per unit mass), and read by ``step % P``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..dynamics._body_law_kernels import _assemble, _eval_at
from ..dynamics._body_step_kernels import _kink, _polar, _slide
from ..kernel_cache import refresh

refresh(__file__)     # drop cached kernels compiled against older callees

STATUS_OK = 0
STATUS_NOT_CONVERGED = 1
STATUS_NON_FINITE = 2
INFO_STEPS = 0          # steps integrated
INFO_MAX_ITER = 1       # most iterations of one step
INFO_ITER_TOTAL = 2     # iterations summed
INFO_STATUS = 3
INFO_FAIL_STEP = 4      # first step not converged (-1: none)
INFO_RECORDS = 5
INFO_WORK = 6           # work the gait has done against friction, J
INFO_DISSIPATED = 7     # energy friction has dissipated, J
INFO_STICK = 8          # point-steps in exact stick (slip exactly zero)
INFO_SIZE = 9


@njit(cache=True)
def _rows(q, k, r, v, tau, body, ca0, sa0, ox, oy, ext):
    """Footprint offsets and point rows of the step whose mid-time row is k, at the
    orientation q[2]."""
    c = math.cos(q[2])
    s = math.sin(q[2])
    for i in range(ox.shape[0]):
        rx = r[k, i, 0]
        ry = r[k, i, 1]
        vx = v[k, i, 0]
        vy = v[k, i, 1]
        ox[i] = c * rx - s * ry
        oy[i] = s * rx + c * ry
        ext[i, 0] = c * vx - s * vy
        ext[i, 1] = s * vx + c * vy
        if body:
            # the law along the body's tangent there (turned by the texture angle)
            a = q[2] + tau[k, i]
            ca = math.cos(a)
            sa = math.sin(a)
            ext[i, 2] = ca * ca0 - sa * sa0
            ext[i, 3] = sa * ca0 + ca * sa0
        else:
            ext[i, 2] = ca0
            ext[i, 3] = sa0


@njit(cache=True)
def _solve(u, uA, uP, order, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, tola, maxit,
           R, J, ev, dx, un):
    """The step's velocity (u) from the extrapolation of the last velocities (uP: the two
    before uA, uP[0:3] then uP[3:6]; ``order`` 0: uA alone, 1: linear, 2: quadratic, whose
    error O(dt^3) leaves one Newton step to the tolerance on a smooth motion).  If Newton
    fails from there, the step may hold a point at rest that Newton did not come near
    (nearly straight bodies pivot at mid-body; the colinear rule near a pivot): each of the
    PIVOTS points of least slip at uA is tried as the pivot (:func:`_pivot`), then Newton
    from uA, the free velocity and rest, then every other point as the pivot.  Returns
    (iterations, converged, residual)."""
    b = np.empty(3)
    for j in range(3):
        b[j] = md[j] * uf[j]
    n = ox.shape[0]
    slip = np.empty(n)
    for i in range(n):
        slip[i] = math.hypot(uA[0] - uA[2] * oy[i] + ext[i, 0],
                             uA[1] + uA[2] * ox[i] + ext[i, 1])
    order_i = np.argsort(slip)
    its = 0
    rn = 0.0
    for attempt in range(5):
        if attempt == 1:
            k, ok = _pivot(u, uA, uf, md, ox, oy, ext, lam, kind, par, tab, tola, R, J, ev,
                           order_i[:PIVOTS])
            its += k
            if ok:
                return its, True, 0.0
            continue
        for j in range(3):
            if attempt == 0:
                if order == 2:
                    u[j] = 3.0 * (uA[j] - uP[j]) + uP[3 + j]
                elif order == 1:
                    u[j] = 2.0 * uA[j] - uP[j]
                else:
                    u[j] = uA[j]
            elif attempt == 2:
                u[j] = uA[j]
            elif attempt == 3:
                u[j] = uf[j]
            else:
                u[j] = 0.0
        # Newton converges in a few iterations or is stuck near a kink: a short leash
        # before the pivots and the next start (the last start gets all of maxit)
        k, conv, rn = _slide(u, uf, b, md, ox, oy, ext, lam, kind, par, tab, assoc, tola,
                             maxit if attempt == 4 else min(maxit, NEWTON_LEASH), R, J, ev,
                             dx, un)
        its += k
        if conv:
            return its, True, rn
    for j in range(3):
        un[j] = u[j]                  # the last Newton iterate, if no pivot is the answer
    k, ok = _pivot(u, uA, uf, md, ox, oy, ext, lam, kind, par, tab, tola, R, J, ev,
                   order_i[PIVOTS:])
    its += k
    if ok:
        return its, True, 0.0
    for j in range(3):
        u[j] = un[j]
    return its, False, rn


#: points of least slip tried as the pivot before Newton's restarts
PIVOTS = 8
#: Newton iterations of a start before the next is tried
NEWTON_LEASH = 30


@njit(cache=True)
def _pivot(u, uA, uf, md, ox, oy, ext, lam, kind, par, tab, tola, R, J, ev, points):
    """Try each of ``points`` as the step's pivot from uA: sticking exactly (its reaction in
    C) or sliding slowly (polar coordinates of its slip).  Returns (tries, found), u the
    solution when found."""
    cw = np.empty(3)
    tries = 0
    for i in points:
        tries += 1
        for j in range(3):
            u[j] = uA[j]
        if _kink(u, uf, md, ox, oy, ext, lam, kind, par, tab, i, tola, R, J, ev, cw):
            return tries, True
        if _polar(u, uf, md, ox, oy, ext, lam, kind, par, tab, i, tola, R, J, ev, cw):
            return tries, True
    return tries, False


@njit(cache=True)
def _energy(u, uf, md, ox, oy, ext, lam, kind, par, tab, R, J, ev, info):
    """Add the step's work of the gait against friction (sum lam_i c_i . R v_i) and its
    dissipation (sum lam_i c_i . gamma_i) to info.  A point that sticks (its slip below
    1e-12 of its velocity scale: the kink solve makes it zero to rounding) does not
    dissipate, but its reaction works on the gait: the reaction is what the step's
    equation needs from it (its residual with the point left out)."""
    js = -1
    for i in range(ox.shape[0]):
        gx = u[0] - u[2] * oy[i] + ext[i, 0]
        gy = u[1] + u[2] * ox[i] + ext[i, 1]
        vs = (abs(ext[i, 0]) + abs(ext[i, 1]) + abs(u[0]) + abs(u[1])
              + abs(u[2]) * (abs(ox[i]) + abs(oy[i])))
        if abs(gx) + abs(gy) <= 1e-12 * vs:
            info[INFO_STICK] += 1.0
            js = i
            continue
        _eval_at(kind, par, tab, ext, i, gx, gy, ev)
        info[INFO_WORK] += lam[i] * (ev[0] * ext[i, 0] + ev[1] * ext[i, 1])
        info[INFO_DISSIPATED] += lam[i] * (ev[0] * gx + ev[1] * gy)
    if js >= 0:
        _assemble(u, uf, md, ox, oy, ext, lam, kind, par, tab, False, R, J, ev, js)
        info[INFO_WORK] -= R[0] * ext[js, 0] + R[1] * ext[js, 1]


@njit(cache=True)
def integrate(q, u, up, r, v, tau, inertia, spin, w, mass, g, dt, qs_eps, body, ca0, sa0,
              kind, par, tab, assoc, mu, tol, maxit, start, count, record_every, rec_t,
              rec_q, rec_u, rec_e, info):
    """Steps start .. start+count-1 of the midpoint scheme (q, u, up updated in place; up (6,)
    holds the two velocities before u, for the extrapolation).  r, v (P, N, 2), tau (P, N): the gait at
    the steps' mid times; inertia, spin (P + 1,): per unit mass at their ends.  qs_eps > 0:
    quasi-static (the momentum weighted by qs_eps against the friction impulse: the net
    friction force and torque vanish to that relative size); 0: Newton-Euler.  rec_e
    (rows, 2): the gait's work and the dissipation so far."""
    P = r.shape[0]
    n = r.shape[1]
    ox = np.empty(n)
    oy = np.empty(n)
    ext = np.empty((n, 4))
    lam = np.empty(n)
    R = np.empty(3)
    J = np.empty((3, 3))
    ev = np.empty(18)
    dx = np.empty(3)
    un = np.empty(3)
    uf = np.empty(3)
    ue = np.empty(3)
    md = np.empty(3)
    for i in range(n):
        lam[i] = w[i] * mass * g * dt
    if start == 0:
        for j in range(INFO_SIZE):
            info[j] = 0.0
        info[INFO_FAIL_STEP] = -1.0
        rec_t[0] = 0.0
        for j in range(3):
            rec_q[0, j] = q[j]
            rec_u[0, j] = u[j]
        rec_e[0, 0] = 0.0
        rec_e[0, 1] = 0.0
        info[INFO_RECORDS] = 1
    nrec = int(info[INFO_RECORDS])
    status = int(info[INFO_STATUS])
    if start == 0 and qs_eps > 0.0:
        # without inertia the body is never at rest: start with the balance half a step
        # before t = 0 (the last mid time of a period), so the first half step is second
        # order as every other one
        _rows(q, P - 1, r, v, tau, body, ca0, sa0, ox, oy, ext)
        for j in range(3):
            md[j] = qs_eps * mass * (inertia[0] if j == 2 else 1.0)
            uf[j] = 0.0
        scale = mass * g * dt * mu / math.sqrt(md[0])
        its, conv, rn = _solve(ue, u, up, 0, uf, md, ox, oy, ext, lam, kind, par, tab,
                               assoc, tol * scale, maxit, R, J, ev, dx, un)
        if not conv or not (math.isfinite(ue[0]) and math.isfinite(ue[1])
                            and math.isfinite(ue[2])):
            for j in range(3):      # no balance found there: start from rest (first order)
                ue[j] = 0.0
        for j in range(3):
            u[j] = ue[j]
            up[j] = ue[j]
            up[3 + j] = ue[j]
    step = start
    for step in range(start, start + count):
        k = step % P
        for j in range(3):
            q[j] += 0.5 * dt * u[j]
        _rows(q, k, r, v, tau, body, ca0, sa0, ox, oy, ext)
        iA = inertia[k]
        iE = inertia[k + 1]
        if qs_eps > 0.0:
            md[0] = qs_eps * mass
            md[1] = qs_eps * mass
            md[2] = qs_eps * mass * iE
            for j in range(3):
                uf[j] = u[j]
        else:
            md[0] = mass
            md[1] = mass
            md[2] = mass * iE
            uf[0] = u[0]
            uf[1] = u[1]
            # angular momentum about the centre: I omega + the gait's own spin
            uf[2] = (iA * u[2] + spin[k] - spin[k + 1]) / iE
        # tolerance: tol of the impulse scale, plus the rounding of the momentum M u_free
        scale = mass * g * dt * mu / math.sqrt(md[0])
        tola = tol * scale + 1e-15 * math.sqrt(md[0] * uf[0] * uf[0] + md[1] * uf[1] * uf[1]
                                               + md[2] * uf[2] * uf[2])
        its, conv, rn = _solve(ue, u, up, min(step, 2), uf, md, ox, oy, ext, lam,
                               kind, par, tab, assoc, tola, maxit, R, J, ev, dx, un)
        info[INFO_ITER_TOTAL] += its
        if its > info[INFO_MAX_ITER]:
            info[INFO_MAX_ITER] = its
        if not (math.isfinite(ue[0]) and math.isfinite(ue[1]) and math.isfinite(ue[2])):
            status = STATUS_NON_FINITE
            info[INFO_FAIL_STEP] = step
            break
        if not conv:
            # a step without a solution: the motion after it would not be the model's
            status = STATUS_NOT_CONVERGED
            info[INFO_FAIL_STEP] = step
            break
        if rn > 0.0:
            # Newton's own convergence: its last sums were at ue
            info[INFO_WORK] += ev[16]
            info[INFO_DISSIPATED] += ev[17]
        else:
            # a pivot's solve (its reaction works on the gait) or an exact residual
            _energy(ue, uf, md, ox, oy, ext, lam, kind, par, tab, R, J, ev, info)
        for j in range(3):
            up[3 + j] = up[j]
            up[j] = u[j]
            u[j] = ue[j]
            q[j] += 0.5 * dt * u[j]
        if (step + 1) % record_every == 0:
            rec_t[nrec] = (step + 1) * dt
            for j in range(3):
                rec_q[nrec, j] = q[j]
                rec_u[nrec, j] = u[j]
            rec_e[nrec, 0] = info[INFO_WORK]
            rec_e[nrec, 1] = info[INFO_DISSIPATED]
            nrec += 1
    info[INFO_STEPS] = step + 1 if status == STATUS_OK else step
    info[INFO_STATUS] = status
    info[INFO_RECORDS] = nrec
