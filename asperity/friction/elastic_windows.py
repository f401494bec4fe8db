"""Friction weighted by an elastic contact, estimated from windows of a scan too large
for one solve (issue 19, item 4).

The contact is long-range: the pressure at a point depends on the whole map, so tiles do
not decouple as they do for area weighting (:mod:`.tiled`).  Instead :func:`derive_windows`
solves K representative *windows* -- square patches of W x W pixels -- each on its own,
as if it were the whole scan pressed at the nominal pressure (free boundary by default),
and reports each window's contact figures and contact-weighted friction, their mean and
their spread.  It is an estimate from K windows of W, never the whole scan's solution.

* Placement (:func:`window_origins`): the range of window origins [0, nx - W] x [0, ny -
  W] is cut into a grid of r x c strata (r c >= K, r / c close to the scan's shape) and
  K of them are taken, spread evenly; ``grid`` puts the windows on the r x c regular grid
  from edge to edge of the scan, ``random`` a uniform origin inside each stratum (NumPy's
  PCG64 stream of ``seed``).  Windows overlap when K W^2
  exceeds the scan's area (said in the result).
* A window is read from the file alone (:func:`read_window`: a few lines of the file at a
  time, cropped), so a task holds its window and its solve, never the scan; a window with
  fewer than :data:`MIN_DEFINED_SHARE` of its pixels defined is skipped (and named).
  With ``random`` placement a skipped window is redrawn in its own stratum (up to
  :data:`MAX_REDRAWS` times, from the stream ``(seed, window, attempt)``: the same
  whatever runs it); the result counts the windows redrawn and those still skipped.
  ``grid`` windows are not redrawn (the grid is the placement asked for).
* Several pressures (an ElasticContact family): each window is solved as a load curve
  (:func:`asperity.contact.iter_load_curve`, each pressure from the previous one's
  solution) and derived at each pressure; the summary gives the spread per pressure.
* ``derive=False`` (``asperity contact --window``): the windows' contact figures only.
* Each window is prepared as a scan of its own (spikes, form and slope removed within it),
  weighted by :func:`asperity.surface.contact_facets.elastic_facets` and derived
  (:func:`asperity.friction.derive.derive`): its principal direction is its own.
* The windows run in this process or as tasks on a Dask cluster (the runner of
  :mod:`.tiled`, the clusters of :mod:`asperity.study.engine`); the results are the same.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_choice, check_instance, check_int
from ..progress import report
from .window_summary import MAX_REDRAWS, MIN_DEFINED_SHARE, summarise

#: smallest window side (pixels): a smaller patch cannot resolve a contact spot
MIN_WINDOW = 16
#: most windows of one estimate
MAX_WINDOWS = 10_000
PLACEMENTS = ("grid", "random")
#: values read at a time when a window is cut from a file's lines
_READ_VALUES = 1 << 22


@dataclass(frozen=True)
class WindowPlan:
    """What every window task needs (picklable: a worker reads its window itself)."""

    heights: object                 # a LineSource (asperity.surface.tiles.open_scan)
    mu_map: object                  # None or a LineSource of the per-pixel friction
    window: int
    origins: tuple                  # ((i0, j0), ...) pixels
    elastic: object                 # ElasticContact of one pressure, boundary set
    options: dict                   # detrend, mu, despike, max_slope
    contact: str
    n_directions: int
    derive: bool = True             # False: the contact figures only (asperity contact)
    strata: tuple | None = None     # random placement: each window's stratum, for redraws
    seed: int = 0
    asked: int | None = None        # windows asked (None: as many as origins)

    @property
    def n_tiles(self) -> int:       # the runner of .tiled counts its items so
        return len(self.origins)


def window_strata(shape, window: int, count: int) -> list[tuple]:
    """The stratum (x0, x1, y0, y1, a, b, r, c) of each of ``count`` windows: origins in
    [x0, x1) x [y0, y1), cell (a, b) of the r x c grid of strata."""
    nx, ny = shape
    sx, sy = nx - window + 1, ny - window + 1          # origins available along x, y
    r = int(min(count, max(1, round(math.sqrt(count * sx / sy)))))
    c = -(-count // r)
    cells = np.round(np.linspace(0, r * c - 1, count)).astype(int)
    out = []
    for k in cells:
        a, b = divmod(int(k), c)
        out.append((a * sx / r, (a + 1) * sx / r, b * sy / c, (b + 1) * sy / c, a, b, r, c))
    return out


def _draw(stratum, shape, window, rng) -> tuple[int, int]:
    """A uniform origin in ``stratum``."""
    x0, x1, y0, y1 = stratum[:4]
    sx, sy = shape[0] - window + 1, shape[1] - window + 1
    u, v = rng.random(2)
    return (min(sx - 1, int(x0 + u * (x1 - x0))), min(sy - 1, int(y0 + v * (y1 - y0))))


def window_positions(shape, window: int) -> int:
    """How many distinct windows of ``window`` pixels a map of ``shape`` holds (origins)."""
    return (shape[0] - window + 1) * (shape[1] - window + 1)


def window_origins(shape, window: int, count: int, placement: str = "grid",
                   seed: int = 0) -> list[tuple[int, int]]:
    """Origins (i0, j0) of ``count`` windows of ``window`` pixels in a map of ``shape``
    (a grid finer than the positions repeats some: :func:`_run` solves each once)."""
    sx, sy = shape[0] - window + 1, shape[1] - window + 1
    rng = np.random.default_rng(seed)
    out = []
    for st in window_strata(shape, window, count):
        a, b, r, c = st[4:]
        if placement == "grid":                        # spread from edge to edge
            out.append((round((sx - 1) * (a / (r - 1) if r > 1 else 0.5)),
                        round((sy - 1) * (b / (c - 1) if c > 1 else 0.5))))
            continue
        out.append(_draw(st, shape, window, rng))
    return out


def read_window(src, i0: int, j0: int, w: int) -> np.ndarray:
    """heights[i0:i0 + w, j0:j0 + w] of a LineSource, read a few of its lines at a time."""
    out = np.empty((w, w))
    if src.axis == 0:
        a0, b0 = i0, j0
    else:
        a0, b0 = j0, i0
    step = max(1, _READ_VALUES // max(1, src.shape[1 - src.axis]))
    for s in range(0, w, step):
        e = min(w, s + step)
        part = src.lines(a0 + s, a0 + e)               # heights[a:b, :] or heights[:, a:b]
        if src.axis == 0:
            out[s:e] = part[:, b0:b0 + w]
        else:
            out[:, s:e] = part[b0:b0 + w, :]
    return out


def window_bytes(window: int, boundary: str) -> float:
    """Memory of one window's work: its solve or its facets, whichever is larger."""
    from ..contact.elastic import BYTES_PER_PIXEL
    from ..surface.facets import facet_bytes
    return float(window) ** 2 * (max(BYTES_PER_PIXEL[boundary], facet_bytes(False, True)) + 32)


