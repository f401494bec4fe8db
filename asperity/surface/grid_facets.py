"""The facets of a block of a height map, element by element: the arithmetic that
:func:`asperity.surface.facets.heightmap_facets` applies to a whole map and
:mod:`asperity.surface.tiles` to each tile, so that both give the same numbers.

A block ``z`` (``z[i, j]`` the height of pixel ``(i0 + i, j0 + j)`` of the map) has
``(R - 1) x (C - 1)`` cells; cell ``(i, j)`` is split along its (i+1, j)-(i, j+1) diagonal
into a *lower* triangle (i,j) (i+1,j) (i,j+1) and an *upper* triangle (i+1,j+1) (i,j+1)
(i+1,j).  Facet arrays hold the lower triangles of every cell (row-major) and then the
upper ones: ``2 nc`` entries, ``nc = (R - 1)(C - 1)``.
"""
from __future__ import annotations

import numpy as np

from ..errors import check_range


def corners(z: np.ndarray):
    """(z00, z10, z01, z11) views of the cell corners of block ``z``."""
    return z[:-1, :-1], z[1:, :-1], z[:-1, 1:], z[1:, 1:]


def cell_gradients(z: np.ndarray, dx: float, dy: float, g: np.ndarray) -> None:
    """Fill ``g`` (2, 2 nc) with the facet gradients (dz/dx, dz/dy); NaN where a corner is
    undefined."""
    z00, z10, z01, z11 = corners(z)
    nxm, nym = z.shape[0] - 1, z.shape[1] - 1
    nc = nxm * nym
    with np.errstate(invalid="ignore"):
        for row, d, pairs in ((0, dx, ((z10, z00), (z11, z01))), (1, dy, ((z01, z00), (z11, z10)))):
            for half, (p, q) in enumerate(pairs):
                out = g[row, half * nc:(half + 1) * nc].reshape(nxm, nym)
                np.subtract(p, q, out=out)
                out /= d


def centroid_heights(z: np.ndarray, zc: np.ndarray) -> None:
    """Fill ``zc`` (2 nc,) with the facets' centroid heights (mean of the three corners)."""
    z00, z10, z01, z11 = corners(z)
    nxm, nym = z.shape[0] - 1, z.shape[1] - 1
    nc = nxm * nym
    for half, (p, q, r) in enumerate(((z00, z10, z01), (z11, z01, z10))):
        out = zc[half * nc:(half + 1) * nc].reshape(nxm, nym)
        np.add(p, q, out=out)
        out += r
        out /= 3.0


def centroid_coordinate(nxm: int, nym: int, d: float, along: int, start: int) -> np.ndarray:
    """(2 nc,) centroid x (``along`` 0, spacing d, first cell index ``start``) or y
    (``along`` 1) of the facets of a block of nxm x nym cells."""
    nc = nxm * nym
    c = np.empty(2 * nc)
    n_along = nxm if along == 0 else nym
    for half, third in enumerate((1 / 3, 2 / 3)):
        k = (np.arange(start, start + n_along) + third) * d
        c[half * nc:(half + 1) * nc].reshape(nxm, nym)[...] = \
            k[:, None] if along == 0 else k[None, :]
    return c


def facet_mu(m: np.ndarray) -> np.ndarray:
    """(2 nc,) local friction of the facets of a per-pixel map block: the mean of each
    triangle's three corners."""
    a, b, c, d = m[:-1, :-1], m[1:, :-1], m[:-1, 1:], m[1:, 1:]
    return np.concatenate([((a + b + c) / 3).ravel(), ((d + c + b) / 3).ravel()])


def shear(zc: np.ndarray, a: float, b: float, x: np.ndarray, y: np.ndarray) -> None:
    """zc -= a x + b y, in place (the mean-slope removal applied to centroid heights)."""
    t = a * x
    t += b * y
    zc -= t


def contact_weight(area: np.ndarray, zc: np.ndarray, rest_level: float | None) -> np.ndarray:
    """Projected area x the spring model's contact weight ``max(zc - rest_level, 0)``
    (``area`` itself under a uniform preload, rest_level None)."""
    if rest_level is None:
        return area
    return area * np.maximum(zc - rest_level, 0.0)


def pressure_weight(area: np.ndarray, pc: np.ndarray) -> np.ndarray:
    """Each facet's normal force, N: projected area x ``pc``, the mean of the pressures
    (Pa) at its three corners (:func:`centroid_heights` of the node pressures), which is
    the integral over the triangle of the pressure interpolated linearly between the
    nodes.  Second order in the pixel size; taking one corner's pressure for the facet (a
    one-sided attribution) would shift the pressure field by a fraction of a pixel
    against the slopes, an error of first order.  ``pc`` is overwritten."""
    pc *= area
    return pc


def wrap_periodic(a: np.ndarray) -> np.ndarray:
    """(nx + 1, ny + 1) copy of a map that is one period, its first row and column repeated
    after the last: the cells across the map's edges become cells of the copy."""
    return np.pad(a, ((0, 1), (0, 1)), mode="wrap")


def rest_level_for_bearing(zc: np.ndarray, area: np.ndarray, fraction: float) -> float:
    """Rest level z0 such that the facets whose centroids lie above z0 hold ``fraction`` of
    the projected area (0 < fraction <= 1): z0 halfway between the lowest facet taken and
    the highest one left out (1: just below the lowest facet)."""
    fraction = check_range("bearing_fraction", fraction, 0.0, 1.0, low_open=True)
    order = np.argsort(zc, kind="stable")[::-1]
    z = zc[order]
    cum = np.cumsum(area[order])
    k = min(int(np.searchsorted(cum, fraction * cum[-1] * (1 - 1e-12))), z.size - 1)
    if k + 1 < z.size:
        return float(0.5 * (z[k] + z[k + 1]))
    return float(z[-1] - 1e-9 * max(z[0] - z[-1], abs(z[-1]), 1e-300))


def columns(gx: np.ndarray, gy: np.ndarray) -> np.ndarray:
    """(n, 2) view whose columns are ``gx`` and ``gy`` without copying either, when they
    are two rows of one (2, n) array; a copy otherwise."""
    if rows_of_one(gx, gy):
        return gx.base.T
    return np.stack([gx, gy]).T


def rows_of_one(gx: np.ndarray, gy: np.ndarray) -> bool:
    """``gx`` and ``gy`` are the two rows of one (2, n) array (what :func:`columns` views)."""
    base = gx.base
    return (base is not None and base is gy.base and base.ndim == 2
            and base.shape == (2, gx.size) and base.flags.c_contiguous
            and gx.ctypes.data == base.ctypes.data
            and gy.ctypes.data == base.ctypes.data + 8 * gx.size)
