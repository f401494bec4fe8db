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

from ..errors import InputError, check_flag, check_instance, check_mu
from ..friction.reservoir import Faces
from ..resources import check_memory
from ._previews import height_preview, mesh_preview
from .friction_map import MAX_MU, check_friction_map
from . import grid_facets as grid
from . import quality as Q
from .facet_checks import check_fields, check_options, check_pressure_field
from .grid_facets import rest_level_for_bearing  # noqa: F401  (re-exported)
from .prepare import DETREND, check_surface_options, prepare_surface  # noqa: F401
from .topography import HeightMap, TriangleMesh

#: default local friction coefficient of a surface when no --mu or friction map is given
DEFAULT_MU = 0.1
#: |n_z| / |n| below which a mesh triangle counts as vertical
VERTICAL_TOL = 1e-9
#: bytes per pixel of a height map's facets and their friction homogenisation (measured
#: peaks, with a margin): two facets per pixel, each with two gradients and a weight, the
#: friction kernel's 1/|n|, masks and the copies made while dropping undefined facets; a
#: rest level (or bearing fraction) adds the facet heights, their sorting and the weights
FACET_BYTES_PER_PIXEL = 80
REST_LEVEL_BYTES_PER_PIXEL = 120
#: a pressure field or a periodic map: wrapped heights and pressures, facet mean pressures
PRESSURE_BYTES_PER_PIXEL = 40


@dataclass(frozen=True)
class FacetSurface:
    """The facets of a surface, ready for the facet homogenisation.

    Every plane triangle of a mesh or of a triangulated height map is a face of the
    homogenisation (SPEC.md section 2), in the surface's own frame (x, y of the file: a
    sliding direction ``psi`` is measured from +x towards +y).  Made by
    :func:`asperity.load_surface` (or :func:`asperity.load_elastic`), or from a caller's own
    arrays; the fields are checked when it is made.

    Parameters
    ----------
    gx, gy : (n,) array_like of float
        Facet gradients dz/dx and dz/dy (finite), only facets that carry load; n >= 1.
    mu : float or (n,) array_like of float
        Local friction coefficient, uniform or one a facet, in [0, 100].
    weight : (n,) array_like of float
        Projected area x contact weight, m^2, finite, >= 0 and not all zero; with a pressure
        field, the normal force each facet carries, N.
    info : dict
        What the facets came from and what was skipped (``source``, ``kind``, ``grid``,
        ``n_undefined``, ...: the keys of ``to_dict()``).
    preview : (nx, ny) array_like of float or None, default None
        A small height array, m (NaN where undefined), for plots.
    extent : (float, float) or None, default None
        Physical size (m) of ``preview``, two lengths > 0.
    quality : dict or None, default None
        Data-quality figures (spikes, undefined pixels, steep facets; the measured-scan
        tutorial's *Data quality*).
    elastic : dict or None, default None
        The contact's figures (the keys of ``asperity contact --json``) when the weights are
        the contact forces of an elastic contact.

    Raises
    ------
    asperity.InputError
        A field of the wrong shape, a non-finite gradient or weight, weights all zero, or a
        friction coefficient out of range (one line naming the field).

    See Also
    --------
    asperity.load_surface, asperity.load_elastic, asperity.derive, asperity.compute_reservoir

    Notes
    -----
    A height map ``heights[i, j] = z(x_i, y_j)`` is triangulated cell by cell, each cell
    split along its (i+1, j)-(i, j+1) diagonal into two triangles of area ``dx dy / 2``; a
    triangle touching an undefined pixel is skipped.  A mesh's triangles are taken as they
    are: vertical triangles and triangles facing down while most face up (undersides of
    overhangs) are skipped and counted.  With a spring rest level ``z0`` a facet weighs
    ``area x max(z_centroid - z0, 0)``; without, its projected area.

    Examples
    --------
    One period of the SPEC.md wedge as two facets, weighted by their horizontal lengths:

    >>> ta, tb = np.tan(np.radians([30.0, 10.0]))
    >>> s = asperity.FacetSurface(gx=np.array([ta, -tb]), gy=np.zeros(2),
    ...                           mu=np.array([0.1, 0.2]), weight=np.array([tb, ta]),
    ...                           info={"source": "one wedge"})
    >>> s.n_facets
    2
    >>> round(asperity.compute_axis_coefficients(s)["mu_a_plus"], 6)
    0.185697
    """

    gx: np.ndarray
    gy: np.ndarray
    mu: float | np.ndarray
    weight: np.ndarray
    info: dict
    preview: np.ndarray | None = field(default=None, repr=False)
    extent: tuple[float, float] | None = None
    quality: dict | None = field(default=None, repr=False, compare=False)
    #: the contact's figures when the weights are contact forces (:mod:`.contact_facets`)
    elastic: dict | None = field(default=None, compare=False)

    kind = "surface"

    def __post_init__(self):
        gx, gy, mu, w, pv = check_fields(self.gx, self.gy, self.mu, self.weight, self.info,
                                         self.preview, self.extent, self.quality)
        object.__setattr__(self, "preview", pv)  # as checked: masked values NaN
        if self.elastic is not None:
            check_instance("elastic", self.elastic, dict)
        for name, v in (("gx", gx), ("gy", gy), ("weight", w), ("mu", mu)):
            object.__setattr__(self, name, v)

    @property
    def n_facets(self) -> int:
        return int(self.gx.size)

    @property
    def n_undefined(self) -> int:
        return int(self.info.get("n_undefined", 0))

    def faces(self) -> Faces:
        """The facets as the homogenisation's ``Faces`` (views, no copies)."""
        n = self.gx.size
        mu = np.broadcast_to(np.asarray(self.mu, dtype=float), (n,))
        return Faces(gradient=grid.columns(self.gx, self.gy), mu=mu, weight=self.weight,
                     names=None)

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