def _read_defined(plan: WindowPlan, k: int):
    """(origin, heights, defined share, rejected origins) of window ``k``: redrawn in its
    stratum while too few of its pixels are defined (random placement, at most
    :data:`MAX_REDRAWS` times)."""
    src, w = plan.heights, plan.window
    origin = plan.origins[k]
    rejected = []
    for attempt in range(MAX_REDRAWS + 1):
        if attempt:
            rng = np.random.default_rng([plan.seed, k, attempt])
            origin = _draw(plan.strata[k], src.shape, w, rng)
        z = read_window(src, origin[0], origin[1], w)
        share = float(np.isfinite(z).mean())
        if share >= MIN_DEFINED_SHARE or plan.strata is None:
            break
        rejected.append([int(origin[0]), int(origin[1])])
    return origin, z, share, rejected


def solve_window(plan: WindowPlan, k: int, tick=None) -> dict:
    """One window's contact and friction (a task); ``skipped`` when too few pixels are
    defined (after the redraws of a random placement)."""
    from ..surface.contact_facets import contact_solutions, elastic_facets
    from ..surface.prepare import DETREND
    from ..surface.quality import remove_spikes
    from ..surface.topography import HeightMap
    from .derive import derive, to_json
    src, w = plan.heights, plan.window
    (i0, j0), z, share, rejected = _read_defined(plan, k)
    out = {"index": k, "origin_px": [int(i0), int(j0)],
           "origin_m": [i0 * src.dx, j0 * src.dy]}
    out["defined_share"] = share
    if plan.strata is not None:
        out["redrawn_from"] = rejected if share >= MIN_DEFINED_SHARE else rejected[:-1]
    if share < MIN_DEFINED_SHARE:
        out["skipped"] = (f"{100 * share:.1f} % of its pixels defined (at least "
                          f"{100 * MIN_DEFINED_SHARE:.0f} % needed)"
                          + (f", after {MAX_REDRAWS} redraws" if plan.strata is not None
                             else ""))
        return out
    o = plan.options
    spikes = 0 if o["despike"] is None else remove_spikes(z, o["despike"])
    hm = HeightMap(z, src.dx, src.dy, source=f"{src.source} window {k}",
                   n_undefined=int(np.count_nonzero(~np.isfinite(z))))
    degree = DETREND[o["detrend"]]
    if degree not in (None, "slope"):
        from ..surface.detrend import detrend
        hm = detrend(hm, degree)
    out["spikes_removed"] = spikes
    e = plan.elastic
    if not plan.derive:                  # the contact figures only
        members = [{"elastic_contact": res.to_dict()} for res in contact_solutions(
            hm, e, e.boundary_or("free"), o["detrend"] == "slope")]
    else:
        fm = None if plan.mu_map is None else read_window(plan.mu_map, i0, j0, w)
        members = []
        for fs in elastic_facets(hm, e, mu=None if fm is not None else o["mu"],
                                 friction_map=fm, level_slope=o["detrend"] == "slope",
                                 info={"file": src.path, "detrend": o["detrend"]},
                                 max_slope=o["max_slope"]):
            d = derive(fs, plan.contact, "closed-form", plan.n_directions)
            j = to_json(d)
            m = {key: j[key] for key in ("mu_a_plus", "mu_a_minus", "mu_b_plus",
                                         "mu_b_minus", "principal_direction_deg",
                                         "anisotropy", "n_facets")}
            m["self_locking"] = bool(d.self_locking)
            m["elastic_contact"] = fs.elastic
            m["tangential"] = [x["tangential"] for x in j["directions"]]
            members.append(m)
            del fs, d, j
    if e.family:
        out["members"] = members
    else:
        out.update(members[0])
    if tick is not None:
        tick(1.0)
    return out


