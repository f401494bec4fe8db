"""The spike filter (README "Data quality") against a Hampel filter written here in plain
NumPy from the README's words alone: the centre left out of its W x W window, the median
of the other defined pixels, robust standard deviation 1.4826 x their median absolute
deviation (at least the smallest non-zero deviation), a spike further than K of them from
the median, and pixels with fewer than W defined neighbours not judged.  The flagged sets
must be identical on random maps with dropouts and planted spikes, for several W and K;
and maps built so that a spike's only evidence lies in the outermost row or column of its
window find a window one row or column short."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from numpy.lib.stride_tricks import sliding_window_view

from asperity.surface.quality import find_spikes


def hampel_numpy(z: np.ndarray, window: int, k: float) -> np.ndarray:
    """The README's spike filter, one pixel's window per row of a (pixels, W*W) array."""
    r = window // 2
    n0, n1 = z.shape
    pad = np.pad(z, r, constant_values=np.nan)
    nb = sliding_window_view(pad, (window, window)).reshape(n0, n1, window * window).copy()
    nb[:, :, (window * window) // 2] = np.nan                 # the centre left out
    count = np.isfinite(nb).sum(axis=2)
    with warnings.catch_warnings():                           # all-NaN windows: not judged
        warnings.simplefilter("ignore", RuntimeWarning)
        med = np.nanmedian(nb, axis=2)
        dev = np.abs(nb - med[:, :, None])
        s = 1.4826 * np.nanmedian(dev, axis=2)
        floor = np.nanmin(np.where(dev > 0, dev, np.nan), axis=2)
    s = np.where(np.isfinite(floor) & (s < floor), floor, s)
    judged = np.isfinite(z) & (count >= window) & (s > 0)
    with np.errstate(invalid="ignore"):
        return judged & (np.abs(z - med) > k * s)


def spiky_map(seed: int, n0: int = 70, n1: int = 55) -> np.ndarray:
    """Rough heights (correlated noise on a tilt, quantised levels in one corner), 2 %
    dropouts (75 % in the opposite corner: pixels with about W defined neighbours), 25
    planted spikes of 2 to 30 standard deviations."""
    rng = np.random.default_rng(seed)
    z = rng.normal(size=(n0, n1))
    z = 0.5 * z + 0.25 * (np.roll(z, 1, 0) + np.roll(z, 1, 1)) + 0.02 * np.arange(n1)
    z[:12, :12] = np.round(z[:12, :12] * 2) / 2                 # quantised: MAD often 0
    z[rng.random(z.shape) < 0.02] = np.nan
    z[-20:, -20:][rng.random((20, 20)) < 0.75] = np.nan        # sparse: few neighbours
    free = np.flatnonzero(np.isfinite(z).ravel())
    spikes = rng.choice(free, 25, replace=False)
    z.ravel()[spikes] += rng.choice([-1.0, 1.0], 25) * rng.uniform(2.0, 30.0, 25)
    return z


@pytest.mark.parametrize("window", [3, 5, 7, 11])
@pytest.mark.parametrize("k", [2.0, 4.0, 8.0])
def test_flagged_sets_equal_an_independent_numpy_hampel_filter(window, k):
    for seed in range(3):
        z = spiky_map(100 * window + seed)
        ref = hampel_numpy(z, window, k)
        got = find_spikes(z, (k, window))
        assert ref.any() and not ref.all()
        diff = np.argwhere(got != ref)
        assert diff.size == 0, f"W {window}, K {k}, seed {seed}: differ at {diff[:5].tolist()}"


@pytest.mark.parametrize("window", [3, 5, 9])
def test_evidence_only_in_the_outermost_row_or_column_of_the_window(window):
    """A spike whose defined neighbours all lie in one outermost row or column of its
    window (one map per side): judged and flagged; a window one short on that side sees
    too few neighbours and flags nothing.  With one of those W neighbours undefined it is
    not judged (fewer than W)."""
    r = window // 2
    for side in ("bottom", "top", "right", "left"):
        z = np.full((4 * window, 4 * window), np.nan)
        i = j = 2 * window
        z[i, j] = 100.0
        edge = np.arange(-r, r + 1, dtype=float)               # W neighbours, spread +-r
        if side == "bottom":
            z[i + r, j - r:j + r + 1] = edge
        elif side == "top":
            z[i - r, j - r:j + r + 1] = edge
        elif side == "right":
            z[i - r:i + r + 1, j + r] = edge
        else:
            z[i - r:i + r + 1, j - r] = edge
        ref = hampel_numpy(z, window, 6.0)
        assert ref[i, j], side                                  # the reference judges it
        got = find_spikes(z, (6.0, window))
        np.testing.assert_array_equal(got, ref, err_msg=f"{side} side, W {window}")
        # one of the W neighbours undefined: W - 1 left, the pixel is not judged
        z[np.isfinite(z) & (z != 100.0) & (z == -r)] = np.nan
        assert not hampel_numpy(z, window, 6.0)[i, j]
        np.testing.assert_array_equal(find_spikes(z, (6.0, window)), hampel_numpy(z, window, 6.0),
                                      err_msg=f"{side} side, W {window}, W - 1 neighbours")
