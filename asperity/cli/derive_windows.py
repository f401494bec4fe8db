"""``asperity derive ... --elastic E --pressure P --window W``: the contact-weighted friction
of a scan estimated from windows (:mod:`asperity.friction.elastic_windows`), in this
process or on a Dask cluster.  Shared by any command that takes the window flags."""
from __future__ import annotations

from ..errors import InputError
from ..progress import progress_bar
from . import whole_flag
from .sources import elastic_from_args, flag_names, surface_options


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
    from ..friction.elastic_windows import derive_windows, window_bytes
    from ..friction.sources import is_texture_file
    from ..surface.tiles import open_scan
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
    if elastic.family:
        raise InputError("--window takes one --pressure (windows of a load curve are not "
                         "supported yet)")
    workers = whole_flag("--workers", args.workers, 0, 4096)
    opts = surface_options(args)
    for k in ("rest_level", "bearing_fraction"):
        opts.pop(k)
    with flag_names():
        src = open_scan(args.texture, unit=opts["unit"], pixel_size=opts["pixel_size"],
                        height_scale=opts["height_scale"])

    def go(client):
        with flag_names(), progress_bar("windows"):
            return derive_windows(args.texture, elastic, **flags, **opts,
                                  contact=args.contact, n_directions=args.directions,
                                  client=client, source=src)
    if not workers and args.scheduler is None:
        s = go(None)
        s["windows"].update(where="in-process", workers=0)
        return s
    if not src.streams:
        raise InputError(f"{src.source}: this file is read whole (gzip, .npz, instrument "
                         f"formats); windows on Dask workers need .npy, .x3p or a text matrix")
    import warnings

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
