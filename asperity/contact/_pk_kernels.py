"""Numba kernels of the Polonsky-Keer iteration (the algorithm and its wrapper in
:mod:`asperity.contact.solver`).

Each kernel is one pass over the pixels that fuses what NumPy would do in several
expressions with temporaries: the solver's memory is its arrays (heights, pressure,
displacement, direction, the product K t, the preconditioned gap M g) and the transform's
buffers, nothing else.

Pixel classes, read from the pressure p and the cap H (``inf`` without hardness):
undefined (the height is NaN: p stays 0), out of contact (p = 0), the *free* set
(0 < p < H: the conjugate-gradient unknowns, where the gap must vanish) and the plastic
set (p = H).  The gap at the start of an iteration is g = u - h - gbar, gbar the mean of
u - h over the free set (the gap mean shift: it fixes the rigid-body approach).

Serial loops: the sums do not depend on the number of threads.
"""
from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def gap_sums(u, h, p, H, c):
    """Over the free set: (sum of u - h - c, sum of (u - h - c)^2, count); also the
    numbers of contact and plastic pixels.  ``c`` (the previous mean gap) keeps the
    squares well conditioned: G = S2 - n (gbar - c)^2."""
    s1 = 0.0
    s2 = 0.0
    n = 0
    nc = 0
    npl = 0
    for i in range(p.size):
        hi = h[i]
        if hi != hi:
            continue
        pi = p[i]
        if pi > 0.0:
            nc += 1
            if pi < H:
                g = u[i] - hi - c
                s1 += g
                s2 += g * g
                n += 1
            else:
                npl += 1
    return s1, s2, n, nc, npl


@njit(cache=True)
def direction(u, h, p, t, H, gbar, beta):
    """t = g + beta t on the free set, 0 elsewhere (g = u - h - gbar); returns sum g t
    (G when the previous step ended on a line minimum of an unchanged set)."""
    sgt = 0.0
    for i in range(p.size):
        pi = p[i]
        hi = h[i]
        if hi == hi and 0.0 < pi < H:
            g = u[i] - hi - gbar
            ti = g + beta * t[i]
            t[i] = ti
            sgt += g * ti
        else:
            t[i] = 0.0
    return sgt


@njit(cache=True)
def step_sums(u, h, p, t, r, H, gbar):
    """Over the free set: sums of r, r t, t and g t (the step length of the iteration:
    tau = sum g t / sum (r - rbar) t, rbar the mean of r over the free set)."""
    sr = 0.0
    srt = 0.0
    st = 0.0
    sgt = 0.0
    for i in range(p.size):
        pi = p[i]
        hi = h[i]
        if hi == hi and 0.0 < pi < H:
            ti = t[i]
            ri = r[i]
            sr += ri
            srt += ri * ti
            st += ti
            sgt += (u[i] - hi - gbar) * ti
    return sr, srt, st, sgt


@njit(cache=True)
def update(u, h, p, t, r, H, gbar, tau, z):
    """The pressure step: p -= tau t on the free set; out of contact where the gap is
    negative (overlap) and plastic where it is positive (release): p -= tau g; then p
    clipped to [0, H].  u becomes u - tau r (exact K p when nothing was clipped or moved
    off the line), r keeps the old pressure (for the change of the iteration).  Returns
    (the sum of p, the number of pixels clipped, the number moved by the gap).  With the
    preconditioner, ``z`` (M g) moves those pixels instead of g (``z`` of size 0: g)."""
    pre = z.size > 0
    total = 0.0
    clipped = 0
    moved = 0
    for i in range(p.size):
        hi = h[i]
        ri = r[i]
        pi = p[i]
        r[i] = pi
        if hi != hi:
            u[i] -= tau * ri
            continue
        if 0.0 < pi < H:
            q = pi - tau * t[i]
        else:
            g = u[i] - hi - gbar
            if (pi <= 0.0 and g < 0.0) or (pi >= H and g > 0.0):
                q = pi - tau * (z[i] if pre else g)
                moved += 1
            else:
                q = pi
        u[i] -= tau * ri
        if q < 0.0:
            q = 0.0
            clipped += 1
        elif q > H:
            q = H
            clipped += 1
        p[i] = q
        total += q
    return total, clipped, moved


