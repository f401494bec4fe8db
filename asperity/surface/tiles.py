"""A height map in tiles: the surface side of a scan derived in bounded memory.

A tile is a block of ``tile_lines`` file lines (:mod:`.readers._streams`) and owns the
cells between its lines and the next line (one line of halo; the spike filter reads
``window // 2`` lines more on each side).  For a tile, this module reads the heights,
marks the spikes, removes the form and builds the facets with the element-by-element
arithmetic of :func:`asperity.surface.facets.heightmap_facets` (:mod:`.grid_facets`), so
that every facet of a tile is the facet of the map read whole, with the same numbers.

A :class:`TilePlan` holds what every tile needs (picklable: a Dask worker opens the file
itself); the global quantities (form coefficients, mean slope, spike positions, rest
level) are found by earlier passes (:mod:`asperity.friction.tiled`).  Facets keep the
order of the whole map: the lower triangles of the tile's cells row by row, then the
upper ones; ``counts`` tells how many of each half every cell row kept, from which the
global index of a facet follows.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from . import grid_facets as grid
from .quality import SlopeStats, add_slopes, find_spikes, steep_facets
from .readers._lines import LineSource
from .readers._streams import open_lines


class ArrayLines(LineSource):
    """A map held in memory (a file that cannot be streamed, read whole; an array)."""

    streams = False

    def __init__(self, array, dx=None, dy=None, source="", path=""):
        self.path, self.shape = str(path), tuple(int(n) for n in array.shape)
        self.dx, self.dy, self.source = dx, dy, source
        self.array = array

    def lines(self, a, b):
        return np.array(self.array[a:b], dtype=np.float64)

    def block(self, axis, a, b):
        return np.array(self.array[a:b] if axis == 0 else self.array[:, a:b], dtype=np.float64)


def open_scan(path, *, unit=None, pixel_size=None, height_scale=1.0) -> LineSource:
    """The heights of a height-map file as lines: streamed when the format allows, else read
    whole (:func:`~asperity.surface.readers.read_surface`).  A mesh is refused."""
    src = open_lines(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
    if src is not None:
        return src
    from .readers import read_surface
    from .topography import HeightMap
    s = read_surface(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
    if not isinstance(s, HeightMap):
        raise InputError(f"{path}: a mesh is derived whole; tiles are for height maps")
    return ArrayLines(s.heights, s.dx, s.dy, s.source, path)


def open_friction_map(friction_map, heights: LineSource) -> LineSource:
    """A per-pixel friction map (file or array) of the shape of ``heights``, as lines."""
    from .readers._files import split_suffix, surface_path
    if isinstance(friction_map, (str, bytes)) or hasattr(friction_map, "__fspath__"):
        p = surface_path(friction_map)
        suffix, gz = split_suffix(p)
        if suffix == ".npy" and not gz and p.is_file():
            from .readers._streams import NpyLines
            src = NpyLines(p, p)
        else:
            from .friction_map import GridShape, read_friction_map
            src = ArrayLines(read_friction_map(p, GridShape(heights.shape)))
    else:
        from .friction_map import check_friction_map
        src = ArrayLines(check_friction_map(friction_map))
    if src.shape != heights.shape:
        raise InputError(f"friction map has shape {src.shape}, the height map {heights.shape}")
    return src


@dataclass(frozen=True)
class TilePlan:
    """What a tile needs: the sources and the global quantities found so far."""

    heights: LineSource
    tile_lines: int
    despike: tuple | None = None
    mu: float | None = None                # uniform local friction (else mu_map)
    mu_map: LineSource | None = None
    form: object | None = None             # a solved asperity.surface.detrend.FormFit
    slope: tuple | None = None             # (a, b) removed from every facet gradient
    max_slope: float | None = None
    rest_level: float | None = None
    need_z: bool = False
    limit_deg: float = 90.0
    spikes: np.ndarray | None = field(default=None, repr=False)   # sorted flat indices

    @property
    def n_tiles(self) -> int:
        return -(-self.heights.n_lines // self.tile_lines)

    def bounds(self, t: int) -> tuple[int, int]:
        n = self.heights.n_lines
        return t * self.tile_lines, min(n, (t + 1) * self.tile_lines)

    def with_(self, **kw) -> "TilePlan":
        return replace(self, **kw)


def _lines_view(z: np.ndarray, axis: int) -> np.ndarray:
    return z if axis == 0 else z.T


def read_tile(plan: TilePlan, t: int, judge: bool = False) -> dict:
    """Heights of tile ``t``'s lines and its halo line, spikes marked (``judge``: found by
    the filter; else from ``plan.spikes``), form removed when the plan has one.

    Returns {"z": block in the heights' orientation, "lo", "hi" (raw heights of the
    tile's own lines; with ``judge`` only), "undefined" (as read; with ``judge``), "spikes"
    (flat indices found)}."""
    src = plan.heights
    axis, n = src.axis, src.n_lines
    l0, l1 = plan.bounds(t)
    e = min(l1 + 1, n)
    r = plan.despike[1] // 2 if (plan.despike is not None and judge) else 0
    a, b = max(0, l0 - r), min(n, e + r)
    z = src.lines(a, b)
    out = {}
    if judge:                                   # the first pass's figures, read once
        from .topography import nan_range
        own = _lines_view(z, axis)[l0 - a:l1 - a]
        out["lo"], out["hi"] = nan_range(own)
        out["undefined"] = int(np.count_nonzero(np.isnan(own)))
    length = src.shape[1 - axis]
    found = np.empty(0, dtype=np.int64)
    if plan.despike is not None:
        if judge:
            rows = (l0 - a, e - a)
            mask = find_spikes(z, plan.despike, rows=rows if axis == 0 else None,
                               cols=rows if axis == 1 else None)
            m = _lines_view(mask, axis)
            lines, pos = np.nonzero(m)
            flat = (lines + l0).astype(np.int64) * length + pos
            found = flat[flat < l1 * length]
        else:
            lo_i, hi_i = np.searchsorted(plan.spikes, [l0 * length, e * length])
            flat = plan.spikes[lo_i:hi_i]
        zl = _lines_view(z, axis)
        zl[flat // length - a, flat % length] = np.nan
    block = np.ascontiguousarray(_lines_view(_lines_view(z, axis)[l0 - a:e - a], axis))
    out["spikes"] = found
    if plan.form is not None:
        i0, j0 = (l0, 0) if axis == 0 else (0, l0)
        block -= plan.form.form(i0, j0, *block.shape)
    out["z"] = block
    return out


def tile_origin(plan: TilePlan, t: int) -> tuple[int, int]:
    l0 = plan.bounds(t)[0]
    return (l0, 0) if plan.heights.axis == 0 else (0, l0)


def mu_block(plan: TilePlan, t: int) -> np.ndarray | None:
    """The friction map's values at the tile's pixels (lines and halo), or None."""
    if plan.mu_map is None:
        return None
    l0, l1 = plan.bounds(t)
    e = min(l1 + 1, plan.heights.n_lines)
    m = plan.mu_map.block(plan.heights.axis, l0, e)
    return m


def gradients(plan: TilePlan, z: np.ndarray):
    """(g (2, 2 nc) with the plan's slope removed, ok mask) of a tile block."""
    nc = (z.shape[0] - 1) * (z.shape[1] - 1)
    g = np.empty((2, 2 * nc))
    grid.cell_gradients(z, plan.heights.dx, plan.heights.dy, g)
    ok = np.isfinite(g[0])
    ok &= np.isfinite(g[1])
    if plan.slope is not None:
        g[0] -= plan.slope[0]
        g[1] -= plan.slope[1]
    return g, ok


def centroids(plan: TilePlan, t: int, z: np.ndarray) -> np.ndarray:
    """(2 nc,) centroid heights of a tile block, sheared by the plan's slope."""
    nxm, nym = z.shape[0] - 1, z.shape[1] - 1
    zc = np.empty(2 * nxm * nym)
    grid.centroid_heights(z, zc)
    if plan.slope is not None:
        i0, j0 = tile_origin(plan, t)
        src = plan.heights
        grid.shear(zc, plan.slope[0], plan.slope[1],
                   grid.centroid_coordinate(nxm, nym, src.dx, 0, i0),
                   grid.centroid_coordinate(nxm, nym, src.dy, 1, j0))
    return zc


@dataclass
class TileFacets:
    """The kept facets of a tile (loaded, defined, not too steep), in the map's order."""

    g: np.ndarray                 # (2, n) gradients
    mu: float | np.ndarray
    w: np.ndarray                 # (n,) weights
    counts: np.ndarray            # (2, cell rows): kept lower / upper facets per cell row
    row0: int                     # first cell row of counts
    n_ok: int                     # defined facets
    n_unloaded: int
    stats: SlopeStats
    zc_max: float | None = None   # highest defined centroid (with a rest level)


def tile_facets(plan: TilePlan, t: int, z: np.ndarray, m: np.ndarray | None) -> TileFacets:
    """The facets of tile ``t`` from its block ``z`` (:func:`read_tile`) and friction map
    block ``m``: slope removed, steep ones dropped, weighted by the rest level."""
    src = plan.heights
    nxm, nym = z.shape[0] - 1, z.shape[1] - 1
    g, ok = gradients(plan, z)
    steep = steep_facets(g[0], g[1], plan.max_slope)
    if steep is not None:
        steep &= ok
    area = np.full(g.shape[1], 0.5 * src.dx * src.dy)
    zc = centroids(plan, t, z) if plan.rest_level is not None else None
    with np.errstate(invalid="ignore"):
        w = grid.contact_weight(area, zc, plan.rest_level)
    stats = SlopeStats(plan.limit_deg)
    add_slopes(stats, g[0][ok], g[1][ok], w[ok], None if steep is None else steep[ok])
    keep = ok & (w > 0)
    if steep is not None:
        keep &= ~steep
    n_unloaded = int(np.count_nonzero(ok) - np.count_nonzero(keep)
                     - (0 if steep is None else np.count_nonzero(steep)))
    counts = keep.reshape(2, nxm, nym).sum(axis=2)
    row0 = tile_origin(plan, t)[0]
    gk = np.empty((2, int(np.count_nonzero(keep))))
    np.compress(keep, g[0], out=gk[0])
    np.compress(keep, g[1], out=gk[1])
    mu = plan.mu if m is None else grid.facet_mu(m)[keep]
    zc_max = None
    if zc is not None and ok.any():
        zc_max = float(zc[ok].max())
    return TileFacets(gk, mu, w[keep], counts, row0, int(np.count_nonzero(ok)), n_unloaded,
                      stats, zc_max)


def preview_step(src: LineSource, size: int = 256) -> int:
    """The step of :func:`asperity.surface._previews.height_preview` for this map."""
    from ._previews import preview_step as step
    return step(src.shape, size)


def preview_part(plan: TilePlan, t: int, z: np.ndarray) -> tuple[int, np.ndarray]:
    """The preview pixels among tile ``t``'s own lines: (first preview line, array)."""
    step = preview_step(plan.heights)
    l0, l1 = plan.bounds(t)
    first = -(-l0 // step) * step
    idx = np.arange(first, l1, step) - l0
    zl = _lines_view(z, plan.heights.axis)
    return first // step, np.array(zl[idx, ::step], dtype=float)


class ScanSurface:
    """What a scan derived in tiles is, for the derivation's report: the ``info`` of the
    facets of the map read whole (:meth:`FacetSurface.to_dict`), the data-quality
    figures, a preview, how it was tiled -- but no facets (:meth:`faces` refuses)."""

    kind = "surface"

    def __init__(self, info: dict, n_facets: int, preview, extent, quality: dict,
                 tiling: dict):
        self.info, self.n_facets = info, int(n_facets)
        self.preview, self.extent = preview, extent
        self.quality, self.tiling = quality, tiling
        self.other = {}                   # contact regime -> Reservoir (figures)

    @property
    def n_undefined(self) -> int:
        return int(self.info.get("n_undefined", 0))

    def to_dict(self) -> dict:
        return {"kind": self.info.get("kind", "surface"), **self.info, "n_facets": self.n_facets}

    def describe(self) -> str:
        from .facets import FacetSurface
        return FacetSurface.describe(self) + (f"; {self.tiling['tiles']} tiles of "
                                              f"{self.tiling['tile_rows']} lines")

    def faces(self):
        raise InputError("a scan derived in tiles keeps no facets in memory; derive it again "
                         "(asperity.friction.tiled.derive_scan) for other directions")
