"""``asperity contact``: the elastic contact of a surface under a nominal pressure (the
area in contact, the pressures, the gap) -- the solution that ``derive --elastic`` weights
the facets with, on its own.  A mesh is pressed as its upper envelope on a grid
(:mod:`asperity.surface.mesh_grid`); ``--window`` estimates a scan's contact from windows
(:func:`asperity.friction.elastic_windows.contact_windows`)."""
from __future__ import annotations

from ..errors import InputError
from . import emit, whole_flag
from .sources import (
    add_source_arguments,
    check_pressures,
    contact_failed,
    flag_names,
    surface_options,
)

#: the wedge textures whose profile the command presses (the others have no profile)
WEDGE_KINDS = ("wedge", "gaussian-wedge")


def add_parser(sub) -> None:
    p = sub.add_parser(
        "contact", help="elastic contact of a surface under a nominal pressure",
        description="Normal, frictionless contact of a rigid rough surface (a height map, "
                    "or a wedge texture's profile over one period) pressed at the nominal "
                    "pressure P onto an elastic half-space of effective modulus E* "
                    "(boundary elements, the Polonsky-Keer conjugate gradient with exact "
                    "load control): the area fraction in contact, the mean and largest "
                    "pressure, the mean gap, the iterations and the residual.  The heights "
                    "are the rigid surface, its highest points touch first; P is the mean "
                    "over the map's projected area (pixel count x pixel area), so the load "
                    "is P times that area.  The surface flags of derive (units, pixel size, "
                    "detrend, despike, max slope) apply unchanged.  A mesh (.stl .obj .ply) "
                    "is pressed as its upper envelope sampled on a regular grid "
                    "(--grid-step).  --window W --windows K solves K windows of a height "
                    "map on their own and reports their spread (an estimate, not the whole "
                    "scan's contact).  Full contact (every "
                    "defined pixel in contact) is a result; a solve that reaches its "
                    "iteration limit exits with status 3 and writes nothing.")
    add_source_arguments(p, friction=False)
    e = p.add_argument_group("elastic contact")
    mod = e.add_mutually_exclusive_group(required=True)
    mod.add_argument("--elastic", type=float, metavar="E_STAR_PA",
                     help="effective modulus E* of the elastic half-space, Pa (> 0)")
    mod.add_argument("--materials", type=float, nargs="+", metavar="X",
                     help="E1 NU1 [E2 NU2]: Young's moduli (Pa) and Poisson's ratios of the "
                          "two bodies, E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2); E1 NU1 "
                          "alone: a rigid counterface (instead of --elastic)")
    e.add_argument("--pressure", type=float, required=True, metavar="P_PA",
                   help="nominal mean pressure over the map's projected area, Pa (> 0)")
    e.add_argument("--boundary", choices=["periodic", "free"], default=None,
                   help="periodic: the map is one period; free: a non-periodic scan (Love's "
                        "coefficients, zero padding); default: free for files and meshes, "
                        "periodic for wedge textures (periodic by construction)")
    e.add_argument("--hardness", type=float, metavar="H_PA",
                   help="perfectly plastic cap of the pressure, Pa (above the mean pressure "
                        "over the defined pixels): pressures clipped at H, the load carried "
                        "by more contact")
    e.add_argument("--grid-step", type=float, metavar="M",
                   help="a mesh: the step (m) of the height grid its upper envelope is "
                        "sampled on (default: its median projected edge length / 4, with "
                        "65536 to 4194304 nodes); nodes no triangle covers are undefined")
    e.add_argument("--tol", type=float, default=1e-8, metavar="X",
                   help="relative tolerance of the iteration: the change of the pressure "
                        "field over the load (1e-15 to 0.1; default 1e-8)")
    e.add_argument("--max-iterations", metavar="N", default=None,
                   help="iteration limit (1 to 1e7; default 10000); reached: exit status 3")
    from .derive_windows import add_window_arguments
    add_window_arguments(p, "and reports each window's contact figures and their spread "
                            "(mean, sd, min, max of the area fraction, the largest pressure "
                            "and the mean gap)")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the "
                                                       "summary")
    p.add_argument("--plot", metavar="FILE.png", help="draw the contact map and the pressure")
    p.add_argument("--save-pressure", metavar="FILE.npy",
                   help="write the pressure (Pa) on the map's own grid as a .npy array: 0 out "
                        "of contact, NaN on undefined pixels (a wedge texture: its profile's "
                        "nodes over one period, 1-D)")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True),
                                       ("--save-pressure", "save_pressure", False)],
                   inputs=["texture"])


def modulus(args) -> float:
    """E* from --elastic or --materials (exactly one is given: the parser sees to it)."""
    from ..errors import InputError
    from .sources import check_modulus
    if args.materials is None:
        return check_modulus(args.elastic)
    m = args.materials
    if len(m) not in (2, 4):
        raise InputError(f"--materials takes E1 NU1 or E1 NU1 E2 NU2 (Pa, Poisson's ratio), "
                         f"got {len(m)} values")
    from ..contact import effective_modulus
    try:
        E = effective_modulus(*m)
    except InputError as exc:
        raise InputError(f"--materials {exc}") from None
    return check_modulus(E, "--materials")


