"""Numba kernels of the slider chain (physics in :mod:`asperity.microslip.quasi_static`
and :mod:`asperity.microslip.dynamic`).

Array-in/array-out loops, no Python objects, no validation (the wrappers validate and
coerce).  Kernels cannot raise: failures come back as integer status codes (``STATUS_*``),
which the wrappers turn into messages or physical outcomes.

The chain (SPEC.md section 5), n nodes on a line:
    kb (n-1,)  axial stiffness of the element between nodes e and e+1 (N/m)
    le (n-1,)  its length (m); its free thermal elongation is alpha_T le dT
    kt (n,)    tangential contact stiffness of node i (N/m), in series with a slider
    cp, cm (n,) slider thresholds mu+ N_i (slides towards +x) and mu- N_i (towards -x), N,
               positive, possibly +inf (self-locking)
    fw (n,)    share of the external tangential force F acting on node i (sums to 1)
State: u (n,) node displacements, s (n,) slider positions; contact force q = kt (u - s),
admissible in [-cm, cp].  Equilibrium of node i (element forces
N_e = kb_e (u_{e+1} - u_e - alpha_T le_e dT)):  N_i - N_{i-1} - q_i + F fw_i = 0.
Slider status: 0 stick, +1 sliding towards +x (q = cp), -1 towards -x (q = -cm).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

STATUS_OK = 0
STATUS_SLIDE_OFF = 1       # no equilibrium: the external load exceeds the sliders' capacity
STATUS_NO_CONVERGENCE = 2  # the active-set iteration (or the prox fixed point) did not converge

#: converged when max |grad Phi| <= _GTOL x the largest force in the sums
_GTOL = 1e-11
#: Hessian regularisation (x k_t) when every slider slides (rigid mode)
_REG = 1e-6


@njit(cache=True)
def solve_tridiag(kb, kd, rhs, u, cw, dw):
    """Solve (K_bar + diag(kd)) u = rhs by the Thomas algorithm (K_bar: the chain's
    element stiffness; kd >= 0 with at least one kd > 0).  cw, dw: work arrays (n,)."""
    n = u.size
    # row i: -kb[i-1] u_{i-1} + (kb[i-1] + kb[i] + kd[i]) u_i - kb[i] u_{i+1} = rhs_i
    b0 = (kb[0] if n > 1 else 0.0) + kd[0]
    cw[0] = (-kb[0] / b0) if n > 1 else 0.0
    dw[0] = rhs[0] / b0
    for i in range(1, n):
        a = -kb[i - 1]
        b = kb[i - 1] + (kb[i] if i < n - 1 else 0.0) + kd[i]
        den = b - a * cw[i - 1]
        cw[i] = (-kb[i] / den) if i < n - 1 else 0.0
        dw[i] = (rhs[i] - a * dw[i - 1]) / den
    u[n - 1] = dw[n - 1]
    for i in range(n - 2, -1, -1):
        u[i] = dw[i] - cw[i] * u[i + 1]


@njit(cache=True)
def _classify(kt, cp, cm, s_old, u, cls):
    """Slider status of the trial forces kt (u - s_old): +1 above cp, -1 below -cm, else 0;
    returns the number of sticking sliders."""
    nst = 0
    for i in range(u.size):
        tq = kt[i] * (u[i] - s_old[i])
        if tq > cp[i]:
            cls[i] = 1
        elif tq < -cm[i]:
            cls[i] = -1
        else:
            cls[i] = 0
            nst += 1
    return nst


@njit(cache=True)
def _energy_gradient(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, u, g):
    """Incremental energy Phi(u) (sliders eliminated by the return mapping) and its
    gradient g = K_bar u - thermal - F fw + q(u) (out); returns (Phi, max |g|, force scale)."""
    n = u.size
    phi = 0.0
    scale = 0.0
    for i in range(n):
        g[i] = -F * fw[i]
        phi -= F * fw[i] * u[i]
    for e in range(n - 1):
        d = u[e + 1] - u[e] - alpha_T * le[e] * dT
        Ne = kb[e] * d
        phi += 0.5 * Ne * d
        g[e] -= Ne
        g[e + 1] += Ne
        a = abs(Ne)
        if a > scale:
            scale = a
    for i in range(n):
        v = u[i] - s_old[i]
        tq = kt[i] * v
        if tq > cp[i]:
            qi = cp[i]
            phi += cp[i] * v - 0.5 * cp[i] * cp[i] / kt[i]
        elif tq < -cm[i]:
            qi = -cm[i]
            phi += -cm[i] * v - 0.5 * cm[i] * cm[i] / kt[i]
        else:
            qi = tq
            phi += 0.5 * tq * v
        g[i] += qi
        a = abs(qi) + abs(F * fw[i])
        if a > scale:
            scale = a
    gmax = 0.0
    for i in range(n):
        if abs(g[i]) > gmax:
            gmax = abs(g[i])
    return phi, gmax, scale


@njit(cache=True)
def solve_step(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, u, s, q, status,
               g, un, gn, du, cls, clsn, cw, dw, max_iter):
    """One load increment of the slider chain to the load (dT, F), exactly (backward Euler
    of the rate-independent law, exact while every slider's slip is monotone over it).

    Minimises the incremental energy Phi(u) -- bars, contact springs, the sliders'
    dissipation, eliminated by the return mapping -- which is convex, C1 and piecewise
    quadratic, by semismooth Newton (Hessian K_bar + diag(k_t of the sticking sliders),
    tridiagonal) with a backtracking line search: globally convergent, and exact once the
    slider status stops changing.  ``u``: starting guess in, solution out.
    Returns (code, Newton iterations); on success s, q, status hold the new state."""
    n = u.size
    kd = np.empty(n)
    # absolute floor of the force scale: the largest finite slider threshold
    cap = 0.0
    for i in range(n):
        if math.isfinite(cp[i]) and cp[i] > cap:
            cap = cp[i]
        if math.isfinite(cm[i]) and cm[i] > cap:
            cap = cm[i]
    phi, gmax, scale = _energy_gradient(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, u, g)
    scale = max(scale, cap)
    nst = _classify(kt, cp, cm, s_old, u, cls)
    code = STATUS_NO_CONVERGENCE
    its = max_iter
    for it in range(1, max_iter + 1):
        if gmax <= _GTOL * scale:
            code = STATUS_OK
            its = it - 1
            break
        for i in range(n):
            g[i] = -g[i]
            # Hessian of the current piece; with every slider sliding the rigid mode is
            # free: a small regularisation keeps the step finite (the line search and the
            # gradient test decide, so the solution does not depend on it)
            kd[i] = kt[i] if cls[i] == 0 else (_REG * kt[i] if nst == 0 else 0.0)
        solve_tridiag(kb, kd, g, du, cw, dw)
        slope = 0.0
        for i in range(n):
            slope -= g[i] * du[i]          # g holds -grad
        step = 1.0
        accepted = False
        for _ in range(60):
            for i in range(n):
                un[i] = u[i] + step * du[i]
            phin, gmaxn, scalen = _energy_gradient(kb, le, kt, cp, cm, fw, alpha_T, dT, F,
                                                   s_old, un, gn)
            if (phin <= phi + 1e-4 * step * slope + 1e-12 * abs(phi)
                    or gmaxn <= _GTOL * max(scalen, cap)):
                accepted = True
                break
            step *= 0.5
        if not accepted:
            # no descent left within rounding: a solution if the gradient is small
            if gmax <= 1e-8 * scale:
                code = STATUS_OK
                its = it
            break
        for i in range(n):
            u[i] = un[i]
            g[i] = gn[i]
        phi, gmax, scale = phin, gmaxn, max(scalen, cap)
        nstn = _classify(kt, cp, cm, s_old, u, clsn)
        same = nstn == nst and step == 1.0 and nst > 0
        if same:
            for i in range(n):
                if clsn[i] != cls[i]:
                    same = False
                    break
        for i in range(n):
            cls[i] = clsn[i]
        nst = nstn
        if same:                           # the exact minimiser of this quadratic piece
            code = STATUS_OK
            its = it
            break
    if code != STATUS_OK:
        return code, its
    for i in range(n):
        tq = kt[i] * (u[i] - s_old[i])
        if tq > cp[i]:
            q[i] = cp[i]
            status[i] = 1
        elif tq < -cm[i]:
            q[i] = -cm[i]
            status[i] = -1
        else:
            q[i] = tq
            status[i] = 0
        s[i] = u[i] - q[i] / kt[i] if status[i] != 0 else s_old[i]
    return STATUS_OK, its


@njit(cache=True)
def march(kb, le, kt, cp, cm, fw, alpha_T, dT_seq, F_seq, u, s, du_seq, status_seq,
          slip_seq, rec_nodes, rec_u, max_iter):
    """March the load points (dT_seq[j], F_seq[j]) from the state (u, s) (updated in place).

    du_seq (m, n): displacement increments of the same points one cycle earlier, the
    starting guess of each increment (exact once the cycle is stabilised); overwritten.
    status_seq (m, n) int8: the slider status over each increment (out).
    slip_seq (m,): the largest |slip| of a slider over each increment (out).
    rec_u (m, len(rec_nodes)): node displacements recorded at each point.
    Returns (code, index of the failing point or -1, total Newton iterations)."""
    n = u.size
    m = dT_seq.size
    s_old = s.copy()
    u_old = u.copy()
    q = np.empty(n)
    g = np.empty(n)
    un = np.empty(n)
    gn = np.empty(n)
    dd = np.empty(n)
    cls = np.empty(n, np.int8)
    clsn = np.empty(n, np.int8)
    cw = np.empty(n)
    dw = np.empty(n)
    st = np.empty(n, np.int8)
    iters = 0
    for j in range(m):
        for i in range(n):
            s_old[i] = s[i]
            u_old[i] = u[i]
            u[i] += du_seq[j, i]
        code, it = solve_step(kb, le, kt, cp, cm, fw, alpha_T, dT_seq[j], F_seq[j], s_old, u, s,
                              q, st, g, un, gn, dd, cls, clsn, cw, dw, max_iter)
        iters += it
        if code != STATUS_OK:
            for i in range(n):
                s[i] = s_old[i]
                u[i] = u_old[i]
            return code, j, iters
        smax = 0.0
        for i in range(n):
            status_seq[j, i] = st[i]
            du_seq[j, i] = u[i] - u_old[i]
            d = abs(s[i] - s_old[i])
            if d > smax:
                smax = d
        slip_seq[j] = smax
        for k in range(rec_nodes.size):
            rec_u[j, k] = u[rec_nodes[k]]
    return STATUS_OK, -1, iters


@njit(cache=True)
def moreau_chain(kb, le, kt, cp, cm, fw, alpha_T, t_pts, dT_pts, F_pts, t_end, dt, mu_mass,
                 ms_mass, damping, r_factor, tol, max_iter, u, v, s, w, xi, rec_every,
                 rec_nodes, rec_u, rec_t):
    """Moreau midpoint time-stepping of the chain with masses (SPEC.md section 4).

    DOFs: node displacements u (masses mu_mass) and slider positions s (masses ms_mass);
    forces at the midpoint q_M: elastic (bars, contact springs), thermal, external F(t) and
    mass-proportional damping (rate ``damping``, implicit).  Each slider carries a friction
    impulse -xi with xi in [-cm dt, cp dt], from the proximal equation
        xi = prox_[-cm dt, cp dt](xi + r w_E),    r = r_factor / G,  G = 1/(ms (1 + damping dt/2))
    solved by fixed-point iteration (tolerance ``tol`` relative to the impulse bound,
    ``max_iter`` iterations) for every slider and step; 0 < r_factor < 2.
    Loads are piecewise linear in time through (t_pts, dT_pts, F_pts).
    Returns (code, steps, max iterations used, sum of iterations)."""
    n = u.size
    nseg = t_pts.size
    fu = np.empty(n)
    fs = np.empty(n)
    um = np.empty(n)
    sm = np.empty(n)
    h = 0.5 * dt
    dfac = 1.0 / (1.0 + damping * h)
    afac = 1.0 - damping * h
    t = 0.0
    k = 0
    step = 0
    max_it = 0
    sum_it = 0
    nrec = 0
    while t < t_end - 0.5 * dt:
        tm = t + h
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
                return STATUS_NO_CONVERGENCE, step, max_it, sum_it
            w[i] = wfree - G * x
            u[i] = um[i] + h * v[i]
            s[i] = sm[i] + h * w[i]
        t += dt
        step += 1
        if rec_every > 0 and step % rec_every == 0 and nrec < rec_t.size:
            rec_t[nrec] = t
            for j in range(rec_nodes.size):
                rec_u[nrec, j] = u[rec_nodes[j]]
            nrec += 1
    return STATUS_OK, step, max_it, sum_it