@njit(cache=True)
def load_sums(p, H):
    """(sum of the pixels below H, number of pixels at H)."""
    f = 0.0
    n = 0
    for i in range(p.size):
        pi = p[i]
        if pi < H:
            f += pi
        else:
            n += 1
    return f, n


@njit(cache=True)
def capped_sums(p, s, H, fixed):
    """sum of min(s p, H) (the pixels at H kept at H when ``fixed``) and the sum of the p
    not capped (the slope in s)."""
    f = 0.0
    df = 0.0
    for i in range(p.size):
        pi = p[i]
        if fixed and pi >= H:
            f += H
            continue
        q = s * pi
        if q < H:
            f += q
            df += pi
        else:
            f += H
    return f, df


@njit(cache=True)
def rescale(p, u, old, s, H, scale_u, fixed):
    """p = min(s p, H) (the pixels at H kept when ``fixed``); u *= s when ``scale_u``;
    returns (sum |p - old|, sum p, number capped by the scaling)."""
    change = 0.0
    total = 0.0
    capped = 0
    for i in range(p.size):
        q = p[i]
        if not (fixed and q >= H):
            q *= s
            if q > H:
                q = H
                capped += 1
            p[i] = q
        total += q
        change += abs(q - old[i])
        if scale_u:
            u[i] *= s
    return change, total, capped


@njit(cache=True)
def final_fields(u, h, p, gap, d):
    """gap = max(u - h + d, 0), 0 in contact, NaN on undefined pixels; p NaN there too.
    Returns (sum of the gap, largest penetration out of contact, count in contact)."""
    total = 0.0
    pen = 0.0
    nc = 0
    for i in range(p.size):
        hi = h[i]
        if hi != hi:
            gap[i] = math.nan
            p[i] = math.nan
            continue
        if p[i] > 0.0:
            gap[i] = 0.0
            nc += 1
            continue
        g = u[i] - hi + d
        if g < 0.0:
            if -g > pen:
                pen = -g
            g = 0.0
        gap[i] = g
        total += g
    return total, pen, nc


@njit(cache=True)
def gap_violation(u, h, p, H, gbar):
    """The complementarity of a solution, from the gap g = u - h - gbar: the largest |g|
    over the free set (0 < p < H, where g must vanish), the largest g over the plastic
    pixels (p >= H, where g > 0 means a pixel at the hardness off the half-space) and the
    largest -g out of contact (p = 0, where g < 0 means a pixel through the half-space)."""
    free = 0.0
    plastic = 0.0
    pen = 0.0
    for i in range(p.size):
        hi = h[i]
        if hi != hi:
            continue
        pi = p[i]
        g = u[i] - hi - gbar
        if pi <= 0.0:
            pen = max(pen, -g)
        elif pi < H:
            free = max(free, abs(g))
        else:
            plastic = max(plastic, g)
    return free, plastic, pen


@njit(cache=True)
def masked_gap(u, h, p, H, gbar, w):
    """w = g = u - h - gbar on the free set and on the pixels the gap moves (out of
    contact with g < 0, plastic with g > 0), 0 elsewhere: the input of the
    preconditioner."""
    for i in range(p.size):
        hi = h[i]
        w[i] = 0.0
        if hi != hi:
            continue
        pi = p[i]
        g = u[i] - hi - gbar
        if 0.0 < pi < H or (pi <= 0.0 and g < 0.0) or (pi >= H and g > 0.0):
            w[i] = g


@njit(cache=True)
def precond_sum(u, h, p, z, H, gbar):
    """Over the free set: sum of g z (g = u - h - gbar, z = M g)."""
    sgz = 0.0
    for i in range(p.size):
        pi = p[i]
        hi = h[i]
        if hi == hi and 0.0 < pi < H:
            sgz += (u[i] - hi - gbar) * z[i]
    return sgz


@njit(cache=True)
def precond_direction(u, h, p, t, z, H, gbar, beta):
    """t = z + beta t on the free set, 0 elsewhere; returns sum g t."""
    sgt = 0.0
    for i in range(p.size):
        pi = p[i]
        hi = h[i]
        if hi == hi and 0.0 < pi < H:
            g = u[i] - hi - gbar
            ti = z[i] + beta * t[i]
            t[i] = ti
            sgt += g * ti
        else:
            t[i] = 0.0
    return sgt
