"""``asperity fit``: fit a friction law (truncated ellipse or star-shaped gauge) to a texture's
directional friction and save it as a gauge file."""
from __future__ import annotations

import argparse
import math
from . import emit

LAWS = {"ellipse": "truncated-ellipse", "star": "star"}


def add_parser(sub) -> None:
    from .derive import add_source_arguments
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
                    "are made from the gauge file by `asperity law`.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    add_source_arguments(p)
    p.add_argument("--law", choices=sorted(LAWS), default="star", help="law to fit")
    p.add_argument("-o", "--output", metavar="GAUGE.json",
                   help="write the gauge file (versioned JSON, see README); without it only the "
                        "fit quality is printed")
    p.add_argument("--directions", type=int, default=720, metavar="N",
                   help="sliding directions fitted (8 to 100000); the law is checked at N more")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (law, source, fit quality, output file)")
    p.add_argument("--plot", metavar="FILE.png", help="draw C, D, the data and the sliding rule")
    p.set_defaults(func=main)


def run(args):
    """Python API of the command: (GaugeLaw, the JSON object printed with --json)."""
    from ..derive import derive
    from ..gauges import fit_derivation
    from .derive import progress_bar, texture_from_args
    texture, _ = texture_from_args(args)
    with progress_bar("facets") as progress:
        d = derive(texture, args.contact, "closed-form", args.directions, progress=progress)
    gl = fit_derivation(d, LAWS[args.law])
    obj = summary(gl)
    if args.output:
        from ..gauge_file import write_gauge
        write_gauge(args.output, gl)
        obj["output"] = str(args.output)
    return gl, obj


def summary(gl) -> dict:
    """JSON summary of a fitted law (no bulky arrays)."""
    out = {"law": gl.kind, "source": gl.source,
           "principal_direction_deg": gl.principal_direction_deg, "fit": gl.fit.to_dict()}
    if gl.kind == "truncated-ellipse":
        out["parameters"] = {**gl.law.C.axes, "theta_rad": gl.law.C.theta}
    else:
        out["parameters"] = {"C_vertices": int(gl.law.C.n), "D_samples": int(gl.law.D.psi.size),
                             "D_flat_edges_deg": [math.degrees(x) for x in gl.law.D.edges]}
    return out


def format_fit(gl) -> str:
    """Fit quality for the terminal."""
    r = gl.fit
    tex = gl.source.get("texture", {})
    lines = [f"law: {gl.kind}   contact: {gl.source.get('contact')}   texture: "
             + ", ".join(f"{k}={v}" for k, v in tex.items() if k in
                         ("kind", "alpha_deg", "beta_deg", "mu_alpha", "mu_beta", "source")),
             f"fitted points: {r.n_points}"]
    if gl.kind == "truncated-ellipse":
        e = gl.law.C
        lines.append(f"  mu_a+ = {e.mu_a_plus:.6f}  mu_a- = {e.mu_a_minus:.6f}  "
                     f"mu_b+ = {e.mu_b_plus:.6f}  mu_b- = {e.mu_b_minus:.6f}"
                     + (f"  (t_a at {gl.principal_direction_deg:.3f} deg)"
                        if gl.principal_direction_deg else ""))
    lines += [f"radial error at the data: max {r.max_radial_error:.3e}, rms {r.rms_radial_error:.3e}",
              f"largest angle between the data force and the law's force: "
              f"{r.max_angle_error_deg:.4g} deg"]
    if r.holdout_directions:
        lines.append(f"off the fitted directions ({r.holdout_directions} midway directions): "
                     f"max magnitude error {r.holdout_max_magnitude_error:.3e}, max angle "
                     f"{r.holdout_max_angle_deg:.4g} deg")
    lines.append(f"C convex: {'yes' if r.C_convex else 'no'} (smallest turning angle "
                 f"{r.C_min_turn_deg:.4g} deg)")
    if r.D_convex is not None:
        lines.append(f"D convex: {'yes' if r.D_convex else 'NO'} (min d(angle)/dpsi "
                     f"{r.D_min_turn_rate:.4g}); closure residual ln h(2pi) - ln h(0) = "
                     f"{r.closure_residual:.3e}, closed by turning the forces "
                     f"{r.closure_max_angle_deg:.3g} deg")
    lines.append(f"dissipation p.s >= 0: {'yes' if r.admissible else 'NO'} "
                 f"(min {r.min_dissipation:.4g})")
    return "\n".join(lines)


def main(args) -> int:
    gl, obj = run(args)
    if args.plot:
        from ..report_gauges import plot_law
        plot_law(gl, args.plot)
    emit(args, obj, format_fit(gl), (("gauge file", args.output),))
    return 0
