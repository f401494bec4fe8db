"""Instrument artefacts: spikes marked undefined, facets steeper than the instrument can
measure dropped, and the figures of what was removed.

* **Spike filter** (``despike``): a pixel is a spike when it lies further than
  ``threshold`` robust standard deviations from the median of its ``window`` x ``window``
  neighbourhood (itself left out; robust standard deviation 1.4826 x the neighbours'
  median absolute deviation from that median, at least the smallest non-zero deviation).
  Spikes become undefined pixels, like the instrument's dropouts, before the form is
  removed.  Only isolated outliers are found: a group of outliers larger than half the
  window is a feature.  Pixels with fewer than ``window`` defined neighbours are not
  judged (the edges of dropouts).  Kernel: :mod:`._spike_kernels`.
* **Maximum slope** (``max_slope``, degrees): facets whose slope (after form and tilt
  removal) exceeds it are dropped; their number and their share of the load are reported.
* **Locking limit**: a facet of slope ``atan |g|`` and local friction ``mu`` can be
  self-locking (for the sliding direction up its gradient) only when ``mu |g| >= 1``.
  :func:`locking_limit_deg` is the largest slope, on a 0.01 deg step, below
  ``atan(1 / largest mu)``: ``max_slope`` at that value gives a finite law.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_int, check_range

#: default and allowed window of the spike filter (pixels, odd)
DESPIKE_WINDOW = 5
DESPIKE_WINDOWS = (3, 15)
#: allowed threshold of the spike filter (robust standard deviations)
DESPIKE_THRESHOLDS = (2.0, 1e6)
#: allowed --max-slope (degrees)
MAX_SLOPE_RANGE = (0.0, 90.0)
#: step of the suggested --max-slope (degrees)
LIMIT_STEP_DEG = 0.01
#: pixels judged per piece of the spike filter (Ctrl-C between pieces)
_SPIKE_PIECE = 1 << 20
#: facets per piece of the slope figures (bounded temporaries)
_PIECE = 1 << 20


def check_despike(threshold, window=None) -> tuple[float, int] | None:
    """(threshold, window) of the spike filter, or None when ``threshold`` is None."""
    if threshold is None:
        if window is not None:
            raise InputError("despike_window needs despike (the filter's threshold)")
        return None
    t = check_range("despike", threshold, *DESPIKE_THRESHOLDS)
    w = check_int("despike_window", DESPIKE_WINDOW if window is None else window,
                  *DESPIKE_WINDOWS)
    if w % 2 == 0:
        raise InputError(f"despike_window must be an odd whole number in "
                         f"[{DESPIKE_WINDOWS[0]}, {DESPIKE_WINDOWS[1]}], got {w}")
    return (t, w)


def check_max_slope(max_slope) -> float | None:
    if max_slope is None:
        return None
    return check_range("max_slope", max_slope, *MAX_SLOPE_RANGE, low_open=True,
                       high_open=True, unit="deg")


def slope_limit2(max_slope_deg: float) -> float:
    """tan^2 of a slope angle: a facet is steeper when gx^2 + gy^2 exceeds it."""
    t = math.tan(math.radians(max_slope_deg))
    return t * t


def find_spikes(z: np.ndarray, despike, rows=None, cols=None) -> np.ndarray:
    """Boolean mask of the spikes of ``z`` among rows ``rows = (i0, i1)`` and columns
    ``cols`` (default: all), judged on the raw heights of ``z`` (module docstring)."""
    from ._spike_kernels import find_spikes as kernel
    threshold, window = despike
    i0, i1 = rows if rows is not None else (0, z.shape[0])
    j0, j1 = cols if cols is not None else (0, z.shape[1])
    z = np.ascontiguousarray(z, dtype=np.float64)
    out = np.zeros((i1 - i0, j1 - j0), dtype=bool)
    per = max(1, _SPIKE_PIECE // max(1, j1 - j0))
    for a in range(0, i1 - i0, per):
        b = min(i1 - i0, a + per)
        kernel(z, window // 2, float(threshold), window, i0 + a, i0 + b, j0, j1, out[a:b])
    return out


def remove_spikes(z: np.ndarray, despike) -> int:
    """Mark the spikes of the whole map ``z`` undefined (NaN, in place); their number."""
    mask = find_spikes(z, despike)
    z[mask] = np.nan
    return int(np.count_nonzero(mask))


def locking_limit_deg(mu_max: float) -> float:
    """The largest slope (deg, a multiple of LIMIT_STEP_DEG) strictly below
    atan(1 / mu_max): no facet that gentle self-locks (90 for mu_max = 0)."""
    if not mu_max > 0:
        return 90.0
    lim = math.degrees(math.atan(1.0 / mu_max))
    k = math.floor(lim / LIMIT_STEP_DEG - 1e-9)
    if k * LIMIT_STEP_DEG >= lim:
        k -= 1
    return round(max(k, 0) * LIMIT_STEP_DEG, 2)


class SlopeStats:
    """Slopes of the facets, accumulated in pieces: the steepest, and the facets above the
    locking limit (count and weight); ``total_weight`` of the facets before any drop."""

    def __init__(self, limit_deg: float):
        self.limit_deg = limit_deg
        self.limit2 = slope_limit2(limit_deg) if limit_deg < 90 else math.inf
        self.max_g2 = 0.0
        self.above = 0
        self.above_weight = 0.0
        self.dropped = 0
        self.dropped_weight = 0.0
        self.total_weight = 0.0

    def add_kept(self, g2: np.ndarray, w: np.ndarray) -> None:
        if g2.size:
            self.max_g2 = max(self.max_g2, float(g2.max()))
        hi = g2 > self.limit2
        self.above += int(np.count_nonzero(hi))
        self.above_weight += float(w[hi].sum())

    def add_dropped(self, n: int, weight: float) -> None:
        self.dropped += int(n)
        self.dropped_weight += float(weight)

    def merge(self, other: "SlopeStats") -> None:
        self.max_g2 = max(self.max_g2, other.max_g2)
        self.above += other.above
        self.above_weight += other.above_weight
        self.dropped += other.dropped
        self.dropped_weight += other.dropped_weight
        self.total_weight += other.total_weight


def quality_stats(*, pixels, undefined, despike, spikes, max_slope, mu_max,
                  stats: SlopeStats) -> dict:
    """The surface's share of the data_quality block (the derivation adds the rest)."""
    tw = stats.total_weight if stats.total_weight > 0 else 1.0
    return {
        "pixels": None if pixels is None else int(pixels),
        "undefined_pixels": int(undefined),
        "undefined_share": float(undefined / pixels) if pixels else 0.0,
        "spike_filter": None if despike is None else {"threshold": float(despike[0]),
                                                      "window": int(despike[1])},
        "spikes_removed": int(spikes),
        "max_slope_deg": max_slope,
        "facets_dropped_by_slope": stats.dropped,
        "dropped_load_share": stats.dropped_weight / tw,
        "steepest_facet_deg": math.degrees(math.atan(math.sqrt(stats.max_g2))),
        "largest_mu": float(mu_max),
        "locking_limit_deg": stats.limit_deg,
        "facets_above_locking_limit": stats.above,
        "load_share_above_locking_limit": stats.above_weight / tw,
    }


