"""The texture/surface arguments shared by every command that reads one (derive, fit,
risk), and turning them into a texture or surface.
"""
from __future__ import annotations

import itertools

from ..errors import InputError
from ..friction.sources import is_texture_file

SPRING_FLAGS = {  # flag dest -> key of the [springs] table / SpringModel field
    "k_n": "k_n", "k_f": "k_f", "preload": "preload", "density": "density",
    "n_springs": "n_springs", "steps_per_period": "steps_per_period",
}


WEDGE_FLAGS = {"alpha": "alpha_deg", "beta": "beta_deg", "mu_alpha": "mu_alpha",
               "mu_beta": "mu_beta", "height": "height"}


SURFACE_FLAGS = ("mu", "friction_map", "unit", "pixel_size", "rest_level", "bearing_fraction",
                 "max_slope", "despike", "despike_window")
#: library field names in messages -> the command-line flag
_FIELD_FLAGS = {"pixel_size": "--pixel-size", "height_scale": "--height-scale",
                "bearing_fraction": "--bearing-fraction",
                "mu ": "--mu ", "unit ": "--unit ", "detrend ": "--detrend ",
                "max_slope": "--max-slope", "despike_window": "--despike-window",
                "despike": "--despike", "tile_lines": "--tile-rows",
                "pressure / E_star": "--pressure / --elastic", "E_star": "--elastic",
                "pressure": "--pressure", "hardness": "--hardness",
                "max_iterations": "--max-iterations", "tol ": "--tol ",
                "window_placement": "--window-placement", "window_seed": "--window-seed",
                "windows": "--windows", "window ": "--window ", "grid_step": "--grid-step",
                "rest_level": "--rest-level", "directions ": "--directions ",
                "boundary ": "--boundary "}
#: the elastic-contact flags (dest -> flag)
ELASTIC_FLAGS = {"elastic": "--elastic", "pressure": "--pressure", "boundary": "--boundary",
                 "hardness": "--hardness", "grid_step": "--grid-step"}


def surface_options(args) -> dict:
    """The surface flags as keyword arguments of load_surface (and derive_scan)."""
    px = args.pixel_size
    if px is not None and len(px) not in (1, 2):
        raise InputError(f"--pixel-size takes one value or two (dx dy), got {len(px)}")
    if args.despike_window is not None and args.despike is None:
        raise InputError("--despike-window needs --despike (the spike filter's threshold)")
    return {"unit": args.unit,
            "pixel_size": None if px is None else (px[0] if len(px) == 1 else tuple(px)),
            "height_scale": args.height_scale, "detrend": args.detrend, "mu": args.mu,
            "friction_map": args.friction_map, "rest_level": args.rest_level,
            "bearing_fraction": args.bearing_fraction, "despike": args.despike,
            "despike_window": args.despike_window, "max_slope": args.max_slope}


#: library wording inside a message (after a file's name) -> the flags
_PHRASES = (("pass unit and pixel_size", "pass --unit and --pixel-size"),
            ("pixel_size is given in unit;", "--pixel-size is given in --unit;"),
            ("pixel_size applies to", "--pixel-size applies to"), ("pass unit", "pass --unit"),
            ("pixel_size in that unit", "--pixel-size in that unit"),
            ("(and height_scale)", "(and --height-scale)"))


class flag_names:
    """Library field names at the start of an InputError's message (and a few phrases
    after a file's name) -> the user's flags; ``fields``: {field: flag} to use instead of
    the surface flags' (the first that starts the message is taken)."""

    def __init__(self, fields=None):
        self.fields = _FIELD_FLAGS if fields is None else fields

    def __enter__(self):
        return self

    def __exit__(self, kind, exc, tb):
        if kind is not None and issubclass(kind, InputError):
            msg = str(exc)
            for field, flag in self.fields.items():
                if msg.startswith(field):
                    raise kind(flag + msg[len(field):]) from None
            new = msg
            for phrase, flags in _PHRASES:
                new = new.replace(phrase, flags)
            if new != msg:
                raise kind(new) from None
        return False


