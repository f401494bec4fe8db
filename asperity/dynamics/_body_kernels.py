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
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

TWO_PI = 2.0 * math.pi
KIND_ELLIPSE = 0     # closed form: par = (a+, a-, b+, b-, cos th, sin th)
KIND_TABLE = 1       # tab (K+1, 4): c_x, c_y, grad h_x, grad h_y on psi_k = 2 pi k / K
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
def _eval(kind, par, tab, gx, gy, out):
    """Law at the slip (gx, gy): out = c_x, c_y, J00, J01, J10, J11 (dc/dgamma),
    hg_x, hg_y (grad h), H00, H01, H10, H11 (Hessian of h), h (value at gamma)."""
    r2 = gx * gx + gy * gy
    if r2 == 0.0:
        for j in range(13):
            out[j] = 0.0
        return
    if kind == KIND_ELLIPSE:
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
def _assemble(u, uf, md, ox, oy, lam, kind, par, tab, want_hull, R, J, ev, skip=-1):
    """R(u) = M (u - uf) + sum lam_i W_i c_i (want_hull: the hull's gradient instead of c and
    its Hessian in J) and J = M + sum lam_i W_i (dc/dgamma)_i W_i^T; returns sum lam_i h_i."""
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
    for i in range(ox.shape[0]):
        oxi = ox[i]
        oyi = oy[i]
        gx = u[0] - u[2] * oyi
        gy = u[1] + u[2] * oxi
        r2 = gx * gx + gy * gy
        rsum += r2
        if r2 < rmin:
            rmin = r2
            imin = i
        if i == skip:
            continue
        _eval(kind, par, tab, gx, gy, ev)
        li = lam[i]
        cx = ev[off]
        cy = ev[off + 1]
        a = ev[off + 2]
        b = ev[off + 3]
        c = ev[off + 4]
        d = ev[off + 5]
        hsum += li * ev[12]
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
    return hsum


@njit(cache=True)
def _gauge(kind, par, tab, cx, cy):
    """k_C(c) of a force per unit load: closed form for the ellipse, else the gauge of the
    hull of C from its support table (max over the table of c.s / h(s))."""
    if kind == KIND_ELLIPSE:
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
def _kink(u, uf, md, ox, oy, lam, kind, par, tab, j, tol_r, R, J, ev):
    """The step's solution with point j sticking: u = omega (oy_j, -ox_j, 1) (a rotation
    about point j, its slip exactly 0), omega from R(u) . n = 0 by a safeguarded 1D Newton;
    accepted (u overwritten, True) if point j's reaction c_j = -(R_x, R_y) / lambda_j lies
    in C.  This is where F is not differentiable: plain Newton cannot converge there."""
    un = np.empty(3)
    n0 = oy[j]
    n1 = -ox[j]
    w = u[2]
    lo = -np.inf
    hi = np.inf
    ok = False
    for it in range(60):
        un[0] = w * n0
        un[1] = w * n1
        un[2] = w
        _assemble(un, uf, md, ox, oy, lam, kind, par, tab, False, R, J, ev)
        d1 = R[0] * n0 + R[1] * n1 + R[2]
        if abs(d1) <= tol_r * math.sqrt(n0 * n0 / md[0] + n1 * n1 / md[1] + 1.0 / md[2]):
            ok = True
            break
        if d1 > 0.0:
            hi = w
        else:
            lo = w
        d2 = (n0 * (J[0, 0] * n0 + J[0, 1] * n1 + J[0, 2])
              + n1 * (J[1, 0] * n0 + J[1, 1] * n1 + J[1, 2])
              + (J[2, 0] * n0 + J[2, 1] * n1 + J[2, 2]))
        wn = w - d1 / d2 if d2 > 0.0 else np.nan
        if not (wn > lo and wn < hi):
            if math.isfinite(lo) and math.isfinite(hi):
                wn = 0.5 * (lo + hi)
            elif math.isfinite(lo):
                wn = lo + 2.0 * abs(lo) + 1e-300
            else:
                wn = hi - 2.0 * abs(hi) - 1e-300
        if wn == w:
            ok = True
            break
        w = wn
    if not ok:
        return False
    cx = -R[0] / lam[j]
    cy = -R[1] / lam[j]
    if _gauge(kind, par, tab, cx, cy) > 1.0 + 1e-12:
        return False
    for k in range(3):
        u[k] = un[k]
    return True