def _finish(gx, gy, mu, area, zc, xy, level_slope, rest_level, bearing_fraction, info,
            max_slope=None, pixels=None, force=None, **extra) -> FacetSurface:
    if rest_level is not None and bearing_fraction is not None:
        raise InputError("give rest_level or bearing_fraction, not both")
    if gx.size == 0:
        raise InputError(f"{info.get('source')}: no facet left (every triangle was undefined, "
                         "degenerate or vertical)")
    if level_slope:
        # shear z -> z - a x - b y: projected areas unchanged, gradients shifted by (a, b)
        a, b = (float(np.dot(area, g) / area.sum()) for g in (gx, gy))
        if grid.rows_of_one(gx, gy):          # our own arrays: shifted in place
            gx -= a
            gy -= b
        else:
            gx, gy = gx - a, gy - b
        if zc is not None:                # zc is our own array: sheared in place
            grid.shear(zc, a, b, xy[0], xy[1])
            del xy
        info["removed_slope"] = [a, b]
    steep = Q.steep_facets(gx, gy, max_slope)
    if bearing_fraction is not None:
        rest_level = grid.rest_level_for_bearing(zc if steep is None else zc[~steep],
                                            area if steep is None else area[~steep],
                                            bearing_fraction)
        info["bearing_fraction"] = float(bearing_fraction)
    if rest_level is not None:
        rest_level = float(rest_level)
        if not math.isfinite(rest_level):
            raise InputError(f"rest_level must be a finite height in m, got {rest_level}")
    if force is None:
        w = grid.contact_weight(area, zc, rest_level)
    else:                                 # the normal force each facet carries, N
        w = grid.pressure_weight(area, force)
        del force
    mu_max = float(mu) if np.isscalar(mu) else float(mu.max())
    stats = Q.SlopeStats(Q.locking_limit_deg(mu_max))
    Q.add_slopes(stats, gx, gy, w, steep)
    loaded = w > 0
    if steep is not None:
        loaded &= ~steep
        if not loaded.any() and steep.all():
            raise InputError(f"max_slope {max_slope:g} deg drops every facet of "
                             f"{info.get('source')} (the gentlest is steeper)")
    info["rest_level_m"] = rest_level
    info["n_unloaded"] = int(gx.size - np.count_nonzero(loaded)
                             - (0 if steep is None else np.count_nonzero(steep)))
    if not loaded.any() and rest_level is None:
        raise InputError(f"{info.get('source')}: no facet carries load (the pressure is "
                         "zero on every defined facet)")
    if not loaded.any():
        raise InputError(f"rest_level {rest_level:g} m lies above the highest facet "
                         f"({float(zc.max()):g} m): nothing is in contact")
    if not loaded.all():
        gx, gy, w = gx[loaded], gy[loaded], w[loaded]
        if not np.isscalar(mu):
            mu = mu[loaded]
    if not grid.rows_of_one(gx, gy):
        g = np.empty((2, gx.size))
        g[0], g[1] = gx, gy
        gx, gy = g[0], g[1]
    quality = Q.quality_stats(pixels=pixels, undefined=info.get("n_undefined", 0),
                              despike=None, spikes=0, max_slope=max_slope, mu_max=mu_max,
                              stats=stats)
    return FacetSurface(gx=gx, gy=gy, mu=mu, weight=np.ascontiguousarray(w), info=info,
                        quality=quality, **extra)


