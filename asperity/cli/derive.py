"""``asperity derive``: a texture's direction-dependent friction, in numbers and as a picture."""
from __future__ import annotations

from ..progress import progress_bar
from . import add_cluster_arguments, emit, whole_flag
from .parsing import DefaultsHelpFormatter
from .sources import (
    add_elastic_arguments,
    add_source_arguments,
    contact_failed,
    elastic_from_args,
    flag_names,
    spring_model_from_args,
    surface_options,
    texture_from_args,
)


def add_parser(sub) -> None:
    p = sub.add_parser(
        "derive", help="direction-dependent friction of a texture",
        description="Direction-dependent friction of a wedge texture or of any surface: the "
                    "reservoir point p(psi) = -lambda_T/lambda_N for every sliding direction psi "
                    "(wedges: from t_a, across the ridges, towards t_b, along them; surfaces: "
                    "from +x towards +y of the file), mu_a+/- and mu_b+/- (surfaces: along, "
                    "against and across the principal direction found), and the diagnostics "
                    "(self-locking, admissibility, associativity). Give a texture file (TOML, "
                    "see the documentation's file formats), the four wedge flags, or a surface file: a triangle mesh "
                    "(.stl .obj .ply), a height map (.npy, text matrix) or an instrument file "
                    "(.x3p .mi .sur .opd .datx ..., needs pip install 'asperity[metrology]'); "
                    "a trailing .gz is read too.",
        formatter_class=DefaultsHelpFormatter)
    add_source_arguments(p)
    add_elastic_arguments(p)
    p.add_argument("--method", choices=["closed-form", "springs"], default="closed-form",
                   help="closed form, or the spring-on-wedge simulation")
    p.add_argument("--directions", type=int, default=72, metavar="N",
                   help="number of equally spaced sliding directions (8 to 100000)")
    s = p.add_argument_group("spring model (--method springs; overrides the file's [springs] table)")
    s.add_argument("--k-n", type=float, metavar="N_M", help="normal stiffness of one spring, N/m")
    s.add_argument("--k-f", type=float, metavar="N_M", help="flexural stiffness of one spring, N/m, or 'inf' (rigid)")
    s.add_argument("--preload", type=float, metavar="N", help="force of a spring whose tip is at the base line z=0, N")
    s.add_argument("--density", type=float, metavar="PER_M2", help="springs per m^2")
    s.add_argument("--n-springs", type=int, metavar="N", help="springs per texture period")
    s.add_argument("--steps-per-period", type=int, metavar="N", help="quasi-static steps per period of travel")
    t = p.add_argument_group(
        "scans in tiles (height maps of any size in bounded memory)",
        "A height map read in lines (.npy, .x3p with binary points, an uncompressed text "
        "matrix) of more than 4194304 pixels (2048 x 2048) is derived in tiles "
        "automatically: read a few hundred MB at a time, in several passes, with the same "
        "result as in memory (to rounding). Other height maps are read whole, then tiled "
        "when --tile-rows is given.")
    t.add_argument("--tile-rows", metavar="N", default=None,
                   help="file lines per tile (1 to 1e9); 0: never tile (the whole map in "
                        "memory); default: automatic, about 256 MB of work per tile")
    add_cluster_arguments(t, "run the tiles on a local Dask cluster of N worker processes (1 "
                             "to 4096; 0: in this process, the default)",
                          "run the tiles on an existing Dask cluster; the workers read the "
                          "tiles from the file's path")
    from .derive_windows import add_window_arguments
    add_window_arguments(p, "and reports each window's contact and friction, their mean and "
                            "spread (several --pressure values: each window solved as a load "
                            "curve, the spread given per pressure)")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the summary")
    p.add_argument("--plot", metavar="FILE.png", help="draw the polar reservoir and T/L against psi "
                                                      "(surfaces: and a height-map preview)")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True)],
                   inputs=["texture", "friction_map"])


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json."""
    from ..friction.derive import derive, to_json
    from .derive_windows import windowed
    if windowed(args):
        from .derive_windows import derive_windows_args
        s = derive_windows_args(args)
        return s, s
    scan = _scan(args)
    if scan is not None:
        d = _derive_tiles(args, *scan)
        return d, to_json(d)
    elastic = elastic_from_args(args, several=True)
    texture, table = texture_from_args(args, several=True)
    if elastic is not None and elastic.family:
        from ..friction.family import derive_family, family_json
        with flag_names(), progress_bar("facets") as progress:
            fam = derive_family(texture, elastic, args.contact, args.directions, progress)
        return fam, family_json(fam)
    if elastic is not None:
        texture = texture[0]
    model = spring_model_from_args(args, table) if args.method == "springs" else None
    with flag_names(), progress_bar("facets") as progress:
        d = derive(texture, args.contact, args.method, args.directions, model, progress=progress)
    return d, to_json(d)


def _scan(args):
    """(lines of the height map, tile lines, workers) when it is derived in tiles, else None."""
    from ..errors import InputError
    from ..friction.sources import is_texture_file
    rows = whole_flag("--tile-rows", args.tile_rows, 0, 10 ** 9)
    workers = whole_flag("--workers", args.workers, 0, 4096)
    distributed = bool(workers) or args.scheduler is not None
    if args.elastic is not None:
        if rows or distributed:
            flag = "--tile-rows" if rows else "--workers" if workers else "--scheduler"
            raise InputError(f"--elastic solves the whole map in memory; not with {flag} "
                             "(the contact is long-range: tiles do not decouple; --window W "
                             "estimates it from windows)")
        return None
    if args.texture is None or is_texture_file(args.texture):
        if rows is not None or distributed:
            flag = "--tile-rows" if rows is not None else \
                "--workers" if workers else "--scheduler"
            raise InputError(f"{flag} applies to height-map files, not to wedge textures")
        return None
    if args.method != "closed-form":
        return None                       # refused by derive as for any surface
    if rows == 0 and distributed:
        raise InputError("--tile-rows 0 keeps the map in memory; --workers and --scheduler "
                         "run tiles")
    from ..friction.tiled import tiles_wanted
    opts = surface_options(args)
    with flag_names():
        src = tiles_wanted(args.texture, unit=opts["unit"], pixel_size=opts["pixel_size"],
                           height_scale=opts["height_scale"], tile_lines=rows,
                           distributed=distributed)
    if src is None:
        return None
    return src, (rows or None), workers


def _derive_tiles(args, src, rows, workers):
    """derive_scan with the command's flags: in this process, or on a Dask cluster."""
    from ..errors import InputError
    from ..friction.tiled import derive_scan
    opts = surface_options(args)
    other = ("windward" if args.contact == "all-faces" else "all-faces") if args.plot else None

    def go(client):
        with flag_names():
            return derive_scan(args.texture, **opts, contact=args.contact,
                               n_directions=args.directions, tile_lines=rows, client=client,
                               other_contact=other, source=src)
    if not workers and args.scheduler is None:
        d = go(None)
        d.texture.tiling.update(where="in-process", workers=0)
        return d
    if not src.streams:
        raise InputError(f"{src.source}: this file is read whole (gzip, .npz, instrument "
                         f"formats); tiles on Dask workers need .npy, .x3p or a text matrix")
    import warnings

    from ..friction.tiled import tile_bytes
    from ..resources import WORKER_BYTES
    from ..study.engine import cluster
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # e.g. distributed's note on a busy dashboard port
        with cluster(args.scheduler, workers or None,
                     WORKER_BYTES + tile_bytes(src, rows)) as (client, where, nw):
            d = go(client)
    d.texture.tiling.update(where=where, workers=nw)
    return d


def main(args) -> int:
    from ..contact.solver import ContactNotConverged
    from ..friction.derive import format_text
    try:
        d, obj = run(args)
    except ContactNotConverged as exc:
        return contact_failed("derive", exc)
    from ..friction.family import LawFamily
    if isinstance(d, dict):                     # --window: an estimate from windows
        from ..friction import window_summary as ws
        family = "per_pressure" in d
        if args.plot:
            (ws.plot_window_family if family else ws.plot_windows)(d, args.plot)
        emit(args, obj, (ws.family_window_text if family else ws.window_text)(d))
        return 0
    if isinstance(d, LawFamily):                # several --pressure values
        from ..friction.family import family_text, plot_family
        if args.plot:
            plot_family(d, args.plot)
        emit(args, obj, family_text(d))
        return 0
    if args.plot:
        from ..friction.plot import plot_derivation
        other = "windward" if d.contact == "all-faces" else "all-faces"
        scan_other = getattr(d.texture, "other", {}).get(other)
        if scan_other is None:
            from ..friction.faces import compute_reservoir
            scan_other = compute_reservoir(d.texture, d.reservoir.psi, other)
        plot_derivation(d, args.plot, other=scan_other)
    emit(args, obj, format_text(d))
    return 0