def run_windows(kind, plan, windows, args=(), tick=None) -> list:
    """The runner's task (:class:`asperity.friction.tiled._Runner`): windows ``windows``."""
    return [solve_window(plan, k, tick) for k in windows]


def check_window_request(shape, window, count, placement, seed) -> tuple[int, int, int]:
    """(window, count, seed) checked against the scan's ``shape``: one line naming the
    flag (the seed as an int: 0.0 or numpy.float64(0) does not seed a generator)."""
    w = check_int("window", window, MIN_WINDOW, None)
    n = check_int("windows", count, 1, MAX_WINDOWS)
    check_choice("placement", placement, PLACEMENTS)
    seed = check_int("seed", seed, 0, 2 ** 63 - 1)
    if w > min(shape):
        raise InputError(f"window {w} pixels is larger than the scan ({shape[0]} x "
                         f"{shape[1]} pixels): at most {min(shape)}")
    return w, n, seed


def derive_windows(path, elastic, *, window, windows=8, placement="grid", seed=0,
                   unit=None, pixel_size=None, height_scale=1.0, detrend="slope", mu=None,
                   friction_map=None, despike=None, despike_window=None, max_slope=None,
                   contact="all-faces", n_directions=72, client=None, source=None) -> dict:
    """Contact-weighted friction of a height-map file estimated from windows of the scan.

    The elastic contact is long-range, so a scan too large for one solve does not split into
    tiles: K representative windows of W x W pixels are each solved on their own, as if each
    were the whole scan pressed at the nominal pressure, and derived (:func:`asperity.derive`
    with the facets weighted by the contact force).  An estimate from K windows of W,
    never the whole scan's solution (the placement rules: the docstring of
    ``asperity.friction.elastic_windows``).

    Parameters
    ----------
    path : str or os.PathLike
        The height-map file.
    elastic : ElasticContact
        One pressure, or several (each window solved as a load curve; the spread given per
        pressure); boundary None: free.
    window : int
        Window side, pixels, >= 16 and at most the scan's smaller side.
    windows : int, default 8
        Number of windows K, in [1, 10000] (at most one a distinct position is solved).
    placement : {"grid", "random"}, default "grid"
        A regular grid from edge to edge, or a uniform origin in each of K strata.
    seed : int, default 0
        Seed of the random placement, >= 0.
    unit, pixel_size, height_scale, detrend, mu, friction_map : optional
        As for :func:`asperity.load_surface` (each window is prepared as a scan of its own).
    despike, despike_window, max_slope : optional
        As for :func:`asperity.load_surface`.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.
    n_directions : int, default 72
        Number of sliding directions, in [8, 100000].
    client : distributed.Client or None, default None
        A dask.distributed client whose workers solve the windows (reading them from the
        file's path).
    source : LineSource or None, default None
        The file already opened by ``asperity.surface.tiles.open_scan``.

    Returns
    -------
    dict
        The JSON object of ``asperity derive --window`` (formats: outputs): ``estimate``
        (what it is), ``windows`` (asked, solved, used, skipped, redrawn), and for ``area_fraction``,
        ``mu_a_plus``, ``mu_a_minus``, ``mu_b_plus``, ``mu_b_minus`` the ``mean``, ``sd``,
        ``min``, ``max`` and ``n`` over the windows; ``directions`` the same per direction.

    Raises
    ------
    asperity.InputError
        An option out of range, a window larger than the scan, too little memory for a
        window, or no window with 80 % of its pixels defined.

    See Also
    --------
    asperity.load_elastic, asperity.derive_scan, asperity.ElasticContact

    Examples
    --------
    >>> w = asperity.derive_windows("surfaces/scan-ridges.txt",
    ...                             asperity.ElasticContact(E_star=1e9, pressure=1e7),
    ...                             window=32, windows=4, mu=0.15)
    >>> print(w["windows"]["used"], "windows:", f"contact {w['area_fraction']['mean']:.4f},",
    ...       f"mu_a+ {w['mu_a_plus']['mean']:.4f} +- {w['mu_a_plus']['sd']:.4f}")
    4 windows: contact 0.1338, mu_a+ 0.1408 +- 0.0023
    """
    from .window_summary import summarise_family
    plan, results = _run(path, elastic, True, window, windows, placement, seed, unit,
                         pixel_size, height_scale, detrend, mu, friction_map, despike,
                         despike_window, max_slope, contact, n_directions, client, source)
    if plan.elastic.family:
        return summarise_family(plan, results, placement, seed)
    return summarise(plan, results, placement, seed)


