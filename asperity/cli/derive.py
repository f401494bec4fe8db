"""``asperity derive``: a texture's direction-dependent friction, in numbers and as a picture."""
from __future__ import annotations

import argparse

from ..progress import progress_bar
from . import emit
from .sources import add_source_arguments, spring_model_from_args, texture_from_args


def add_parser(sub) -> None:
    p = sub.add_parser(
        "derive", help="direction-dependent friction of a texture",
        description="Direction-dependent friction of a wedge texture or of any surface: the "
                    "reservoir point p(psi) = -lambda_T/lambda_N for every sliding direction psi "
                    "(wedges: from t_a, across the ridges, towards t_b, along them; surfaces: "
                    "from +x towards +y of the file), mu_a+/- and mu_b+/- (surfaces: along, "
                    "against and across the principal direction found), and the diagnostics "
                    "(self-locking, admissibility, associativity). Give a texture file (TOML, "
                    "see README), the four wedge flags, or a surface file: a triangle mesh "
                    "(.stl .obj .ply), a height map (.npy, text matrix) or an instrument file "
                    "(.x3p .mi .sur .opd .datx ..., needs pip install 'asperity[metrology]'); "
                    "a trailing .gz is read too.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    add_source_arguments(p)
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
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the summary")
    p.add_argument("--plot", metavar="FILE.png", help="draw the polar reservoir and T/L against psi "
                                                      "(surfaces: and a height-map preview)")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True)],
                   inputs=["texture", "friction_map"])


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json."""
    from ..friction.derive import derive, to_json
    texture, table = texture_from_args(args)
    model = spring_model_from_args(args, table) if args.method == "springs" else None
    with progress_bar("facets") as progress:
        d = derive(texture, args.contact, args.method, args.directions, model, progress=progress)
    return d, to_json(d)


def main(args) -> int:
    from ..friction.derive import format_text
    d, obj = run(args)
    if args.plot:
        from ..friction.faces import compute_reservoir
        from ..friction.plot import plot_derivation
        other = "windward" if d.contact == "all-faces" else "all-faces"
        plot_derivation(d, args.plot, other=compute_reservoir(d.texture, d.reservoir.psi, other))
    emit(args, obj, format_text(d))
    return 0
