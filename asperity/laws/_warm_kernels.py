"""Warm-started numba kernels of the support sets and star polygons
(:mod:`asperity.laws._set_kernels`): the projection onto a support set and its radial
function started from the last step's sample interval and root, with the boundary data near
an exactly evaluated point from Taylor series, and the star polygon's edge found from the
last one.  The point mass of the Moreau solver calls them once a step
(:mod:`asperity.laws._law_kernels`); they agree with the plain kernels to rounding
(tests/test_law_warm.py).

Kernels that allocate nothing are compiled with ``_nrt=False`` (no reference counts:
numba increfs and decrefs every array argument of a call with atomic operations, which
cost a Moreau step of a point mass ~200 ns of its ~300;
:mod:`asperity.dynamics._moreau_kernels`).
"""
from __future__ import annotations

import math

from numba import njit

from ..kernel_cache import refresh
from ._set_kernels import TWO_PI, star_radial_edge, support_project_full, tan_integral

refresh(__file__)     # drop cached kernels compiled against older callees

#: a warm start of the projection onto a support set (columns of a caller's row): the sample
#: interval, and the offset t in it with cos psi, sin psi, h, tan delta evaluated there
#: (h = 0: nothing evaluated yet), and the offset of the last root
PW_K, PW_T, PW_C, PW_S, PW_H, PW_TDE, PW_R, PW_SIZE = 0, 1, 2, 3, 4, 5, 6, 7
_SIXTH, _THIRD, _12TH, _20TH, _24TH = 1.0 / 6.0, 1.0 / 3.0, 1.0 / 12.0, 1.0 / 20.0, 1.0 / 24.0
#: how far from the kept point (rad) the boundary data come from Taylor series
PW_STEP = 1e-4


@njit(cache=True, _nrt=False, inline="always")
def _ends(tab, off, n, ka):
    """Rows and psi of both ends of the sample interval ka in [0, n) (no division)."""
    kb = ka + 1
    if kb < n:
        return off + ka, off + kb, tab[off + ka, 0], tab[off + kb, 0]
    return off + ka, off, tab[off + ka, 0], tab[off, 0] + TWO_PI


@njit(cache=True, _nrt=False, error_model="numpy")
def _eval_point(tab, off, n, ka, t, wk):
    """Exact boundary data at offset t of the sample interval ka, kept in wk."""
    ra, rb, a, b = _ends(tab, off, n, ka)
    d = b - a
    d0 = tab[ra, 2]
    d1 = tab[rb, 2]
    psi = a + t
    wk[PW_K] = ka
    wk[PW_T] = t
    wk[PW_C] = math.cos(psi)
    wk[PW_S] = math.sin(psi)
    wk[PW_H] = math.exp(tab[ra, 1] + tan_integral(d0, d1, d, t))
    wk[PW_TDE] = math.tan(d0 + (d1 - d0) * (t / d))


@njit(cache=True, _nrt=False, inline="always", error_model="numpy")
def _taylor(wk, dd, st):
    """(cos psi, sin psi, h, tan delta) at offset st from the anchor kept in wk, by their
    Taylor series there (h to fourth order, tan delta to third, cos and sin to fifth)."""
    Ta = wk[PW_TDE]
    T2 = Ta * Ta
    k = dd * (3.0 + 2.0 * dd)
    h2 = T2 + (1.0 + T2) * dd                               # h'' / h at the anchor
    h3 = Ta * (T2 + (1.0 + T2) * k)                         # h''' / h
    h4 = Ta * h3 + (1.0 + T2) * dd * (3.0 * T2 + k * (1.0 + 3.0 * T2))
    h = wk[PW_H] * (1.0 + st * (Ta + st * (0.5 * h2 + st * (_SIXTH * h3
                                                            + st * _24TH * h4))))
    dT = dd * st
    T = Ta + (1.0 + T2) * dT * (1.0 + Ta * dT + (1.0 + 3.0 * T2) * dT * dT * _THIRD)
    q = st * st
    cs = 1.0 - 0.5 * q * (1.0 - q * _12TH)
    sn = st * (1.0 - q * _SIXTH * (1.0 - q * _20TH))
    return wk[PW_C] * cs - wk[PW_S] * sn, wk[PW_S] * cs + wk[PW_C] * sn, h, T


