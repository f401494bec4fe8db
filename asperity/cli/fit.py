"""``asperity fit``: fit a friction law (truncated ellipse or star-shaped gauge) to a texture's
directional friction and save it as a gauge file."""
from __future__ import annotations

from ..laws.summary import format_fit, summary
from . import emit
from .parsing import DefaultsHelpFormatter

LAWS = {"ellipse": "truncated-ellipse", "star": "star"}


def add_parser(sub) -> None:
    from .sources import add_elastic_arguments, add_source_arguments
    p = sub.add_parser(
        "fit", help="fit a friction law to a texture and save it as a gauge file",
        description="Derive the directional friction p(psi) of a texture or surface (closed "
                    "form, as `asperity derive`) and fit a friction law to it: 'star' (default) "
                    "is a Walker-Leine law with a star-shaped reservoir C through the data and a "
                    "convex sliding set D integrated from the sliding rule -- it follows "
                    "non-convex (windward) reservoirs and non-associated sliding; 'ellipse' is "
                    "the truncated ellipse of Antoni et al. (eq. 18: mu_a+-, mu_b+-) with "
                    "associated sliding. Prints the fit quality: radial error, force-direction "
                    "error, and the law against the texture at the directions midway between "
                    "the fitted ones (not used in the fit). Exports (CSV table, Abaqus block) "
                    "are made from the gauge file by `asperity law`. With --elastic and several "
                    "--pressure values (strictly increasing) one law is fitted a pressure, "
                    "the same kind for each: a law family, written as a version-2 gauge file "
                    "(the documentation's file formats); --plot then draws the members' reservoirs coloured by pressure.",
        formatter_class=DefaultsHelpFormatter)
    add_source_arguments(p)
    add_elastic_arguments(p)
    p.add_argument("--law", choices=sorted(LAWS), default="star", help="law to fit")
    p.add_argument("-o", "--output", metavar="GAUGE.json",
                   help="write the gauge file (versioned JSON, see the documentation's file formats); without it only the "
                        "fit quality is printed")
    p.add_argument("--directions", type=int, default=720, metavar="N",
                   help="sliding directions fitted (8 to 100000); the law is checked at N more")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (law, source, fit quality, output file)")
    p.add_argument("--plot", metavar="FILE.png", help="draw C, D, the data and the sliding rule")
    p.set_defaults(func=main, outputs=[("-o", "output", False), ("--plot", "plot", True)],
                   inputs=["texture", "friction_map"])


def run(args):
    """Python API of the command: (GaugeLaw, or GaugeFamily with several --pressure values,
    the JSON object printed with --json)."""
    from ..friction.derive import derive
    from ..laws.fitting import fit_derivation
    from ..progress import progress_bar
    from .sources import elastic_from_args, flag_names, texture_from_args
    elastic = elastic_from_args(args, several=True)
    if elastic is not None and elastic.family:
        gl = _fit_family(args, elastic)
        from ..laws.family_report import family_summary
        obj = family_summary(gl)
    else:
        texture, _ = texture_from_args(args)
        with flag_names(), progress_bar("facets") as progress:
            d = derive(texture, args.contact, "closed-form", args.directions,
                       progress=progress)
        gl = fit_derivation(d, LAWS[args.law])
        obj = summary(gl)
    if args.output:
        from ..laws.gauge_file import write_gauge
        write_gauge(args.output, gl)
        obj["output"] = str(args.output)
    return gl, obj


def _fit_family(args, elastic):
    """One law per --pressure value (same kind and options), as a GaugeFamily."""
    from ..errors import InputError
    from ..friction.family import derive_family
    from ..laws.family import GaugeFamily
    from ..laws.fitting import fit_derivation
    from ..progress import progress_bar
    from .sources import flag_names, texture_from_args
    ps = elastic.pressures                  # strictly increasing (elastic_from_args)
    textures, _ = texture_from_args(args, several=True)
    with flag_names(), progress_bar("facets") as progress:
        fam = derive_family(textures, elastic, args.contact, args.directions, progress)
    laws = []
    for p, d in zip(ps, fam.members):
        try:
            laws.append(fit_derivation(d, LAWS[args.law]))
        except InputError as exc:
            raise InputError(f"--pressure {p:g} Pa: {exc}") from None
    return GaugeFamily(ps, tuple(laws))


def main(args) -> int:
    from ..contact.solver import ContactNotConverged
    from .sources import contact_failed
    try:
        gl, obj = run(args)
    except ContactNotConverged as exc:
        return contact_failed("fit", exc)
    from ..laws.family import GaugeFamily
    if isinstance(gl, GaugeFamily):
        from ..laws.family_report import format_family, plot_family
        if args.plot:
            plot_family(gl, args.plot)
        emit(args, obj, format_family(gl), (("gauge file (version 2, a law family)",
                                             args.output),))
        return 0
    if args.plot:
        from ..laws.plot import plot_law
        plot_law(gl, args.plot)
    emit(args, obj, format_fit(gl), (("gauge file", args.output),))
    return 0
