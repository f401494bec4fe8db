"""Numba kernels of the streamed facet reservoir (physics in :mod:`asperity.friction.faces`,
wrapper and validation in :mod:`asperity.friction.facet_reservoir`).

Array-in/array-out loops, no validation, no Python objects.  Per facet the wrapper
stores ``gx, gy`` (gradient), ``a = 1/sqrt(1 + gx^2 + gy^2)``, ``mu`` and ``w`` (weight,
zero-weight facets removed; the wrapper maps indices back to the caller's facets).

For a sliding direction ``s = (c, s)`` and a facet, with ``slope = g.s`` and
``q = sqrt(1 + slope^2)``, the reference quantities of ``compute_face_reservoir`` are

    fz = a - mu slope / q,   hx = gx a + mu c / q,   hy = gy a + mu s / q .

Multiplying numerator and denominator by ``q`` gives, with ``D = a q - mu slope``,

    w hx / fz = w (gx a q + mu c) / D ,      fz <= LOCK_TOL  <=>  D <= LOCK_TOL q ,

one square root and one division per facet-direction.  The innermost loop (facets of a
cache-sized chunk, one direction) has no branches: the selects compile to masked vector
operations, and its sums are float64 vector accumulators (``reassoc``).  No ``contract``
flag: the decision quantities ``slope``, ``D`` are rounded exactly as written, so the
scalar re-scan that finds the first self-locking facet of a chunk (:func:`_first_locked`)
takes the same decisions as the vector sweep, and ``slope`` is bitwise the reference's
``gx*cos(psi) + gy*sin(psi)`` (same windward / level decisions).

``tol`` is LOCK_TOL, ``stol`` LEVEL_SLOPE_TOL.  Modes: ``MODE_ALL`` (all faces loaded),
``MODE_WINDWARD`` (faces with slope > stol), ``MODE_LEVEL`` (faces with |slope| <= stol,
the windward fallback).  Accumulator slots per
worker and direction (``acc[t, j, :]``): ``ACC_PX, ACC_PY`` (sums of w h / fz over loaded,
non-locking facets), ``ACC_W`` (sum of loaded weights, locking ones included), ``ACC_NLOCK``
(loaded self-locking facets), ``ACC_NLOAD`` (loaded facets), ``ACC_NSTEEP`` (loaded facets
with |g| > stol, level mode only).  Counts are exact float64 integers.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

MODE_ALL = 0
MODE_WINDWARD = 1
MODE_LEVEL = 2

ACC_PX, ACC_PY, ACC_W, ACC_NLOCK, ACC_NLOAD, ACC_NSTEEP = range(6)
N_ACC = 6

#: reassociation for the vectorised sums; no 'contract' (see the module docstring), no
#: 'nnan'/'ninf' (the lock comparisons must stay exact)
FASTMATH = {"reassoc", "nsz", "arcp"}


@njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def _sweep_all(gx, gy, a, mu, w, c, s, tol, stol):
    """(sum w hx/fz, sum w hy/fz, non-locking count) over the facets given, all loaded."""
    px = 0.0
    py = 0.0
    nok = 0.0
    for i in range(gx.size):
        g1 = gx[i]
        g2 = gy[i]
        m = mu[i]
        wi = w[i]
        sl = g1 * c + g2 * s
        q = math.sqrt(1.0 + sl * sl)
        aq = a[i] * q
        d = aq - m * sl
        ok = d > tol * q
        inv = wi / d if ok else 0.0
        px += inv * (g1 * aq + m * c)
        py += inv * (g2 * aq + m * s)
        nok += 1.0 if ok else 0.0
    return px, py, nok


@njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def _sweep_all_mu(gx, gy, a, m, w, c, s, tol, stol):
    """:func:`_sweep_all` with one friction coefficient ``m`` for every facet."""
    px = 0.0
    py = 0.0
    nok = 0.0
    mc = m * c
    ms = m * s
    for i in range(gx.size):
        g1 = gx[i]
        g2 = gy[i]
        wi = w[i]
        sl = g1 * c + g2 * s
        q = math.sqrt(1.0 + sl * sl)
        aq = a[i] * q
        d = aq - m * sl
        ok = d > tol * q
        inv = wi / d if ok else 0.0
        px += inv * (g1 * aq + mc)
        py += inv * (g2 * aq + ms)
        nok += 1.0 if ok else 0.0
    return px, py, nok


@njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def _sweep_windward(gx, gy, a, mu, w, c, s, tol, stol):
    """(sum w hx/fz, sum w hy/fz, sum w, non-locking count, windward count), windward."""
    px = 0.0
    py = 0.0
    ww = 0.0
    nok = 0.0
    nw = 0.0
    for i in range(gx.size):
        g1 = gx[i]
        g2 = gy[i]
        m = mu[i]
        wi = w[i]
        sl = g1 * c + g2 * s
        q = math.sqrt(1.0 + sl * sl)
        aq = a[i] * q
        d = aq - m * sl
        wind = sl > stol
        # not windward: threshold +inf, never "ok" (d is finite); a select, not a branch
        ok = d > (tol * q if wind else math.inf)
        inv = wi / d if ok else 0.0
        px += inv * (g1 * aq + m * c)
        py += inv * (g2 * aq + m * s)
        fw = 1.0 if wind else 0.0
        ww += wi * fw
        nw += fw
        nok += 1.0 if ok else 0.0
    return px, py, ww, nok, nw


@njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def _sweep_windward_mu(gx, gy, a, m, w, c, s, tol, stol):
    """:func:`_sweep_windward` with one friction coefficient ``m`` for every facet."""
    px = 0.0
    py = 0.0
    ww = 0.0
    nok = 0.0
    nw = 0.0
    mc = m * c
    ms = m * s
    for i in range(gx.size):
        g1 = gx[i]
        g2 = gy[i]
        wi = w[i]
        sl = g1 * c + g2 * s
        q = math.sqrt(1.0 + sl * sl)
        aq = a[i] * q
        d = aq - m * sl
        wind = sl > stol
        # not windward: threshold +inf, never "ok" (d is finite); a select, not a branch
        ok = d > (tol * q if wind else math.inf)
        inv = wi / d if ok else 0.0
        px += inv * (g1 * aq + mc)
        py += inv * (g2 * aq + ms)
        fw = 1.0 if wind else 0.0
        ww += wi * fw
        nw += fw
        nok += 1.0 if ok else 0.0
    return px, py, ww, nok, nw


@njit(cache=True, error_model="numpy")
def _sweep_level(gx, gy, a, mu, mu_uniform, w, lo, hi, c, s, tol, stol):
    """Level-face sums (windward fallback; rare, so plain scalar code with branches):
    (sum w hx/fz, sum w hy/fz, sum w, non-locking count, level count, steep level count)."""
    px = 0.0
    py = 0.0
    ww = 0.0
    nok = 0.0
    nl = 0.0
    nsteep = 0.0
    for i in range(lo, hi):
        g1 = gx[i]
        g2 = gy[i]
        sl = g1 * c + g2 * s
        if abs(sl) > stol:
            continue
        m = mu[0] if mu_uniform else mu[i]
        wi = w[i]
        q = math.sqrt(1.0 + sl * sl)
        aq = a[i] * q
        d = aq - m * sl
        nl += 1.0
        ww += wi
        if math.hypot(g1, g2) > stol:
            nsteep += 1.0
        if d > tol * q:
            nok += 1.0
            inv = wi / d
            px += inv * (g1 * aq + m * c)
            py += inv * (g2 * aq + m * s)
    return px, py, ww, nok, nl, nsteep


@njit(cache=True, error_model="numpy")
def _first_locked(gx, gy, a, mu, mu_uniform, lo, hi, c, s, tol, stol, mode):
    """Index of the first loaded self-locking facet in lo..hi-1 (-1: none).

    Same arithmetic as the sweeps (no contraction), hence the same decisions."""
    for i in range(lo, hi):
        m = mu[0] if mu_uniform else mu[i]
        sl = gx[i] * c + gy[i] * s
        if mode == MODE_WINDWARD and not sl > stol:
            continue
        if mode == MODE_LEVEL and abs(sl) > stol:
            continue
        q = math.sqrt(1.0 + sl * sl)
        d = a[i] * q - m * sl
        if not d > tol * q:
            return i
    return -1


@njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def facet_sweep(gx, gy, a, mu, mu_uniform, w, cs, ss, mode, tol, stol,
                f0, f1, d0, d1, chunk, acc, first):
    """Accumulate the reservoir sums of directions (cs, ss) into ``acc``/``first``.

    Worker ``t`` (one per thread, ``prange``) handles facets ``f0[t]..f1[t]-1`` and
    directions ``d0[t]..d1[t]-1``: facets in chunks of ``chunk`` (kept in cache), every
    direction over each chunk.  ``acc[t, j, :]`` (zeroed by the caller) receives the
    sums (slots ``ACC_*``), ``first[t, j]`` (-1 on entry) the index of the first
    loaded self-locking facet met by worker t.  Workers own increasing facet ranges, so the
    first worker with ``first >= 0`` holds the overall first.  ``mu`` has one element when
    ``mu_uniform``.
    """
    nw = f0.size
    for t in prange(nw):
        lo = f0[t]
        while lo < f1[t]:
            hi = min(lo + chunk, f1[t])
            for j in range(d0[t], d1[t]):
                c = cs[j]
                s = ss[j]
                nlock = 0.0
                if mode == MODE_ALL:
                    if mu_uniform:
                        px, py, nok = _sweep_all_mu(gx[lo:hi], gy[lo:hi], a[lo:hi], mu[0],
                                                     w[lo:hi], c, s, tol, stol)
                    else:
                        px, py, nok = _sweep_all(gx[lo:hi], gy[lo:hi], a[lo:hi], mu[lo:hi],
                                                  w[lo:hi], c, s, tol, stol)
                    acc[t, j, ACC_PX] += px
                    acc[t, j, ACC_PY] += py
                    nlock = (hi - lo) - nok
                    acc[t, j, ACC_NLOAD] += hi - lo
                elif mode == MODE_WINDWARD:
                    if mu_uniform:
                        px, py, ww, nok, nwind = _sweep_windward_mu(
                            gx[lo:hi], gy[lo:hi], a[lo:hi], mu[0], w[lo:hi], c, s, tol, stol)
                    else:
                        px, py, ww, nok, nwind = _sweep_windward(
                            gx[lo:hi], gy[lo:hi], a[lo:hi], mu[lo:hi], w[lo:hi], c, s, tol, stol)
                    acc[t, j, ACC_PX] += px
                    acc[t, j, ACC_PY] += py
                    acc[t, j, ACC_W] += ww
                    acc[t, j, ACC_NLOAD] += nwind
                    nlock = nwind - nok
                else:
                    px, py, ww, nok, nlev, nst = _sweep_level(gx, gy, a, mu, mu_uniform, w,
                                                              lo, hi, c, s, tol, stol)
                    acc[t, j, ACC_PX] += px
                    acc[t, j, ACC_PY] += py
                    acc[t, j, ACC_W] += ww
                    acc[t, j, ACC_NLOAD] += nlev
                    acc[t, j, ACC_NSTEEP] += nst
                    nlock = nlev - nok
                if nlock > 0.0:
                    acc[t, j, ACC_NLOCK] += nlock
                    if first[t, j] < 0:
                        i = _first_locked(gx, gy, a, mu, mu_uniform, lo, hi, c, s, tol, stol,
                                          mode)
                        if i >= 0:
                            first[t, j] = i
            lo = hi


@njit(cache=True, parallel=True, error_model="numpy")
def prepare(gx, gy, mu, w, a, mu_max):
    """Fill ``a = 1/sqrt(1 + gx*gx + gy*gy)`` (rounded as the NumPy reference) and count
    (non-finite gradients, bad mu (not in [0, mu_max]), bad weights (non-finite or < 0),
    positive weights).  ``mu`` has one element or n."""
    n = gx.size
    bad_g = 0
    bad_w = 0
    npos = 0
    for i in prange(n):
        g1 = gx[i]
        g2 = gy[i]
        wi = w[i]
        if not (math.isfinite(g1) and math.isfinite(g2)):
            bad_g += 1
        if not (math.isfinite(wi) and wi >= 0.0):
            bad_w += 1
        if wi > 0.0:
            npos += 1
        a[i] = 1.0 / math.sqrt(1.0 + g1 * g1 + g2 * g2)
    bad_mu = 0
    for i in prange(mu.size):
        m = mu[i]
        if not (m >= 0.0 and m <= mu_max):
            bad_mu += 1
    return bad_g, bad_mu, bad_w, npos


@njit(cache=True, parallel=True, fastmath={"reassoc", "nsz", "arcp"}, error_model="numpy")
def locked_weight(gx, gy, mu, mu_uniform, w, cs, ss, windward, tol, stol):
    """Per direction j: (weight of the loaded facets that cannot be climbed, loaded weight),
    with the reference's test ``1/|n| - mu slope / sqrt(1 + slope^2) <= tol``; windward:
    only facets with slope > stol are loaded.  Parallel over directions."""
    m = cs.shape[0]
    out = np.zeros((m, 2))
    for j in prange(m):
        c = cs[j]
        s = ss[j]
        lw = 0.0
        tw = 0.0
        for i in range(gx.size):
            slope = gx[i] * c + gy[i] * s
            mi = mu[0] if mu_uniform else mu[i]
            fz = 1.0 / math.sqrt(1.0 + gx[i] * gx[i] + gy[i] * gy[i]) \
                - mi * slope / math.sqrt(1.0 + slope * slope)
            wl = w[i] if (slope > stol or not windward) else 0.0
            tw += wl
            lw += wl if fz <= tol else 0.0
        out[j, 0] = lw
        out[j, 1] = tw
    return out
