"""Any surface -> facets: triangulated height maps and triangle meshes as friction faces.

The homogenisation (:mod:`asperity.friction.faces`) averages the reservoir point of plane faces
over their horizontal-area weights.  A measured or designed surface is a set of plane
triangles, so every triangle (facet) is a face:

* gradient ``g = (dz/dx, dz/dy)`` of the triangle's plane;
* local friction ``mu``: uniform, or a per-facet value from a friction map;
* weight = projected (horizontal) area x the spring model's contact weight.  With a
  uniform preload (the default) every spring is equally compressed and the contact
  weight is 1.  With a spring *rest level* ``z0`` only points above ``z0`` touch the
  counter-face and a linear spring at height ``z`` carries a load proportional to
  ``z - z0``; a facet then weighs ``area x max(z_centroid - z0, 0)`` (exact for a facet
  wholly above ``z0``, the integral of a linear function over a triangle), so the
  result depends on the load level, as it physically does.

A height map ``heights[i, j] = z(x_i, y_j)`` is triangulated cell by cell, each cell
(i, j)-(i+1, j+1) split along its (i+1, j)-(i, j+1) diagonal into two triangles of area
``dx dy / 2``; a triangle touching an undefined pixel is skipped.  A mesh's triangles are
taken as they are: vertical triangles (no projected area) and triangles facing down
while most face up (undersides of overhangs, which a tip coming from above cannot touch)
are skipped and counted.

The surface frame is the file's (x, y): a sliding direction ``psi`` is measured from +x
towards +y.  :func:`asperity.friction.derive.derive` finds the principal direction (lay) and
reports mu along and against it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_mu, check_range
from ..friction.reservoir import Faces

#: default local friction coefficient of a surface when no --mu or friction map is given
DEFAULT_MU = 0.1
#: detrending choices: name -> polynomial degree (None: keep the form)
DETREND = {"none": None, "slope": "slope", "mean": 0, "plane": 1, "poly2": 2, "poly3": 3}
#: |n_z| / |n| below which a mesh triangle counts as vertical
VERTICAL_TOL = 1e-9


@dataclass(frozen=True)
class FacetSurface:
    """The facets of a surface, ready for the facet homogenisation.

    gx, gy   : (n,) float, facet gradients (only facets that carry load)
    mu       : float (uniform) or (n,) float, local friction
    weight   : (n,) float, projected area x contact weight, m^2 (> 0)
    info     : what it came from and what was skipped (see :meth:`to_dict`)
    preview  : small (nx, ny) height array (m) and its physical size, for plots
    """

    gx: np.ndarray
    gy: np.ndarray
    mu: float | np.ndarray
    weight: np.ndarray
    info: dict
    preview: np.ndarray | None = field(default=None, repr=False)
    extent: tuple[float, float] | None = None

    kind = "surface"

    @property
    def n_facets(self) -> int:
        return int(self.gx.size)

    @property
    def n_undefined(self) -> int:
        return int(self.info.get("n_undefined", 0))

    def faces(self) -> Faces:
        """The facets as :class:`~asperity.friction.reservoir.Faces` (views, no copies)."""
        n = self.gx.size
        mu = np.broadcast_to(np.asarray(self.mu, dtype=float), (n,))
        return Faces(gradient=_columns(self.gx, self.gy), mu=mu, weight=self.weight, names=None)

    def to_dict(self) -> dict:
        return {"kind": self.info.get("kind", "surface"), **self.info, "n_facets": self.n_facets}

    def describe(self) -> str:
        i = self.info
        size = i.get("physical_size_m")
        s = f"surface: {i.get('source')} ({i.get('kind')}"
        if size:
            s += f", {size[0] * 1e3:.4g} x {size[1] * 1e3:.4g} mm"
        s += f"), {self.n_facets} facets"
        mu = i.get("mu")
        s += f", local friction {'map ' + str(i.get('friction_map')) if mu is None else f'mu = {mu:g}'}"
        return s


def _columns(gx: np.ndarray, gy: np.ndarray) -> np.ndarray:
    """(n, 2) view whose columns are ``gx`` and ``gy`` without copying either, when they
    are two rows of one (2, n) array; a copy otherwise."""
    base = gx.base
    if base is not None and base is gy.base and base.ndim == 2 and base.shape[0] == 2:
        return base.T
    return np.stack([gx, gy]).T


def _contact_weight(area: np.ndarray, zc: np.ndarray, rest_level: float | None) -> np.ndarray:
    if rest_level is None:
        return area
    return area * np.maximum(zc - rest_level, 0.0)


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


def _finish(gx, gy, mu, area, zc, xy, level_slope, rest_level, bearing_fraction, info,
            **extra) -> FacetSurface:
    if rest_level is not None and bearing_fraction is not None:
        raise InputError("give rest_level or bearing_fraction, not both")
    if gx.size == 0:
        raise InputError(f"{info.get('source')}: no facet left (every triangle was undefined, "
                         "degenerate or vertical)")
    if level_slope:
        # shear z -> z - a x - b y: projected areas unchanged, gradients shifted by (a, b)
        a, b = (float(np.dot(area, g) / area.sum()) for g in (gx, gy))
        gx, gy = gx - a, gy - b
        zc = zc - (a * xy[0] + b * xy[1])
        info["removed_slope"] = [a, b]
    if bearing_fraction is not None:
        rest_level = rest_level_for_bearing(zc, area, bearing_fraction)
        info["bearing_fraction"] = float(bearing_fraction)
    if rest_level is not None:
        rest_level = float(rest_level)
        if not math.isfinite(rest_level):
            raise InputError(f"rest_level must be a finite height in m, got {rest_level}")
    w = _contact_weight(area, zc, rest_level)
    loaded = w > 0
    info["rest_level_m"] = rest_level
    info["n_unloaded"] = int(gx.size - np.count_nonzero(loaded))
    if not loaded.any():
        raise InputError(f"rest_level {rest_level:g} m lies above the highest facet "
                         f"({float(zc.max()):g} m): nothing is in contact")
    if not loaded.all():
        gx, gy, w = gx[loaded], gy[loaded], w[loaded]
        if not np.isscalar(mu):
            mu = mu[loaded]
    g = np.empty((2, gx.size))
    g[0], g[1] = gx, gy
    return FacetSurface(gx=g[0], gy=g[1], mu=mu, weight=np.ascontiguousarray(w), info=info, **extra)


def _facet_mu(mu, friction_map, to_facets):
    """Uniform float, or a per-facet array from a friction map."""
    if friction_map is None:
        return check_mu("mu", DEFAULT_MU if mu is None else mu)
    if mu is not None:
        raise InputError("give mu or a friction map, not both")
    return to_facets(np.asarray(friction_map, dtype=float))


def heightmap_facets(hm, *, mu=None, friction_map=None, rest_level=None,
                     bearing_fraction=None, level_slope=False, info=None) -> FacetSurface:
    """Facets of a :class:`~asperity.surface.topography.HeightMap` (two triangles per cell).

    friction_map: (nx, ny) local friction per pixel; a facet takes the mean of its
    three corners.  level_slope: remove the area-weighted mean gradient (the surface
    is sheared so that its facets' mean slope is zero; for a periodic texture over whole
    periods this changes nothing, unlike a least-squares plane).
    """
    z = np.asarray(hm.heights, dtype=float)
    if z.ndim != 2 or z.shape[0] < 2 or z.shape[1] < 2:
        raise InputError(f"{hm.source}: a height map needs at least 2 x 2 pixels, got {z.shape}")
    dx, dy = float(hm.dx), float(hm.dy)
    z00, z10, z01, z11 = z[:-1, :-1], z[1:, :-1], z[:-1, 1:], z[1:, 1:]
    # lower triangle (i,j) (i+1,j) (i,j+1); upper triangle (i+1,j+1) (i,j+1) (i+1,j)
    gx = np.concatenate([((z10 - z00) / dx).ravel(), ((z11 - z01) / dx).ravel()])
    gy = np.concatenate([((z01 - z00) / dy).ravel(), ((z11 - z10) / dy).ravel()])
    zc = np.concatenate([((z00 + z10 + z01) / 3.0).ravel(), ((z11 + z01 + z10) / 3.0).ravel()])
    ok = np.isfinite(gx) & np.isfinite(gy)
    n_cells_tri = gx.size

    def per_vertex(m):
        if m.shape != z.shape:
            raise InputError(f"friction map has shape {m.shape}, the height map {z.shape}")
        a, b, c, d = m[:-1, :-1], m[1:, :-1], m[:-1, 1:], m[1:, 1:]
        return np.concatenate([((a + b + c) / 3).ravel(), ((d + c + b) / 3).ravel()])[ok]

    fmu = _facet_mu(mu, friction_map, per_vertex)
    info = dict(info or {})
    info.update(kind="heightmap", source=hm.source, grid=[int(z.shape[0]), int(z.shape[1])],
                pixel_size_m=[dx, dy], physical_size_m=[dx * z.shape[0], dy * z.shape[1]],
                n_undefined=int(getattr(hm, "n_undefined", np.count_nonzero(~np.isfinite(z)))),
                n_skipped_undefined=int(n_cells_tri - ok.sum()),
                mu=None if not np.isscalar(fmu) else float(fmu))
    area = np.full(int(ok.sum()), 0.5 * dx * dy)
    xy = None
    if level_slope:
        i, j = np.meshgrid(np.arange(z.shape[0] - 1), np.arange(z.shape[1] - 1), indexing="ij")
        xy = (np.concatenate([(i + 1 / 3) * dx, (i + 2 / 3) * dx], axis=None)[ok],
              np.concatenate([(j + 1 / 3) * dy, (j + 2 / 3) * dy], axis=None)[ok])
    return _finish(gx[ok], gy[ok], fmu, area, zc[ok], xy, level_slope, rest_level,
                   bearing_fraction, info,
                   preview=_preview(z), extent=(dx * z.shape[0], dy * z.shape[1]))


def mesh_facets(mesh, *, mu=None, friction_map=None, rest_level=None,
                bearing_fraction=None, level_slope=False, info=None) -> FacetSurface:
    """Facets of a :class:`~asperity.surface.topography.TriangleMesh`.

    friction_map: one local friction value per triangle of ``mesh.faces``.
    """
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    p0, p1, p2 = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    n = np.cross(p1 - p0, p2 - p0)
    nlen = np.linalg.norm(n, axis=1)
    up_share = float(np.sum(np.where(n[:, 2] > 0, n[:, 2], 0.0)))
    down_share = float(np.sum(np.where(n[:, 2] < 0, -n[:, 2], 0.0)))
    sign = 1.0 if up_share >= down_share else -1.0       # the sheet's own up
    nz = sign * n[:, 2]
    vertical = np.abs(n[:, 2]) <= VERTICAL_TOL * np.maximum(nlen, 1e-300)
    facing = (nz > 0) & ~vertical
    gx = -sign * n[facing, 0] / nz[facing]
    gy = -sign * n[facing, 1] / nz[facing]
    area = 0.5 * nz[facing]
    zc = (p0[facing, 2] + p1[facing, 2] + p2[facing, 2]) / 3.0

    def per_face(m):
        if m.shape != (f.shape[0],):
            raise InputError(f"friction map has {m.size} values, the mesh {f.shape[0]} triangles")
        return m[facing]

    fmu = _facet_mu(mu, friction_map, per_face)
    lo, hi = v.min(axis=0), v.max(axis=0)
    info = dict(info or {})
    info.update(kind="mesh", source=mesh.source, n_triangles=int(f.shape[0]),
                physical_size_m=[float(hi[0] - lo[0]), float(hi[1] - lo[1])],
                n_undefined=0, n_skipped_degenerate=int(getattr(mesh, "n_degenerate", 0)),
                n_skipped_vertical=int(vertical.sum()),
                n_skipped_overhanging=int(np.count_nonzero(~facing & ~vertical)),
                mu=None if not np.isscalar(fmu) else float(fmu))
    xy = ((p0[facing, 0] + p1[facing, 0] + p2[facing, 0]) / 3.0,
          (p0[facing, 1] + p1[facing, 1] + p2[facing, 1]) / 3.0)
    return _finish(gx, gy, fmu, area, zc, xy, level_slope, rest_level, bearing_fraction, info,
                   preview=_mesh_preview(p0, p1, p2, lo, hi),
                   extent=(float(hi[0] - lo[0]), float(hi[1] - lo[1])))


def _preview(z: np.ndarray, size: int = 256) -> np.ndarray:
    step = max(1, int(math.ceil(max(z.shape) / size)))
    return np.array(z[::step, ::step], dtype=float)


def _mesh_preview(p0, p1, p2, lo, hi, size: int = 160) -> np.ndarray:
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


def surface_facets(surface, **kwargs) -> FacetSurface:
    """Facets of a HeightMap or TriangleMesh (see :func:`heightmap_facets`, :func:`mesh_facets`)."""
    if hasattr(surface, "heights"):
        return heightmap_facets(surface, **kwargs)
    return mesh_facets(surface, **kwargs)


def load_surface(path, *, unit=None, pixel_size=None, height_scale=1.0, detrend="slope",
                 mu=None, friction_map=None, rest_level=None,
                 bearing_fraction=None) -> FacetSurface:
    """Read a mesh or height-map file and return its facets.

    detrend: one of :data:`DETREND`: "slope" (default) removes the mean facet gradient
    (zero mean slope, exact for periodic textures over whole periods); "mean", "plane",
    "poly2", "poly3" subtract a least-squares polynomial of that degree (form removal)
    before triangulation; "none" keeps the heights as read.  friction_map: a file (read by :func:`asperity.surface.friction_map.read_friction_map`)
    or an array.  rest_level (m, from the detrended mean plane) or bearing_fraction
    (share of the projected area in contact) select the spring rest level; neither:
    uniform preload.
    """
    from .friction_map import read_friction_map
    from .readers import read_surface
    if detrend not in DETREND:
        raise InputError(f"detrend must be one of {', '.join(DETREND)}, got {detrend!r}")
    s = read_surface(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
    if DETREND[detrend] not in (None, "slope"):
        from .detrend import detrend as _detrend
        s = _detrend(s, DETREND[detrend])
    fm = friction_map
    info = {"file": str(path), "detrend": detrend, "height_scale": float(height_scale)}
    if isinstance(friction_map, (str, bytes)) or hasattr(friction_map, "__fspath__"):
        info["friction_map"] = str(friction_map)
        fm = read_friction_map(friction_map, s)
    if fm is not None:
        fm = np.asarray(fm, dtype=float)
        if not np.all(np.isfinite(fm)) or np.any(fm < 0):
            raise InputError("friction map values must be finite and >= 0")
    return surface_facets(s, mu=mu, friction_map=fm, rest_level=rest_level,
                          bearing_fraction=bearing_fraction, level_slope=detrend == "slope",
                          info=info)