def contact_windows(path, elastic, *, window, windows=8, placement="grid", seed=0,
                    unit=None, pixel_size=None, height_scale=1.0, detrend="slope",
                    despike=None, despike_window=None, client=None, source=None) -> dict:
    """The elastic contact of a height-map file estimated from windows (as
    :func:`derive_windows`, the contact figures only): the JSON object of ``asperity
    contact --window`` (file formats, outputs)."""
    from .window_summary import contact_summary
    plan, results = _run(path, elastic, False, window, windows, placement, seed, unit,
                         pixel_size, height_scale, detrend, None, None, despike,
                         despike_window, None, "all-faces", 72, client, source)
    return contact_summary(plan, results, placement, seed)


def _run(path, elastic, derive, window, windows, placement, seed, unit, pixel_size,
         height_scale, detrend, mu, friction_map, despike, despike_window, max_slope,
         contact, n_directions, client, source):
    """(the plan, each window's result), the inputs checked first."""
    from dataclasses import replace

    from ..surface.contact_facets import check_elastic
    from ..surface.prepare import check_surface_options
    from ..surface.tiles import open_friction_map, open_scan
    from .reservoir import check_contact
    from .tiled import _Runner
    elastic = check_elastic(elastic)
    despike, max_slope = check_surface_options(detrend=detrend, mu=mu, despike=despike,
                                               despike_window=despike_window,
                                               max_slope=max_slope)
    if mu is not None and friction_map is not None:
        raise InputError("give mu or a friction map, not both")
    check_contact(contact)
    n_dir = check_int("directions", n_directions, 8, 100_000)
    if client is not None:
        from distributed import Client
        check_instance("client", client, Client, "dask.distributed Client")
    if source is not None:
        from ..surface.readers._lines import LineSource
        check_instance("source", source, LineSource, "scan opened by open_scan")
    src = source if source is not None else open_scan(
        path, unit=unit, pixel_size=pixel_size, height_scale=height_scale)
    w, n, seed = check_window_request(src.shape, window, windows, placement, seed)
    if client is not None and not src.streams:
        raise InputError(f"{src.source}: this file is read whole (gzip, .npz, instrument "
                         f"formats); windows on Dask workers need .npy, .x3p or a text matrix")
    boundary = elastic.boundary_or("free")
    from ..resources import check_memory
    check_memory(window_bytes(w, boundary), f"a window of {w} x {w} pixels",
                 "lower --window")
    # a window solved twice gives the same result twice: at most one a position (a 64 x 64
    # scan holds one window of 64, and solved 10000 identical ones for --windows 10000)
    k = min(n, window_positions(src.shape, w))
    origins = window_origins(src.shape, w, k, placement, seed)
    strata = window_strata(src.shape, w, k) if placement == "random" else None
    first = sorted({o: i for i, o in reversed(list(enumerate(origins)))}.values())
    origins = tuple(origins[i] for i in first)      # strata narrower than a pixel repeat
    strata = None if strata is None else tuple(strata[i] for i in first)
    plan = WindowPlan(src, None if friction_map is None else open_friction_map(friction_map,
                                                                                src),
                      w, origins, replace(elastic, boundary=boundary),
                      {"detrend": detrend, "mu": mu, "despike": despike,
                       "max_slope": max_slope}, contact, n_dir, derive=derive,
                      strata=strata, seed=seed, asked=n)
    report(0.0, "windows")
    results = _Runner(plan, client, run_windows, "lower --window").map(
        "window", plan, label="windows", numbered=False)
    return plan, results
