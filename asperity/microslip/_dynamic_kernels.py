"""Numba kernel of the slider chain with masses: Moreau midpoint time-stepping (physics in
:mod:`asperity.microslip.dynamic`; the chain's arrays as in
:mod:`asperity.microslip._chain_kernels`).

Array-in/array-out loops, no Python objects, no validation (the wrapper validates and
coerces); failures come back as integer status codes.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ._chain_kernels import STATUS_NO_CONVERGENCE, STATUS_OK

refresh(__file__)     # drop cached kernels compiled against older callees


@njit(cache=True)
def moreau_chain(kb, le, kt, cp, cm, fw, alpha_T, t_pts, dT_pts, F_pts, step0, step1, dt,
                 mu_mass, ms_mass, damping, r_factor, tol, max_iter, u, v, s, w, xi,
                 rec_every, rec_nodes, rec_u, rec_t, istate):
    """Moreau midpoint time-stepping of the chain with masses (SPEC.md section 4): the steps
    step0 .. step1 - 1, step j going from t = j dt to (j + 1) dt.

    DOFs: node displacements u (masses mu_mass) and slider positions s (masses ms_mass);
    forces at the midpoint q_M: elastic (bars, contact springs), thermal, external F(t) and
    mass-proportional damping (rate ``damping``, implicit).  Each slider carries a friction
    impulse -xi with xi in [-cm dt, cp dt], from the proximal equation
        xi = prox_[-cm dt, cp dt](xi + r w_E),    r = r_factor / G,  G = 1/(ms (1 + damping dt/2))
    solved by fixed-point iteration (tolerance ``tol`` relative to the impulse bound,
    ``max_iter`` iterations) for every slider and step; 0 < r_factor < 2.
    Loads are piecewise linear in time through (t_pts, dT_pts, F_pts).
    State carried from call to call: u, v, s, w, xi and istate = [segment of the loads,
    records written]; the time is computed from the step index, so the steps run in pieces
    (consecutive ranges) give exactly the result of one call.  After step j + 1 a multiple
    of ``rec_every``, u[rec_nodes] and t go to the next row of rec_u, rec_t.
    Returns (code, steps done, max iterations used, sum of iterations)."""
    n = u.size
    nseg = t_pts.size
    fu = np.empty(n)
    fs = np.empty(n)
    um = np.empty(n)
    sm = np.empty(n)
    h = 0.5 * dt
    dfac = 1.0 / (1.0 + damping * h)
    afac = 1.0 - damping * h
    k = istate[0]
    nrec = istate[1]
    max_it = 0
    sum_it = 0
    done = 0
    for step in range(step0, step1):
        tm = (step + 0.5) * dt
        while k < nseg - 2 and tm > t_pts[k + 1]:
            k += 1
        f = (tm - t_pts[k]) / (t_pts[k + 1] - t_pts[k])
        dT = dT_pts[k] + f * (dT_pts[k + 1] - dT_pts[k])
        F = F_pts[k] + f * (F_pts[k + 1] - F_pts[k])
        for i in range(n):
            um[i] = u[i] + h * v[i]
            sm[i] = s[i] + h * w[i]
        for i in range(n):
            qi = kt[i] * (um[i] - sm[i])
            fu[i] = F * fw[i] - qi
            fs[i] = qi
        for e in range(n - 1):
            Ne = kb[e] * (um[e + 1] - um[e] - alpha_T * le[e] * dT)
            fu[e] += Ne
            fu[e + 1] -= Ne
        for i in range(n):
            v[i] = (afac * v[i] + dt * fu[i] / mu_mass[i]) * dfac
            wfree = (afac * w[i] + dt * fs[i] / ms_mass[i]) * dfac
            G = dfac / ms_mass[i]
            r = r_factor / G
            lo = -cm[i] * dt
            hi = cp[i] * dt
            bound = max(min(cp[i], cm[i]) * dt, 1e-300)
            x = xi[i]
            conv = False
            it = 0
            for it in range(1, max_iter + 1):
                wE = wfree - G * x
                y = x + r * wE
                xn = min(max(y, lo), hi)
                d = abs(xn - x)
                x = xn
                if d <= tol * bound:
                    conv = True
                    break
            xi[i] = x
            sum_it += it
            if it > max_it:
                max_it = it
            if not conv:
                istate[0] = k
                istate[1] = nrec
                return STATUS_NO_CONVERGENCE, done, max_it, sum_it
            w[i] = wfree - G * x
            u[i] = um[i] + h * v[i]
            s[i] = sm[i] + h * w[i]
        done += 1
        if rec_every > 0 and (step + 1) % rec_every == 0 and nrec < rec_t.size:
            rec_t[nrec] = (step + 1) * dt
            for j in range(rec_nodes.size):
                rec_u[nrec, j] = u[rec_nodes[j]]
            nrec += 1
    istate[0] = k
    istate[1] = nrec
    return STATUS_OK, done, max_it, sum_it
