"""Numba kernel of the spike filter (criterion and wrapper in :mod:`asperity.surface.quality`).

A Hampel identifier with the centre left out: for each defined pixel, the median ``m`` and
the median absolute deviation ``MAD`` of the defined pixels of its (2r+1) x (2r+1)
neighbourhood other than itself (clipped at the edges of the block); the robust scale is
``s = 1.4826 MAD``, raised to the smallest non-zero deviation of a neighbour from ``m``
(quantised data, where more than half the neighbours are equal, would give MAD = 0).  The
pixel is a spike when ``|z - m| > threshold * s``.  Pixels with fewer than
``min_neighbours`` defined neighbours, or with ``s = 0`` (every neighbour equal), are not
judged.  Decisions depend only on the raw heights inside the window, so a block with r
lines of halo gives the decisions of the whole map.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange


@njit(cache=True)
def _sort(v, n):
    """Insertion sort of v[:n] in place (n is at most a few dozen)."""
    for i in range(1, n):
        x = v[i]
        k = i - 1
        while k >= 0 and v[k] > x:
            v[k + 1] = v[k]
            k -= 1
        v[k + 1] = x


@njit(cache=True)
def _median(v, n):
    _sort(v, n)
    h = n // 2
    if n % 2 == 1:
        return v[h]
    return 0.5 * (v[h - 1] + v[h])


@njit(cache=True, parallel=True)
def find_spikes(z, r, threshold, min_neighbours, i0, i1, j0, j1, out):
    """out[i - i0, j - j0] = True where pixel (i, j) of ``z`` (rows i0..i1-1, columns
    j0..j1-1) is a spike (module docstring); False elsewhere.  NaN marks undefined."""
    nr, nc = z.shape
    w = 2 * r + 1
    for i in prange(i0, i1):
        buf = np.empty(w * w)
        dev = np.empty(w * w)
        for j in range(j0, j1):
            out[i - i0, j - j0] = False
            zc = z[i, j]
            if not math.isfinite(zc):
                continue
            n = 0
            for ii in range(max(0, i - r), min(nr, i + r + 1)):
                for jj in range(max(0, j - r), min(nc, j + r + 1)):
                    if ii == i and jj == j:
                        continue
                    v = z[ii, jj]
                    if math.isfinite(v):
                        buf[n] = v
                        n += 1
            if n < min_neighbours:
                continue
            m = _median(buf, n)
            floor = math.inf
            for k in range(n):
                d = abs(buf[k] - m)
                dev[k] = d
                if 0.0 < d < floor:
                    floor = d
            s = 1.4826 * _median(dev, n)
            if floor < math.inf and s < floor:
                s = floor
            if s > 0.0 and abs(zc - m) > threshold * s:
                out[i - i0, j - j0] = True
