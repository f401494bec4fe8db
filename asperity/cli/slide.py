"""``asperity slide``: a point mass launched on a frictional plane, integrated with the Moreau
solver until it sticks (deflection of the path by anisotropic friction)."""
from __future__ import annotations

import math

from . import json_text, written_lines
from .parsing import DefaultsHelpFormatter

LAWS = ("coulomb", "ellipse", "collinear", "componentwise", "star")
#: rows of the CSV table / points of the plot at most (every k-th step is kept)
MAX_ROWS = 20000
EXIT_NOT_CONVERGED = 3


def add_parser(sub) -> None:
    p = sub.add_parser(
        "slide", help="slide a body on a friction law until it sticks (Moreau time-stepping)",
        description="Launch a point mass from the origin at speed --u0 in direction --angle "
                    "(deg, from t_a towards t_b) on a plane with dry friction and integrate its "
                    "motion with the Moreau midpoint scheme until it sticks (exact stick: the "
                    "velocity becomes exactly zero). The law is a gauge file's (GAUGE, written "
                    "by `asperity fit`: its truncated ellipse or star-shaped law, or with --law "
                    "collinear a force along the sliding direction with the file's magnitudes) "
                    "or a built-in one: coulomb (mu1 alone, or mu1 = mu2), ellipse (associated "
                    "orthotropic), collinear (force along the sliding direction, magnitude from "
                    "the ellipse), star (non-convex windward wedge reservoir stretched to mu1 "
                    "along t_a and mu2 along t_b) or componentwise (Hu et al.'s rule of --mu-f, "
                    "--mu-b, --mu-t: each component of the unit slip scaled by its own "
                    "coefficient, forward = +t_a). Prints the rest point, stop time and the "
                    "deflection: the signed angle from the initial velocity to the line from "
                    "start to rest (positive towards t_b). Exit status 3 if the fixed-point "
                    "iteration did not converge at some step (reported, with the residual). A "
                    "gauge file holding a law family (version 2) needs --pressure, the body's "
                    "nominal normal pressure: its law is taken at it. With --body disc, ring, "
                    "rectangle or a TOML body file a rigid body slides and spins instead "
                    "(--omega0), every contact point of its footprint on the law at its own "
                    "velocity; it prints the rest point and angle, when sliding and spinning "
                    "stopped and, for a disc or ring, the terminal ratio v / (R omega) "
                    "(0.653 for a uniformly loaded disc, 1 for a ring). An external force "
                    "or torque, constant or periodic (--force, --torque, --force-amplitude, "
                    "--waveform, --period), needs --t-end and reports the drift and rotation "
                    "per cycle.",
        formatter_class=DefaultsHelpFormatter)
    p.add_argument("gauge", nargs="?", metavar="GAUGE.json", help="gauge file (asperity fit)")
    p.add_argument("--law", choices=LAWS, default=None,
                   help="law (default: the gauge file's; without one componentwise if "
                        "--mu-f/--mu-b/--mu-t are given, coulomb if only --mu1 is given or "
                        "mu1 = mu2, else ellipse)")
    p.add_argument("--pressure", type=float, metavar="P_PA",
                   help="nominal normal pressure of the body on the plane, Pa: required when "
                        "the gauge file holds a law family (version 2), whose law is taken at "
                        "it (interpolated between the members); refused otherwise")
    p.add_argument("--mu1", type=float, metavar="X", help="friction coefficient along t_a")
    p.add_argument("--mu2", type=float, metavar="Y", help="friction coefficient along t_b")
    from .parsing import add_componentwise_flags
    add_componentwise_flags(p)
    p.add_argument("--u0", type=float, required=True, metavar="M_S", help="initial speed (m/s)")
    p.add_argument("--angle", type=float, required=True, metavar="DEG",
                   help="direction of the initial velocity (deg from t_a towards t_b)")
    p.add_argument("--mass", type=float, default=None, metavar="KG",
                   help="mass (kg; default 1; a body file gives its own)")
    p.add_argument("--g", type=float, default=9.81, metavar="M_S2",
                   help="gravity: normal force m g (m/s^2)")
    p.add_argument("--dt", type=float, default=1e-4, metavar="S", help="time step (s)")
    p.add_argument("--t-end", type=float, default=None, metavar="S",
                   help="end time (s); default: until the body sticks")
    p.add_argument("--tol", type=float, default=1e-12,
                   help="tolerance of each step's solve, in [1e-15, 1e-3]: the point mass's "
                        "fixed point (friction impulse per normal impulse), a body's Newton "
                        "iteration (relative residual)")
    p.add_argument("--max-iterations", type=int, default=2000, metavar="N",
                   help="iteration limit of each step's solve, 1 to 1e6 (fixed point; a "
                        "body: Newton)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw the path")
    p.add_argument("--csv", metavar="FILE.csv",
                   help="write the path: t,x,y,vx,vy (point mass) or t,x,y,theta,vx,vy,omega "
                        "(a body)")
    b = p.add_argument_group(
        "bodies", "a rigid body with a footprint instead of the point mass: it slides and "
        "spins, every contact point with the law at its own velocity (exact stick of the "
        "body). JSON adds final_angle_rad, slide_stop_time, spin_stop_time, together, "
        "terminal_ratio (discs and rings), the body, and under a load its drift")
    b.add_argument("--body", default="point", metavar="point|disc|ring|rectangle|BODY.toml",
                   help="the body: the point mass, a disc or ring (--radius), a rectangle "
                        "(--size) or a TOML body file (shape, size, mass, pressure: see "
                        "surfaces/body-plate.toml)")
    b.add_argument("--radius", type=float, metavar="M",
                   help="radius of a disc or ring (m, in [1e-9, 1000])")
    b.add_argument("--size", type=float, nargs=2, metavar=("A", "B"),
                   help="sides of a rectangle (m, each in [1e-9, 1000]; A along the body's x)")
    b.add_argument("--omega0", type=float, default=None, metavar="RAD_S",
                   help="initial spin (rad/s, counter-clockwise, in [-1e6, 1e6]; default 0)")
    b.add_argument("--contact-points", type=int, default=None, metavar="N",
                   help="contact points sampling the footprint (default per shape: disc 1024, "
                        "ring 512, rectangle 1024; a body file's own count is replaced)")
    b.add_argument("--pressure-profile", choices=("uniform", "hertz", "linear"), default=None,
                   help="normal pressure over the footprint (default uniform; hertz: discs; "
                        "linear: with --centre-of-pressure, inside the footprint's core)")
    b.add_argument("--centre-of-pressure", type=float, nargs=2, metavar=("X", "Y"),
                   help="centre of pressure of the linear profile (m, body frame, from the "
                        "centroid)")
    b.add_argument("--texture-angle", type=float, default=None, metavar="DEG",
                   help="angle of the law's t_a axis from x (deg, in [-360, 360]; default 0): "
                        "the texture is fixed to the support")
    b.add_argument("--force", type=float, nargs=2, metavar=("FX", "FY"),
                   help="constant external force on the body (N); needs --t-end")
    b.add_argument("--torque", type=float, metavar="TZ",
                   help="constant external torque on the body (N m); needs --t-end")
    b.add_argument("--force-amplitude", type=float, nargs="+", metavar="A",
                   help="amplitude of the periodic load: AX AY [AT] (N, N, N m), with "
                        "--waveform square or sine and --period; needs --t-end")
    b.add_argument("--period", type=float, default=None, metavar="S",
                   help="period of the periodic load (s, in [1e-9, 1e9]; default 1)")
    b.add_argument("--waveform", choices=("none", "square", "sine"), default=None,
                   help="shape of the periodic load: square (+A the first half of each period, "
                        "-A the second), sine, or none (default: a constant load only)")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True), ("--csv", "csv", False)],
                   inputs=["gauge", "body"])


