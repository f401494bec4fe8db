"""``asperity derive``: a texture's direction-dependent friction, in numbers and as a picture."""
from __future__ import annotations

import argparse
import json

from ..errors import InputError

SPRING_FLAGS = {  # flag dest -> key of the [springs] table / SpringModel field
    "k_n": "k_n", "k_f": "k_f", "preload": "preload", "density": "density",
    "n_springs": "n_springs", "steps_per_period": "steps_per_period",
}
WEDGE_FLAGS = {"alpha": "alpha_deg", "beta": "beta_deg", "mu_alpha": "mu_alpha",
               "mu_beta": "mu_beta", "height": "height"}


def add_parser(sub) -> None:
    p = sub.add_parser(
        "derive", help="direction-dependent friction of a texture",
        description="Direction-dependent friction of a wedge texture: the reservoir point "
                    "p(psi) = -lambda_T/lambda_N for every sliding direction psi (from t_a, "
                    "across the ridges, towards t_b, along them), mu_a+/-, mu_b+/-, and the "
                    "diagnostics (self-locking, admissibility, associativity). Give a texture "
                    "file (TOML, see README) or the four wedge flags.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("texture", nargs="?", help="texture file (.toml)")
    g = p.add_argument_group("wedge texture given by flags (instead of a file)")
    g.add_argument("--alpha", type=float, metavar="DEG", help="slope of the face rising towards +t_a, in (0, 90)")
    g.add_argument("--beta", type=float, metavar="DEG", help="slope of the face falling towards +t_a, in (0, 90)")
    g.add_argument("--mu-alpha", type=float, metavar="X", help="local friction on the alpha face, >= 0")
    g.add_argument("--mu-beta", type=float, metavar="Y", help="local friction on the beta face, >= 0")
    g.add_argument("--height", type=float, metavar="M", help="wedge height in m (the friction does not depend on it)")
    p.add_argument("--contact", choices=["all-faces", "windward"], default="all-faces",
                   help="all-faces: compliant springs touch every face; windward: rigid asperities, "
                        "only faces facing the motion")
    p.add_argument("--method", choices=["closed-form", "springs"], default="closed-form",
                   help="closed form, or the spring-on-wedge simulation")
    p.add_argument("--directions", type=int, default=72, metavar="N",
                   help="number of equally spaced sliding directions (8 to 100000)")
    s = p.add_argument_group("spring model (--method springs; overrides the file's [springs] table)")
    s.add_argument("--k-n", type=float, metavar="N_M", help="normal stiffness of one spring, N/m")
    s.add_argument("--k-f", type=str, metavar="N_M", help="flexural stiffness of one spring, N/m, or 'inf' (rigid)")
    s.add_argument("--preload", type=float, metavar="N", help="force of a spring whose tip is at the base line z=0, N")
    s.add_argument("--density", type=float, metavar="PER_M2", help="springs per m^2")
    s.add_argument("--n-springs", type=int, metavar="N", help="springs per texture period")
    s.add_argument("--steps-per-period", type=int, metavar="N", help="quasi-static steps per period of travel")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the summary")
    p.add_argument("--plot", metavar="FILE.png", help="draw the polar reservoir and T/L against psi")
    p.set_defaults(func=main)


def texture_from_args(args):
    """(texture, springs table) from a texture file or the wedge flags."""
    from ..texture import WedgeTexture, load_texture_file
    given = {k: getattr(args, k) for k in WEDGE_FLAGS if getattr(args, k) is not None}
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
    try:
        return WedgeTexture(**{WEDGE_FLAGS[k]: v for k, v in given.items()}), {}
    except InputError as exc:
        msg = str(exc)
        for flag, field in WEDGE_FLAGS.items():
            if msg.startswith(field + " "):
                msg = "--" + flag.replace("_", "-") + msg[len(field):]
        raise InputError(msg) from None


def spring_model_from_args(args, table: dict):
    from ..springs import SpringModel
    d = dict(table)
    for dest, key in SPRING_FLAGS.items():
        v = getattr(args, dest, None)
        if v is not None:
            d[key] = v
    return SpringModel.from_dict(d)


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json."""
    from ..derive import derive, to_json
    texture, table = texture_from_args(args)
    model = spring_model_from_args(args, table) if args.method == "springs" else None
    d = derive(texture, args.contact, args.method, args.directions, model)
    return d, to_json(d)


def main(args) -> int:
    from ..derive import format_text
    d, obj = run(args)
    if args.plot:
        from ..closed_form import compute_reservoir
        from ..plotting import plot_derivation
        other = "windward" if d.contact == "all-faces" else "all-faces"
        plot_derivation(d, args.plot, other=compute_reservoir(d.texture, d.reservoir.psi, other))
    if args.json:
        print(json.dumps(obj, indent=2, allow_nan=False))
    else:
        print(format_text(d))
        if args.plot:
            print(f"plot written to {args.plot}")
    return 0
