"""``asperity crawl``: a body that changes shape (a snake, a crawling robot) moves on a
direction-dependent friction law; how fast, which way, at what cost."""
from __future__ import annotations

from .parsing import DefaultsHelpFormatter

EXIT_NOT_CONVERGED = 3


def add_parser(sub) -> None:
    p = sub.add_parser(
        "crawl", help="crawl a shape-changing body (snake gait) on a friction law",
        description="A slender body of length --length bends with a gait (default: the "
                    "curvature wave kappa L = A cos 2 pi (k s / L + t / T), s from tail to "
                    "head, the wave running from head to tail) and rests on --points contact "
                    "points, each on the friction law at its own velocity (rigid motion + the "
                    "gait's). Its centre of mass and mean tangent angle follow Newton-Euler "
                    "with exact Moreau stick (or, with --quasi-static, zero net force and "
                    "torque at every instant). The law: a gauge file (LAW.json), a texture or "
                    "surface file (fitted on the fly, as `asperity fit` does), or three "
                    "coefficients --mu-f --mu-b --mu-t (forward = towards the head) with "
                    "--rule. On the body (skin, scales: the law's +x along the local tangent "
                    "towards the head, turned by --texture-angle) or on the ground (--texture-on "
                    "ground: +x along --texture-angle from the body's initial heading). Prints "
                    "the speed in body lengths per period (head-ward positive, a dynamic run "
                    "averaged after its transient), the heading drift, the cost of transport "
                    "and the Froude number. Exit status 3 if a step's solve did not converge.",
        formatter_class=DefaultsHelpFormatter)
    from .sources import add_source_arguments
    add_source_arguments(p)
    law = next(a for a in p._actions if a.dest == "texture")
    law.metavar = "LAW"
    law.help = ("gauge file (.json, asperity fit), or a texture or surface file fitted on the "
                "fly as `asperity fit` fits it (with the texture and surface flags below; "
                "--contact, --fit-law)")
    from .parsing import add_componentwise_flags
    add_componentwise_flags(p, "a law of three coefficients (with --rule)")
    p.add_argument("--rule", choices=("componentwise", "associated", "colinear"),
                   default=None,
                   help="how the three coefficients make a law (default componentwise): "
                        "componentwise (Hu et al.), associated (maximum dissipation on the "
                        "two half-ellipses: the truncated ellipse) or colinear (force opposite "
                        "to the slip)")
    p.add_argument("--fit-law", choices=("star", "ellipse"), default="star",
                   help="the law fitted to a texture or surface file")
    p.add_argument("--pressure", type=float, metavar="P_PA",
                   help="the body's nominal pressure: takes a law family's law at it")
    p.add_argument("--texture-on", choices=("body", "ground"), default="body",
                   help="where the texture is: on the body (the law turns with the tangent) "
                        "or on the ground (fixed in the world)")
    p.add_argument("--texture-angle", type=float, default=0.0, metavar="DEG",
                   help="angle of the law's +x from the tangent (body) or from the initial "
                        "heading (ground), deg in [-360, 360]")
    g = p.add_argument_group("gait")
    g.add_argument("--amplitude", type=float, default=None, metavar="A",
                   help="curvature amplitude A = kappa L, in [0, 100] (default 7)")
    g.add_argument("--waves", type=float, default=None, metavar="K",
                   help="waves along the body k, in (0, 20] (default 1)")
    g.add_argument("--length", type=float, default=None, metavar="M", help="body length L (m, default 1)")
    g.add_argument("--period", type=float, default=None, metavar="S", help="gait period T (s, default 1)")
    g.add_argument("--gait", metavar="FILE.toml",
                   help="gait file (Fourier curvature or a table of joint angles; see "
                        "surfaces/gaits/); replaces --amplitude, --waves, --length, --period")
    r = p.add_argument_group("run")
    r.add_argument("--points", default="100", metavar="N",
                   help="contact points along the body, 3 to 1e5")
    r.add_argument("--periods", default=None, metavar="N",
                   help="gait periods to run, 1 to 1e5 (default 1 quasi-static, 8 dynamic)")
    mode = r.add_mutually_exclusive_group()
    mode.add_argument("--quasi-static", action="store_true",
                      help="no inertia: zero net friction force and torque at every instant")
    mode.add_argument("--gravity", type=float, default=None, metavar="G",
                      help="gravity (m/s^2, in [1e-6, 1e4]; default 9.81): the normal load "
                           "and, with the period and length, the Froude number")
    r.add_argument("--dt", type=float, default=None, metavar="S",
                   help="time step (s); rounded to a whole number of steps per period "
                        "(default: 200 a period: the dynamic speed within 3e-4 of its limit)")
    r.add_argument("--tol", type=float, default=1e-12,
                   help="relative tolerance of each step's Newton solve, in [1e-15, 1e-3]")
    r.add_argument("--max-iterations", default="200", metavar="N",
                   help="iterations of each Newton solve at most, 1 to 1e6")
    from .crawl_design import add_flags
    add_flags(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--csv", metavar="FILE.csv",
                   help="write t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s (centre of "
                        "mass, mean tangent angle)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw the body over its last period along the path, and the speed "
                        "(with --optimise: the objective over the search's grid, the "
                        "optimiser's path and the optimum)")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True), ("--csv", "csv", False)],
                   inputs=["texture", "gait", "friction_map"])


