"""Numba kernels of the friction sets as the solvers use them (sets in
:mod:`asperity.laws.sets` and :mod:`asperity.laws.convex_set`, wrappers in
:mod:`asperity.laws.planar`): radial function, gauge and Euclidean projection of each kind.

Array-in/array-out loops, no Python objects, no validation (the wrappers validate and coerce).

A set (reservoir ``C`` or sliding set ``D`` of a contact) is ``(kind, par, tab, off, n)``:

* ``SET_DISC``      par[0] = radius;
* ``SET_ELLIPSE``   truncated ellipse, par = (A+, A-, B+, B-, cos theta, sin theta): semi-axis
                    A+ along +t_a, A- along -t_a, B+- along +-t_b, t_a at angle theta;
* ``SET_STAR``      star-shaped polygon, rows off..off+n-1 of tab: (x, y, polar angle), the
                    angles increasing from tab[off, 2] over less than a full turn;
* ``SET_SUPPORT``   convex set from samples of its support function (laws.convex_set.ConvexSet),
                    rows (psi, ln h, delta, h, h', cos psi, sin psi); between samples delta
                    is linear in psi and ln h its exact integral of tan(delta); a repeated
                    psi is a flat edge.

All sets are per unit normal impulse; the solver scales by the contact's normal impulse.

Kernels that allocate nothing are compiled with ``_nrt=False`` (no reference counts:
numba increfs and decrefs every array argument of a call with atomic operations, which
cost a Moreau step of a point mass ~200 ns of its ~300;
:mod:`asperity.dynamics._moreau_kernels`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

SET_DISC = 0
SET_ELLIPSE = 1
SET_STAR = 2
SET_SUPPORT = 3
TWO_PI = 2.0 * math.pi


@njit(cache=True, _nrt=False)
def tan_integral(d0, d1, length, t):
    """Integral of tan(delta(u)) du over [0, t], delta linear from d0 (u=0) to d1 (u=length)."""
    dd = (d1 - d0) * (t / length)
    if dd == 0.0:
        return t * math.tan(d0)
    dt = d0 + dd
    s = math.sin(0.5 * dd)
    x = math.tan(dt) * math.sin(dd) - 2.0 * s * s
    return math.log1p(x) * t / dd


@njit(cache=True, _nrt=False)
def _ellipse_local(par, x0, x1):
    c, s = par[4], par[5]
    xa = c * x0 + s * x1
    xb = -s * x0 + c * x1
    A = par[0] if xa >= 0.0 else par[1]
    B = par[2] if xb >= 0.0 else par[3]
    return xa, xb, A, B


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def ellipse_gauge(par, x0, x1):
    xa, xb, A, B = _ellipse_local(par, x0, x1)
    return math.hypot(xa / A, xb / B)


@njit(cache=True, _nrt=False)
def star_radial_edge(tab, off, n, phi):
    """Radial function of the star-shaped polygon at phi (ray-edge intersection) and the
    edge it meets (its first vertex, 0 .. n-1)."""
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
    return (v0x * dy - v0y * dx) / (ux * dy - uy * dx), lo


@njit(cache=True, _nrt=False)
def star_radial(tab, off, n, phi):
    """Radial function of the star-shaped polygon: ray-edge intersection."""
    return star_radial_edge(tab, off, n, phi)[0]


@njit(cache=True, _nrt=False)
def _psi_k(tab, off, n, K):
    q = K // n
    return tab[off + (K - q * n), 0] + TWO_PI * q


@njit(cache=True, _nrt=False)
def _row(K, n):
    return K - (K // n) * n


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def _visible_pred(tab, row, psi, x0, x1, psr):
    """Predicate R at a sample: True once the projection lies at or before this normal."""
    c = tab[row, 5]
    s = tab[row, 6]
    v = x0 * c + x1 * s - tab[row, 3]
    if v > 0.0:
        return (-x0 * s + x1 * c - tab[row, 4]) <= 0.0
    return psi > psr


@njit(cache=True, _nrt=False)
def _project_interval(tab, off, n, x0, x1, ka, psr):
    """The projection of an outside point x whose normal lies in the sample interval
    [psi_ka, psi_ka+1] (a flat edge if they are equal): (y0, y1, t, phi, rr) with t the
    normal's offset psi - psi_ka, phi the polar angle of y and rr = |y| (the radial function
    of the set at phi).  Safeguarded Newton iteration on F(psi) = x.s_perp - h' from the
    linear interpolation of F."""
    kb = ka + 1
    ra = off + _row(ka, n)
    rb = off + _row(kb, n)
    a = _psi_k(tab, off, n, ka)
    d = _psi_k(tab, off, n, kb) - a
    if d <= 0.0:                                        # flat edge with normal psi_a
        c = tab[ra, 5]
        s = tab[ra, 6]
        v = x0 * c + x1 * s - tab[ra, 3]
        y0 = x0 - v * c
        y1 = x1 - v * s
        return y0, y1, 0.0, math.atan2(y1, y0), math.hypot(y0, y1)
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
    phi = psi + de
    return rr * math.cos(phi), rr * math.sin(phi), t, phi, rr


@njit(cache=True, _nrt=False)
def support_project_full(tab, off, n, x0, x1):
    """Euclidean projection of x onto the convex set with what the law needs beside it:
    (y0, y1, inside, ka, t, phi, rr) -- ka the row of the sample interval of the normal
    (-1 inside or on the boundary), t the normal's offset in it, phi the polar angle of y,
    rr = |y| on the boundary (the radial function at phi; inside: rho(phi)).

    The projection of an outside point is the boundary point y(psi) = h s + h' s_perp whose
    normal psi solves F(psi) = x.s_perp(psi) - h'(psi) = 0 with x.s(psi) > h(psi).  On the
    arc of normals with x.s > h (less than a half turn, containing the normal psi_r of the
    boundary point on the ray of x) F decreases; outside it the predicate
    R(psi) = (F <= 0 if visible else psi > psi_r) continues monotonically, so a binary search
    over the samples finds the interval (or the flat edge) of the root and a safeguarded
    Newton iteration finishes inside it."""
    r = math.hypot(x0, x1)
    if r == 0.0:
        return x0, x1, True, -1, 0.0, 0.0, support_radial(tab, off, n, 0.0)[0]
    phi = math.atan2(x1, x0)
    rho, psr = support_radial(tab, off, n, phi)
    if r <= rho:
        return x0, x1, True, -1, 0.0, phi, rho
    if r <= rho * (1.0 + 1e-14):
        # outside by rounding only: x is its own projection (on a flat edge the search
        # below would see x.s - h <= 0 at the edge's normal and jump to the edge's end)
        return x0, x1, False, -1, 0.0, phi, rho
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
    ka = lo - 1
    y0, y1, t, phi, rr = _project_interval(tab, off, n, x0, x1, ka, psr)
    return y0, y1, False, _row(ka, n), t, phi, rr


@njit(cache=True, _nrt=False)
def support_project(tab, off, n, x0, x1):
    """Euclidean projection of x onto the convex set; (y0, y1, inside)
    (see :func:`support_project_full`)."""
    y0, y1, inside, ka, t, phi, rr = support_project_full(tab, off, n, x0, x1)
    return y0, y1, inside


@njit(cache=True, _nrt=False)
def set_radial(kind, par, tab, off, n, phi):
    """Radial function rho(phi) of a set."""
    if kind == SET_DISC:
        return par[0]
    if kind == SET_ELLIPSE:
        return 1.0 / ellipse_gauge(par, math.cos(phi), math.sin(phi))
    if kind == SET_STAR:
        return star_radial(tab, off, n, phi)
    return support_radial(tab, off, n, phi)[0]


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
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
