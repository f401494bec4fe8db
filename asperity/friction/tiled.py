"""Directional friction of a height-map scan of any size, in tiles of bounded memory.

:func:`derive_scan` gives the :class:`~asperity.friction.derive.Derivation` of
``derive(load_surface(path, ...))`` without ever holding all the facets: the map is read
tile by tile (:mod:`asperity.surface.tiles`) in passes over the tiles
(:mod:`.tile_tasks`), each reduced here in tile order:

1. ``prep``: spikes, undefined pixels, the height range, the least-squares form (normal
   equations summed over the tiles), the mean facet slope, the friction map's largest value;
2. with a bearing fraction, the centroid heights' range, histograms and the few values
   around the rest level (exact: the same order statistics as the whole map);
3. ``sweep``: the reservoir sums of every direction, psi +- h for dT/dpsi included, and
   the facets' figures (counts, slopes, preview);
4. ``sweep`` again for what the first sweep decides: the axis directions of the principal
   direction, the load share of the self-locking directions, the other contact regime
   (figures), the windward fallback on level facets.

The self-locking facet named for a direction is the first in the whole map's facet order
(its index is rebuilt from the tiles' counts per cell row).  Results agree with the
in-memory path to rounding (sums taken in another order), and are the same wherever the
tiles run: in this process or as tasks on a Dask cluster (``client``), whose workers read
their tiles from the file themselves.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_choice, check_instance, check_int, check_mu
from ..progress import report
from .tile_tasks import run_tiles

#: height maps with more pixels than this are derived in tiles when the format streams
AUTO_TILE_PIXELS = 1 << 22
#: memory a tile's work may take (bytes), and what it takes per pixel (measured, margin)
TILE_BYTES = 256 << 20
TILE_BYTES_PER_PIXEL = 200
#: facet-directions of a tiled derivation at most (about 2 hours on 2 cores)
MAX_SCAN_WORK = 2e13
#: Dask tasks per worker (each a run of consecutive tiles)
TASKS_PER_WORKER = 4


def default_tile_lines(src) -> int:
    """Lines per tile so that a tile's work takes about :data:`TILE_BYTES`."""
    per_line = src.shape[1 - src.axis] * TILE_BYTES_PER_PIXEL
    return int(max(1, min(src.n_lines, TILE_BYTES // max(1, per_line))))


class _Runner:
    """Runs a pass over every tile, in this process or on a Dask client (``task``: what
    runs a group of tiles, :func:`.tile_tasks.run_tiles` by default)."""

    def __init__(self, plan, client, task=run_tiles, lower="lower --tile-rows"):
        self.client = client
        self.task = task
        self.lower = lower
        self.n = plan.n_tiles
        self.passes = 0
        if client is not None:
            nw = max(1, len(client.scheduler_info(n_workers=-1)["workers"]))
            k = min(self.n, TASKS_PER_WORKER * nw)
            edges = np.linspace(0, self.n, k + 1).round().astype(int)
            self.groups = [list(range(a, b)) for a, b in zip(edges[:-1], edges[1:]) if b > a]

    def map(self, kind, plan, args=(), label="tiles", numbered=True) -> list:
        self.passes += 1
        if numbered:                        # a scan's tiles take passes; windows one
            label = f"pass {self.passes}: {label}"
        report(0.0, label)
        if self.client is None:
            out = []
            for t in range(self.n):
                out += self.task(kind, plan, [t], args,
                                 tick=lambda f, t=t: report((t + f) / self.n, label))
            return out
        return self._dask(kind, plan, args, label)

    def _dask(self, kind, plan, args, label) -> list:
        from distributed import as_completed
        c = self.client
        pf = c.scatter(plan, broadcast=True, hash=False)
        futs = [c.submit(self.task, kind, pf, g, args, pure=False) for g in self.groups]
        where = {f.key: i for i, f in enumerate(futs)}
        parts = [None] * len(futs)
        try:
            for done, fut in enumerate(as_completed(futs), start=1):
                try:
                    parts[where[fut.key]] = fut.result()
                except (ImportError, AttributeError) as exc:
                    raise InputError(f"the Dask workers cannot run asperity ({type(exc).__name__}"
                                     f": {exc}); install the same asperity on every worker") \
                        from None
                except Exception as exc:
                    if type(exc).__name__ != "KilledWorker":
                        raise
                    from ..errors import ResourceError
                    raise ResourceError(f"a Dask worker died running the tiles (out of "
                                        f"memory?); {self.lower} or give the workers more "
                                        f"memory") from None
                report(done / len(futs), label)
        finally:
            for f in futs:
                f.cancel()
        return [r for p in parts for r in p]


def derive_scan(path, *, unit=None, pixel_size=None, height_scale=1.0, detrend="slope",
                mu=None, friction_map=None, rest_level=None, bearing_fraction=None,
                despike=None, despike_window=None, max_slope=None, contact="all-faces",
                n_directions=72, tile_lines=None, client=None, other_contact=None,
                source=None):
    """Directional friction of a height-map file of any size, derived in tiles of bounded memory.

    The result of ``derive(load_surface(path, ...))`` without ever holding all the facets:
    the map is read tile by tile in passes (spikes, form and slope; with a bearing fraction
    the rest level; the reservoir sums of every direction; the axis directions of the
    principal direction found), each reduced in tile order.  Results agree with the
    in-memory path to rounding (sums in another order), wherever the tiles run: in this
    process or as tasks on a Dask cluster.

    Parameters
    ----------
    path : str or os.PathLike
        The height-map file (``.npy``, ``.x3p`` and text matrices stream; other formats are
        read whole).
    unit, pixel_size, height_scale, detrend, mu, friction_map : optional
        As for :func:`asperity.load_surface`.
    rest_level, bearing_fraction, despike, despike_window, max_slope : optional
        As for :func:`asperity.load_surface`.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.
    n_directions : int, default 72
        Number of sliding directions, in [8, 100000].
    tile_lines : int or None, default None
        File lines per tile, >= 1; None: about 256 MiB of work a tile.
    client : distributed.Client or None, default None
        A dask.distributed client whose workers run the tiles, reading the file themselves
        (a path they can open; a streaming format).
    other_contact : {"all-faces", "windward"} or None, default None
        Also the reservoir of that regime (``d.texture.other``).
    source : LineSource or None, default None
        The file already opened by ``asperity.surface.tiles.open_scan``.

    Returns
    -------
    Derivation
        As :func:`asperity.derive` returns it; ``texture`` describes the scan (``n_facets``,
        ``tiling``).

    Raises
    ------
    asperity.InputError
        As for :func:`asperity.load_surface` and :func:`asperity.derive`; a mesh, a map of
        fewer than 2 x 2 pixels, more than 2e13 facet-directions, or a tile too large for
        the memory.

    See Also
    --------
    asperity.derive, asperity.load_surface, asperity.derive_windows

    Examples
    --------
    The 64 x 64 ridged scan in four tiles of 16 lines gives what the whole map gives:

    >>> d = asperity.derive_scan("surfaces/scan-ridges.txt", mu=0.15, tile_lines=16)
    >>> print(d.texture.tiling["tiles"], "tiles,", d.texture.n_facets, "facets,",
    ...       f"t_a at {d.principal_direction_deg:.2f} deg, mu_a+ = {d.axes['mu_a_plus']:.6f}")
    4 tiles, 7938 facets, t_a at 0.32 deg, mu_a+ = 0.157659
    >>> whole = asperity.derive(asperity.load_surface("surfaces/scan-ridges.txt", mu=0.15))
    >>> print(f"{whole.axes['mu_a_plus']:.6f}")
    0.157659
    """
    from ..surface import quality as Q
    from ..surface.facet_checks import check_options
    from ..surface.facets import DEFAULT_MU, DETREND
    from ..surface.friction_map import MAX_MU
    from ..surface.tiles import TilePlan, open_friction_map, open_scan
    from .reservoir import check_contact
    check_choice("detrend", detrend, tuple(DETREND))
    rest_level, bearing_fraction = check_options(rest_level, bearing_fraction, False, None)
    despike = Q.check_despike(despike, despike_window)
    max_slope = Q.check_max_slope(max_slope)
    check_contact(contact)
    if other_contact is not None:
        check_contact(other_contact, "other_contact")
    n = check_int("directions", n_directions, 8, 100_000)
    if client is not None:
        from distributed import Client
        check_instance("client", client, Client, "dask.distributed Client")
    if source is not None:
        from ..surface.readers._lines import LineSource
        check_instance("source", source, LineSource, "scan opened by open_scan")
    if mu is not None and friction_map is not None:
        raise InputError("give mu or a friction map, not both")
    if friction_map is None:
        mu = check_mu("mu", DEFAULT_MU if mu is None else mu, MAX_MU)
    src = source if source is not None else open_scan(
        path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
    try:
        if min(src.shape) < 2:
            raise InputError(f"{src.source}: a height map needs at least 2 x 2 pixels, got "
                             f"{src.shape}")
        from ..resources import check_work
        nx, ny = src.shape
        check_work(2.0 * (nx - 1) * (ny - 1) * 3 * n, MAX_SCAN_WORK,
                   f"{src.source}: a {nx} x {ny} grid x {n} directions (facet-directions)",
                   "lower --directions or crop the scan")
        lines = default_tile_lines(src) if tile_lines is None else \
            check_int("tile_lines", tile_lines, 1, 10 ** 9)
        lines = min(lines, src.n_lines)
        if client is not None and not src.streams:
            raise InputError(f"{src.source}: this file is read whole (gzip, .npz, instrument "
                             f"formats); tiles on Dask workers need .npy, .x3p or a text matrix")
        _check_tile_memory(src, lines)
        plan = TilePlan(heights=src, tile_lines=lines, despike=despike, mu=mu,
                        mu_map=None if friction_map is None else open_friction_map(friction_map,
                                                                                   src),
                        max_slope=max_slope)
        run = _Runner(plan, client)
        from .tile_reduce import assemble, bearing_level, prepare
        plan, info, prep = prepare(run, plan, path, detrend, friction_map, height_scale)
        if bearing_fraction is not None:
            plan = plan.with_(rest_level=bearing_level(run, plan, bearing_fraction))
            info["bearing_fraction"] = float(bearing_fraction)
        elif rest_level is not None:
            plan = plan.with_(rest_level=float(rest_level), need_z=True)
        return assemble(run, plan, info, prep, contact, n, other_contact)
    finally:
        if source is None:         # the file's handles (reopened if read again); a refusal
            src.close()            # midway left them to the garbage collector


def tile_bytes(src, lines=None) -> float:
    """Memory of the work on one tile of ``lines`` file lines (default: the default)."""
    lines = default_tile_lines(src) if lines is None else min(lines, src.n_lines)
    return float(lines * src.shape[1 - src.axis] * TILE_BYTES_PER_PIXEL)


def _check_tile_memory(src, lines) -> None:
    from ..resources import check_memory
    check_memory(tile_bytes(src, lines), f"a tile of {lines} lines of {src.source}",
                 "lower --tile-rows")


def tiles_wanted(path, *, unit=None, pixel_size=None, height_scale=1.0, tile_lines=None,
                 distributed=False):
    """The scan opened as lines when it should be derived in tiles, else None:
    ``tile_lines`` 0 never, >= 1 always (so does ``distributed``), None when the format
    streams and the map has more than :data:`AUTO_TILE_PIXELS` pixels.  Meshes: None."""
    from ..surface.readers import reader_for
    from ..surface.tiles import open_scan
    if tile_lines == 0 and not distributed:
        return None
    if reader_for(path)[0].name == "mesh":
        if tile_lines or distributed:
            raise InputError(f"{path}: a mesh is derived whole; tiles and workers are for "
                             f"height maps")
        return None
    if tile_lines is None and not distributed:
        from ..surface.readers._streams import open_lines
        src = open_lines(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
        if src is None or math.prod(src.shape) <= AUTO_TILE_PIXELS:
            return None
        return src
    return open_scan(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