def surface_from_args(args, progress=None, elastic=None):
    """FacetSurface from a surface file and the surface flags (with ``elastic``: the list
    of contact-weighted FacetSurfaces, one a pressure)."""
    from ..surface.facets import load_surface
    with flag_names():                    # the library's field names as the user's flags
        if elastic is None:
            return load_surface(args.texture, **surface_options(args))
        from ..surface.contact_facets import load_elastic
        opts = {k: v for k, v in surface_options(args).items()
                if k not in ("rest_level", "bearing_fraction")}
        return load_elastic(args.texture, elastic, grid_step=args.grid_step, **opts)


def add_elastic_arguments(p) -> None:
    """--elastic E* --pressure P [P ...] [--boundary] [--hardness]: load shares from an
    elastic contact solution (derive, fit, risk)."""
    e = p.add_argument_group(
        "elastic contact (load shares from a contact solution; height maps, meshes and "
        "wedge textures)",
        "The surface (a height map, or a wedge texture's profile over one period) is pressed "
        "at the nominal pressure P onto an elastic half-space of effective modulus E* "
        "(frictionless normal contact, Polonsky-Keer); each facet's load share is the "
        "normal force it carries, the facet law unchanged.  Not right where the pressure "
        "reaches the hardness nor where sliding redistributes the load.")
    e.add_argument("--elastic", type=float, metavar="E_STAR_PA",
                   help="effective modulus E* of the elastic half-space, Pa (> 0)")
    e.add_argument("--pressure", type=float, nargs="+", metavar="P_PA",
                   help="nominal mean pressure over the map's projected area, Pa (> 0); "
                        "several (derive, fit): a law for each, a law family")
    e.add_argument("--boundary", choices=["periodic", "free"], default=None,
                   help="periodic: the map is one period; free: a non-periodic scan "
                        "(default: free for files, periodic for wedge textures)")
    e.add_argument("--hardness", type=float, metavar="H_PA",
                   help="perfectly plastic cap of the pressure, Pa (above the pressure)")
    e.add_argument("--grid-step", type=float, metavar="M",
                   help="a mesh: the step (m) of the height grid its upper envelope is "
                        "pressed on, each triangle weighing the force of the nodes it "
                        "holds (default: its median projected edge length / 4)")


#: exit status when the contact solve reaches its iteration limit (as ``slide``'s)
EXIT_NOT_CONVERGED = 3


def contact_failed(command: str, exc) -> int:
    """Report a contact solve that did not converge (one line, nothing written): exit 3."""
    import sys
    r = exc.result
    print(f"asperity {command}: error: the elastic contact did not converge at --pressure "
          f"{r.pressure_asked:g} in {r.iterations} iteration{'s' * (r.iterations != 1)} "
          f"(residual {r.residual:.3g}); "
          "nothing written", file=sys.stderr)
    return EXIT_NOT_CONVERGED


def elastic_from_args(args, several: bool):
    """The ElasticContact of the elastic flags, or None when --elastic is not given;
    ``several``: several pressures are allowed (else one line refuses them)."""
    given = [f for d, f in ELASTIC_FLAGS.items() if getattr(args, d, None) is not None]
    if getattr(args, "elastic", None) is None:
        if given:
            raise InputError(f"{given[0]} needs --elastic (the effective modulus E*, Pa)")
        return None
    if args.pressure is None:
        raise InputError("--elastic needs --pressure (the nominal pressure, Pa)")
    for d, flag in (("rest_level", "--rest-level"), ("bearing_fraction", "--bearing-fraction")):
        if getattr(args, d, None) is not None:
            raise InputError(f"--elastic sets the load shares; not with {flag}")
    if getattr(args, "method", "closed-form") != "closed-form":
        raise InputError("--elastic weights the closed form; --method springs has its own "
                         "load model")
    from ..surface.contact_facets import ElasticContact
    p = args.pressure
    E = check_modulus(args.elastic)
    with flag_names():
        elastic = ElasticContact(E, p[0] if len(p) == 1 else tuple(p),
                                 boundary=args.boundary, hardness=args.hardness)
    check_pressures(E, elastic.pressures)
    for a, b in itertools.pairwise(elastic.pressures if several else ()):
        if not b > a:                       # a family (derive, fit): each pressure once
            raise InputError(f"--pressure values of a law family must be strictly "
                             f"increasing, got {b:g} after {a:g}")
    if elastic.family and not several:
        raise InputError("several --pressure values make a family of laws (derive and fit "
                         "take them); this command takes the law at one pressure: give one "
                         "--pressure")
    return elastic