def _facet_mu(mu, friction_map, to_facets):
    """Uniform float, or a per-facet array from a friction map."""
    if friction_map is None:
        return check_mu("mu", DEFAULT_MU if mu is None else mu, MAX_MU)
    if mu is not None:
        raise InputError("give mu or a friction map, not both")
    return to_facets(check_friction_map(friction_map))


def facet_bytes(rest_level: bool, pressure: bool = False) -> float:
    """Memory per height-map pixel of the facets and their homogenisation (bytes)."""
    return float(FACET_BYTES_PER_PIXEL + (REST_LEVEL_BYTES_PER_PIXEL if rest_level else 0)
                 + (PRESSURE_BYTES_PER_PIXEL if pressure else 0))


def heightmap_facets(hm, *, mu=None, friction_map=None, rest_level=None,
                     bearing_fraction=None, level_slope=False, info=None,
                     max_slope=None, pressure=None, periodic=False) -> FacetSurface:
    """Facets of a :class:`~asperity.surface.topography.HeightMap` (two triangles per cell).

    friction_map: (nx, ny) local friction per pixel; a facet takes the mean of its
    three corners.  level_slope: remove the area-weighted mean gradient (the surface
    is sheared so that its facets' mean slope is zero; for a periodic texture over whole
    periods this changes nothing, unlike a least-squares plane).  max_slope (deg): drop
    the facets steeper than that (after the slope removal), counted in ``quality``.  The
    facet arrays are built in place (about :data:`FACET_BYTES_PER_PIXEL` bytes per pixel
    with the homogenisation); a map that does not fit in memory is refused first.

    pressure: (nx, ny) node pressures, Pa (0 out of contact, NaN on undefined pixels): a
    facet weighs the normal force it carries (:func:`.grid_facets.pressure_weight`, N).
    periodic: the map is one period, the cells across its edges are facets too.  Either
    adds :data:`PRESSURE_BYTES_PER_PIXEL` bytes a pixel.
    """
    check_instance("surface", hm, HeightMap, "HeightMap")
    rest_level, bearing_fraction = check_options(rest_level, bearing_fraction, level_slope,
                                                  info)
    max_slope = Q.check_max_slope(max_slope)
    periodic = check_flag("periodic", periodic)
    z = hm.heights
    if z.shape[0] < 2 or z.shape[1] < 2:
        raise InputError(f"{hm.source}: a height map needs at least 2 x 2 pixels, got {z.shape}")
    name = hm.source or "the height map"
    need_z = rest_level is not None or bearing_fraction is not None
    pressure = check_pressure_field(pressure, z, need_z)
    check_memory(z.size * facet_bytes(need_z, pressure is not None or periodic),
                 f"the facets of {name} ({z.shape[0]} x {z.shape[1]} pixels)",
                 "crop or resample the scan to fewer points")
    shape = z.shape
    if periodic:
        z = grid.wrap_periodic(z)
        pressure = None if pressure is None else grid.wrap_periodic(pressure)
    dx, dy = float(hm.dx), float(hm.dy)
    nxm, nym = z.shape[0] - 1, z.shape[1] - 1
    nc = nxm * nym
    # lower triangle (i,j) (i+1,j) (i,j+1); upper triangle (i+1,j+1) (i,j+1) (i+1,j)
    g = np.empty((2, 2 * nc))
    grid.cell_gradients(z, dx, dy, g)
    ok = np.isfinite(g[0])
    ok &= np.isfinite(g[1])
    zc = None
    if need_z:
        zc = np.empty(2 * nc)
        grid.centroid_heights(z, zc)
    force = None if pressure is None else np.empty(2 * nc)
    if pressure is not None:              # the node pressures' mean on each facet
        grid.centroid_heights(pressure, force)
        del pressure
    n_ok = int(np.count_nonzero(ok))
    every = n_ok == ok.size

    def keep(a):
        """``a`` (facets along the last axis) without the undefined facets."""
        if every:
            return a
        out = np.empty(a.shape[:-1] + (n_ok,))
        for idx in np.ndindex(*a.shape[:-1]):
            np.compress(ok, a[idx], out=out[idx])
        return out

    def per_vertex(m):
        if m.shape != shape:
            raise InputError(f"friction map has shape {m.shape}, the height map {shape}")
        return keep(grid.facet_mu(grid.wrap_periodic(m) if periodic else m))

    fmu = _facet_mu(mu, friction_map, per_vertex)
    g = keep(g)
    zc = keep(zc) if need_z else None
    force = None if force is None else keep(force)
    info = dict(info or {})
    info.update(kind="heightmap", source=hm.source, grid=[int(shape[0]), int(shape[1])],
                pixel_size_m=[dx, dy], physical_size_m=[dx * shape[0], dy * shape[1]],
                n_undefined=int(hm.n_undefined),
                n_skipped_undefined=int(ok.size - n_ok),
                mu=None if not np.isscalar(fmu) else float(fmu))
    info.update({"periodic": True} if periodic else {})
    xy = None
    if level_slope and need_z:            # facet centroids, to shear the heights
        xy = [keep(grid.centroid_coordinate(nxm, nym, d, along, 0))
              for d, along in ((dx, 0), (dy, 1))]
    del ok
    area = np.full(n_ok, 0.5 * dx * dy)
    return _finish(g[0], g[1], fmu, area, zc, xy, level_slope, rest_level,
                   bearing_fraction, info, max_slope=max_slope, pixels=hm.heights.size,
                   preview=height_preview(hm.heights), extent=(dx * shape[0], dy * shape[1]),
                   force=force)