@njit(cache=True, _nrt=False, error_model="numpy")
def _project_interval_warm(tab, off, n, x0, x1, ka, wk):
    """The projection of x when its normal lies in the smooth sample interval ka and x sees
    the whole interval (both ends visible): Halley's iteration on F(psi) = x.s_perp - h'
    from the last root kept in wk (if in this interval; else from the linear interpolation
    of F).  Within PW_STEP of the anchor kept in wk (an exactly evaluated point; and with the
    change of delta below PW_STEP) h, tan delta, cos psi and sin psi come from their Taylor
    series at the anchor (relative errors ~1e-16), farther away from an exact evaluation that
    becomes the anchor; so a projection near the last costs no transcendental function.
    Halley's error is ~K step^3 (K ~ 1 + (d delta / d psi)^2): a step with K step^3 < 1e-17
    is the last.  Returns (y0, y1, rr, ux, uy): y, |y| and y / |y|."""
    ra, rb, a, b = _ends(tab, off, n, ka)
    d = b - a
    dd = (tab[rb, 2] - tab[ra, 2]) / d
    kk = 1.0 + dd * dd
    tlo = 0.0
    thi = d
    if int(wk[PW_K]) == ka and wk[PW_H] > 0.0 and 0.0 < wk[PW_T] < d:
        t = wk[PW_R]
        if not 0.0 < t < d:
            t = wk[PW_T]
    else:
        ca, sa, cb, sb = tab[ra, 5], tab[ra, 6], tab[rb, 5], tab[rb, 6]
        Fa = -x0 * sa + x1 * ca - tab[ra, 4]
        Fb = -x0 * sb + x1 * cb - tab[rb, 4]
        t = d * Fa / (Fa - Fb) if Fa > Fb else 0.5 * d
        if not 0.0 < t < d:
            t = 0.5 * d
        _eval_point(tab, off, n, ka, t, wk)
    ta = wk[PW_T]
    c = s = h = T = 0.0
    last = False
    for _ in range(100):
        # the boundary data at t: Taylor series at the anchor, or exact (a new anchor)
        st = t - ta
        if abs(st) <= PW_STEP and abs(dd * st) <= PW_STEP:
            c, s, h, T = _taylor(wk, dd, st)
        else:
            _eval_point(tab, off, n, ka, t, wk)
            ta = t
            c, s, h, T = wk[PW_C], wk[PW_S], wk[PW_H], wk[PW_TDE]
        if last:
            break
        xs = x0 * c + x1 * s
        F = -x0 * s + x1 * c - h * T
        if F <= 0.0:
            thi = t
        else:
            tlo = t
        T2 = T * T
        dF = -xs - h * (T2 + (1.0 + T2) * dd)
        tn = 0.5 * (tlo + thi)
        halley = False
        if dF < 0.0:
            d2F = -(F + h * T) - h * T * (T2 + (1.0 + T2) * dd * (3.0 + 2.0 * dd))
            den = 2.0 * dF * dF - F * d2F
            cand = t - 2.0 * F * dF / den if den > 0.0 else t - F / dF
            if tlo < cand < thi:
                tn = cand
                halley = den > 0.0
        st = tn - t
        if abs(st) <= 4e-16 * (1.0 + abs(a + t)) or thi - tlo <= 4e-16 * (1.0 + abs(a + t)):
            break
        if halley and kk * st * st * abs(st) <= 1e-17:
            last = True                      # tn is the root: its boundary data, then stop
        t = tn
    wk[PW_R] = t
    hp = h * T
    y0 = h * c - hp * s
    y1 = h * s + hp * c
    rr = h * math.sqrt(1.0 + T * T)
    return y0, y1, rr, y0 / rr, y1 / rr


@njit(cache=True, _nrt=False, error_model="numpy")
def _bracket(tab, off, n, ka, x0, x1):
    """Where the projection's normal lies against the sample interval ka (both ends
    visible with a margin): 0 inside it, -1 before, +1 after, 2 unknown (an end not
    clearly visible)."""
    ra, rb, a, b = _ends(tab, off, n, ka)
    va = x0 * tab[ra, 5] + x1 * tab[ra, 6] - tab[ra, 3]
    vb = x0 * tab[rb, 5] + x1 * tab[rb, 6] - tab[rb, 3]
    if va <= 1e-12 * tab[ra, 3] or vb <= 1e-12 * tab[rb, 3]:
        return 2
    if -x0 * tab[ra, 6] + x1 * tab[ra, 5] - tab[ra, 4] <= 0.0:
        return -1
    if -x0 * tab[rb, 6] + x1 * tab[rb, 5] - tab[rb, 4] > 0.0:
        return 1
    return 0