@njit(cache=True)
def _polar(u, uf, md, ox, oy, lam, kind, par, tab, j, tol_r, R, J, ev):
    """The step's solution with point j sliding slowly: unknowns (rho, phi, omega) with
    gamma_j = rho (cos phi, sin phi) and u = (gamma_j + omega (oy_j, -ox_j), omega).  In
    these coordinates point j's force c(phi) is smooth even at rho = 0, where F has its kink
    (plain Newton on u then only creeps).  Newton on the three equations R = 0 with a
    backtracking search on |R|; accepted (u overwritten, True) on convergence with rho >= 0."""
    un = np.empty(3)
    x = np.empty(3)
    dx = np.empty(3)
    xn = np.empty(3)
    Jp = np.empty((3, 3))
    oxj = ox[j]
    oyj = oy[j]
    gx = u[0] - u[2] * oyj
    gy = u[1] + u[2] * oxj
    x[0] = math.sqrt(gx * gx + gy * gy)
    x[1] = math.atan2(gy, gx)
    x[2] = u[2]
    lj = lam[j]
    rn = np.inf
    for it in range(40):
        # residual at x (and its norm), Jacobian
        cph = math.cos(x[1])
        sph = math.sin(x[1])
        un[0] = x[0] * cph + x[2] * oyj
        un[1] = x[0] * sph - x[2] * oxj
        un[2] = x[2]
        _assemble(un, uf, md, ox, oy, lam, kind, par, tab, False, R, J, ev, j)
        _eval(kind, par, tab, cph, sph, ev)
        cx, cy = ev[0], ev[1]
        # dc/dphi = J(unit) s_perp
        dcx = -ev[2] * sph + ev[3] * cph
        dcy = -ev[4] * sph + ev[5] * cph
        R[0] += lj * cx
        R[1] += lj * cy
        R[2] += lj * (oxj * cy - oyj * cx)
        rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
        if rn <= tol_r:
            if x[0] < 0.0:
                return False
            for k in range(3):
                u[k] = un[k]
            return True
        for k in range(3):
            Jp[k, 0] = J[k, 0] * cph + J[k, 1] * sph
            Jp[k, 1] = x[0] * (-J[k, 0] * sph + J[k, 1] * cph)
            Jp[k, 2] = J[k, 0] * oyj - J[k, 1] * oxj + J[k, 2]
        Jp[0, 1] += lj * dcx
        Jp[1, 1] += lj * dcy
        Jp[2, 1] += lj * (oxj * dcy - oyj * dcx)
        for k in range(3):
            R[k] = -R[k]
        if not _solve3(Jp, R, dx):
            return False
        step = 1.0
        ok = False
        for _ in range(40):
            for k in range(3):
                xn[k] = x[k] + step * dx[k]
            cph = math.cos(xn[1])
            sph = math.sin(xn[1])
            un[0] = xn[0] * cph + xn[2] * oyj
            un[1] = xn[0] * sph - xn[2] * oxj
            un[2] = xn[2]
            _assemble(un, uf, md, ox, oy, lam, kind, par, tab, False, R, J, ev, j)
            _eval(kind, par, tab, cph, sph, ev)
            R[0] += lj * ev[0]
            R[1] += lj * ev[1]
            R[2] += lj * (oxj * ev[1] - oyj * ev[0])
            r2 = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
            if r2 < rn:
                ok = True
                break
            step *= 0.5
        if not ok:
            return False
        for k in range(3):
            x[k] = xn[k]
    return False


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
def _merit(u, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev):
    hs = _assemble(u, uf, md, ox, oy, lam, kind, par, tab, False, R, J, ev)
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
def _ray(d, b, md, ox, oy, lam, kind, par, tab, ev):
    """s with R(s d) . d = 0 on the ray of d (exact: c depends only on the slip direction):
    s = (b.d - sum lam_i c_i . W_i^T d) / d^T M d."""
    num = b[0] * d[0] + b[1] * d[1] + b[2] * d[2]
    den = md[0] * d[0] * d[0] + md[1] * d[1] * d[1] + md[2] * d[2] * d[2]
    for i in range(ox.shape[0]):
        gx = d[0] - d[2] * oy[i]
        gy = d[1] + d[2] * ox[i]
        _eval(kind, par, tab, gx, gy, ev)
        num -= lam[i] * (ev[0] * gx + ev[1] * gy)
    return num / den


