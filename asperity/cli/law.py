"""``asperity law``: evaluate, draw and export the friction law of a gauge file."""
from __future__ import annotations

from . import json_text, written_lines
from .parsing import DefaultsHelpFormatter


def add_parser(sub) -> None:
    p = sub.add_parser(
        "law", help="evaluate, draw or export a gauge file's friction law",
        description="Read a gauge file written by `asperity fit` and evaluate its law: --psi "
                    "gives the friction force p = -lambda_T/lambda_N (per unit normal load) for "
                    "sliding in direction psi (deg, in the frame of the source: wedge textures "
                    "from t_a towards t_b, surfaces from +x towards +y), with its tangential "
                    "and lateral parts and the Walker-Leine alpha. Where the law is set-valued "
                    "(windward, sliding along the ridges) every force on a segment slides that "
                    "way: p is the point on the ray of the middle of D's flat edge and the "
                    "segment's ends are given. Exports: --csv (psi_deg,p_a,p_b in the "
                    "principal frame, t_a along the gauge's principal direction) and --abaqus "
                    "(*FRICTION, ANISOTROPIC block of the best symmetric orthotropic ellipse of "
                    "the gauge's own law, with comment lines naming the law and its source and "
                    "stating what the ellipse loses). A law family (a version-2 gauge file) is "
                    "taken at --pressure; without it --csv adds a pressure_Pa column and holds "
                    "every member, --abaqus writes one block a member, --plot draws the "
                    "members' reservoirs coloured by pressure. Instead of a gauge file, --mu-f --mu-b "
                    "--mu-t give the componentwise law (Hu et al.: p = (mu_f or mu_b) (u.t_a) "
                    "t_a + mu_t (u.t_b) t_b for the unit slip u, forward = +t_a); --output "
                    "writes its gauge file.",
        formatter_class=DefaultsHelpFormatter)
    p.add_argument("gauge", nargs="?", metavar="GAUGE.json",
                   help="gauge file written by asperity fit (or law --output)")
    from .parsing import add_componentwise_flags
    add_componentwise_flags(p, "the componentwise law instead of a gauge file")
    p.add_argument("-o", "--output", metavar="GAUGE.json",
                   help="write the componentwise law of --mu-f --mu-b --mu-t as a gauge file "
                        "(as `asperity fit -o` writes a fitted one)")
    p.add_argument("--psi", type=float, metavar="DEG", help="sliding direction in degrees")
    p.add_argument("--pressure", type=float, metavar="P_PA",
                   help="a law family (version-2 gauge file): take the law at this nominal "
                        "pressure, Pa (interpolated between the members, within their range); "
                        "without it a family's exports hold every member")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw C, D, the data and the sliding rule")
    p.add_argument("--csv", metavar="FILE.csv", help="write the polar table psi_deg,p_a,p_b")
    p.add_argument("--csv-directions", type=int, default=360, metavar="N",
                   help="directions of the CSV table (4 to 1000000)")
    p.add_argument("--abaqus", metavar="FILE.inp",
                   help="write an Abaqus *FRICTION, ANISOTROPIC block (symmetric orthotropic "
                        "approximation of the gauge's own law)")
    from .law_fe import FE_OUTPUTS, add_fe_flags
    add_fe_flags(p)
    p.set_defaults(func=main, outputs=[("--plot", "plot", True), ("--csv", "csv", False),
                                       ("--abaqus", "abaqus", False),
                                       ("--output", "output", False), *FE_OUTPUTS],
                   inputs=["gauge"])
    _add_gwfl(p)


def _add_gwfl(p) -> None:
    """--gwfl: the law as GetFEM weak-form macros (asperity.fe.gwfl)."""
    p.add_argument("--gwfl", metavar="FILE",
                   help="write the law as GetFEM weak-form language (GWFL) macros: the "
                        "plan-view traction p(psi) of the slip increment (a piecewise-linear "
                        "table within 1e-4 of --psi) and the strip's bed law (mu+ = p(0).x, "
                        "mu- = -p(180).x), with a header naming the variables they expect; "
                        "a law family needs --pressure")
    outputs = p.get_default("outputs")
    p.set_defaults(outputs=outputs + [("--gwfl", "gwfl", False)])