def mesh_facets(mesh, *, mu=None, friction_map=None, rest_level=None,
                bearing_fraction=None, level_slope=False, info=None,
                max_slope=None, force=None) -> FacetSurface:
    """Facets of a :class:`~asperity.surface.topography.TriangleMesh`.

    friction_map: one local friction value per triangle of ``mesh.faces``; max_slope as
    for :func:`heightmap_facets`.  force: None, or the normal force (N, >= 0) on each
    triangle of ``mesh.faces`` (an elastic contact's, :func:`.mesh_grid.face_forces`): a
    facet then weighs that force; triangles skipped as vertical or overhanging carry
    none (their share of it is ``info["force_skipped_share"]``).
    """
    check_instance("surface", mesh, TriangleMesh, "TriangleMesh")
    rest_level, bearing_fraction = check_options(rest_level, bearing_fraction, level_slope,
                                                  info)
    max_slope = Q.check_max_slope(max_slope)
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
    fpc = None
    if force is not None:                 # the facet's mean pressure: force / its area
        F = np.asarray(force, dtype=float)
        if F.shape != (f.shape[0],) or not np.all(np.isfinite(F)) or (F < 0).any():
            raise InputError(f"force must hold {f.shape[0]} finite forces >= 0 (one a "
                             "triangle)")
        total = float(F.sum())
        skipped = total - float(F[facing].sum())
        fpc = F[facing] / area
    lo, hi = v.min(axis=0), v.max(axis=0)
    info = dict(info or {})
    info.update(kind="mesh", source=mesh.source, n_triangles=int(f.shape[0]),
                physical_size_m=[float(hi[0] - lo[0]), float(hi[1] - lo[1])],
                n_undefined=0, n_skipped_degenerate=int(getattr(mesh, "n_degenerate", 0)),
                n_skipped_vertical=int(vertical.sum()),
                n_skipped_overhanging=int(np.count_nonzero(~facing & ~vertical)),
                mu=None if not np.isscalar(fmu) else float(fmu))
    if fpc is not None:
        info["force_skipped_share"] = skipped / total if total > 0 else 0.0
    xy = ((p0[facing, 0] + p1[facing, 0] + p2[facing, 0]) / 3.0,
          (p0[facing, 1] + p1[facing, 1] + p2[facing, 1]) / 3.0)
    return _finish(gx, gy, fmu, area, zc, xy, level_slope, rest_level, bearing_fraction, info,
                   max_slope=max_slope, preview=mesh_preview(p0, p1, p2, lo, hi),
                   extent=(float(hi[0] - lo[0]), float(hi[1] - lo[1])), force=fpc)


def surface_facets(surface, **kwargs) -> FacetSurface:
    """Facets of a HeightMap or TriangleMesh (see :func:`heightmap_facets`, :func:`mesh_facets`)."""
    check_instance("surface", surface, (HeightMap, TriangleMesh), "HeightMap or TriangleMesh")
    if isinstance(surface, HeightMap):
        return heightmap_facets(surface, **kwargs)
    return mesh_facets(surface, **kwargs)