def law_from_args(args):
    """The PlanarLaw of the arguments: a gauge file, a texture or surface (a file or the
    wedge flags) fitted on the fly, or three coefficients with --rule."""
    from ..crawling.solver import coefficient_law
    from ..errors import InputError
    from .parsing import COMPONENTWISE_FLAGS, componentwise_given
    from .sources import WEDGE_FLAGS, flag_names
    from .sources import SURFACE_FLAGS
    src = args.texture
    wedge = any(getattr(args, k) is not None for k in WEDGE_FLAGS)
    surface = [k for k in SURFACE_FLAGS if getattr(args, k, None) is not None]
    if args.height_scale != 1.0:
        surface.append("height_scale")
    if surface and (src is None or str(src).lower().endswith(".json")):
        raise InputError(f"--{surface[0].replace('_', '-')} applies to a texture or surface "
                         f"file, not to {'a gauge file' if src else 'three coefficients'}")
    if src is None and not wedge:
        if not componentwise_given(args):
            raise InputError("no law: give a gauge file, a texture or surface file (or the "
                             "wedge flags), or --mu-f, --mu-b and --mu-t (with --rule)")
        if args.pressure is not None:
            raise InputError("--pressure takes a law family's law; three coefficients do "
                             "not depend on it")
        missing = [f for d, f, _ in COMPONENTWISE_FLAGS if getattr(args, d) is None]
        if missing:
            raise InputError(f"{', '.join(missing)} must be given too (a law of three "
                             "coefficients needs --mu-f, --mu-b and --mu-t)")
        with flag_names({d + " ": f + " " for d, f, _ in COMPONENTWISE_FLAGS}):
            return coefficient_law(args.mu_f, args.mu_b, args.mu_t, args.rule or
                                   "componentwise")
    if componentwise_given(args) or args.rule is not None:
        raise InputError("--mu-f/--mu-b/--mu-t and --rule make a law of three coefficients; "
                         f"they do not apply with {src or 'the wedge flags'} (the texture "
                         "gives the law)")
    from ..laws import planar as L
    if src is not None and str(src).lower().endswith(".json"):
        from ..laws.family import GaugeFamily, law_at
        from ..laws.gauge_file import read_gauge
        if wedge:
            raise InputError("the wedge flags make a texture; they do not apply with a gauge "
                             f"file ({src})")
        gl = read_gauge(src)
        if args.pressure is not None and not isinstance(gl, GaugeFamily):
            raise InputError(f"--pressure applies to a law family; {src} holds one law")
        gl, _ = law_at(gl, args.pressure, "--pressure", str(src))
        return L.from_gauge(gl)
    if args.pressure is not None:
        raise InputError("--pressure applies to a law family's gauge file, not to a texture "
                         "fitted here (fit a family with `asperity fit --elastic`)")
    from ..crawling.solver import fitted_law
    from ..progress import progress_bar
    from .sources import texture_from_args
    texture, _ = texture_from_args(args)
    with flag_names(), progress_bar("facets") as progress:
        return fitted_law(texture, args.fit_law, contact=args.contact, progress=progress)