@njit(cache=True)
def _min_sphere(d, b, md, ox, oy, lam, kind, par, tab, tolG, maxit, R, J, ev, work):
    """Minimise G(d) = sum lam_i h(W_i^T d) - b.d over |d|_M = 1 from the direction d
    (overwritten by the minimiser); returns (min G, iterations).  Stops as soon as
    G < -tolG (a sliding direction) or the Riemannian gradient vanishes."""
    sq = np.empty(3)
    for j in range(3):
        sq[j] = math.sqrt(md[j])
    e = np.empty(3)
    n = 0.0
    for j in range(3):
        e[j] = sq[j] * d[j]
        n += e[j] * e[j]
    n = math.sqrt(n)
    for j in range(3):
        e[j] /= n
        d[j] = e[j] / sq[j]
    zero = np.zeros(3)
    t1 = np.empty(3)
    t2 = np.empty(3)
    en = np.empty(3)
    dn = np.empty(3)
    G = 0.0
    it = 0
    for it in range(1, maxit + 1):
        # G(d) = sum lam h - b.d; gradient in e: M^-1/2 (sum lam W grad h - b)
        hs = _assemble(d, zero, md, ox, oy, lam, kind, par, tab, True, R, J, ev)
        G = hs - (b[0] * d[0] + b[1] * d[1] + b[2] * d[2])
        if G < -tolG:
            return G, it
        # R = M d + sum lam W grad h  -> grad G(d) = R - M d - b
        ge = work
        for j in range(3):
            ge[j] = (R[j] - md[j] * d[j] - b[j]) / sq[j]
        # tangent basis
        ax = 0
        if abs(e[1]) < abs(e[ax]):
            ax = 1
        if abs(e[2]) < abs(e[ax]):
            ax = 2
        for j in range(3):
            t1[j] = -e[ax] * e[j]
        t1[ax] += 1.0
        n = math.sqrt(t1[0] ** 2 + t1[1] ** 2 + t1[2] ** 2)
        for j in range(3):
            t1[j] /= n
        t2[0] = e[1] * t1[2] - e[2] * t1[1]
        t2[1] = e[2] * t1[0] - e[0] * t1[2]
        t2[2] = e[0] * t1[1] - e[1] * t1[0]
        a1 = t1[0] * ge[0] + t1[1] * ge[1] + t1[2] * ge[2]
        a2 = t2[0] * ge[0] + t2[1] * ge[1] + t2[2] * ge[2]
        if math.sqrt(a1 * a1 + a2 * a2) <= 1e-3 * tolG:
            return G, it
        # Hessian of G in e (J - M holds sum lam W H W^T), reduced; minus G on the sphere
        B11 = 0.0
        B12 = 0.0
        B22 = 0.0
        for j in range(3):
            for k in range(3):
                h = (J[j, k] - (md[j] if j == k else 0.0)) / (sq[j] * sq[k])
                B11 += t1[j] * h * t1[k]
                B12 += t1[j] * h * t2[k]
                B22 += t2[j] * h * t2[k]
        B11 -= G
        B22 -= G
        # make it positive definite
        tr = 0.5 * (B11 + B22)
        disc = math.sqrt(max(0.0, 0.25 * (B11 - B22) ** 2 + B12 * B12))
        lmin = tr - disc
        gn = math.sqrt(a1 * a1 + a2 * a2)
        shift = 0.0
        if lmin <= 1e-12 * (abs(tr) + gn):
            shift = -lmin + 1e-6 * (abs(tr) + gn) + 1e-300
        B11 += shift
        B22 += shift
        det = B11 * B22 - B12 * B12
        x1 = -(B22 * a1 - B12 * a2) / det
        x2 = -(B11 * a2 - B12 * a1) / det
        step = 1.0
        moved = False
        for _ in range(40):
            for j in range(3):
                en[j] = e[j] + step * (x1 * t1[j] + x2 * t2[j])
            n = math.sqrt(en[0] ** 2 + en[1] ** 2 + en[2] ** 2)
            for j in range(3):
                en[j] /= n
                dn[j] = en[j] / sq[j]
            hs2 = _assemble(dn, zero, md, ox, oy, lam, kind, par, tab, True, R, J, ev)
            G2 = hs2 - (b[0] * dn[0] + b[1] * dn[1] + b[2] * dn[2])
            if G2 < G:
                moved = True
                break
            step *= 0.5
        if not moved:
            return G, it
        for j in range(3):
            e[j] = en[j]
            d[j] = dn[j]
    return G, it