def _g2(gx, gy, a, b):
    g2 = gx[a:b] * gx[a:b]
    g2 += gy[a:b] * gy[a:b]
    return g2


def steep_facets(gx: np.ndarray, gy: np.ndarray, max_slope) -> np.ndarray | None:
    """Mask of the facets steeper than ``max_slope`` (deg); None when none is (or no
    max_slope).  Same arithmetic for a whole map and for its tiles."""
    if max_slope is None:
        return None
    lim2 = slope_limit2(max_slope)
    steep = None
    for a in range(0, gx.size, _PIECE):
        b = min(gx.size, a + _PIECE)
        s = _g2(gx, gy, a, b) > lim2
        if s.any():
            if steep is None:
                steep = np.zeros(gx.size, dtype=bool)
            steep[a:b] = s
    return steep


def add_slopes(stats: SlopeStats, gx: np.ndarray, gy: np.ndarray, w: np.ndarray,
               steep: np.ndarray | None) -> None:
    """Add facets (gradients, weights) to ``stats``: those in ``steep`` as dropped."""
    stats.total_weight += float(w.sum())
    for a in range(0, gx.size, _PIECE):
        b = min(gx.size, a + _PIECE)
        g2, wa = _g2(gx, gy, a, b), w[a:b]
        if steep is not None:
            s = steep[a:b]
            stats.add_dropped(np.count_nonzero(s), wa[s].sum())
            g2, wa = g2[~s], wa[~s]
        stats.add_kept(g2, wa)
