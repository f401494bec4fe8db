"""Numba kernels of the rigid-body solver: the friction law at a contact point and the
assembled equations of a step (:mod:`asperity.dynamics._body_kernels` has the overview).

``_eval`` gives the sliding force c (per unit normal load), its Jacobian dc/dgamma and the
gradient, Hessian and value of the support function h of (the hull of) C -- closed forms
for the (truncated) ellipse, linear interpolation in psi of tables on a uniform grid
otherwise; ``_assemble`` sums the points' contributions to the residual and Jacobian of a
step; ``_merit``, ``_ray``, ``_solve3`` serve the Newton iterations.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

TWO_PI = 2.0 * math.pi
KIND_ELLIPSE = 0     # closed form: par = (a+, a-, b+, b-, cos th, sin th)
KIND_TABLE = 1       # tab (K+1, 4): c_x, c_y, grad h_x, grad h_y on psi_k = 2 pi k / K
KIND_COMPONENTWISE = 2   # closed form, Hu et al.: par = (mu_f, mu_b, mu_t, mu_t, 1, 0)


@njit(cache=True)
def _eval(kind, par, tab, gx, gy, out):
    """Law at the slip (gx, gy): out = c_x, c_y, J00, J01, J10, J11 (dc/dgamma),
    hg_x, hg_y (grad h), H00, H01, H10, H11 (Hessian of h), h (value at gamma)."""
    r2 = gx * gx + gy * gy
    if r2 == 0.0:
        for j in range(13):
            out[j] = 0.0
        return
    if kind == KIND_ELLIPSE or kind == KIND_COMPONENTWISE:
        co, si = par[4], par[5]
        la = co * gx + si * gy
        lb = -si * gx + co * gy
        A = par[0] if la >= 0.0 else par[1]
        B = par[2] if lb >= 0.0 else par[3]
        A2 = A * A
        B2 = B * B
        h = math.sqrt(A2 * la * la + B2 * lb * lb)
        ya = A2 * la / h
        yb = B2 * lb / h
        # local Jacobian D/h - y y^T / h
        j00 = A2 / h - ya * ya / h
        j01 = -ya * yb / h
        j11 = B2 / h - yb * yb / h
        cx = co * ya - si * yb
        cy = si * ya + co * yb
        # R J R^T
        r00 = co * co * j00 - 2.0 * co * si * j01 + si * si * j11
        r11 = si * si * j00 + 2.0 * co * si * j01 + co * co * j11
        r01 = co * si * (j00 - j11) + (co * co - si * si) * j01
        out[0] = cx
        out[1] = cy
        out[2] = r00
        out[3] = r01
        out[4] = r01
        out[5] = r11
        out[6] = cx
        out[7] = cy
        out[8] = r00
        out[9] = r01
        out[10] = r01
        out[11] = r11
        out[12] = h
        if kind == KIND_COMPONENTWISE:
            # the force (mu_{f|b} u_x, mu_t u_y) of the unit slip u (aligned: co = 1, si = 0);
            # dc/dgamma = diag(A, B) (I - u u^T) / |gamma|; the hull is C's (above)
            r = math.sqrt(r2)
            ux = gx / r
            uy = gy / r
            out[0] = A * ux
            out[1] = B * uy
            out[2] = A * (1.0 - ux * ux) / r
            out[3] = -A * ux * uy / r
            out[4] = -B * ux * uy / r
            out[5] = B * (1.0 - uy * uy) / r
        return
    K = tab.shape[0] - 1
    dpsi = TWO_PI / K
    psi = math.atan2(gy, gx)
    if psi < 0.0:
        psi += TWO_PI
    x = psi / dpsi
    k = int(x)
    if k >= K:
        k = K - 1
    t = x - k
    # s_perp / |gamma| = (-gy, gx) / r2
    px = -gy / r2
    py = gx / r2
    for j in range(2):
        a0 = tab[k, j]
        a1 = tab[k + 1, j]
        out[j] = a0 + t * (a1 - a0)
        d = (a1 - a0) / dpsi
        out[2 + 2 * j] = d * px
        out[3 + 2 * j] = d * py
        b0 = tab[k, 2 + j]
        b1 = tab[k + 1, 2 + j]
        out[6 + j] = b0 + t * (b1 - b0)
        e = (b1 - b0) / dpsi
        out[8 + 2 * j] = e * px
        out[9 + 2 * j] = e * py
    out[12] = out[6] * gx + out[7] * gy


@njit(cache=True)
def _eval_at(kind, par, tab, ext, i, gx, gy, out):
    """:func:`_eval` at point i's slip (gx, gy) in the kernel's frame: with point rows
    (``ext.shape[0] > 0``) the law of point i is turned by its angle (cos, sin) =
    (ext[i, 2], ext[i, 3]): evaluated at the slip turned back, its forces and Jacobians
    turned forward (c -> R c, J -> R J R^T)."""
    if ext.shape[0] == 0:
        _eval(kind, par, tab, gx, gy, out)
        return
    ca = ext[i, 2]
    sa = ext[i, 3]
    _eval(kind, par, tab, ca * gx + sa * gy, -sa * gx + ca * gy, out)
    for o in (0, 6):
        x = out[o]
        y = out[o + 1]
        out[o] = ca * x - sa * y
        out[o + 1] = sa * x + ca * y
        a = out[o + 2]
        b = out[o + 3]
        c = out[o + 4]
        d = out[o + 5]
        # R J (rows), then (R J) R^T (columns)
        p = ca * a - sa * c
        q = ca * b - sa * d
        r = sa * a + ca * c
        t = sa * b + ca * d
        out[o + 2] = p * ca - q * sa
        out[o + 3] = p * sa + q * ca
        out[o + 4] = r * ca - t * sa
        out[o + 5] = r * sa + t * ca


@njit(cache=True)
def _assemble(u, uf, md, ox, oy, ext, lam, kind, par, tab, want_hull, R, J, ev, skip=-1):
    """R(u) = M (u - uf) + sum lam_i W_i c_i (want_hull: the hull's gradient instead of c and
    its Hessian in J) and J = M + sum lam_i W_i (dc/dgamma)_i W_i^T; returns sum lam_i h_i.
    skip >= 0: leave out point ``skip`` and every point at the same spot (its group).
    ext (n, 4) or (0, 4): per point, a slip offset (ext[i, 0], ext[i, 1]) added to W_i^T u
    (a point that moves in the body: a crawling body's gait) and the angle of its law
    (:func:`_eval_at`); none for a rigid body.  With rows, ev (18,) also gets the
    sum lam_i c_i . offset_i (ev[16]: the gait's work against friction) and
    sum lam_i c_i . gamma_i (ev[17]: the dissipation) of the points summed."""
    for j in range(3):
        R[j] = md[j] * (u[j] - uf[j])
        for k in range(3):
            J[j, k] = 0.0
        J[j, j] = md[j]
    hsum = 0.0
    off = 6 if want_hull else 0
    rmin = np.inf
    imin = -1
    rsum = 0.0
    moving = ext.shape[0] > 0
    work = 0.0
    dissipated = 0.0
    for i in range(ox.shape[0]):
        oxi = ox[i]
        oyi = oy[i]
        gx = u[0] - u[2] * oyi
        gy = u[1] + u[2] * oxi
        if moving:
            gx += ext[i, 0]
            gy += ext[i, 1]
        r2 = gx * gx + gy * gy
        rsum += r2
        if r2 < rmin:
            rmin = r2
            imin = i
        if skip >= 0 and oxi == ox[skip] and oyi == oy[skip]:
            continue
        _eval_at(kind, par, tab, ext, i, gx, gy, ev)
        li = lam[i]
        cx = ev[off]
        cy = ev[off + 1]
        a = ev[off + 2]
        b = ev[off + 3]
        c = ev[off + 4]
        d = ev[off + 5]
        hsum += li * ev[12]
        if moving:
            # the gait's work against friction and the dissipation (ev[16], ev[17])
            work += li * (cx * ext[i, 0] + cy * ext[i, 1])
            dissipated += li * (cx * gx + cy * gy)
        R[0] += li * cx
        R[1] += li * cy
        R[2] += li * (oxi * cy - oyi * cx)
        # W J W^T with W = [[1, 0], [0, 1], [-oy, ox]]
        J[0, 0] += li * a
        J[0, 1] += li * b
        J[1, 0] += li * c
        J[1, 1] += li * d
        J[0, 2] += li * (-a * oyi + b * oxi)
        J[1, 2] += li * (-c * oyi + d * oxi)
        J[2, 0] += li * (-oyi * a + oxi * c)
        J[2, 1] += li * (-oyi * b + oxi * d)
        J[2, 2] += li * (oyi * oyi * a - oyi * oxi * (b + c) + oxi * oxi * d)
    ev[13] = imin                      # the point of least slip (a kink of F near it)
    ev[14] = rmin
    ev[15] = rsum / ox.shape[0]
    if moving:
        ev[16] = work
        ev[17] = dissipated
    return hsum


@njit(cache=True)
def _gauge(kind, par, tab, cx, cy):
    """k_C(c) of a force per unit load: closed form for the ellipse, else the gauge of the
    hull of C from its support table (max over the table of c.s / h(s))."""
    if kind == KIND_ELLIPSE or kind == KIND_COMPONENTWISE:
        co, si = par[4], par[5]
        la = co * cx + si * cy
        lb = -si * cx + co * cy
        A = par[0] if la >= 0.0 else par[1]
        B = par[2] if lb >= 0.0 else par[3]
        return math.sqrt((la / A) ** 2 + (lb / B) ** 2)
    K = tab.shape[0] - 1
    g = 0.0
    for k in range(K):
        psi = TWO_PI * k / K
        c = math.cos(psi)
        s = math.sin(psi)
        h = tab[k, 2] * c + tab[k, 3] * s
        v = (cx * c + cy * s) / h
        if v > g:
            g = v
    return g


@njit(cache=True)
def _solve3(J, r, x):
    """x = J^-1 r by Cramer's rule; returns False if J is singular."""
    a, b, c = J[0, 0], J[0, 1], J[0, 2]
    d, e, f = J[1, 0], J[1, 1], J[1, 2]
    g, h, k = J[2, 0], J[2, 1], J[2, 2]
    A = e * k - f * h
    B = f * g - d * k
    C = d * h - e * g
    det = a * A + b * B + c * C
    if det == 0.0 or not math.isfinite(det):
        return False
    x[0] = (A * r[0] + (c * h - b * k) * r[1] + (b * f - c * e) * r[2]) / det
    x[1] = (B * r[0] + (a * k - c * g) * r[1] + (c * d - a * f) * r[2]) / det
    x[2] = (C * r[0] + (b * g - a * h) * r[1] + (a * e - b * d) * r[2]) / det
    return True


@njit(cache=True)
def _merit(u, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev):
    hs = _assemble(u, uf, md, ox, oy, ext, lam, kind, par, tab, False, R, J, ev)
    if assoc:
        f = 0.0
        for j in range(3):
            f += 0.5 * md[j] * (u[j] - uf[j]) ** 2
        return f + hs
    f = 0.0
    for j in range(3):
        f += 0.5 * R[j] * R[j] / md[j]
    return f


@njit(cache=True)
def _ray(d, b, md, ox, oy, ext, lam, kind, par, tab, ev):
    """s with R(s d) . d = 0 on the ray of d (exact: c depends only on the slip direction):
    s = (b.d - sum lam_i c_i . W_i^T d) / d^T M d.  A rigid footprint only (ext empty: with
    slip offsets c varies along the ray)."""
    num = b[0] * d[0] + b[1] * d[1] + b[2] * d[2]
    den = md[0] * d[0] * d[0] + md[1] * d[1] * d[1] + md[2] * d[2] * d[2]
    for i in range(ox.shape[0]):
        gx = d[0] - d[2] * oy[i]
        gy = d[1] + d[2] * ox[i]
        _eval(kind, par, tab, gx, gy, ev)
        num -= lam[i] * (ev[0] * gx + ev[1] * gy)
    return num / den


@njit(cache=True)
def _group_load(ox, oy, ext, lam, j):
    """The normal impulse of point j's group: the points at exactly its spot (they slip and
    stick together)."""
    s = 0.0
    for i in range(ox.shape[0]):
        if ox[i] == ox[j] and oy[i] == oy[j]:
            s += lam[i]
    return s


@njit(cache=True)
def _slip_towards(kind, par, tab, cx, cy):
    """The slip direction psi (rad) whose sliding force c(psi) points along (cx, cy): the
    normal of the ellipse at its point in that direction (closed form), else the table's
    direction whose force makes the least angle with it, refined linearly to the crossing
    of the cross product with its neighbours."""
    if kind == KIND_ELLIPSE:
        co, si = par[4], par[5]
        la = co * cx + si * cy
        lb = -si * cx + co * cy
        A = par[0] if la >= 0.0 else par[1]
        B = par[2] if lb >= 0.0 else par[3]
        na = la / (A * A)
        nb = lb / (B * B)
        return math.atan2(si * na + co * nb, co * na - si * nb)
    if kind == KIND_COMPONENTWISE:
        # c = (mu_{f|b} u_x, mu_t u_y): the slip along (c_x / mu_{f|b}, c_y / mu_t)
        A = par[0] if cx >= 0.0 else par[1]
        return math.atan2(cy / par[2], cx / A)
    K = tab.shape[0] - 1
    best = -2.0
    kb = 0
    cn = math.sqrt(cx * cx + cy * cy)
    for k in range(K):
        a = tab[k, 0]
        b = tab[k, 1]
        v = (a * cx + b * cy) / (math.sqrt(a * a + b * b) * cn + 1e-300)
        if v > best:
            best = v
            kb = k
    dpsi = TWO_PI / K
    x0 = tab[kb, 0] * cy - tab[kb, 1] * cx
    for k2 in (kb + 1, kb - 1):
        kk = k2 % K
        x1 = tab[kk, 0] * cy - tab[kk, 1] * cx
        if x0 == 0.0 or (x0 > 0.0) != (x1 > 0.0):
            t = x0 / (x0 - x1) if x0 != x1 else 0.0
            return (kb + t * (k2 - kb)) * dpsi
    return kb * dpsi
