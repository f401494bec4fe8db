"""Form removal: subtract a least-squares polynomial of the heights (mean, plane, poly2,
poly3) from a height map or a mesh, undefined pixels left out of the fit.

A height map's form is fitted by :class:`FormFit`, block by block of grid lines: the
normal equations of the fit are accumulated in a basis of Legendre polynomials of the
grid coordinates scaled to [-1, 1] (nearly orthogonal on a regular grid, so the normal
equations are well conditioned and the blocks may come in any size), then solved once.
The whole map in memory is one block; a scan read in tiles (:mod:`asperity.surface.tiles`)
adds its tiles one by one and gets the same form to rounding.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import InputError, check_int
from .topography import HeightMap, Surface, TriangleMesh


def _monomials(degree: int) -> list[tuple[int, int]]:
    return [(a, t - a) for t in range(degree + 1) for a in range(t, -1, -1)]


def _legendre(t: np.ndarray, degree: int) -> np.ndarray:
    """(n, degree + 1) Legendre polynomials P_0 .. P_degree at t (three-term recurrence)."""
    p = np.empty((t.size, degree + 1))
    p[:, 0] = 1.0
    if degree >= 1:
        p[:, 1] = t
    for k in range(1, degree):
        p[:, k + 1] = ((2 * k + 1) * t * p[:, k] - k * p[:, k - 1]) / (k + 1)
    return p


def _unit(n: int, start: int, count: int) -> np.ndarray:
    """Grid indices start .. start+count-1 of a line of n points scaled to [-1, 1]."""
    i = np.arange(start, start + count, dtype=np.float64)
    return (2.0 * i - (n - 1)) / (n - 1) if n > 1 else np.zeros(count)


class FormFit:
    """Least-squares polynomial of total degree ``degree`` in (x, y) through the defined
    pixels of an ``nx`` x ``ny`` grid, accumulated block by block.

    ``add(z, i0, j0)`` adds the block ``z = heights[i0:i0+R, j0:j0+C]`` (NaN undefined);
    ``solve()`` fixes the coefficients; ``form(i0, j0, R, C)`` evaluates the form on a
    block.  The sums use einsum loops (no BLAS), so a block's contribution does not depend
    on the number of threads.  The fitted surface is the same polynomial as a monomial
    fit in metres (the space of polynomials of a degree does not depend on the basis).
    """

    def __init__(self, degree: int, nx: int, ny: int):
        self.degree = check_int("degree", degree, 0, 10)
        self.nx, self.ny = int(nx), int(ny)
        self.terms = _monomials(self.degree)
        d = self.degree + 1
        self.gram = np.zeros((d, d, d, d))      # [a, c, b, d]: sum P_a P_c (x) P_b P_d (y)
        self.rhs = np.zeros((d, d))             # [a, b]: sum z P_a(x) P_b(y)
        self.count = 0
        self.coef = None

    def add(self, z: np.ndarray, i0: int = 0, j0: int = 0) -> None:
        rows, cols = z.shape
        if rows == 0 or cols == 0:
            return
        pu = _legendre(_unit(self.nx, i0, rows), self.degree)
        pv = _legendre(_unit(self.ny, j0, cols), self.degree)
        ok = np.isfinite(z)
        m = ok.astype(np.float64)
        z0 = np.where(ok, z, 0.0)
        mvv = np.einsum("ij,jb,jd->ibd", m, pv, pv, optimize=False)
        self.gram += np.einsum("ia,ic,ibd->acbd", pu, pu, mvv, optimize=False)
        zv = np.einsum("ij,jb->ib", z0, pv, optimize=False)
        self.rhs += np.einsum("ia,ib->ab", pu, zv, optimize=False)
        self.count += int(np.count_nonzero(ok))

    def solve(self, name: str = "the height map") -> np.ndarray:
        k = len(self.terms)
        if self.count < k:
            raise InputError(f"{name}: a degree-{self.degree} form needs at least {k} "
                             f"defined points, the surface has {self.count}")
        g = np.array([[self.gram[a, c, b, d] for c, d in self.terms] for a, b in self.terms])
        r = np.array([self.rhs[a, b] for a, b in self.terms])
        self.coef, *_ = np.linalg.lstsq(g, r, rcond=None)
        return self.coef

    def form(self, i0: int, j0: int, rows: int, cols: int) -> np.ndarray:
        """(rows, cols) form heights at pixels [i0:i0+rows, j0:j0+cols] (elementwise sums in
        a fixed order: the same values for a pixel whatever block it is evaluated in)."""
        pu = _legendre(_unit(self.nx, i0, rows), self.degree)
        pv = _legendre(_unit(self.ny, j0, cols), self.degree)
        q = np.zeros((rows, self.degree + 1))
        for c, (a, b) in zip(self.coef, self.terms):
            q[:, b] += c * pu[:, a]
        out = np.zeros((rows, cols))
        for b in range(self.degree + 1):
            out += q[:, b, None] * pv[None, :, b]
        return out


def detrend(surface: Surface, degree: int) -> Surface:
    """Subtract the least-squares polynomial in (x, y) of total degree ``degree`` from z.

    degree 0 removes the mean height, 1 a tilted plane, 2 a quadratic form, 3 ...
    The fit runs over the defined pixels of a height map (undefined stay NaN; by
    :class:`FormFit`) or over the vertices of a mesh.  Returns a new object of the same type.
    """
    deg = check_int("degree", degree, 0, 10)
    terms = _monomials(deg)
    if isinstance(surface, HeightMap):
        fit = FormFit(deg, surface.nx, surface.ny)
        fit.add(surface.heights)
        fit.solve(surface.source)
        return replace(surface, heights=surface.heights - fit.form(0, 0, surface.nx,
                                                                    surface.ny))
    if not isinstance(surface, TriangleMesh):
        raise InputError(f"detrend needs a HeightMap or TriangleMesh, got {type(surface).__name__}")
    xs, ys, zs = surface.vertices[:, 0], surface.vertices[:, 1], surface.vertices[:, 2]
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
    verts = surface.vertices.copy()
    verts[:, 2] = zs - A @ coef
    return replace(surface, vertices=verts, kept_faces=surface.kept_faces)
