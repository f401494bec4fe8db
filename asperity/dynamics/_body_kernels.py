"""Numba kernels of the rigid-body solver (physics in :mod:`asperity.dynamics.body`).

Array-in/array-out loops, no Python objects, no validation (the wrapper validates).  A step
solves for the three velocities u = (vx, vy, omega), not for 2N contact impulses:

* law evaluation at a slip gamma: ``_eval`` gives the sliding force c (per unit normal
  load), its Jacobian dc/dgamma, and the gradient, Hessian and value of the support
  function h of (the hull of) C -- closed forms for the disc and the (truncated) ellipse,
  linear interpolation in psi of tables on a uniform grid otherwise;
* stick: ``_min_sphere`` minimises G(d) = sum_i lambda_i h(W_i^T d) - b.d over the unit
  sphere |d|_M = 1 (Riemannian Newton in the coordinates e = M^(1/2) d); the body sticks,
  u_E = 0 exactly, iff min G >= -tol * scale (b = M u_free);
* sliding: Newton with a backtracking line search on R(u) = M (u - u_free) +
  sum_i lambda_i W_i c(gamma_i) = 0 (merit F(u) for associated laws, 1/2 |R|^2_{M^-1}
  otherwise).

The law and the step's equations are in :mod:`._body_law_kernels`, the stick test and the
sliding solve in :mod:`._body_step_kernels`; this module has the step and the time loop.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

# KIND_*: the law kinds the wrapper (asperity.dynamics.body) passes, kept here for it
from ..kernel_cache import refresh
from ._body_law_kernels import (KIND_COMPONENTWISE, KIND_ELLIPSE, KIND_TABLE,  # noqa: F401
                                TWO_PI, _ray)
from ._body_step_kernels import _min_sphere, _slide

refresh(__file__)     # drop cached kernels compiled against older callees

STATUS_OK = 0
STATUS_NOT_CONVERGED = 1
STATUS_NON_FINITE = 2
INFO_STEPS = 0          # steps integrated
INFO_STOP_STEP = 1      # steps done when the body last came to rest (-1: moving at the end)
INFO_MAX_ITER = 2       # most iterations of one step
INFO_ITER_TOTAL = 3     # iterations summed
INFO_STATUS = 4
INFO_FAIL_STEP = 5      # first step not converged (-1: none)
INFO_RECORDS = 6
INFO_HALTED = 7
INFO_SLIDE_LAST = 8     # steps done when |v| was last above the stop threshold (-1: never)
INFO_SPIN_LAST = 9      # the same for rho |omega|
INFO_LAST_VX = 10       # the last velocity before the final rest
INFO_LAST_VY = 11
INFO_LAST_W = 12
INFO_MAX_RESIDUAL = 13  # largest final relative residual of a sliding step
INFO_SIZE = 14
FORCE_SQUARE = 1
FORCE_SINE = 2


@njit(cache=True)
def _force(fpar, t, out):
    kind = int(fpar[0])
    w = 0.0
    if kind == FORCE_SQUARE:
        w = 1.0 if (t / fpar[1]) % 1.0 < 0.5 else -1.0
    elif kind == FORCE_SINE:
        w = math.sin(TWO_PI * t / fpar[1])
    for j in range(3):
        out[j] = fpar[2 + j] + fpar[5 + j] * w


@njit(cache=True)
def step_velocity(uA, uP, warm, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, tol, maxit,
                  scale, out, R, J, ev, work):
    """The end velocity of one step (out) from the start velocity uA (uP the one before,
    used if warm) and the free velocity uf.  scale: the impulse scale
    sum_i lam_i mu_max / sqrt(m) of the tolerances.  Returns (iterations, status, relative residual)."""
    b = np.empty(3)
    d = np.empty(3)
    dx = np.empty(3)
    un = np.empty(3)
    for j in range(3):
        b[j] = md[j] * uf[j]
    if b[0] == 0.0 and b[1] == 0.0 and b[2] == 0.0:
        for j in range(3):
            out[j] = 0.0
        return 0, STATUS_OK, 0.0
    # tolerance on residuals and margins (units of M^(1/2) velocity): tol times the impulse
    # scale, plus the rounding floor of the momentum M u_free itself
    tola = tol * scale + 1e-15 * math.sqrt(md[0] * uf[0] * uf[0] + md[1] * uf[1] * uf[1]
                                           + md[2] * uf[2] * uf[2])
    its = 0
    rn = 0.0
    if uA[0] != 0.0 or uA[1] != 0.0 or uA[2] != 0.0:
        # moving: Newton from the linear extrapolation of the last two velocities (second
        # order in dt on a smooth motion: one or two iterations); a collapse towards the
        # stick of the body is caught inside _slide
        for j in range(3):
            out[j] = 2.0 * uA[j] - uP[j] if warm else uA[j]
        k, conv, rn = _slide(out, uf, b, md, ox, oy, ext, lam, kind, par, tab, assoc, tola,
                             maxit, R, J, ev, dx, un)
        its += k
        if conv:
            return its, STATUS_OK, rn / scale
        if out[0] != 0.0 or out[1] != 0.0 or out[2] != 0.0:
            for j in range(3):
                d[j] = out[j]
        else:
            for j in range(3):
                d[j] = uA[j]
    else:
        # from rest: along the free motion
        for j in range(3):
            d[j] = uf[j]
    for attempt in range(4):
        s = _ray(d, b, md, ox, oy, ext, lam, kind, par, tab, ev)
        if s <= 0.0:
            # no sliding on this ray: find the direction of least margin; the body sticks
            # iff the margin is not negative
            G, k = _min_sphere(d, b, md, ox, oy, ext, lam, kind, par, tab, tola, maxit, R,
                               J, ev, work)
            its += k
            if G >= -tola:
                for j in range(3):
                    out[j] = 0.0
                return its, STATUS_OK, 0.0
            s = _ray(d, b, md, ox, oy, ext, lam, kind, par, tab, ev)
            if s <= 0.0:
                s = -G
        for j in range(3):
            out[j] = s * d[j]
        k, conv, rn = _slide(out, uf, b, md, ox, oy, ext, lam, kind, par, tab, assoc, tola,
                             maxit, R, J, ev, dx, un)
        its += k
        if conv:
            return its, STATUS_OK, rn / scale
        # Newton collapsed (e.g. towards the stick of the body): start again from its point
        if out[0] != 0.0 or out[1] != 0.0 or out[2] != 0.0:
            for j in range(3):
                d[j] = out[j]
    return its, STATUS_NOT_CONVERGED, rn / scale


@njit(cache=True)
def integrate(q, u, pts, md, lam, kind, par, tab, assoc, fpar, dt, n_steps, start, count,
              tol, maxit, scale, stop_v, rho, halt, record_every, rec_t, rec_q, rec_u, info):
    """Steps start .. start+count-1 of the midpoint scheme; q, u updated in place (law
    frame).  lam: normal impulse per step of each point; md = (m, m, I)."""
    n = pts.shape[0]
    ox = np.empty(n)
    oy = np.empty(n)
    ext = np.zeros((0, 4))       # a rigid footprint: no slip offsets, one law orientation
    R = np.empty(3)
    J = np.empty((3, 3))
    ev = np.empty(16)
    work = np.empty(3)
    f = np.empty(3)
    uf = np.empty(3)
    ue = np.empty(3)
    if start == 0:
        for j in range(INFO_SIZE):
            info[j] = 0.0
        info[INFO_STOP_STEP] = -1.0
        info[INFO_FAIL_STEP] = -1.0
        if u[0] == 0.0 and u[1] == 0.0 and u[2] == 0.0:
            info[INFO_STOP_STEP] = 0.0
        info[INFO_SLIDE_LAST] = 0.0 if math.hypot(u[0], u[1]) > stop_v else -1.0
        info[INFO_SPIN_LAST] = 0.0 if rho * abs(u[2]) > stop_v else -1.0
        rec_t[0] = 0.0
        for j in range(3):
            rec_q[0, j] = q[j]
            rec_u[0, j] = u[j]
        info[INFO_RECORDS] = 1
    nrec = int(info[INFO_RECORDS])
    status = int(info[INFO_STATUS])
    forced = fpar[0] != 0.0 or fpar[2] != 0.0 or fpar[3] != 0.0 or fpar[4] != 0.0
    step = start
    halted = False
    stuck = False
    bprev = np.zeros(3)
    up = np.zeros(3)
    warm = False
    for step in range(start, start + count):
        tM = (step + 0.5) * dt
        for j in range(3):
            q[j] += 0.5 * dt * u[j]
        _force(fpar, tM, f)
        for j in range(3):
            uf[j] = u[j] + dt * f[j] / md[j]
        # a body at rest under the same impulse stays at rest (bit for bit, no solve)
        if stuck and md[0] * uf[0] == bprev[0] and md[1] * uf[1] == bprev[1] \
                and md[2] * uf[2] == bprev[2]:
            for j in range(3):
                ue[j] = 0.0
            its = 0
            st = STATUS_OK
        else:
            c = math.cos(q[2])
            s = math.sin(q[2])
            for i in range(n):
                ox[i] = c * pts[i, 0] - s * pts[i, 1]
                oy[i] = s * pts[i, 0] + c * pts[i, 1]
            its, st, res = step_velocity(u, up, warm, uf, md, ox, oy, ext, lam, kind, par,
                                         tab, assoc, tol, maxit, scale, ue, R, J, ev, work)
            if res > info[INFO_MAX_RESIDUAL]:
                info[INFO_MAX_RESIDUAL] = res
        info[INFO_ITER_TOTAL] += its
        if its > info[INFO_MAX_ITER]:
            info[INFO_MAX_ITER] = its
        if st != STATUS_OK and status == STATUS_OK:
            status = st
            info[INFO_FAIL_STEP] = step
        moving_before = u[0] != 0.0 or u[1] != 0.0 or u[2] != 0.0
        if not (math.isfinite(ue[0]) and math.isfinite(ue[1]) and math.isfinite(ue[2])):
            status = STATUS_NON_FINITE
            info[INFO_FAIL_STEP] = step
            halted = True
            break
        rest = ue[0] == 0.0 and ue[1] == 0.0 and ue[2] == 0.0
        if rest:
            stuck = True
            for j in range(3):
                bprev[j] = md[j] * uf[j]
            if moving_before:
                info[INFO_LAST_VX] = u[0]
                info[INFO_LAST_VY] = u[1]
                info[INFO_LAST_W] = u[2]
            if info[INFO_STOP_STEP] < 0:
                info[INFO_STOP_STEP] = step + 1
        else:
            stuck = False
            info[INFO_STOP_STEP] = -1.0
        if math.hypot(ue[0], ue[1]) > stop_v:
            info[INFO_SLIDE_LAST] = step + 1
        if rho * abs(ue[2]) > stop_v:
            info[INFO_SPIN_LAST] = step + 1
        warm = moving_before and not rest
        for j in range(3):
            up[j] = u[j]
            u[j] = ue[j]
            q[j] += 0.5 * dt * u[j]
        last = step == n_steps - 1
        if (step + 1) % record_every == 0 or last or (halt and rest and not forced):
            rec_t[nrec] = (step + 1) * dt
            for j in range(3):
                rec_q[nrec, j] = q[j]
                rec_u[nrec, j] = u[j]
            nrec += 1
        if halt and rest and not forced:
            halted = True
            break
    info[INFO_STEPS] = step + 1
    info[INFO_HALTED] = 1.0 if halted else 0.0
    info[INFO_STATUS] = status
    info[INFO_RECORDS] = nrec
