"""``asperity derive ... --elastic E --pressure P --window W``: the contact-weighted friction
of a scan estimated from windows (:mod:`asperity.friction.elastic_windows`), in this
process or on a Dask cluster.  Shared by any command that takes the window flags."""
from __future__ import annotations

from ..errors import InputError
from ..progress import progress_bar
from . import whole_flag
from .sources import elastic_from_args, flag_names, surface_options


def add_window_arguments(p, what: str) -> None:
    """--window W --windows K --window-placement --window-seed and --workers/--scheduler
    (``what``: the end of the group's description, what is reported)."""
    from . import add_cluster_arguments
    w = p.add_argument_group(
        "elastic contact of scans beyond one solve (windows)",
        "The contact is long-range: tiles do not decouple.  With --elastic and --pressure, "
        "--window W solves K windows of W x W pixels of a height map, each on its own (read "
        "from the file alone, free boundary by default), " + what + ": an estimate from K "
        "windows, not the whole scan's contact.  A random window with fewer than 80 % of "
        "its pixels defined is redrawn in its stratum (at most 16 times; the output counts "
        "them).  --workers / --scheduler run the windows on a Dask cluster.")
    w.add_argument("--window", metavar="W", default=None,
                   help="window side in pixels, 16 to the scan's smaller side (default: none, no windows)")
    w.add_argument("--windows", metavar="K", default=None,
                   help="number of windows, 1 to 10000 (default 8)")
    w.add_argument("--window-placement", choices=["grid", "random"], default=None,
                   help="grid: a regular grid from edge to edge of the scan; random: a uniform "
                        "position in each stratum (--window-seed) (default grid)")
    w.add_argument("--window-seed", metavar="S", default=None,
                   help="seed of --window-placement random (default 0)")
    if not any(a.dest == "workers" for a in p._actions):
        add_cluster_arguments(w, "run the windows on a local Dask cluster of N worker "
                                 "processes (1 to 4096; 0: in this process, the default)",
                              "run the windows on an existing Dask cluster; the workers read "
                              "the windows from the file's path")


def windowed(args) -> bool:
    """--window is given (its companions without it are refused)."""
    if args.window is None:
        for d in ("windows", "window_placement", "window_seed"):
            if getattr(args, d) is not None:
                raise InputError(f"--{d.replace('_', '-')} needs --window (the window side "
                                 "in pixels)")
        return False
    return True


def window_flags(args) -> dict:
    """The window flags checked: window, windows, placement, seed (keyword arguments of
    :func:`asperity.friction.elastic_windows.derive_windows`)."""
    from ..friction.elastic_windows import MAX_WINDOWS, MIN_WINDOW
    w = whole_flag("--window", args.window, MIN_WINDOW, 10 ** 9)
    k = whole_flag("--windows", args.windows, 1, MAX_WINDOWS)
    seed = whole_flag("--window-seed", args.window_seed, 0, 2 ** 63 - 1)
    placement = args.window_placement or "grid"
    if seed is not None and placement != "random":
        raise InputError("--window-seed applies to --window-placement random")
    return dict(window=w, windows=8 if k is None else k, placement=placement,
                seed=0 if seed is None else seed)


def derive_windows_args(args) -> dict:
    """The JSON object of ``derive --window`` from the command's flags."""
    from ..friction.elastic_windows import derive_windows
    from ..friction.sources import is_texture_file
    if args.elastic is None:
        raise InputError("--window needs --elastic and --pressure (windows of an elastic "
                         "contact; area weighting decouples in tiles: --tile-rows)")
    flags = window_flags(args)
    if args.texture is None or is_texture_file(args.texture):
        raise InputError("--window applies to height-map files, not to wedge textures (a "
                         "texture is one period: derive it whole)")
    if getattr(args, "grid_step", None) is not None:
        raise InputError("--window takes windows of a height map; --grid-step applies to "
                         "meshes")
    if getattr(args, "tile_rows", None) is not None:
        raise InputError("--window solves windows; not with --tile-rows")
    elastic = elastic_from_args(args, several=True)
    opts = surface_options(args)
    for k in ("rest_level", "bearing_fraction"):
        opts.pop(k)

    def run(src, client):
        return derive_windows(args.texture, elastic, **flags, **opts, contact=args.contact,
                              n_directions=args.directions, client=client, source=src)
    return on_cluster(args, elastic, flags, opts, run)


def contact_windows_args(args, elastic) -> dict:
    """The JSON object of ``asperity contact --window`` (``elastic``: its ElasticContact)."""
    from ..friction.elastic_windows import contact_windows
    from ..friction.sources import is_texture_file
    flags = window_flags(args)
    if args.texture is None or is_texture_file(args.texture):
        raise InputError("--window applies to height-map files, not to wedge textures (a "
                         "texture is one period: press it whole)")
    for flag, given in (("--grid-step", args.grid_step), ("--save-pressure",
                                                         args.save_pressure)):
        if given is not None:
            raise InputError(f"--window solves windows of a height map on their own; not "
                             f"with {flag}")
    opts = surface_options(args)
    for k in ("rest_level", "bearing_fraction", "mu", "friction_map", "max_slope"):
        opts.pop(k)
    if args.max_slope is not None:
        raise InputError("--window gives the windows' contact figures; --max-slope (the "
                         "steep facets' load share) applies to a whole map")

    def run(src, client):
        return contact_windows(args.texture, elastic, **flags, **opts, client=client,
                               source=src)
    return on_cluster(args, elastic, flags, opts, run)


def on_cluster(args, elastic, flags, opts, run) -> dict:
    """``run(source, client)`` in this process or on the cluster of --workers /
    --scheduler; the result's ``windows`` says where."""
    from ..surface.tiles import open_scan
    workers = whole_flag("--workers", args.workers, 0, 4096)
    with flag_names():
        try:
            src = open_scan(args.texture, unit=opts["unit"], pixel_size=opts["pixel_size"],
                            height_scale=opts["height_scale"])
        except InputError as exc:
            if "a mesh is derived whole" not in str(exc):
                raise
            raise InputError(f"{args.texture}: --window takes windows of a height map; a "
                             "mesh is pressed whole (on its height grid, --grid-step)") from None

    def go(client):
        with flag_names(), progress_bar("windows"):
            return run(src, client)
    if not workers and args.scheduler is None:
        s = go(None)
        s["windows"].update(where="in-process", workers=0)
        return s
    if not src.streams:
        raise InputError(f"{src.source}: this file is read whole (gzip, .npz, instrument "
                         f"formats); windows on Dask workers need .npy, .x3p or a text matrix")
    import warnings

    from ..friction.elastic_windows import window_bytes
    from ..resources import WORKER_BYTES
    from ..study.engine import cluster
    boundary = elastic.boundary_or("free")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with cluster(args.scheduler, workers or None,
                     WORKER_BYTES + window_bytes(flags["window"], boundary)) as (client, where,
                                                                                  nw):
            s = go(client)
    s["windows"].update(where=where, workers=nw)
    return s