def check_modulus(E, flag: str = "--elastic") -> float:
    """E* in the contact solver's range, named by ``flag`` (--elastic, or --materials for
    the modulus the materials give), before any work."""
    from ..contact.solver import E_RANGE
    from ..errors import check_range
    if flag == "--elastic":
        return check_range(flag, E, *E_RANGE, unit="Pa")
    if not E_RANGE[0] <= E <= E_RANGE[1]:
        raise InputError(f"{flag} gives E* = {E:.4g} Pa, outside [{E_RANGE[0]:g}, "
                         f"{E_RANGE[1]:g}] Pa")
    return E


def check_pressures(E: float, pressures) -> None:
    """Every --pressure over E* in the solver's range, before any work (a wedge's profile
    is sampled for it before the solve checks it)."""
    from ..contact.solver import PRESSURE_OVER_E
    from ..errors import check_range
    for p in pressures:
        check_range("--pressure / --elastic", p / E, *PRESSURE_OVER_E)


def add_source_arguments(p, friction: bool = True, contact_default: str | None = "all-faces",
                         contact_note: str = "") -> None:
    """The texture/surface arguments and --contact, shared by every command that reads one
    (``friction`` False: without the friction and load-model flags, which then read as
    not given: --mu, --friction-map, --rest-level, --bearing-fraction, --contact).
    ``contact_default`` None: --contact not given reads as None (the command decides),
    ``contact_note`` then says in its help what that means."""
    p.add_argument("texture", nargs="?", metavar="TEXTURE_OR_SURFACE",
                   help="texture file (.toml) or surface file (mesh, height map, instrument file)")
    g = p.add_argument_group("wedge texture given by flags (instead of a file)")
    g.add_argument("--alpha", type=float, metavar="DEG", help="slope of the face rising towards +t_a, in (0, 90)")
    g.add_argument("--beta", type=float, metavar="DEG", help="slope of the face falling towards +t_a, in (0, 90)")
    g.add_argument("--mu-alpha", type=float, metavar="X", help="local friction on the alpha face, >= 0")
    g.add_argument("--mu-beta", type=float, metavar="Y", help="local friction on the beta face, >= 0")
    g.add_argument("--height", type=float, metavar="M", help="wedge height in m (the friction does not depend on it)")
    f = p.add_argument_group("surface files (meshes, height maps, instrument files)")
    if not friction:
        p.set_defaults(mu=None, friction_map=None, rest_level=None, bearing_fraction=None,
                       contact="all-faces")
    else:
        f.add_argument("--mu", type=float, metavar="X",
                       help="uniform local friction coefficient of the surface, >= 0 (default 0.1)")
        f.add_argument("--friction-map", metavar="FILE",
                       help="local friction per pixel (height maps: same grid) or per triangle "
                            "(meshes), .npy or text; instead of --mu")
    f.add_argument("--unit", metavar="UNIT",
                   help="length unit of the file's numbers (and of --pixel-size): m, mm, um "
                        "or nm; needed where the file states none (meshes, .npy, bare text "
                        "matrices); where the file states one, --unit replaces it (a file "
                        "written in another unit than it says: an x3p's heights and spacing, "
                        "a text matrix's heights; its '# Width:' keeps its own unit)")
    f.add_argument("--pixel-size", type=float, nargs="+", metavar="D",
                   help="pixel size (one value, or dx dy) in --unit, for height maps without sizes")
    f.add_argument("--height-scale", type=float, default=1.0, metavar="F",
                   help="multiply the heights by F (> 0), e.g. to study a scaled texture")
    f.add_argument("--detrend", choices=["slope", "none", "mean", "plane", "poly2", "poly3"],
                   default="slope", help="tilt/form removal: slope = remove the mean facet "
                   "gradient (zero mean slope; exact for periodic textures); mean/plane/poly2/"
                   "poly3 = subtract a least-squares polynomial of that degree from the heights; "
                   "none = as read")
    f.add_argument("--max-slope", type=float, metavar="DEG",
                   help="drop the facets steeper than DEG degrees (after form and tilt "
                        "removal), in (0, 90): slopes the instrument cannot measure; their "
                        "number and load share are reported (data_quality)")
    f.add_argument("--despike", type=float, metavar="K",
                   help="spike filter (height maps): mark undefined the pixels further than K "
                        "robust standard deviations (1.4826 x MAD) from the median of their "
                        "neighbourhood (itself left out), K in [2, 1e6], e.g. 8")
    f.add_argument("--despike-window", type=int, metavar="W",
                   help="neighbourhood of --despike: W x W pixels, W odd in [3, 15] "
                        "(default 5)")
    if not friction:
        return
    load = f.add_mutually_exclusive_group()
    load.add_argument("--rest-level", type=float, metavar="M",
                      help="spring rest level in m above the detrended mean plane: only points "
                           "above it carry load, in proportion to their height above it "
                           "(default: uniform preload, every facet loaded alike)")
    load.add_argument("--bearing-fraction", type=float, metavar="F",
                      help="rest level put where a share F in (0, 1] of the projected area is "
                           "in contact (the load level, as a bearing-area fraction)")
    p.add_argument("--contact", choices=["all-faces", "windward"], default=contact_default,
                   help="all-faces: compliant springs touch every face; windward: rigid asperities, "
                        "only faces facing the motion" + contact_note)


