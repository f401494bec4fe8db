"""Small height arrays of a surface for plots (the facets keep one beside them)."""
from __future__ import annotations

import math

import numpy as np


def preview_step(shape, size: int = 256) -> int:
    """Every how many pixels a preview of a map of ``shape`` keeps one (at most ``size``
    per side): the in-memory and the tiled previews use the same."""
    return max(1, int(math.ceil(max(shape) / size)))


def height_preview(z: np.ndarray, size: int = 256) -> np.ndarray:
    step = preview_step(z.shape, size)
    return np.array(z[::step, ::step], dtype=float)


def mesh_preview(p0, p1, p2, lo, hi, size: int = 160) -> np.ndarray:
    """Centroid heights binned on a small grid (mean per bin; NaN where empty)."""
    c = (p0 + p1 + p2) / 3.0
    span = np.maximum(hi - lo, 1e-300)
    nx = size
    ny = max(2, int(round(size * span[1] / span[0]))) if span[0] > 0 else size
    ix = np.clip(((c[:, 0] - lo[0]) / span[0] * nx).astype(int), 0, nx - 1)
    iy = np.clip(((c[:, 1] - lo[1]) / span[1] * ny).astype(int), 0, ny - 1)
    s = np.zeros((nx, ny))
    k = np.zeros((nx, ny))
    np.add.at(s, (ix, iy), c[:, 2])
    np.add.at(k, (ix, iy), 1.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(k > 0, s / np.where(k > 0, k, 1.0), np.nan)