def _gwfl(args, gl) -> None:
    """Write --gwfl (after the law is resolved; a family needs --pressure)."""
    from ..errors import InputError
    from ..laws.family import GaugeFamily
    if isinstance(gl, GaugeFamily):
        raise InputError(f"--gwfl writes one law; {args.gauge} holds a law family over the "
                         f"pressures {gl.pressures[0]:g} to {gl.pressures[-1]:g} Pa: give "
                         "--pressure")
    from ..fe.gwfl import write_gwfl
    name = args.gauge or "componentwise law (--mu-f --mu-b --mu-t)"
    if args.pressure is not None:
        name = f"{name} at {args.pressure:g} Pa"
    write_gwfl(args.gwfl, gl, f"{name} ({getattr(gl, 'kind', 'law')})")


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json."""
    from ..errors import InputError, check_int, check_range
    from ..laws.gauge_file import read_gauge
    from ..laws.summary import force_at, summary
    if args.psi is not None:
        check_range("--psi", args.psi, -3600.0, 3600.0, unit="deg")
    check_int("--csv-directions", args.csv_directions, 4, 1_000_000)
    from .parsing import componentwise_given
    if args.gauge is not None and (componentwise_given(args) or args.output):
        raise InputError("--mu-f/--mu-b/--mu-t and --output make a componentwise law; they do "
                         "not apply with a gauge file")
    if args.pressure is not None and args.gauge is None:
        raise InputError("--pressure applies to a law family (a version-2 gauge file)")
    gl = _componentwise(args) if args.gauge is None else read_gauge(args.gauge)
    from ..laws.family import GaugeFamily, law_at
    if isinstance(gl, GaugeFamily) and args.pressure is None:
        if getattr(args, "gwfl", None):
            _gwfl(args, gl)
        return _family(args, gl)
    if args.pressure is not None and not isinstance(gl, GaugeFamily):
        raise InputError(f"--pressure applies to a law family; {args.gauge} holds one law "
                         "(version 1)")
    gl, how = law_at(gl, args.pressure, "--pressure", str(args.gauge))
    obj = force_at(gl, args.psi) if args.psi is not None else summary(gl)
    if how is not None:
        obj["family_pressure"] = how
    if args.csv:
        from ..laws.export import write_csv
        write_csv(args.csv, gl, args.csv_directions)
    if args.abaqus:
        from ..laws.export import write_abaqus
        write_abaqus(args.abaqus, gl)
    if args.plot:
        from ..laws.plot import plot_law
        plot_law(gl, args.plot)
    if getattr(args, "gwfl", None):
        _gwfl(args, gl)
    _abaqus_user(args, gl, obj, how)
    return gl, obj


def _componentwise(args):
    """The GaugeLaw of --mu-f --mu-b --mu-t (written to --output)."""
    from ..errors import InputError
    from ..laws.componentwise import coefficients, componentwise_gauge
    from .parsing import componentwise_from_args, componentwise_given
    if not componentwise_given(args):
        raise InputError("give a gauge file (GAUGE.json) or the componentwise law's --mu-f "
                         "--mu-b --mu-t")
    gl = componentwise_gauge(**coefficients(componentwise_from_args(args)))
    if args.output:
        from ..laws.gauge_file import write_gauge
        write_gauge(args.output, gl)
    return gl


def _family(args, fam):
    """A law family without --pressure: its summary and every member's exports."""
    from ..errors import InputError
    from ..laws import family_report as R
    if args.psi is not None:
        raise InputError(f"{args.gauge} holds a law family over the pressures "
                         f"{fam.pressures[0]:g} to {fam.pressures[-1]:g} Pa: --psi needs "
                         "--pressure (the nominal contact pressure, Pa)")
    from ..io import write_text_atomic
    if args.csv:
        write_text_atomic(args.csv, R.family_table(fam, args.csv_directions))
    if args.abaqus:
        write_text_atomic(args.abaqus, R.family_abaqus(fam))
    if args.plot:
        R.plot_family(fam, args.plot)
    obj = R.family_summary(fam)
    _abaqus_user(args, fam, obj, None)
    return fam, obj


def _abaqus_user(args, gauge, obj, how) -> None:
    """--fric / --vfric / --vfriction / --abaqus-user: the routines, in ``obj["abaqus_user"]``."""
    from .law_fe import write_fe
    src = args.gauge or "--mu-f/--mu-b/--mu-t"
    what = f"{src} ({gauge.kind})" + (f" at {args.pressure:g} Pa" if how else "")
    done = write_fe(args, gauge, what)
    if done is not None:
        obj["abaqus_user"] = done


def main(args) -> int:
    import sys
    gl, obj = run(args)
    outputs = [(what, getattr(args, flag)) for flag, what in
               (("csv", "polar table"), ("abaqus", "Abaqus block"), ("plot", "plot"),
                ("output", "gauge file"), ("gwfl", "GWFL law"))
               if getattr(args, flag)]
    from .law_fe import written
    outputs += written(args)
    stream = sys.stderr if any(v == "-" for _, v in outputs) else sys.stdout

    def say(text):
        print(text, file=stream)
    if args.json:
        say(json_text(obj))
        return 0
    if args.psi is not None:
        say(f"psi = {obj['psi_deg']:g} deg: p = ({obj['p'][0]:.6f}, {obj['p'][1]:.6f})  "
            f"tangential = {obj['tangential']:.6f}  lateral = {obj['lateral']:.6f}  "
            f"alpha = {obj['alpha']:.6f}")
        if obj["set_valued"]:
            a, b = obj["segment"]
            say(f"set-valued: any force on the segment ({a[0]:.6f}, {a[1]:.6f}) -- "
                f"({b[0]:.6f}, {b[1]:.6f}) slides in this direction")
    else:
        from ..laws.family import GaugeFamily
        say(f"gauge file: {args.gauge or args.output or '(not written: --output GAUGE.json)'}")
        if isinstance(gl, GaugeFamily):
            from ..laws.family_report import format_family
            say(format_family(gl))
        else:
            from ..laws.summary import format_fit
            if obj.get("family_pressure"):
                from ..laws.family import how_words
                say(how_words(obj["family_pressure"]))
            say(format_fit(gl))
    written_lines(outputs, stream)
    return 0