def build_law(args):
    """The PlanarLaw selected by the arguments (validated)."""
    return _build(args)[0]


def _build(args):
    """(PlanarLaw, how a law family was taken at --pressure or None)."""
    from ..dynamics.moreau import LIMITS
    from ..errors import InputError, check_range
    from ..laws import planar as L
    if args.pressure is not None and not args.gauge:
        raise InputError("--pressure takes the law of a law family (a version-2 gauge file) at "
                         "the body's nominal pressure; built-in laws do not depend on it")
    from .parsing import componentwise_from_args, componentwise_given
    cw = componentwise_given(args)
    if cw and args.law not in (None, "componentwise"):
        raise InputError(f"--mu-f/--mu-b/--mu-t are the componentwise law's, not --law {args.law}'s")
    if args.gauge:
        if cw:
            raise InputError("--mu-f/--mu-b/--mu-t do not apply with a gauge file (the file "
                             "holds the law)")
        if args.mu1 is not None or args.mu2 is not None:
            raise InputError("--mu1/--mu2 do not apply with a gauge file (the file holds the law)")
        if args.law == "coulomb":
            raise InputError("--law coulomb takes --mu1, not a gauge file")
        from ..laws.family import GaugeFamily, law_at
        from ..laws.gauge_file import read_gauge
        gl = read_gauge(args.gauge)
        if args.pressure is not None and not isinstance(gl, GaugeFamily):
            raise InputError(f"--pressure applies to a law family; {args.gauge} holds one law "
                             "(version 1)")
        gl, how = law_at(gl, args.pressure, "--pressure", str(args.gauge))
        kind = args.law
        if kind == "ellipse" and gl.kind != "truncated-ellipse":
            raise InputError(f"--law ellipse needs a truncated-ellipse gauge file, "
                             f"{args.gauge} holds a {gl.kind} law (use --law collinear or the "
                             "file's own)")
        if kind in ("star", "componentwise") and gl.kind != kind:
            raise InputError(f"--law {kind} needs a {kind} gauge file, {args.gauge} holds a "
                             f"{gl.kind} law (use --law collinear or the file's own)")
        return L.from_gauge(gl, None if kind in (None, "ellipse", "star") else kind), how
    if cw or args.law == "componentwise":
        if args.mu1 is not None or args.mu2 is not None:
            raise InputError("--mu1/--mu2 do not apply to the componentwise law (it takes "
                             "--mu-f, --mu-b, --mu-t)")
        return componentwise_from_args(args), None
    if args.mu1 is None:
        raise InputError("--mu1 is required without a gauge file (friction coefficient along "
                         "t_a, in [1e-6, 100])")
    mu1 = check_range("--mu1", args.mu1, *LIMITS["mu"])
    mu2 = None if args.mu2 is None else check_range("--mu2", args.mu2, *LIMITS["mu"])
    law = args.law or ("coulomb" if mu2 is None or mu2 == mu1 else "ellipse")
    if law == "coulomb":
        if mu2 is not None and mu2 != mu1:
            raise InputError(f"--law coulomb is isotropic: give --mu1 alone or --mu2 equal to "
                             f"it, got --mu1 {mu1:g} --mu2 {mu2:g}")
        return L.coulomb_law(mu1), None
    if mu2 is None:
        raise InputError(f"--law {law} needs --mu2 (friction coefficient along t_b, in [1e-6, 100])")
    if law == "ellipse":
        return L.ellipse_law(mu1, mu2), None
    if law == "collinear":
        return L.collinear_law(mu1=mu1, mu2=mu2), None
    return L.star_law(mu1, mu2), None


