"""Numba kernels of the rigid-body solver: the stick test (the least margin of the
limit set over the unit sphere) and the sliding solve with its kink cases (a point that
nearly sticks) (:mod:`asperity.dynamics._body_kernels` has the overview).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..kernel_cache import refresh
from ._body_law_kernels import (_assemble, _eval_at, _gauge, _group_load, _merit, _ray,
                                _slip_towards, _solve3)

refresh(__file__)     # drop cached kernels compiled against older callees


@njit(cache=True)
def _kink(u, uf, md, ox, oy, ext, lam, kind, par, tab, j, tol_r, R, J, ev, cw):
    """The step's solution with point j sticking: u = omega (oy_j, -ox_j, 1) (a rotation
    about point j, its slip exactly 0), omega from R(u) . n = 0 by a safeguarded 1D Newton;
    accepted (u overwritten, True) if the reaction of point j's group (the points at its
    spot, load lambda_g) c = -(R_x, R_y) / lambda_g lies in C.  This is where F is not
    differentiable: plain Newton cannot converge there.  Otherwise cw = (c_x, c_y, omega)
    of that solution with cw[2] NaN if the 1D solve failed: the reaction lies outside C,
    the group slides slowly and its slip direction is the one whose force points along
    c (:func:`_polar` starts there)."""
    un = np.empty(3)
    n0 = oy[j]
    n1 = -ox[j]
    # a crawling body's point j has its own slip offset: it sticks on u = base + omega n
    bx = -ext[j, 0] if ext.shape[0] > 0 else 0.0
    by = -ext[j, 1] if ext.shape[0] > 0 else 0.0
    w = u[2]
    lo = -np.inf
    hi = np.inf
    ok = False
    for it in range(60):
        un[0] = w * n0 + bx
        un[1] = w * n1 + by
        un[2] = w
        # point j's group left out: its force is the reaction (on a crawling body its
        # slip on this line is zero only to rounding, and a rounding slip has a full force)
        _assemble(un, uf, md, ox, oy, ext, lam, kind, par, tab, False, R, J, ev, j)
        d1 = R[0] * n0 + R[1] * n1 + R[2]
        # |R.n| <= |R|_(M^-1) |n|_M: the 1D residual within the tolerance of the 3D one
        if abs(d1) <= tol_r * math.sqrt(md[0] * n0 * n0 + md[1] * n1 * n1 + md[2]):
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
    cw[2] = np.nan
    if not ok:
        return False
    lg = _group_load(ox, oy, ext, lam, j)
    cx = -R[0] / lg
    cy = -R[1] / lg
    lx, ly = cx, cy
    if ext.shape[0] > 0:
        # the reaction in the frame of point j's law
        lx = ext[j, 2] * cx + ext[j, 3] * cy
        ly = -ext[j, 3] * cx + ext[j, 2] * cy
    if _gauge(kind, par, tab, lx, ly) > 1.0 + 1e-12:
        cw[0] = cx
        cw[1] = cy
        cw[2] = w
        return False
    for k in range(3):
        u[k] = un[k]
    return True


@njit(cache=True)
def _polar(u, uf, md, ox, oy, ext, lam, kind, par, tab, j, tol_r, R, J, ev, cw):
    """The step's solution with point j sliding slowly: unknowns (rho, phi, omega) with
    gamma_j = rho (cos phi, sin phi) and u = (gamma_j + omega (oy_j, -ox_j), omega).  In
    these coordinates the force c(phi) of point j's group (the points at its spot) is smooth
    even at rho = 0, where F has its kink
    (plain Newton on u then only creeps).  Newton on the three equations R = 0 with a
    backtracking search on |R| that keeps rho >= 0; accepted (u overwritten, True) on
    convergence.  Starts from the pivot about point j found by :func:`_kink` (cw, rho = 0,
    phi the slip direction whose force points along the reaction the pivot needs: exact as
    rho -> 0) when there is one, else from u."""
    un = np.empty(3)
    x = np.empty(3)
    dx = np.empty(3)
    xn = np.empty(3)
    Jp = np.empty((3, 3))
    oxj = ox[j]
    oyj = oy[j]
    # a crawling body's point j: its slip offset (bx, by) and the angle of its law
    moving = ext.shape[0] > 0
    bx = ext[j, 0] if moving else 0.0
    by = ext[j, 1] if moving else 0.0
    if math.isfinite(cw[2]):
        # from the pivot about point j, sliding the way its needed reaction points
        x[0] = 0.0
        if moving:
            ca = ext[j, 2]
            sa = ext[j, 3]
            x[1] = (_slip_towards(kind, par, tab, ca * cw[0] + sa * cw[1],
                                  -sa * cw[0] + ca * cw[1]) + math.atan2(sa, ca))
        else:
            x[1] = _slip_towards(kind, par, tab, cw[0], cw[1])
        x[2] = cw[2]
    else:
        gx = u[0] - u[2] * oyj + bx
        gy = u[1] + u[2] * oxj + by
        x[0] = math.sqrt(gx * gx + gy * gy)
        x[1] = math.atan2(gy, gx)
        x[2] = u[2]
    lj = _group_load(ox, oy, ext, lam, j)
    rn = np.inf
    for it in range(40):
        # residual at x (and its norm), Jacobian
        cph = math.cos(x[1])
        sph = math.sin(x[1])
        un[0] = x[0] * cph + x[2] * oyj - bx
        un[1] = x[0] * sph - x[2] * oxj - by
        un[2] = x[2]
        _assemble(un, uf, md, ox, oy, ext, lam, kind, par, tab, False, R, J, ev, j)
        _eval_at(kind, par, tab, ext, j, cph, sph, ev)
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
        # the slip rho stays >= 0 (a negative one would turn the force along the slip)
        step = 1.0
        if x[0] + dx[0] < 0.0:
            step = 0.5 * x[0] / -dx[0]
            if step <= 0.0:
                return False
        ok = False
        for _ in range(40):
            for k in range(3):
                xn[k] = x[k] + step * dx[k]
            cph = math.cos(xn[1])
            sph = math.sin(xn[1])
            un[0] = xn[0] * cph + xn[2] * oyj - bx
            un[1] = xn[0] * sph - xn[2] * oxj - by
            un[2] = xn[2]
            _assemble(un, uf, md, ox, oy, ext, lam, kind, par, tab, False, R, J, ev, j)
            _eval_at(kind, par, tab, ext, j, cph, sph, ev)
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
def _min_sphere(d, b, md, ox, oy, ext, lam, kind, par, tab, tolG, maxit, R, J, ev, work):
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
        hs = _assemble(d, zero, md, ox, oy, ext, lam, kind, par, tab, True, R, J, ev)
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
            hs2 = _assemble(dn, zero, md, ox, oy, ext, lam, kind, par, tab, True, R, J, ev)
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
def _accept(f, f2, g0, R, dx, rn, rn2, step, assoc, noise):
    """Whether the line search takes the step: the merit falls (Armijo, c1 = 1e-4), or, for
    the convex F of an associated law, where F's change is below its own rounding (it sums
    n + 3 terms: a Newton step near the solution changes it by ~|R|^2, which vanishes in
    the rounding long before the residual is within tolerance), the approximate Wolfe
    conditions of Hager and Zhang (SIAM J. Optim. 16, 2005) on the slope F'(s) = R(s).dx,
    which is computed without cancellation: 0.9 F'(0) <= F'(s) <= 0.8 |F'(0)| (on a
    quadratic F these imply Armijo with c1 = 0.1).  A slope that is still at most 1e-4 of
    the first one (F'(s) <= 1e-4 F'(0)) implies Armijo on a convex F outright:
    F(s) - F(0) <= s F'(s).  For the residual's merit 1/2 |R|^2 (non-associated laws) a
    decrease of |R|, which is resolved down to the rounding of R itself."""
    if not assoc:
        return rn2 < rn
    if f2 <= f + 1e-4 * step * g0:
        return True
    g2 = R[0] * dx[0] + R[1] * dx[1] + R[2] * dx[2]
    if g2 <= 1e-4 * g0:
        return True
    return abs(f2 - f) <= noise * abs(f) and 0.9 * g0 <= g2 <= -0.8 * g0


@njit(cache=True)
def _slide(u, uf, b, md, ox, oy, ext, lam, kind, par, tab, assoc, tol_r, maxit, R, J, ev, dx, un):
    """Newton with a backtracking line search on R(u) = 0 from u (overwritten).
    Returns (iterations, converged, final relative residual measure)."""
    f = _merit(u, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev)
    # rounding of the merit: F sums n + 3 positive terms (associated); the residual's
    # merit is resolved down to the rounding of R itself, far below the tolerance
    noise = (ox.shape[0] + 4) * 2.3e-16
    rn = 0.0
    for it in range(1, maxit + 1):
        rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
        if rn <= tol_r:
            return it, True, rn
        for j in range(3):
            R[j] = -R[j]
        if not _solve3(J, R, dx):
            return it, False, rn
        if (abs(dx[0]) <= 4e-16 * abs(u[0]) and abs(dx[1]) <= 4e-16 * abs(u[1])
                and abs(dx[2]) <= 4e-16 * abs(u[2])):
            # the Newton step is below the rounding of u: the residual is at its floor
            # (near a point that almost sticks, dc/dgamma ~ 1/|gamma| amplifies the
            # rounding of u); within 1e3 of the tolerance that is convergence
            return it, rn <= 1e3 * tol_r, rn
        # slope of the merit along dx at the start: F' = R.dx (associated), |R|^2' = -2|R|^2
        g0 = -(R[0] * dx[0] + R[1] * dx[1] + R[2] * dx[2])
        step = 1.0
        ok = False
        for _ in range(60):
            for j in range(3):
                un[j] = u[j] + step * dx[j]
            f2 = _merit(un, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev)
            rn2 = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
            if _accept(f, f2, g0, R, dx, rn, rn2, step, assoc, noise):
                ok = True
                break
            step *= 0.5
        if not ok:
            _merit(u, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev)
            rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
            return it, rn <= 1e3 * tol_r, rn
        if step < 1.0 and ev[14] < 1e-2 * ev[15]:
            # the Newton step was damped next to a point that (nearly) sticks: try the
            # solution with that point sticking exactly
            jk = int(ev[13])
            cw = np.empty(3)
            if _kink(u, uf, md, ox, oy, ext, lam, kind, par, tab, jk, tol_r, R, J, ev, cw):
                return it, True, 0.0
            for k in range(3):
                dx[k] = un[k]
            if _polar(dx, uf, md, ox, oy, ext, lam, kind, par, tab, jk, tol_r, R, J, ev, cw):
                for k in range(3):
                    u[k] = dx[k]
                return it, True, 0.0
            _merit(un, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev)
        if step < 1.0 and ext.shape[0] == 0:
            # a damped step: is the motion collapsing towards the stick of the body?  The
            # exact solve on the ray of the new point tells (s <= 0: no sliding there; a
            # rigid footprint only: a crawling body's points move in it)
            s = _ray(un, b, md, ox, oy, ext, lam, kind, par, tab, ev)
            if s <= 0.0:
                for j in range(3):
                    u[j] = un[j]
                return it, False, rn
            if assoc and s != 1.0:
                # the exact minimum of F on that ray is lower still
                for j in range(3):
                    un[j] *= s
                f2 = _merit(un, uf, md, ox, oy, ext, lam, kind, par, tab, assoc, R, J, ev)
        for j in range(3):
            u[j] = un[j]
        f = f2
    rn = math.sqrt(R[0] * R[0] / md[0] + R[1] * R[1] / md[1] + R[2] * R[2] / md[2])
    return maxit, rn <= tol_r, rn