def load_surface(path, *, unit=None, pixel_size=None, height_scale=1.0, detrend="slope",
                 mu=None, friction_map=None, rest_level=None, bearing_fraction=None,
                 despike=None, despike_window=None, max_slope=None) -> FacetSurface:
    """Read a mesh or height-map file and return its facets, ready for :func:`asperity.derive`.

    The file is read by :func:`asperity.read_surface`; spikes are marked undefined, the form
    removed, and every triangle becomes a facet (:class:`asperity.FacetSurface`, whose Notes
    say how).

    Parameters
    ----------
    path : str or os.PathLike
        The file; formats by suffix as for :func:`asperity.read_surface`.
    unit : str or None, default None
        Length unit of the file's numbers (m, mm, um, nm, ...), as for ``read_surface``.
    pixel_size : float or (float, float) or None, default None
        Grid spacing of a height map in ``unit``, as for ``read_surface``.
    height_scale : float, default 1.0
        Factor on the heights after conversion to metres, in [1e-6, 1e6].
    detrend : {"slope", "none", "mean", "plane", "poly2", "poly3"}, default "slope"
        "slope" removes the mean facet gradient (zero mean slope, exact for periodic
        textures over whole periods); "mean", "plane", "poly2", "poly3" subtract a
        least-squares polynomial of that degree (form removal) before triangulation; "none"
        keeps the heights as read.
    mu : float or None, default None
        Uniform local friction coefficient, in [0, 100]; None: 0.1 (or the friction map).
    friction_map : str, os.PathLike, array_like or None, default None
        Local friction per pixel (height map) or per triangle (mesh): a file or an array;
        not with ``mu``.
    rest_level : float or None, default None
        Spring rest level, m from the detrended mean plane: only facets above it touch,
        each weighing ``area x (z_centroid - rest_level)``; not with ``bearing_fraction``.
    bearing_fraction : float or None, default None
        Share of the projected area in contact, in (0, 1], which sets the rest level.
        Neither: a uniform preload, every facet weighing its projected area.
    despike : float or None, default None
        Threshold of the spike filter, robust standard deviations, in [2, 1e6]: pixels that
        far from the median of their neighbourhood become undefined (height maps only).
    despike_window : int or None, default None
        Odd side of the spike filter's window, pixels, in [3, 15] (default 5); needs
        ``despike``.
    max_slope : float or None, default None
        Drop the facets steeper than this, degrees, in (0, 90), after the form removal.

    Returns
    -------
    FacetSurface
        The facets that carry load, with ``info`` (source, grid, what was skipped) and
        ``quality`` (the data-quality figures).

    Raises
    ------
    asperity.InputError
        A missing or malformed file, an option out of range or given with one it excludes,
        no facet left, or a surface too large for the memory (one line).

    See Also
    --------
    asperity.read_surface, asperity.derive, asperity.derive_scan, asperity.load_elastic

    Examples
    --------
    A mesh (micrometres) of four periods of the SPEC.md wedge with one friction value per
    triangle, and a 64 x 64 height map (two facets a cell):

    >>> s = asperity.load_surface("surfaces/wedge-30-10.stl", unit="um",
    ...                           friction_map="surfaces/wedge-30-10-friction.txt")
    >>> print(s.n_facets, f"mu_a+ = {asperity.derive(s).axes['mu_a_plus']:.6f}")
    16 mu_a+ = 0.185697
    >>> asperity.load_surface("surfaces/scan-ridges.txt", mu=0.15).n_facets
    7938
    """
    despike, max_slope = check_surface_options(detrend=detrend, mu=mu, despike=despike,
                                               despike_window=despike_window,
                                               max_slope=max_slope)
    rest_level, bearing_fraction = check_options(rest_level, bearing_fraction, False, None)
    prep = prepare_surface(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale,
                           detrend=detrend, friction_map=friction_map, despike=despike,
                           point_bytes=facet_bytes(rest_level is not None
                                                   or bearing_fraction is not None))
    out = surface_facets(prep.surface, mu=mu, friction_map=prep.friction_map,
                         rest_level=rest_level, bearing_fraction=bearing_fraction,
                         level_slope=prep.level_slope, info=prep.info, max_slope=max_slope)
    out.quality.update(prep.quality)
    return out
