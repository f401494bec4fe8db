"""Numba kernels of one spring tip on a piecewise-linear profile (physics in
:mod:`asperity.texture.springs`): locating the tip, the return mapping on a face and at a
corner, and the update of one tip over a step.  Array-in/array-out, no validation; the
status codes are those of :mod:`asperity.texture._spring_kernels`.  numba's cache does not
follow a change of this file into the kernels that inline these functions: change
_spring_kernels.py (at least its docstring) in the same commit.

Profile arrays (one period of the texture, see texture.Profile):
    xs (k+1,), zs (k+1,)  nodes, xs[0] = 0, xs[k] = L
    seg_mu (k,)           local friction of segment j
    seg_loaded (k,) int8  1 if tips on segment j can carry load (contact regime)
The tip x coordinate is stored unwrapped; segment ``J`` (any integer) is segment
``J mod k`` shifted by ``(J div k) L``.  Node ``J`` is the left end of segment ``J``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

#: tip modes
FREE = 0
FACE = 1
NODE = 2
_MAX_CROSSINGS = 64
_MAX_ITER = 200
#: relative slack of the Coulomb-cone test (keeps tips left on the cone boundary by the
#: return mapping from being re-projected every step)
_CONE_TOL = 1e-12


@njit(cache=True)
def locate(x, xs):
    """Unwrapped segment index J containing x (xs[j] + qL <= x < xs[j+1] + qL)."""
    k = xs.size - 1
    L = xs[k]
    q = math.floor(x / L)
    xm = x - q * L
    if xm >= L:
        xm -= L
        q += 1
    if xm < 0.0:
        xm = 0.0
    j = np.searchsorted(xs, xm, side="right") - 1
    if j < 0:
        j = 0
    if j > k - 1:
        j = k - 1
    return int(q) * k + j


@njit(cache=True)
def seg_geom(J, xs, zs):
    """(j, xl, xr, zl, zr, g) of the unwrapped segment J."""
    k = xs.size - 1
    L = xs[k]
    j = J % k
    if j < 0:
        j += k
    q = (J - j) // k
    off = q * L
    xl = xs[j] + off
    # the last segment's right end is the next period's first node, computed as that
    # node is (xs[0] = 0): a tip on a node is on both of its segments' ends exactly
    xr = xs[j + 1] + off if j + 1 < k else (q + 1) * L
    zl = zs[j]
    zr = zs[j + 1]
    g = (zr - zl) / (xs[j + 1] - xs[j])
    return j, xl, xr, zl, zr, g


@njit(cache=True)
def height(x, xs, zs):
    J = locate(x, xs)
    j, xl, xr, zl, zr, g = seg_geom(J, xs, zs)
    return zl + g * (x - xl)


@njit(cache=True)
def _slip_for_normal(G1, G2, K1, K2, muR):
    """Slip (D1, D2) in face coordinates for a fixed friction capacity muR >= 0.

    Solves  G + K D + muR D/|D| = 0  (K = diag(K1, K2) > 0): D_j = -t G_j/(t K_j + muR)
    with t = |D| the root of  sum G_j^2/(t K_j + muR)^2 = 1, which is convex and
    decreasing in t, so Newton from a point left of the root converges monotonically.
    Returns (D1, D2, ok).
    """
    Gn = math.sqrt(G1 * G1 + G2 * G2)
    if Gn <= muR:
        return 0.0, 0.0, True
    Kmax = max(K1, K2)
    t = (Gn - muR) / Kmax  # phi(t) >= 0 here
    ok = False
    for _ in range(_MAX_ITER):
        a1 = t * K1 + muR
        a2 = t * K2 + muR
        phi = G1 * G1 / (a1 * a1) + G2 * G2 / (a2 * a2) - 1.0
        dphi = -2.0 * (G1 * G1 * K1 / (a1 * a1 * a1) + G2 * G2 * K2 / (a2 * a2 * a2))
        if dphi >= 0.0 or phi <= 0.0:
            # phi <= 0: at the root to round-off (Newton approaches it from the left)
            ok = True
            break
        dt = -phi / dphi
        t += dt
        if abs(dt) <= 1e-14 * t:
            ok = True
            break
    a1 = t * K1 + muR
    a2 = t * K2 + muR
    return -t * G1 / a1, -t * G2 / a2, ok


@njit(cache=True)
def _face_return(g, mu, kn, kf, z_rest, xl, zl, xo, dy_tr, bx):
    """Backward-Euler return mapping of one tip on the (extended) plane of one segment.

    Plane z = zl + g (x - xl); tip starts at horizontal x = xo with trial y-offset
    dy_tr (tip y minus new base y); base at bx.  Face coordinates xi1 (up the slope,
    e1 = (1, 0, g)/n) and xi2 (= y), n = sqrt(1 + g^2).  Reaction on the tip
    R = (kf dx, kf dy, kn (z - z_rest)); G = (R.e1, R.e2) its tangential part,
    R_n = R.m (m = (-g, 0, 1)/n).  Stick if |G| <= mu R_n.  Otherwise slide by D:
    G + K D = -mu R_n(D) D/|D| with K = diag((kf + kn g^2)/n^2, kf) and
    R_n(D) = R_n + a1 D1, a1 = g (kn - kf)/n^2; solved for R_n by bracketed secant
    (Illinois) on [0, |G|/mu] with the inner monotone Newton of _slip_for_normal.

    Returns (code, x_new, dy_new, sliding): code 0 ok, 1 the tip separates (even the
    frictionless equilibrium on this plane has R_n <= 0), 2 no convergence.
    """
    n2 = 1.0 + g * g
    n = math.sqrt(n2)
    Rx = kf * (xo - bx)
    Ry = kf * dy_tr
    Rz = kn * (zl + g * (xo - xl) - z_rest)
    G1 = (Rx + g * Rz) / n
    G2 = Ry
    Rn = (Rz - g * Rx) / n
    Gn = math.sqrt(G1 * G1 + G2 * G2)
    if Rn > 0.0 and Gn <= mu * Rn * (1.0 + _CONE_TOL):
        return 0, xo, dy_tr, False
    K1 = (kf + kn * g * g) / n2
    K2 = kf
    a1 = g * (kn - kf) / n2
    d10 = -G1 / K1
    d20 = -G2 / K2
    R0 = Rn + a1 * d10  # normal force at the frictionless equilibrium
    if R0 <= 0.0:
        return 1, xo, dy_tr, False
    if mu <= 0.0:
        return 0, xo + d10 / n, dy_tr + d20, True
    # h(R) = R - Rn - a1 D1(R): h(0) = -R0 < 0, h(Gn/mu) = Gn/mu - Rn > 0
    lo = 0.0
    hlo = -R0
    hi = Gn / mu
    hhi = hi - Rn
    if hhi <= 0.0:  # cannot happen when sliding; guard against round-off
        return 0, xo, dy_tr, False
    scale = hi + abs(Rn)
    side = 0
    R = 0.0
    D1 = 0.0
    D2 = 0.0
    conv = False
    for _ in range(_MAX_ITER):
        R = (lo * hhi - hi * hlo) / (hhi - hlo)
        if not (R > lo and R < hi):
            R = 0.5 * (lo + hi)
        D1, D2, ok = _slip_for_normal(G1, G2, K1, K2, mu * R)
        if not ok:
            return 2, xo, dy_tr, False
        h = R - Rn - a1 * D1
        if abs(h) <= 1e-14 * scale or (hi - lo) <= 1e-15 * scale:
            conv = True
            break
        if h < 0.0:
            lo = R
            hlo = h
            if side == -1:
                hhi *= 0.5
            side = -1
        else:
            hi = R
            hhi = h
            if side == 1:
                hlo *= 0.5
            side = 1
    if not conv:
        return 2, xo, dy_tr, False
    return 0, xo + D1 / n, dy_tr + D2, True


@njit(cache=True)
def _corner(gl, gr, mul, mur, Rx, Ry, Rz, kf, dy_tr):
    """Tip held at a node (valley or ridge line): x fixed, slides along the node line (y).

    The in-plane part (Rx, Rz) is decomposed on the two face normals,
    (Rx, Rz) = N_l m_l + N_r m_r; the Coulomb capacity along the line is
    mu_l N_l+ + mu_r N_r+ (N+ = max(N, 0)).  1D return mapping on R_y = kf dy.
    Returns (dy_new, sliding).
    """
    nl = math.sqrt(1.0 + gl * gl)
    nr = math.sqrt(1.0 + gr * gr)
    det = (gr - gl) / (nl * nr)
    if abs(det) > 1e-12:
        # [-gl/nl, -gr/nr; 1/nl, 1/nr] [Nl, Nr] = [Rx, Rz]
        Nl = (Rx / nr + gr * Rz / nr) / det
        Nr = (-Rx / nl - gl * Rz / nl) / det
    else:
        Nl = 0.5 * (Rz - gl * Rx) / nl
        Nr = Nl
    cap = mul * max(Nl, 0.0) + mur * max(Nr, 0.0)
    if abs(Ry) <= cap * (1.0 + _CONE_TOL):
        return dy_tr, False
    if Ry > 0.0:
        return cap / kf, True
    return -cap / kf, True


@njit(cache=True)
def update_tip(mode, J, xt, dy_tr, bx, xs, zs, seg_mu, seg_loaded, kn, kf, z_rest):
    """Move one tip to its equilibrium for the new base position.

    Returns (code, mode, J, xt, dy, sliding).  code: 0 ok, 2 no convergence,
    3 too many face crossings.
    """
    came = 0  # +1 arrived at a node moving right, -1 moving left, 0 held there before
    landed = False
    for _ in range(_MAX_CROSSINGS):
        if mode == FREE:
            Jb = locate(bx, xs)
            j, xl, xr, zl, zr, g = seg_geom(Jb, xs, zs)
            zb = zl + g * (bx - xl)
            if seg_loaded[j] == 0 or zb <= z_rest or landed:
                return 0, FREE, Jb, bx, 0.0, False
            # touch down under the base and relax on that face
            landed = True
            mode = FACE
            J = Jb
            xt = bx
            dy_tr = 0.0
            came = 0
            continue
        if mode == FACE:
            j, xl, xr, zl, zr, g = seg_geom(J, xs, zs)
            if seg_loaded[j] == 0:
                mode = FREE
                continue
            code, xn, dyn, sl = _face_return(g, seg_mu[j], kn, kf, z_rest, xl, zl, xt, dy_tr, bx)
            if code == 2:
                return 2, mode, J, xt, dy_tr, False
            if code == 1:
                mode = FREE
                continue
            if xn > xr:
                # the share of the slip up to the node (a tip already on it: none)
                f = (xr - xt) / (xn - xt) if xn > xt else 0.0
                f = min(max(f, 0.0), 1.0)
                dy_tr = dy_tr + f * (dyn - dy_tr)
                xt = xr
                J = J + 1
                mode = NODE
                came = 1
                continue
            if xn < xl:
                f = (xl - xt) / (xn - xt) if xn < xt else 0.0
                f = min(max(f, 0.0), 1.0)
                dy_tr = dy_tr + f * (dyn - dy_tr)
                xt = xl
                mode = NODE
                came = -1
                continue
            if zl + g * (xn - xl) <= z_rest:
                mode = FREE
                continue
            return 0, FACE, J, xn, dyn, sl
        # mode == NODE: node J = left end of segment J, right end of segment J-1
        jr, xl_r, xr_r, zl_r, zr_r, gr = seg_geom(J, xs, zs)
        jl, xl_l, xr_l, zl_l, zr_l, gl = seg_geom(J - 1, xs, zs)
        xnode = xl_r
        znode = zl_r
        if znode <= z_rest:
            mode = FREE
            continue
        first_right = came > 0 or (came == 0 and bx >= xnode)
        moved = False
        for attempt in range(2):
            right = first_right if attempt == 0 else not first_right
            if right:
                if seg_loaded[jr] == 0:
                    if came > 0 or (came == 0 and attempt == 0):
                        mode = FREE
                        moved = True
                        break
                    continue
                code, xn, dyn, sl = _face_return(gr, seg_mu[jr], kn, kf, z_rest, xl_r, zl_r,
                                                 xnode, dy_tr, bx)
                if code == 2:
                    return 2, mode, J, xt, dy_tr, False
                if code == 1:
                    if attempt == 0:
                        mode = FREE
                        moved = True
                        break
                    continue
                if (not sl) or xn > xnode:
                    mode = FACE
                    moved = True
                    break
            else:
                if seg_loaded[jl] == 0:
                    if came < 0 or (came == 0 and attempt == 0):
                        mode = FREE
                        moved = True
                        break
                    continue
                code, xn, dyn, sl = _face_return(gl, seg_mu[jl], kn, kf, z_rest, xl_l, zl_l,
                                                 xnode, dy_tr, bx)
                if code == 2:
                    return 2, mode, J, xt, dy_tr, False
                if code == 1:
                    if attempt == 0:
                        mode = FREE
                        moved = True
                        break
                    continue
                if (not sl) or xn < xnode:
                    mode = FACE
                    J = J - 1
                    moved = True
                    break
        if moved:
            xt = xnode
            came = 0
            continue
        # held at the node: both faces push the tip back towards it
        Rx = kf * (xnode - bx)
        Ry = kf * dy_tr
        Rz = kn * (znode - z_rest)
        dyn, sl = _corner(gl, gr, seg_mu[jl], seg_mu[jr], Rx, Ry, Rz, kf, dy_tr)
        return 0, NODE, J, xnode, dyn, sl
    return 3, mode, J, xt, dy_tr, False