@njit(cache=True)
def _slide(u, uf, b, md, ox, oy, lam, kind, par, tab, assoc, tol_r, maxit, R, J, ev, dx, un):
    """Newton with a backtracking line search on R(u) = 0 from u (overwritten).
    Returns (iterations, converged, final relative residual measure)."""
    f = _merit(u, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev)
    rn = 0.0
    for it in range(1, maxit + 1):
        rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
        if rn <= tol_r:
            return it, True, rn
        for j in range(3):
            R[j] = -R[j]
        if not _solve3(J, R, dx):
            return it, False, rn
        step = 1.0
        ok = False
        for _ in range(60):
            for j in range(3):
                un[j] = u[j] + step * dx[j]
            f2 = _merit(un, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev)
            rn2 = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
            # F cannot resolve changes below its rounding (~1e-16 F) while the residual
            # still can: a full step that lowers the residual is taken too
            if f2 < f or (f2 <= f + 1e-15 * abs(f) and rn2 < rn):
                ok = True
                break
            step *= 0.5
        if not ok:
            _merit(u, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev)
            rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
            return it, rn <= 1e3 * tol_r, rn
        if step < 1.0 and ev[14] < 1e-2 * ev[15]:
            # the Newton step was damped next to a point that (nearly) sticks: try the
            # solution with that point sticking exactly
            jk = int(ev[13])
            if _kink(u, uf, md, ox, oy, lam, kind, par, tab, jk, tol_r, R, J, ev):
                return it, True, 0.0
            for k in range(3):
                dx[k] = un[k]
            if _polar(dx, uf, md, ox, oy, lam, kind, par, tab, jk, tol_r, R, J, ev):
                for k in range(3):
                    u[k] = dx[k]
                return it, True, 0.0
            _merit(un, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev)
        if step < 1.0:
            # a damped step: is the motion collapsing towards the stick of the body?  The
            # exact solve on the ray of the new point tells (s <= 0: no sliding there)
            s = _ray(un, b, md, ox, oy, lam, kind, par, tab, ev)
            if s <= 0.0:
                for j in range(3):
                    u[j] = un[j]
                return it, False, rn
            if assoc and s != 1.0:
                # the exact minimum of F on that ray is lower still
                for j in range(3):
                    un[j] *= s
                f2 = _merit(un, uf, md, ox, oy, lam, kind, par, tab, assoc, R, J, ev)
        for j in range(3):
            u[j] = un[j]
        f = f2
    rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
    return maxit, rn <= tol_r, rn


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
def step_velocity(uA, uP, warm, uf, md, ox, oy, lam, kind, par, tab, assoc, tol, maxit, scale,
                  out, R, J, ev, work):
    """The end velocity of one step (out) from the start velocity uA (uP the one before,
    used if warm) and the free velocity uf.  scale: the impulse scale sum_i lam_i mu_max / sqrt(m) of the tolerances.
    Returns (iterations, status, relative residual)."""
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
        k, conv, rn = _slide(out, uf, b, md, ox, oy, lam, kind, par, tab, assoc, tola,
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
        s = _ray(d, b, md, ox, oy, lam, kind, par, tab, ev)
        if s <= 0.0:
            # no sliding on this ray: find the direction of least margin; the body sticks
            # iff the margin is not negative
            G, k = _min_sphere(d, b, md, ox, oy, lam, kind, par, tab, tola, maxit, R,
                               J, ev, work)
            its += k
            if G >= -tola:
                for j in range(3):
                    out[j] = 0.0
                return its, STATUS_OK, 0.0
            s = _ray(d, b, md, ox, oy, lam, kind, par, tab, ev)
            if s <= 0.0:
                s = -G
        for j in range(3):
            out[j] = s * d[j]
        k, conv, rn = _slide(out, uf, b, md, ox, oy, lam, kind, par, tab, assoc, tola,
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
            its, st, res = step_velocity(u, up, warm, uf, md, ox, oy, lam, kind, par, tab, assoc, tol,
                                         maxit, scale, ue, R, J, ev, work)
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
