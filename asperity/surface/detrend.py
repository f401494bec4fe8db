"""Form removal: subtract a least-squares polynomial of the heights (mean, plane, poly2,
poly3) from a height map or a mesh, undefined pixels left out of the fit.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import InputError, check_int
from .topography import HeightMap, Surface, TriangleMesh


def _monomials(degree: int) -> list[tuple[int, int]]:
    return [(a, t - a) for t in range(degree + 1) for a in range(t, -1, -1)]


def detrend(surface: Surface, degree: int) -> Surface:
    """Subtract the least-squares polynomial in (x, y) of total degree ``degree`` from z.

    degree 0 removes the mean height, 1 a tilted plane, 2 a quadratic form, 3 ...
    The fit runs over the defined pixels of a height map (undefined stay NaN) or over
    the vertices of a mesh.  Returns a new object of the same type.
    """
    deg = check_int("degree", degree, 0, 10)
    terms = _monomials(deg)
    if isinstance(surface, HeightMap):
        x = np.arange(surface.nx) * surface.dx
        y = np.arange(surface.ny) * surface.dy
        z = surface.heights
        ok = np.isfinite(z)
        ii, jj = np.nonzero(ok)
        xs, ys, zs = x[ii], y[jj], z[ok]
    elif isinstance(surface, TriangleMesh):
        xs, ys, zs = surface.vertices[:, 0], surface.vertices[:, 1], surface.vertices[:, 2]
    else:
        raise InputError(f"detrend needs a HeightMap or TriangleMesh, got {type(surface).__name__}")
    if zs.size < len(terms):
        raise InputError(f"{surface.source}: a degree-{deg} form needs at least {len(terms)} "
                         f"defined points, the surface has {zs.size}")
    # centred and scaled coordinates keep the least-squares problem well conditioned
    cx, cy = 0.5 * (xs.max() + xs.min()), 0.5 * (ys.max() + ys.min())
    sx = 0.5 * (xs.max() - xs.min()) or 1.0
    sy = 0.5 * (ys.max() - ys.min()) or 1.0
    u, v = (xs - cx) / sx, (ys - cy) / sy
    A = np.stack([u ** a * v ** b for a, b in terms], axis=1)
    coef, *_ = np.linalg.lstsq(A, zs, rcond=None)
    if isinstance(surface, HeightMap):
        U, V = ((x - cx) / sx)[:, None], ((y - cy) / sy)[None, :]
        form = sum(c * U ** a * V ** b for c, (a, b) in zip(coef, terms))
        return replace(surface, heights=surface.heights - form)
    verts = surface.vertices.copy()
    verts[:, 2] = zs - A @ coef
    return replace(surface, vertices=verts, kept_faces=surface.kept_faces)