def run(args):
    """Python API of the command: (law, Result, the JSON object printed with --json)."""
    from ..dynamics.moreau import LIMITS, MAX_STEPS, Settings, check_t_end, point_mass, simulate
    from ..dynamics.summary import path_csv, slide_summary
    from ..errors import InputError, check_int, check_range
    u0 = check_range("--u0", args.u0, 0.0, 1e4, unit="m/s")
    angle = check_range("--angle", args.angle, -360.0, 360.0, unit="deg")
    if args.body != "point":
        return run_body(args)
    _refuse_body_options(args)
    mass = check_range("--mass", 1.0 if args.mass is None else args.mass, *LIMITS["mass"],
                       unit="kg")
    g = check_range("--g", args.g, *LIMITS["g"], unit="m/s^2")
    dt = check_range("--dt", args.dt, *LIMITS["dt"], unit="s")
    tol = check_range("--tol", args.tol, 1e-15, 1e-3)
    maxit = check_int("--max-iterations", args.max_iterations, 1, 1_000_000)
    law, how = _build(args)
    halt = args.t_end is None
    if halt:
        t_end = 1.5 * u0 / (g * law.min_tangential()) + 10 * dt
    else:
        t_end = check_t_end("--t-end", args.t_end, dt)
    n = round(t_end / dt)
    if n > MAX_STEPS:
        raise InputError(f"--t-end / --dt gives {n:.3g} steps, at most {MAX_STEPS:.0e}: raise "
                         "--dt or lower --t-end")
    rec = max(1, n // MAX_ROWS) if (args.plot or args.csv) else max(1, n)
    a = math.radians(angle)
    res = simulate(point_mass(law, mass), [u0 * math.cos(a), u0 * math.sin(a)], dt=dt,
                   t_end=t_end, g=g, settings=Settings(tol=tol, max_iterations=maxit),
                   record_every=rec, halt_at_rest=halt)
    obj = slide_summary(law, res, u0=u0, angle_deg=angle, mass=mass, g=g, dt=dt,
                        t_end=None if halt else t_end, tol=tol)
    if args.gauge:
        obj["gauge"] = str(args.gauge)
    if how is not None:
        obj["family_pressure"] = how
    if args.csv:
        from ..io import write_text_atomic
        write_text_atomic(args.csv, path_csv(res))
    if args.plot:
        from ..dynamics.plot import plot_path
        plot_path(args.plot, res, law, angle)
    return law, res, obj


#: options that apply to a body only (not to the point mass), with their flags
BODY_OPTIONS = (("radius", "--radius"), ("size", "--size"), ("omega0", "--omega0"),
                ("contact_points", "--contact-points"), ("pressure_profile", "--pressure-profile"),
                ("centre_of_pressure", "--centre-of-pressure"),
                ("texture_angle", "--texture-angle"), ("force", "--force"),
                ("torque", "--torque"), ("force_amplitude", "--force-amplitude"),
                ("period", "--period"), ("waveform", "--waveform"))


def _refuse_body_options(args) -> None:
    from ..errors import InputError
    for dest, flag in BODY_OPTIONS:
        if getattr(args, dest, None) is not None:
            raise InputError(f"{flag} applies to a body (--body disc, ring, rectangle or a body "
                             "file), not to the point mass")


def _force(args):
    """The external load of the options (a moreau.Force), or None."""
    from ..dynamics.moreau import Force
    from ..errors import InputError, check_range
    amp = args.force_amplitude
    wave = args.waveform
    if amp is not None and len(amp) not in (2, 3):
        raise InputError(f"--force-amplitude takes AX AY or AX AY AT (2 or 3 numbers), got "
                         f"{len(amp)}")
    if amp is not None and wave in (None, "none"):
        raise InputError("--force-amplitude needs --waveform square or sine (the shape of the "
                         "periodic load)")
    if wave not in (None, "none") and amp is None:
        raise InputError(f"--waveform {wave} needs --force-amplitude AX AY [AT]")
    if args.period is not None and wave in (None, "none"):
        raise InputError("--period applies to a periodic load (--waveform square or sine)")
    const = [0.0, 0.0, 0.0]
    if args.force is not None:
        const[:2] = [check_range("--force", v, -1e12, 1e12, unit="N") for v in args.force]
    if args.torque is not None:
        const[2] = check_range("--torque", args.torque, -1e12, 1e12, unit="N m")
    if args.force is None and args.torque is None and amp is None:
        return None
    a = [0.0, 0.0, 0.0]
    if amp is not None:
        a[:len(amp)] = [check_range("--force-amplitude", v, -1e12, 1e12) for v in amp]
    period = 1.0 if args.period is None else \
        check_range("--period", args.period, 1e-9, 1e9, unit="s")
    if args.t_end is None:
        raise InputError("--force, --torque and --force-amplitude need --t-end (a body under "
                         "a load need not come to rest)")
    return Force(constant=tuple(const), amplitude=tuple(a), period=period,
                 waveform=wave or "none")


_OPTION_WORDS = (("t_end / dt", "--t-end / --dt"), ("raise dt", "raise --dt"),
                 ("inertia must", "the body's inertia (its size and --mass) must"),
                 ("t_end must be given", "--t-end must be given"), ("give t_end", "give --t-end"),
                 ("lower t_end", "lower --t-end"), ("u0 must", "--u0 must"),
                 ("omega0 must", "--omega0 must"),
                 ("points must not all lie at one spot", ("the body's contact points "
                  "(--contact-points, or a body file's points) must not all lie at one spot")))


def run_body(args):
    """``asperity slide --body ...``: (law, BodyResult, the JSON object); the body run is
    :func:`asperity.dynamics.body_api.slide_body`."""
    from ..dynamics.body import BodySettings
    from ..dynamics.body_api import make_body, slide_body
    from ..dynamics.moreau import LIMITS, check_t_end
    from ..errors import InputError, check_int, check_range
    u0 = check_range("--u0", args.u0, 0.0, 1e4, unit="m/s")
    angle = check_range("--angle", args.angle, -360.0, 360.0, unit="deg")
    g = check_range("--g", args.g, *LIMITS["g"], unit="m/s^2")
    dt = check_range("--dt", args.dt, *LIMITS["dt"], unit="s")
    tol = check_range("--tol", args.tol, 1e-15, 1e-3)
    maxit = check_int("--max-iterations", args.max_iterations, 1, 1_000_000)
    omega0 = 0.0 if args.omega0 is None else \
        check_range("--omega0", args.omega0, -1e6, 1e6, unit="rad/s")
    tex = 0.0 if args.texture_angle is None else \
        check_range("--texture-angle", args.texture_angle, -360.0, 360.0, unit="deg")
    t_end = None if args.t_end is None else \
        check_t_end("--t-end", args.t_end, dt)
    force = _force(args)
    law, how = _build(args)
    body = make_body(args.body, radius=args.radius, size=args.size,
                     contact_points=args.contact_points, pressure_profile=args.pressure_profile,
                     centre_of_pressure=args.centre_of_pressure, mass=args.mass, cli=True)
    try:
        run = slide_body(law, body, u0, angle, omega0, g=g, dt=dt, t_end=t_end, force=force,
                         texture_angle_deg=tex,
                         settings=BodySettings(tol=tol, max_iterations=maxit))
    except InputError as exc:          # the API's names said as the options
        msg = str(exc)
        for a, b in _OPTION_WORDS:
            msg = msg.replace(a, b, 1)
        raise type(exc)(msg) from None
    obj = run.summary
    if args.gauge:
        obj["gauge"] = str(args.gauge)
    if how is not None:
        obj["family_pressure"] = how
    if args.csv:
        from ..dynamics.body_api import body_csv
        from ..io import write_text_atomic
        write_text_atomic(args.csv, body_csv(run.result))
    if args.plot:
        from ..dynamics.body_api import body_words
        from ..dynamics.plot import plot_body_path
        plot_body_path(args.plot, run.result, body.footprint.outline, law, angle,
                       f"{body_words(obj['body'])}\n{law.description}")
    return law, run.result, obj


def main(args) -> int:
    import sys

    from .slide_text import say_body, steps_words
    law, res, obj = run(args)
    outputs = [(what, getattr(args, flag)) for flag, what in
               (("csv", "path table"), ("plot", "plot")) if getattr(args, flag)]
    stream = sys.stderr if any(v == "-" for _, v in outputs) else sys.stdout

    def say(text):
        print(text, file=stream)
    if args.json:
        say(json_text(obj))
    else:
        say(f"law: {law.description}")
        if obj.get("family_pressure"):
            from ..laws.family import how_words
            say(how_words(obj["family_pressure"]))
        if "body" in obj:
            say_body(say, obj)
        elif obj["rest"] is not None:
            say(f"rest at ({obj['rest'][0]:.6g}, {obj['rest'][1]:.6g}) m after "
                f"{obj['stop_time']:.6g} s ({steps_words(obj)}), "
                f"distance {obj['distance']:.6g} m")
        else:
            say(f"still moving at t = {obj['t_end']:g} s: position "
                f"({obj['final_position'][0]:.6g}, {obj['final_position'][1]:.6g}) m")
        say(f"deflection: {obj['deflection_deg']:+.4f} deg (from the initial velocity to the "
            f"line start -> {'rest' if obj['rest'] is not None else 'end'})")
        what = "Newton iterations" if "body" in obj else "fixed-point iterations"
        say(f"{what} per step: max {obj['max_iterations_used']}, mean "
            f"{obj['mean_iterations']:.3g}")
        written_lines(outputs, stream)
    if res.status != "ok":
        print(f"asperity slide: error: {res.status_message()}", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    return 0