def run(args) -> tuple[dict, object, dict]:
    """(the JSON object, the ContactResult, what the picture needs); with --window (the
    JSON object, None, None)."""
    from ..friction.sources import is_texture_file
    from ..surface.contact_facets import ElasticContact
    from .derive_windows import contact_windows_args, windowed
    win = windowed(args)
    E = modulus(args)
    with flag_names():
        ec = ElasticContact(E, args.pressure, boundary=args.boundary, hardness=args.hardness,
                            tol=args.tol, max_iterations=whole_flag(
                                "--max-iterations", args.max_iterations, 1, 10 ** 7))
    check_pressures(E, ec.pressures)
    if win:
        return contact_windows_args(args, ec), None, None
    for flag, given in (("--workers", args.workers), ("--scheduler", args.scheduler)):
        if given is not None:
            raise InputError(f"{flag} runs windows (--window W); one contact is solved in "
                             "this process")
    if args.texture is not None and not is_texture_file(args.texture):
        return _map(args, ec)
    return _texture(args, ec)


def _core(res) -> dict:
    """The contact's keys (the documentation's file formats): ContactResult.to_dict (derive's elastic_contact
    block) and full_contact."""
    return {**res.to_dict(), "full_contact": res.full_contact}


def _map(args, ec):
    from ..contact.elastic import BYTES_PER_PIXEL
    from ..errors import InputError, check_range
    from ..surface.contact_facets import contact_solutions
    from ..surface.facets import facet_bytes, heightmap_facets, mesh_facets
    from ..surface.mesh_grid import face_forces, mesh_heightmap
    from ..surface.prepare import check_surface_options, prepare_surface
    from ..surface.topography import TriangleMesh
    o = surface_options(args)
    boundary = ec.boundary_or("free")
    periodic = boundary == "periodic"
    with flag_names():
        despike, max_slope = check_surface_options(
            detrend=o["detrend"], mu=None, despike=o["despike"],
            despike_window=o["despike_window"], max_slope=o["max_slope"])
        if args.grid_step is not None:
            check_range("--grid-step", args.grid_step, 0.0, None, low_open=True, unit="m")
        per_point = BYTES_PER_PIXEL[boundary] + 16 + (0 if max_slope is None
                                                      else facet_bytes(False, True))
        prep = prepare_surface(args.texture, unit=o["unit"], pixel_size=o["pixel_size"],
                               height_scale=o["height_scale"], detrend=o["detrend"],
                               friction_map=None, despike=despike, point_bytes=per_point)
        mesh = prep.surface if isinstance(prep.surface, TriangleMesh) else None
        mg = None
        if mesh is not None:
            if periodic:
                raise InputError("--boundary of a mesh must be free (its height grid is no "
                                 "period of a texture), got periodic")
            mg = mesh_heightmap(mesh, args.grid_step, per_point)
            hm = mg.heightmap
        elif args.grid_step is not None:
            raise InputError(f"--grid-step applies to meshes; {args.texture} is a height map "
                             "(its own grid)")
        else:
            hm = prep.surface
        res = next(contact_solutions(hm, ec, boundary, prep.level_slope))
    nx, ny = hm.heights.shape
    dx, dy = float(hm.dx), float(hm.dy)
    if mesh is None:
        desc = {**prep.info, "kind": "heightmap", "source": hm.source, "grid": [nx, ny],
                "pixel_size_m": [dx, dy], "physical_size_m": [dx * nx, dy * ny],
                "n_undefined": int(hm.n_undefined), **({"periodic": True} if periodic else {})}
    else:
        desc = {**prep.info, "kind": "mesh", "source": mesh.source,
                "n_triangles": mesh.n_faces, **mg.to_dict(), "pixel_size_m": [dx, dy],
                "physical_size_m": [dx * nx, dy * ny], "n_undefined": int(hm.n_undefined)}
    q = {"pixels": nx * ny, "undefined_pixels": int(hm.n_undefined),
         "undefined_share": hm.n_undefined / (nx * ny), **prep.quality}
    if max_slope is not None:                  # the steep facets' share of the contact load
        with flag_names():
            if mesh is None:
                fs = heightmap_facets(hm, info=dict(prep.info), level_slope=prep.level_slope
                                      and not periodic, max_slope=max_slope,
                                      pressure=res.pressure, periodic=periodic)
            else:
                fs = mesh_facets(mesh, info=dict(prep.info), level_slope=prep.level_slope,
                                 max_slope=max_slope,
                                 force=face_forces(mesh, mg, res.pressure))
        q.update({k: fs.quality[k] for k in ("max_slope_deg", "facets_dropped_by_slope",
                                             "dropped_load_share", "steepest_facet_deg")})
        del fs
    obj = {"texture": desc, **_core(res), "data_quality": q}
    title = f"{hm.source} ({nx} x {ny} pixels)" if mesh is None else \
        f"{mesh.source}: {mesh.n_faces} triangles on a {nx} x {ny} grid of {dx:.3g} m"
    return obj, res, {"profile": False, "heights": None, "save": res.pressure,
                      "title": title}