def texture_from_args(args, several: bool = False):
    """(texture or surface, springs table) from a texture file, the wedge flags or a surface
    file; with the elastic flags the texture weighted by the contact force (``several``: a
    list of them, one a pressure)."""
    elastic = elastic_from_args(args, several)
    if getattr(args, "grid_step", None) is not None and (args.texture is None
                                                         or is_texture_file(args.texture)):
        raise InputError("--grid-step applies to meshes, not to wedge textures")
    texture, table = _texture_from_args(args, elastic)
    if elastic is None:
        return texture, table
    if not isinstance(texture, list):
        from ..friction.elastic import elastic_textures
        with flag_names():
            texture = elastic_textures(texture, elastic)
    return (texture if several else texture[0]), table


def _texture_from_args(args, elastic):
    from ..texture.wedges import WedgeTexture, load_texture_file
    given = {k: getattr(args, k) for k in WEDGE_FLAGS if getattr(args, k) is not None}
    if args.texture is not None and not is_texture_file(args.texture):
        if given:
            flag = "--" + next(iter(given)).replace("_", "-")
            raise InputError(f"give a surface file or the wedge flags, not both ({flag} with {args.texture})")
        return surface_from_args(args, elastic=elastic), {}
    surface_given = [k for k in SURFACE_FLAGS if getattr(args, k, None) is not None]
    if surface_given:
        raise InputError(f"--{surface_given[0].replace('_', '-')} applies to surface files, not to "
                         "wedge textures")
    if args.texture is not None:
        if given:
            flag = "--" + next(iter(given)).replace("_", "-")
            raise InputError(f"give a texture file or the wedge flags, not both ({flag} with {args.texture})")
        tf = load_texture_file(args.texture)
        return tf.texture, tf.springs
    if not given:
        raise InputError("no texture: give a texture file or --alpha, --beta, --mu-alpha, --mu-beta")
    for k in ("alpha", "beta", "mu_alpha", "mu_beta"):
        if k not in given:
            raise InputError(f"missing --{k.replace('_', '-')} (a wedge given by flags needs "
                             "--alpha, --beta, --mu-alpha, --mu-beta)")
    with flag_names({field + " ": "--" + flag.replace("_", "-") + " "
                     for flag, field in WEDGE_FLAGS.items()}):
        return WedgeTexture(**{WEDGE_FLAGS[k]: v for k, v in given.items()}), {}


def spring_model_from_args(args, table: dict):
    from ..texture.spring_model import SpringModel
    d = dict(table)
    fields = {}                       # a value from a flag: the message names the flag
    for dest, key in SPRING_FLAGS.items():
        v = getattr(args, dest, None)
        if v is not None:
            d[key] = v
            if key in ("k_f", "k_n"):     # the ratio of the two, before either alone
                fields = {"springs.k_f / k_n ": "--k-f / --k-n ", **fields}
            fields[f"springs.{key} "] = "--" + dest.replace("_", "-") + " "
    with flag_names(fields):          # (from_dict's messages start with springs.)
        return SpringModel.from_dict(d)