def run(args):
    """Python API of the command: (law, CrawlResult, gait, the JSON object)."""
    from ..crawling.gait import CurvatureWave
    from ..crawling.output import summary
    from ..crawling.solver import STEPS_PER_PERIOD, CrawlSettings, crawl
    from ..errors import InputError, check_range
    from . import whole_flag
    points = whole_flag("--points", args.points, 3, 100_000)
    periods = whole_flag("--periods", args.periods, 1, 100_000)
    maxit = whole_flag("--max-iterations", args.max_iterations, 1, 1_000_000)
    tol = check_range("--tol", args.tol, 1e-15, 1e-3)
    g = 9.81 if args.gravity is None else check_range("--gravity", args.gravity, 1e-6, 1e4,
                                                      unit="m/s^2")
    tex = check_range("--texture-angle", args.texture_angle, -360.0, 360.0, unit="deg")
    from .crawl_design import check_args
    check_args(args)
    if args.gait is not None:
        given = [f for f, d in (("--amplitude", "amplitude"), ("--waves", "waves"),
                                ("--length", "length"), ("--period", "period"))
                 if getattr(args, d) is not None]
        if given:
            raise InputError(f"{given[0]} does not apply with --gait (the gait file gives the "
                             "gait)")
        from ..crawling.gait_file import read_gait
        gait = read_gait(args.gait)
    else:
        from .sources import flag_names
        with flag_names({"amplitude ": "--amplitude ", "waves ": "--waves ",
                         "length ": "--length ", "period ": "--period "}):
            gait = CurvatureWave(
                amplitude=7.0 if args.amplitude is None else args.amplitude,
                waves=1.0 if args.waves is None else args.waves,
                period=1.0 if args.period is None else args.period,
                length=1.0 if args.length is None else args.length)
    P = STEPS_PER_PERIOD
    if args.dt is not None:
        dt = check_range("--dt", args.dt, 1e-9, float(gait.period) / 8, unit="s")
        P = max(8, round(float(gait.period) / dt))
    law = law_from_args(args)
    settings = CrawlSettings(tol=tol, max_iterations=maxit)
    design = None
    if args.optimise is not None:
        from .crawl_design import optimise
        gait, design = optimise(args, law, g, tex, settings)
    res = crawl(law, gait=gait, points=points, periods=periods,
                quasi_static=args.quasi_static, g=g, steps_per_period=P,
                texture_on=args.texture_on, texture_angle_deg=tex,
                settings=settings)
    obj = summary(res, law)
    if design is not None:
        obj["optimum"] = design.to_json()
    if args.texture:
        obj["source"] = str(args.texture)
    if args.csv:
        from ..crawling.output import csv_text
        from ..io import write_text_atomic
        write_text_atomic(args.csv, csv_text(res))
    if args.plot and design is not None:
        from ..crawling.design_plot import plot_design
        plot_design(args.plot, design, obj)
    elif args.plot:
        from ..crawling.output import plot
        plot(args.plot, res, gait, obj)
    return law, res, gait, obj


def main(args) -> int:
    import sys

    from ..crawling.output import text
    from . import emit
    _law, res, _gait, obj = run(args)
    lines = text(obj)
    if "optimum" in obj:
        from .crawl_design import text_lines
        lines = text_lines(obj) + "\n" + lines
    emit(args, obj, lines, (("path table", args.csv),) if args.csv else ())
    if res.status != "ok":
        print(f"asperity crawl: error: {res.message}", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    return 0
