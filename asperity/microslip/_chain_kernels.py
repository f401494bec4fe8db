"""Numba kernels of the slider chain, quasi-static (physics in
:mod:`asperity.microslip.quasi_static`; the Moreau kernel of :mod:`asperity.microslip.dynamic`
is in :mod:`asperity.microslip._dynamic_kernels`).

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
#: Hessian regularisation when every slider slides (rigid mode): x the smaller of the
#: node's contact stiffness and its elements' stiffness, so that it never stiffens the
#: chain's deformation modes (a bed much stiffer than the chain would else slow Newton)
_REG = 1e-6
#: from this Newton iteration on, an iteration that no longer moves u (within rounding)
#: ends the increment if the gradient is at the rounding of the force terms
_STALL_CHECK = 20


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
        th = alpha_T * le[e] * dT
        d = u[e + 1] - u[e] - th
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
def _rounding_scale(kb, le, kt, alpha_T, dT, s_old, u):
    """1e-3 x the largest term of an element force kb (u_{e+1} - u_e - alpha_T le dT) or of
    a contact force kt (u - s): a force that is a small difference of large terms is only
    known to the rounding of the large ones, so a gradient below _GTOL x this (~50
    roundings) is as small as it can get (the test of a stalled iteration)."""
    n = u.size
    rnd = 0.0
    for e in range(n - 1):
        a = kb[e] * max(abs(alpha_T * le[e] * dT), abs(u[e]), abs(u[e + 1]))
        if a > rnd:
            rnd = a
    for i in range(n):
        a = kt[i] * max(abs(u[i]), abs(s_old[i]))
        if a > rnd:
            rnd = a
    return 1e-3 * rnd


@njit(cache=True)
def _rigid_line_search(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, u, du, un, gn):
    """The step t in (0, 1] minimising Phi(u + t du) (convex, C1: bisection on the sign of
    its derivative).  Used when every slider slides: the regularised Newton step along the
    rigid mode is then huge and may overshoot far past the state where a slider sticks
    (a line search that only asks for decrease would then crawl back)."""
    n = u.size
    a, b = 0.0, 1.0
    for i in range(n):
        un[i] = u[i] + du[i]
    _energy_gradient(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, un, gn)
    d = 0.0
    for i in range(n):
        d += gn[i] * du[i]
    if d <= 0.0:
        return 1.0
    for _ in range(60):
        t = 0.5 * (a + b)
        for i in range(n):
            un[i] = u[i] + t * du[i]
        _energy_gradient(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, un, gn)
        d = 0.0
        for i in range(n):
            d += gn[i] * du[i]
        if d > 0.0:
            b = t
        else:
            a = t
        if b - a <= 1e-14 * b:
            break
    return b if a == 0.0 else a


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
            if cls[i] == 0:
                kd[i] = kt[i]
            elif nst == 0:
                kd[i] = _REG * min(kt[i], kb[i - 1] if i > 0 else kt[i],
                                   kb[i] if i < n - 1 else kt[i])
            else:
                kd[i] = 0.0
        solve_tridiag(kb, kd, g, du, cw, dw)
        slope = 0.0
        for i in range(n):
            slope -= g[i] * du[i]          # g holds -grad
        step = 1.0
        accepted = False
        if nst == 0:
            step = _rigid_line_search(kb, le, kt, cp, cm, fw, alpha_T, dT, F, s_old, u, du, un,
                                      gn)
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
            if gmax <= 1e-8 * scale or gmax <= _GTOL * _rounding_scale(kb, le, kt, alpha_T,
                                                                      dT, s_old, u):
                code = STATUS_OK
                its = it
            break
        moved = 0.0
        size = 0.0
        if it >= _STALL_CHECK:
            for i in range(n):
                moved = max(moved, abs(un[i] - u[i]))
                size = max(size, abs(u[i]))
        for i in range(n):
            u[i] = un[i]
            g[i] = gn[i]
        phi, gmax, scale = phin, gmaxn, max(scalen, cap)
        if it >= _STALL_CHECK and moved <= 4e-16 * size and gmax <= _GTOL * max(
                scale, _rounding_scale(kb, le, kt, alpha_T, dT, s_old, u)):
            code = STATUS_OK                   # stalled at the rounding of u
            its = it
            break
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
def _least_motion(kt, cp, cm, u_old, s_old, u, s, q):
    """Select among equal solutions.  When every contact force is at its threshold after a
    converged increment (sliding, or sticking exactly at the threshold), the incremental
    energy is flat along the rigid translation u + t (its slope, the sum of the slider
    forces less F, is zero there): a whole interval of t are exact solutions (e.g. mu+ =
    mu-, both ends of a bar sliding apart).  Take the one that moves the chain least, t
    minimising sum kt_i (u_i + t - u_old_i)^2 while every slider keeps its direction: the
    limit of any small viscosity, and no drift for a symmetric contact.  q: the contact
    forces (in); u, s updated."""
    n = u.size
    lo = -np.inf
    hi = np.inf
    num = 0.0
    den = 0.0
    for i in range(n):
        v = u[i] - s_old[i]
        if q[i] >= cp[i] * (1.0 - 1e-9):
            lo = max(lo, cp[i] / kt[i] - v)
        elif q[i] <= -cm[i] * (1.0 - 1e-9):
            hi = min(hi, -cm[i] / kt[i] - v)
        else:
            return                                  # a contact sticks: the solution is unique
        num -= kt[i] * (u[i] - u_old[i])
        den += kt[i]
    lo = min(lo, 0.0)
    hi = max(hi, 0.0)
    t = min(max(num / den, lo), hi)
    if t == 0.0:
        return
    for i in range(n):
        u[i] += t
        s[i] = u[i] - q[i] / kt[i]


@njit(cache=True)
def march(kb, le, kt, cp, cm, fw, alpha_T, dT_seq, F_seq, u, s, du_seq, slip_seq, rec_nodes,
          rec_u, max_iter):
    """March the load points (dT_seq[j], F_seq[j]) from the state (u, s) (updated in place).
    The state carries everything: a sequence marched in pieces (consecutive slices of the
    arrays) gives exactly the same result as in one call.

    du_seq (m, n): displacement increments of the same points one cycle earlier, the
    starting guess of each increment (exact once the cycle is stabilised); overwritten.
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
        _least_motion(kt, cp, cm, u_old, s_old, u, s, q)
        smax = 0.0
        for i in range(n):
            du_seq[j, i] = u[i] - u_old[i]
            d = abs(s[i] - s_old[i])
            if d > smax:
                smax = d
        slip_seq[j] = smax
        for k in range(rec_nodes.size):
            rec_u[j, k] = u[rec_nodes[k]]
    return STATUS_OK, -1, iters