@njit(cache=True, _nrt=False, error_model="numpy")
def support_project_warm(tab, off, n, x0, x1, wk):
    """:func:`support_project` for arguments near the last one (time steps, iterations):
    (y0, y1, inside, rr, ux, uy) with rr = |y| on the boundary (inside: rho at x's angle)
    and u = y / |y|.  ``wk`` (at least PW_SIZE,) keeps the warm start (PW_* columns; PW_K
    = -1 before the first call).  When x lies outside and the normal of its projection is
    in the kept interval or up to 3 intervals away (told by the signs of F at the ends, both
    clearly visible -- then x is outside and every normal in between is visible), the
    searches are skipped (:func:`_project_interval_warm`); otherwise the full search.
    Same projection as :func:`support_project` to ~1e-15."""
    k0 = int(wk[PW_K])
    if 0 <= k0 < n:
        ka = k0
        for _ in range(4):
            w = _bracket(tab, off, n, ka, x0, x1)
            if w == 2:
                break
            if w == 0:
                ra, rb, a, b = _ends(tab, off, n, ka)
                if b <= a:
                    break                               # a flat edge: the full path
                y0, y1, rr, ux, uy = _project_interval_warm(tab, off, n, x0, x1, ka, wk)
                return y0, y1, False, rr, ux, uy
            ka += w
            if ka < 0:
                ka = n - 1
            elif ka >= n:
                ka = 0
    y0, y1, inside, ka, t, phi, rr = support_project_full(tab, off, n, x0, x1)
    wk[PW_K] = ka
    wk[PW_T] = t
    wk[PW_H] = 0.0
    r = math.hypot(y0, y1)
    if r == 0.0:
        return y0, y1, inside, rr, 1.0, 0.0
    return y0, y1, inside, rr, y0 / r, y1 / r


@njit(cache=True, _nrt=False, error_model="numpy")
def support_radial_warm(tab, off, n, ux, uy, wk, dphi):
    """(rho, ok): the radial function of the convex set along the unit vector u from the
    warm start of the last projection (:func:`support_project_warm`): Newton on
    cross(y(psi), u) = 0 from the last root, the boundary data from the Taylor series at the
    kept anchor, started dphi / (1 + delta') away (dphi: the angle from the ray of the last
    root to u); the last step once below 1e-8 rad (quadratic convergence); ok False (rho 0)
    when that is not possible (no kept point, a flat edge, the ray outside the kept
    interval or beyond the series' reach): then ask :func:`support_radial`."""
    ka = int(wk[PW_K])
    if not (0 <= ka < n and wk[PW_H] > 0.0):
        return 0.0, False
    ra, rb, a, b = _ends(tab, off, n, ka)
    d = b - a
    if d <= 0.0:
        return 0.0, False
    dd = (tab[rb, 2] - tab[ra, 2]) / d
    ta = wk[PW_T]
    t = wk[PW_R] + dphi / (1.0 + dd)
    if not 0.0 <= t <= d:
        t = ta
    last = False
    for _ in range(8):
        st = t - ta
        if not (abs(st) <= PW_STEP and abs(dd * st) <= PW_STEP):
            return 0.0, False
        c, s, h, T = _taylor(wk, dd, st)
        T2 = T * T
        if last:
            return h * math.sqrt(1.0 + T2), True
        hp = h * T
        y0 = h * c - hp * s
        y1 = h * s + hp * c
        f = y0 * uy - y1 * ux                       # cross(y, u)
        g = h * (1.0 + T2 + (1.0 + T2) * dd)        # h + h'': dy/dpsi = g s_perp
        df = g * (-s * uy - c * ux)
        if df == 0.0 or y0 * ux + y1 * uy <= 0.0:
            return 0.0, False
        tn = t - f / df
        if not 0.0 <= tn <= d:
            return 0.0, False
        if abs(tn - t) <= 1e-15 * (1.0 + abs(a + t)):
            return h * math.sqrt(1.0 + T2), True
        last = abs(tn - t) <= 1e-8
        t = tn
    return 0.0, False


@njit(cache=True, _nrt=False, error_model="numpy")
def star_radial_dir(tab, off, n, ux, uy, k0):
    """(rho, k): radial function of the star-shaped polygon along the unit vector u and the
    edge k (from vertex k to k + 1) hit, found from edge k0 by a walk of up to 3 edges
    (cross products, no angle) or by :func:`star_radial_edge`'s search."""
    k = k0
    if 0 <= k < n:
        for _ in range(4):
            k1 = k + 1 if k + 1 < n else 0
            v0x = tab[off + k, 0]
            v0y = tab[off + k, 1]
            v1x = tab[off + k1, 0]
            v1y = tab[off + k1, 1]
            if v0x * uy - v0y * ux < 0.0:             # u before vertex k
                k = k - 1 if k > 0 else n - 1
            elif ux * v1y - uy * v1x <= 0.0:          # u at or after vertex k + 1
                k = k1
            else:
                dx = v1x - v0x
                dy = v1y - v0y
                return (v0x * dy - v0y * dx) / (ux * dy - uy * dx), k
    return star_radial_edge(tab, off, n, math.atan2(uy, ux))
