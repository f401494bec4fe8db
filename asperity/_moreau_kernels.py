"""Numba kernels of the Moreau time-stepping solver (physics in :mod:`asperity.moreau`, sets
and laws in :mod:`asperity.laws`).

Array-in/array-out loops, no Python objects, no validation (the wrappers validate and coerce).
Kernels cannot raise: failures come back in the ``info`` array (see ``INFO_*`` and
``STATUS_*``), which moreau.py turns into a status and a message.

A set (reservoir ``C`` or sliding set ``D`` of a contact) is ``(kind, par, tab, off, n)``:

* ``SET_DISC``      par[0] = radius;
* ``SET_ELLIPSE``   truncated ellipse, par = (A+, A-, B+, B-, cos theta, sin theta): semi-axis
                    A+ along +t_a, A- along -t_a, B+- along +-t_b, t_a at angle theta;
* ``SET_STAR``      star-shaped polygon, rows off..off+n-1 of tab: (x, y, polar angle), the
                    angles increasing from tab[off, 2] over less than a full turn;
* ``SET_SUPPORT``   convex set from samples of its support function (gauges.ConvexSet),
                    rows (psi, ln h, delta, h, h', cos psi, sin psi); between samples delta
                    is linear in psi and ln h its exact integral of tan(delta); a repeated
                    psi is a flat edge.

All sets are per unit normal impulse; the solver scales by the contact's normal impulse.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

SET_DISC = 0
SET_ELLIPSE = 1
SET_STAR = 2
SET_SUPPORT = 3

STATUS_OK = 0
STATUS_NOT_CONVERGED = 1   # the fixed-point iteration hit its limit above the tolerance
STATUS_NON_FINITE = 2      # a velocity became NaN/inf (integration stopped)

INFO_STEPS = 0             # steps integrated
INFO_STOP_STEP = 1         # steps done when the body last came to rest (-1: moving at the end)
INFO_MAX_ITER = 2          # largest number of fixed-point iterations in one step
INFO_STATUS = 3
INFO_FAIL_STEP = 4         # first step (0-based) that did not converge (-1: none)
INFO_FAIL_RESIDUAL = 5     # its residual
INFO_MAX_RESIDUAL = 6      # largest final residual over all steps
INFO_RECORDS = 7           # rows written to the record arrays
INFO_ITER_TOTAL = 8        # fixed-point iterations summed over the steps
INFO_SIZE = 9

TWO_PI = 2.0 * math.pi

FORCE_NONE = 0
FORCE_SQUARE = 1
FORCE_SINE = 2


@njit(cache=True)
def tan_integral(d0, d1, length, t):
    """Integral of tan(delta(u)) du over [0, t], delta linear from d0 (u=0) to d1 (u=length)."""
    dd = (d1 - d0) * (t / length)
    if dd == 0.0:
        return t * math.tan(d0)
    dt = d0 + dd
    s = math.sin(0.5 * dd)
    x = math.tan(dt) * math.sin(dd) - 2.0 * s * s
    return math.log1p(x) * t / dd


# ----------------------------------------------------------------------------- ellipse

@njit(cache=True)
def _ellipse_local(par, x0, x1):
    c, s = par[4], par[5]
    xa = c * x0 + s * x1
    xb = -s * x0 + c * x1
    A = par[0] if xa >= 0.0 else par[1]
    B = par[2] if xb >= 0.0 else par[3]
    return xa, xb, A, B


@njit(cache=True)
def ellipse_project(par, x0, x1):
    """Euclidean projection of x onto the truncated ellipse; (y0, y1, inside).

    In the quadrant of x the set coincides with the full ellipse of that quadrant's axes and
    the truncated ellipse is C1, so the projection onto that ellipse is the answer:
    y_i = A_i^2 x_i / (A_i^2 + t) with t >= 0 the root of sum (A_i x_i / (A_i^2 + t))^2 = 1.
    The left side is convex and decreasing in t; Newton from the lower bound
    t0 = |(A x_a, B x_b)| - max(A, B)^2 converges monotonically."""
    xa, xb, A, B = _ellipse_local(par, x0, x1)
    ga = xa / A
    gb = xb / B
    if ga * ga + gb * gb <= 1.0:
        return x0, x1, True
    A2 = A * A
    B2 = B * B
    pa = A * xa
    pb = B * xb
    t = math.sqrt(pa * pa + pb * pb) - max(A2, B2)
    if t < 0.0:
        t = 0.0
    for _ in range(100):
        ea = pa / (A2 + t)
        eb = pb / (B2 + t)
        F = ea * ea + eb * eb - 1.0
        dF = -2.0 * (ea * ea / (A2 + t) + eb * eb / (B2 + t))
        step = -F / dF
        t += step
        if step <= 1e-15 * (t + A2 + B2):
            break
    ya = A2 * xa / (A2 + t)
    yb = B2 * xb / (B2 + t)
    c, s = par[4], par[5]
    return c * ya - s * yb, s * ya + c * yb, False


@njit(cache=True)
def ellipse_gauge(par, x0, x1):
    xa, xb, A, B = _ellipse_local(par, x0, x1)
    return math.hypot(xa / A, xb / B)


# ----------------------------------------------------------------------------- star polygon

@njit(cache=True)
def star_radial(tab, off, n, phi):
    """Radial function of the star-shaped polygon: ray-edge intersection."""
    a0 = tab[off, 2]
    pm = a0 + (phi - a0) % TWO_PI
    lo = 0
    hi = n - 1
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if tab[off + mid, 2] <= pm:
            lo = mid
        else:
            hi = mid - 1
    k1 = lo + 1 if lo + 1 < n else 0
    v0x = tab[off + lo, 0]
    v0y = tab[off + lo, 1]
    dx = tab[off + k1, 0] - v0x
    dy = tab[off + k1, 1] - v0y
    ux = math.cos(pm)
    uy = math.sin(pm)
    return (v0x * dy - v0y * dx) / (ux * dy - uy * dx)


# ----------------------------------------------------------------------------- support-function set

@njit(cache=True)
def _psi_k(tab, off, n, K):
    q = K // n
    return tab[off + (K - q * n), 0] + TWO_PI * q


@njit(cache=True)
def _row(K, n):
    return K - (K // n) * n


@njit(cache=True)
def support_radial(tab, off, n, phi):
    """(rho, psi): radial function of the convex set along the ray phi and the normal
    direction psi of the boundary point on that ray (the edge normal on a flat edge)."""
    b0 = tab[off, 0] + tab[off, 2]
    pm = b0 + (phi - b0) % TWO_PI
    lo = 0
    hi = n - 1
    while lo < hi:                       # last K with beta(K) = psi_K + delta_K <= pm
        mid = (lo + hi + 1) // 2
        if tab[off + mid, 0] + tab[off + mid, 2] <= pm:
            lo = mid
        else:
            hi = mid - 1
    K = lo
    r0 = off + K
    r1 = off + _row(K + 1, n)
    psi0 = tab[r0, 0]
    psi1 = _psi_k(tab, off, n, K + 1)
    d = psi1 - psi0
    if d <= 0.0:                          # the ray hits a flat edge (normal psi0)
        return tab[r0, 3] / math.cos(pm - psi0), psi0
    d0 = tab[r0, 2]
    d1 = tab[r1, 2]
    sd = d + (d1 - d0)                    # change of the polar angle over the interval
    if sd <= 1e-300:                      # a corner: the whole interval has one point
        return tab[r0, 3] / math.cos(d0), psi0
    t = (pm - psi0 - d0) * d / sd
    if t < 0.0:
        t = 0.0
    elif t > d:
        t = d
    de = d0 + (d1 - d0) * t / d
    lnh = tab[r0, 1] + tan_integral(d0, d1, d, t)
    return math.exp(lnh) / math.cos(de), psi0 + t


@njit(cache=True)
def _visible_pred(tab, row, psi, x0, x1, psr):
    """Predicate R at a sample: True once the projection lies at or before this normal."""
    c = tab[row, 5]
    s = tab[row, 6]
    v = x0 * c + x1 * s - tab[row, 3]
    if v > 0.0:
        return (-x0 * s + x1 * c - tab[row, 4]) <= 0.0
    return psi > psr


@njit(cache=True)
def support_project(tab, off, n, x0, x1):
    """Euclidean projection of x onto the convex set; (y0, y1, inside).

    The projection of an outside point is the boundary point y(psi) = h s + h' s_perp whose
    normal psi solves F(psi) = x.s_perp(psi) - h'(psi) = 0 with x.s(psi) > h(psi).  On the
    arc of normals with x.s > h (less than a half turn, containing the normal psi_r of the
    boundary point on the ray of x) F decreases; outside it the predicate
    R(psi) = (F <= 0 if visible else psi > psi_r) continues monotonically, so a binary search
    over the samples finds the interval (or the flat edge) of the root and a safeguarded
    Newton iteration finishes inside it."""
    r = math.hypot(x0, x1)
    if r == 0.0:
        return x0, x1, True
    rho, psr = support_radial(tab, off, n, math.atan2(x1, x0))
    if r <= rho:
        return x0, x1, True
    # window of samples with psi in (psr - pi, psr + pi): K in [klo, khi]
    base = 0
    while _psi_k(tab, off, n, base) > psr:
        base -= n
    while _psi_k(tab, off, n, base + n) <= psr:
        base += n
    lo = base - n
    hi = base + n
    while lo < hi:                                      # first K with psi_K > psr - pi
        mid = (lo + hi) // 2
        if _psi_k(tab, off, n, mid) > psr - math.pi:
            hi = mid
        else:
            lo = mid + 1
    klo = lo
    lo = klo
    hi = base + 2 * n
    while lo < hi:                                      # first K with psi_K >= psr + pi
        mid = (lo + hi) // 2
        if _psi_k(tab, off, n, mid) >= psr + math.pi:
            hi = mid
        else:
            lo = mid + 1
    khi = lo - 1
    lo = klo
    hi = khi + 1
    while lo < hi:                                      # first K with R true
        mid = (lo + hi) // 2
        if _visible_pred(tab, off + _row(mid, n), _psi_k(tab, off, n, mid), x0, x1, psr):
            hi = mid
        else:
            lo = mid + 1
    kb = lo
    ka = kb - 1
    ra = off + _row(ka, n)
    rb = off + _row(kb, n)
    a = _psi_k(tab, off, n, ka)
    d = _psi_k(tab, off, n, kb) - a
    if d <= 0.0:                                        # flat edge with normal psi_a
        c = tab[ra, 5]
        s = tab[ra, 6]
        v = x0 * c + x1 * s - tab[ra, 3]
        return x0 - v * c, x1 - v * s, False
    d0 = tab[ra, 2]
    d1 = tab[rb, 2]
    dd = (d1 - d0) / d
    lnh0 = tab[ra, 1]
    # initial guess: linear interpolation of F between the ends when both are visible
    ca, sa, cb, sb = tab[ra, 5], tab[ra, 6], tab[rb, 5], tab[rb, 6]
    Fa = -x0 * sa + x1 * ca - tab[ra, 4]
    Fb = -x0 * sb + x1 * cb - tab[rb, 4]
    t = 0.5 * d
    if x0 * ca + x1 * sa > tab[ra, 3] and x0 * cb + x1 * sb > tab[rb, 3] and Fa > Fb:
        t = d * Fa / (Fa - Fb)
    tlo = 0.0
    thi = d
    h = 0.0
    de = d0
    psi = a
    for _ in range(100):
        psi = a + t
        de = d0 + dd * t
        h = math.exp(lnh0 + tan_integral(d0, d1, d, t))
        c = math.cos(psi)
        s = math.sin(psi)
        xs = x0 * c + x1 * s
        tde = math.tan(de)
        F = -x0 * s + x1 * c - h * tde
        vis = xs > h
        if (F <= 0.0) if vis else (psi > psr):
            thi = t
        else:
            tlo = t
        tn = 0.5 * (tlo + thi)
        if vis:
            dF = -xs - h * (tde * tde + (1.0 + tde * tde) * dd)
            if dF < 0.0:
                cand = t - F / dF
                if tlo < cand < thi:
                    tn = cand
        if abs(tn - t) <= 4e-16 * (1.0 + abs(psi)) or thi - tlo <= 4e-16 * (1.0 + abs(psi)):
            t = tn
            psi = a + t
            de = d0 + dd * t
            h = math.exp(lnh0 + tan_integral(d0, d1, d, t))
            break
        t = tn
    rr = h / math.cos(de)
    return rr * math.cos(psi + de), rr * math.sin(psi + de), False


# ----------------------------------------------------------------------------- dispatch

@njit(cache=True)
def set_radial(kind, par, tab, off, n, phi):
    """Radial function rho(phi) of a set."""
    if kind == SET_DISC:
        return par[0]
    if kind == SET_ELLIPSE:
        return 1.0 / ellipse_gauge(par, math.cos(phi), math.sin(phi))
    if kind == SET_STAR:
        return star_radial(tab, off, n, phi)
    return support_radial(tab, off, n, phi)[0]


@njit(cache=True)
def set_gauge(kind, par, tab, off, n, x0, x1):
    """Gauge k(x) = |x| / rho(angle x) of a set."""
    if kind == SET_ELLIPSE:
        return ellipse_gauge(par, x0, x1)
    r = math.hypot(x0, x1)
    if r == 0.0:
        return 0.0
    if kind == SET_DISC:
        return r / par[0]
    return r / set_radial(kind, par, tab, off, n, math.atan2(x1, x0))


@njit(cache=True)
def set_project(kind, par, tab, off, n, x0, x1):
    """Euclidean projection onto a convex set (disc, ellipse or support set); (y0, y1, inside)."""
    if kind == SET_DISC:
        r = math.hypot(x0, x1)
        if r <= par[0]:
            return x0, x1, True
        f = par[0] / r
        return x0 * f, x1 * f, False
    if kind == SET_ELLIPSE:
        return ellipse_project(par, x0, x1)
    return support_project(tab, off, n, x0, x1)


@njit(cache=True)
def law_point(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, x0, x1):
    """The Walker-Leine law at the prox argument x (per unit normal impulse, already scaled
    by alpha): y = prox_D(x), then the reservoir point P on the ray of y with
    k_C(P) chosen so that alpha(P) P = y, i.e. |P| = k rho_D / (1 - k + k rho_D / rho_C) with
    k = k_D(y).  Returns (P0, P1, inside)."""
    y0, y1, inside = set_project(dk, dp, dtab, doff, dn, x0, x1)
    if assoc:
        return y0, y1, inside
    r = math.hypot(y0, y1)
    if r == 0.0:
        return 0.0, 0.0, inside
    phi = math.atan2(y1, y0)
    rc = set_radial(ck, cp, ctab, coff, cn, phi)
    rd = set_radial(dk, dp, dtab, doff, dn, phi)
    k = r / rd
    if k > 1.0:
        k = 1.0
    t = k * rd / (1.0 - k + k * rd / rc)
    return t * y0 / r, t * y1 / r, inside


@njit(cache=True)
def law_alpha(assoc, ck, cp, ctab, coff, cn, dk, dp, dtab, doff, dn, P0, P1):
    """alpha(P) = 1 / (k_D(P) - k_C(P) + 1)."""
    if assoc:
        return 1.0
    r = math.hypot(P0, P1)
    if r == 0.0:
        return 1.0
    phi = math.atan2(P1, P0)
    rc = set_radial(ck, cp, ctab, coff, cn, phi)
    rd = set_radial(dk, dp, dtab, doff, dn, phi)
    return 1.0 / (r / rd - r / rc + 1.0)


@njit(cache=True)
def project_many(kind, par, tab, x):
    """(m, 2) projections and (m,) inside flags of the (m, 2) points x onto one set."""
    m = x.shape[0]
    out = np.empty((m, 2))
    ins = np.empty(m, np.bool_)
    n = tab.shape[0]
    for i in range(m):
        a, b, c = set_project(kind, par, tab, 0, n, x[i, 0], x[i, 1])
        out[i, 0] = a
        out[i, 1] = b
        ins[i] = c
    return out, ins


@njit(cache=True)
def radial_many(kind, par, tab, phi):
    m = phi.shape[0]
    out = np.empty(m)
    n = tab.shape[0]
    for i in range(m):
        out[i] = set_radial(kind, par, tab, 0, n, phi[i])
    return out


@njit(cache=True)
def law_point_many(assoc, ck, cp, ctab, dk, dp, dtab, x):
    m = x.shape[0]
    out = np.empty((m, 2))
    ins = np.empty(m, np.bool_)
    for i in range(m):
        a, b, c = law_point(assoc, ck, cp, ctab, 0, ctab.shape[0], dk, dp, dtab, 0,
                            dtab.shape[0], x[i, 0], x[i, 1])
        out[i, 0] = a
        out[i, 1] = b
        ins[i] = c
    return out, ins


# ----------------------------------------------------------------------------- time stepping

@njit(cache=True)
def _force(fpar, ftab, step, t, ndof, out):
    """External force at the midpoint time t: table row if given, else
    constant + amplitude * w(t) with w the square wave (+1 on the first half period) or
    sin(2 pi t / T)."""
    if ftab.shape[0] > 0:
        for j in range(ndof):
            out[j] = ftab[step, j]
        return
    kind = int(fpar[0])
    T = fpar[1]
    w = 0.0
    if kind == FORCE_SQUARE:
        ph = (t / T) % 1.0
        w = 1.0 if ph < 0.5 else -1.0
    elif kind == FORCE_SINE:
        w = math.sin(TWO_PI * t / T)
    for j in range(ndof):
        out[j] = fpar[2 + j] + fpar[5 + j] * w



@njit(cache=True, error_model="numpy")
def _end_velocity(ue, uf, minv, P, ow, nc, ndof):
    """u_E = u_free - M^-1 W P (contact impulses Lambda_i = -P_i; ``ow`` the contact
    offsets turned to the current angle, used when ndof == 3)."""
    for j in range(ndof):
        ue[j] = uf[j]
    for i in range(nc):
        ue[0] -= minv[0] * P[i, 0]
        ue[1] -= minv[1] * P[i, 1]
        if ndof == 3:
            ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] - ow[i, 1] * P[i, 0])

@njit(cache=True)
def integrate(q0, u0, minv, offsets, lam_n, assoc, kinds, pars, tabs, offs, ns,
              fpar, ftab, t0, dt, n_steps, r, tol, max_iter, full_rank, halt_at_rest,
              record_every, rec_t, rec_q, rec_u, info):
    """Moreau midpoint time-stepping of a body on a plane (SPEC.md section 4).

    q0, u0 : (ndof,) ndof = 2 (point mass x, y) or 3 (rigid body x, y, theta)
    minv   : (ndof,) inverse mass matrix diagonal
    offsets: (nc, 2) contact points in the body frame (rotated by theta at q_M)
    lam_n  : (nc,) normal impulse per step of each contact (share * m g dt)
    assoc  : (nc,) C is D (alpha = 1)
    kinds  : (nc, 2) set kinds of C and D; pars (nc, 2, 8); tabs (rows, 8) all tables,
             offs/ns (nc, 2) their first row and length
    fpar, ftab : external force (see _force)
    r      : prox parameter (0 < r < 2 / max eig(W^T M^-1 W)); the iteration uses r alpha_i
             at contact i (the normal cone is a cone, any positive multiple is valid)
    tol    : fixed-point tolerance on max_i |P_i^{k+1} - P_i^k| / lam_n_i
    full_rank : W^T has full column rank: all contacts sticking means u_E = 0 exactly
    halt_at_rest : stop integrating once at rest under no external force (nothing can move)
    Records every ``record_every`` steps (and the initial state) into rec_*; info as INFO_*.
    """
    ndof = q0.shape[0]
    nc = offsets.shape[0]
    q = q0.copy()
    u = u0.copy()
    f = np.zeros(ndof)
    qm = np.zeros(ndof)
    uf = np.zeros(ndof)
    ue = np.zeros(ndof)
    P = np.zeros((nc, 2))
    Pn = np.zeros((nc, 2))
    ow = np.zeros((nc, 2))
    stick = np.zeros(nc, np.bool_)
    unforced = ftab.shape[0] == 0 and int(fpar[0]) == FORCE_NONE
    if unforced:
        for j in range(ndof):
            if fpar[2 + j] != 0.0:
                unforced = False
    for j in range(INFO_SIZE):
        info[j] = 0.0
    info[INFO_STOP_STEP] = -1.0
    info[INFO_FAIL_STEP] = -1.0
    moving0 = False
    for j in range(ndof):
        if u[j] != 0.0:
            moving0 = True
    if not moving0:
        info[INFO_STOP_STEP] = 0.0
    nrec = 0
    rec_t[0] = t0
    for j in range(ndof):
        rec_q[0, j] = q[j]
        rec_u[0, j] = u[j]
    nrec = 1
    max_it = 0
    it_total = 0
    status = STATUS_OK
    step = 0
    for step in range(n_steps):
        tm = t0 + (step + 0.5) * dt
        _force(fpar, ftab, step, tm, ndof, f)
        for j in range(ndof):
            qm[j] = q[j] + 0.5 * dt * u[j]
            uf[j] = u[j] + dt * minv[j] * f[j]
        if ndof == 3:
            c = math.cos(qm[2])
            s = math.sin(qm[2])
            for i in range(nc):
                ow[i, 0] = c * offsets[i, 0] - s * offsets[i, 1]
                ow[i, 1] = s * offsets[i, 0] + c * offsets[i, 1]
        res = 0.0
        it = 0
        for it in range(1, max_iter + 1):
            _end_velocity(ue, uf, minv, P, ow, nc, ndof)   # u_E for Lambda_i = -P_i
            res = 0.0
            for i in range(nc):
                g0 = ue[0]
                g1 = ue[1]
                if ndof == 3:
                    g0 -= ue[2] * ow[i, 1]
                    g1 += ue[2] * ow[i, 0]
                ln = lam_n[i]
                p0 = P[i, 0] / ln
                p1 = P[i, 1] / ln
                al = law_alpha(assoc[i], kinds[i, 0], pars[i, 0], tabs, offs[i, 0], ns[i, 0],
                               kinds[i, 1], pars[i, 1], tabs, offs[i, 1], ns[i, 1], p0, p1)
                z0 = al * (p0 + r * g0 / ln)
                z1 = al * (p1 + r * g1 / ln)
                a, b, ins = law_point(assoc[i], kinds[i, 0], pars[i, 0], tabs, offs[i, 0],
                                      ns[i, 0], kinds[i, 1], pars[i, 1], tabs, offs[i, 1],
                                      ns[i, 1], z0, z1)
                stick[i] = ins
                e = math.hypot(a - p0, b - p1)
                if e > res:
                    res = e
                Pn[i, 0] = a * ln
                Pn[i, 1] = b * ln
            for i in range(nc):
                P[i, 0] = Pn[i, 0]
                P[i, 1] = Pn[i, 1]
            if res <= tol:
                break
        it_total += it
        if it > max_it:
            max_it = it
        if res > info[INFO_MAX_RESIDUAL]:
            info[INFO_MAX_RESIDUAL] = res
        if res > tol and status == STATUS_OK:
            status = STATUS_NOT_CONVERGED
            info[INFO_FAIL_STEP] = step
            info[INFO_FAIL_RESIDUAL] = res
        _end_velocity(ue, uf, minv, P, ow, nc, ndof)
        all_stick = full_rank
        for i in range(nc):
            if not stick[i]:
                all_stick = False
        if all_stick and res <= tol:
            for j in range(ndof):
                ue[j] = 0.0
        finite = True
        moving = False
        for j in range(ndof):
            if not math.isfinite(ue[j]):
                finite = False
            if ue[j] != 0.0:
                moving = True
        if not finite:
            status = STATUS_NON_FINITE
            if info[INFO_FAIL_STEP] < 0:
                info[INFO_FAIL_STEP] = step
            break
        was_moving = False
        for j in range(ndof):
            if u[j] != 0.0:
                was_moving = True
            q[j] = qm[j] + 0.5 * dt * ue[j]
            u[j] = ue[j]
        if not moving:
            if was_moving:
                info[INFO_STOP_STEP] = step + 1
        else:
            info[INFO_STOP_STEP] = -1.0
        done = step + 1
        last = done == n_steps or (halt_at_rest and unforced and not moving)
        if (done % record_every == 0 or last) and nrec < rec_t.shape[0]:
            rec_t[nrec] = t0 + done * dt
            for j in range(ndof):
                rec_q[nrec, j] = q[j]
                rec_u[nrec, j] = u[j]
            nrec += 1
        if halt_at_rest and unforced and not moving:
            break
    info[INFO_STEPS] = step + 1 if n_steps > 0 else 0
    if status == STATUS_NON_FINITE:
        info[INFO_STEPS] = step
    info[INFO_MAX_ITER] = max_it
    info[INFO_STATUS] = status
    info[INFO_RECORDS] = nrec
    info[INFO_ITER_TOTAL] = it_total
    return q, u