def _texture(args, ec):
    from ..errors import InputError
    from ..friction.elastic import wedge_heightmap
    from ..surface.contact_facets import contact_solutions
    from .sources import _texture_from_args
    tex, _ = _texture_from_args(args, None)
    kind = getattr(tex, "kind", "")
    if kind not in WEDGE_KINDS:
        raise InputError(f"asperity contact takes a height map or a wedge texture, got a "
                         f"{kind or type(tex).__name__} texture")
    if args.grid_step is not None:
        raise InputError("--grid-step applies to meshes, not to wedge textures")
    if ec.boundary_or("periodic") != "periodic":
        raise InputError("--boundary of a wedge texture must be periodic (the texture "
                         "repeats by construction), got free")
    hm, prof, dx = wedge_heightmap(tex, ec.pressure / ec.E_star)
    with flag_names():
        res = next(contact_solutions(hm, ec, "periodic", False))
    n = hm.heights.shape[0]
    desc = {**tex.to_dict(), "kind": kind, "source": f"{kind} profile", "profile_nodes": n,
            "period_m": float(prof.period), "node_spacing_m": float(dx), "periodic": True}
    obj = {"texture": desc, **_core(res)}
    return obj, res, {"profile": True, "heights": hm.heights, "save": res.pressure[:, 0],
                      "title": f"{kind} texture, profile of {n} nodes a period"}


def text(obj: dict, res) -> str:
    from ..surface.contact_facets import contact_lines
    t = obj["texture"]
    if t["kind"] == "heightmap":
        (nx, ny), (dx, dy) = t["grid"], t["pixel_size_m"]
        head = (f"surface: {t['source']} ({nx} x {ny} pixels of {dx:.4g} x {dy:.4g} m, "
                f"{t['n_undefined']} undefined)")
    elif t["kind"] == "mesh":
        (nx, ny), h = t["grid"], t["grid_step_m"]
        head = (f"mesh: {t['source']} ({t['n_triangles']} triangles), pressed as its upper "
                f"envelope on {nx} x {ny} nodes of {h:.4g} m"
                + (" (the default step)" if t["grid_step_default"] else "")
                + f"; {t['n_undefined']} nodes under no triangle (undefined)")
    else:
        head = (f"texture: {t['kind']}, profile of {t['profile_nodes']} nodes over its period "
                f"{t['period_m']:.4g} m (plane strain)")
    lines = [head, *contact_lines(obj)[:2]]    # the contact's figures, as derive prints them
    if obj["full_contact"]:
        lines.append("  full contact: every defined pixel is in contact (a result: the "
                     "pressure is at or above the one that flattens the surface)")
    if res.plastic_fraction:
        lines.append(f"  {100 * res.plastic_fraction:.3g} % of the defined pixels at the "
                     "hardness (plastic)")
    q = obj.get("data_quality")
    if q and q.get("max_slope_deg") is not None:
        lines.append(f"data quality: --max-slope {q['max_slope_deg']:g}: "
                     f"{q['facets_dropped_by_slope']} steeper facets carry "
                     f"{100 * q['dropped_load_share']:.3g} % of the contact load (the contact "
                     "itself is solved on every defined pixel)")
    if q and q.get("spike_filter"):
        lines.append(f"data quality: {q['spikes_removed']} spikes marked undefined "
                     f"(--despike {q['spike_filter']['threshold']:g})")
    return "\n".join(lines)


def main(args) -> int:
    import numpy as np

    from ..contact.solver import ContactNotConverged
    from ..io import atomic_path
    try:
        obj, res, pic = run(args)
    except ContactNotConverged as exc:
        return contact_failed("contact", exc)
    if res is None:                             # --window: an estimate from windows
        from ..friction.window_summary import contact_window_text, plot_contact_windows
        if args.plot:
            plot_contact_windows(obj, args.plot)
        emit(args, obj, contact_window_text(obj))
        return 0
    written = []
    if args.save_pressure:
        with atomic_path(args.save_pressure) as tmp, open(tmp, "wb") as f:
            np.save(f, np.asarray(pic["save"], dtype=np.float64))
        written.append(("pressure", args.save_pressure))
    if args.plot:
        from ..contact.plot import plot_contact
        plot_contact(res, args.plot, heights=pic["heights"], title=pic["title"],
                     profile=pic["profile"])
    emit(args, obj, text(obj, res), tuple(written))
    return 0
