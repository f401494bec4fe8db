"""The design flags of ``asperity crawl``: ``--optimise amplitude,waves`` finds the fastest
(or, with ``--objective cost``, the cheapest) curvature wave for the law, then crawls it."""
from __future__ import annotations


def add_flags(p) -> None:
    d = p.add_argument_group("design (the fastest or cheapest gait)")
    d.add_argument("--optimise", metavar="PARAMS",
                   help="optimise the curvature wave's amplitude and/or waves (comma list: "
                        "amplitude,waves or A,k; the other stays at --amplitude / --waves), "
                        "then crawl the optimum; gaits that cross themselves are infeasible")
    d.add_argument("--objective", choices=("speed", "cost"), default=None,
                   help="speed: the largest head-ward speed (default); cost: the least cost "
                        "of transport among gaits that move head-ward")
    d.add_argument("--bounds", metavar="P=LO:HI[,P=LO:HI]",
                   help="search box, e.g. amplitude=0.5:12,waves=0.5:3 (the defaults; A and "
                        "k also name them); amplitude within [0, 100], waves within (0, 20]")
    d.add_argument("--optimise-points", default="60", metavar="N",
                   help="contact points of the search's crawls, 3 to 1e5 (the optimum is "
                        "then crawled at --points)")
    d.add_argument("--optimise-steps", default="100", metavar="N",
                   help="steps per period of the search's crawls, 8 to 1e5")
    d.add_argument("--optimise-grid", default="7", metavar="N",
                   help="values per parameter of the coarse grid the search starts from "
                        "(and the plot maps), 3 to 41")
    d.add_argument("--max-evaluations", default="300", metavar="N",
                   help="crawls of the Nelder-Mead stage at most, 1 to 1e5")


def parse_bounds(text) -> dict:
    """``amplitude=0.5:12,waves=0.5:3`` -> {name: (lo, hi)} (checked by the design)."""
    from ..errors import InputError, number_from_text
    out = {}
    if text is None:
        return out
    for part in str(text).split(","):
        name, eq, rng = part.partition("=")
        lo, colon, hi = rng.partition(":")
        if not eq or not colon or not name.strip():
            raise InputError(f"--bounds: {part.strip()!r} must be NAME=LOW:HIGH (e.g. "
                             f"amplitude=0.5:12,waves=0.5:3)")
        out[name.strip()] = (number_from_text(f"--bounds {name.strip()} low", lo.strip()),
                             number_from_text(f"--bounds {name.strip()} high", hi.strip()))
    return out


def check_args(args) -> None:
    """Design flags without --optimise, or with a gait file, refused in one line."""
    from ..errors import InputError
    if getattr(args, "optimise", None) is None:
        for flag, dest, default in (("--objective", "objective", None),
                                    ("--bounds", "bounds", None),
                                    ("--optimise-points", "optimise_points", "60"),
                                    ("--optimise-steps", "optimise_steps", "100"),
                                    ("--optimise-grid", "optimise_grid", "7"),
                                    ("--max-evaluations", "max_evaluations", "300")):
            if getattr(args, dest, default) != default:
                raise InputError(f"{flag} applies with --optimise only")
        return
    if args.gait is not None:
        raise InputError("--optimise varies the curvature wave; it does not apply with --gait")


def optimise(args, law, g, tex, settings):
    """(the optimum's CurvatureWave, the DesignResult) of the command's arguments."""
    from ..crawling.design import optimise_gait, parse_params
    from ..crawling.gait import CurvatureWave
    from ..errors import InputError
    from . import whole_flag
    from .sources import flag_names
    with flag_names({"params": "--optimise"}):
        names = parse_params(args.optimise)
    for name in names:
        if getattr(args, name) is not None:
            raise InputError(f"--{name} does not apply when --optimise varies {name} (give "
                             f"its range with --bounds {name}=LOW:HIGH)")
    bounds = parse_bounds(args.bounds)
    kw = {"points": whole_flag("--optimise-points", args.optimise_points, 3, 100_000),
          "steps_per_period": whole_flag("--optimise-steps", args.optimise_steps, 8, 100_000),
          "grid": whole_flag("--optimise-grid", args.optimise_grid, 3, 41),
          "max_evaluations": whole_flag("--max-evaluations", args.max_evaluations, 1, 100_000)}
    fixed = {"amplitude": 7.0 if args.amplitude is None else args.amplitude,
             "waves": 1.0 if args.waves is None else args.waves,
             "length": 1.0 if args.length is None else args.length,
             "period": 1.0 if args.period is None else args.period}
    periods = whole_flag("--periods", args.periods, 1, 100_000)
    with flag_names({"bounds.": "--bounds ", "objective": "--objective"}):
        res = optimise_gait(law, params=names, objective=args.objective or "speed",
                            bounds=bounds, quasi_static=args.quasi_static, g=g,
                            texture_on=args.texture_on, texture_angle_deg=tex,
                            periods=periods, settings=settings, **fixed, **kw)
    gait = CurvatureWave(amplitude=res.optimum["amplitude"], waves=res.optimum["waves"],
                         period=fixed["period"], length=fixed["length"])
    return gait, res


def text_lines(obj: dict) -> str:
    """The lines the command adds for an optimisation."""
    o = obj["optimum"]
    cost = o["search_cost_of_transport"]
    bounds = ", ".join(f"{k} in [{lo:g}, {hi:g}]" for k, (lo, hi) in o["bounds"].items())
    return "\n".join([
        (f"optimum ({o['objective']}; {bounds}): amplitude {o['amplitude']:.5g}, waves "
        f"{o['waves']:.5g}"),
        f"  at the search's {o['search_points']} points, {o['search_steps_per_period']} steps "
        f"a period: speed {o['search_speed_body_lengths_per_period']:+.6g}, cost of "
        f"transport " + (f"{cost:.5g}" if cost is not None else "none"),
        f"  {o['evaluations']} crawls ({o['infeasible_evaluations']} infeasible) in "
        f"{o['seconds']:.3g} s; {o['method']}; " + ("converged" if o["converged"] else
                                                   "NOT converged: " + o["message"]),
        "the crawl at the optimum:"])
