"""``asperity risk``: will an assembly creep, cycle after cycle, and how far?

texture (or gauge, or explicit coefficients) -> mu+ / mu- along the assembly's slip axis ->
quasi-static ratchet analysis of the assembly under its load cycles -> verdict.  With
``--map`` the verdict and drift per cycle over a grid of two wedge-texture parameters.
"""
from __future__ import annotations

import argparse

from ..errors import InputError
from . import emit
from .derive import WEDGE_FLAGS, add_source_arguments

MAP_PARAMS = {"alpha": "alpha_deg", "beta": "beta_deg", "mu_alpha": "mu_alpha",
              "mu_beta": "mu_beta"}


def add_parser(sub) -> None:
    p = sub.add_parser(
        "risk", help="ratchet verdict of an assembly under load cycles, from a texture",
        description="Cumulative microslip check (SPEC.md 5): the texture's friction along the "
                    "assembly's slip axis (mu+ resists sliding towards +x, mu- towards -x), "
                    "the assembly (two-node model or strip, see README) marched through its "
                    "load cycles until the cycle is stabilised, and the verdict: shakedown or "
                    "ratchet, with dT_c, the margin dT_range/(2 dT_c), the drift per cycle "
                    "(negative: towards -x), the drift after N cycles and the cycles until the "
                    "tolerance is reached.  Without a texture the assembly file's [friction] "
                    "table is used.  --map P=LO:HI:N P=LO:HI:N draws the verdict over a grid "
                    "of two wedge parameters (alpha, beta, mu_alpha, mu_beta).",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    add_source_arguments(p)
    p.add_argument("assembly", metavar="ASSEMBLY.toml", help="assembly file (see README)")
    p.add_argument("--cycles", type=float, default=None, metavar="N",
                   help="load cycles to assess (e.g. 1e6; default: the file's loading.cycles, "
                        "else 1e6)")
    p.add_argument("--tolerance", type=float, default=None, metavar="MM",
                   help="displacement the assembly may drift, in mm (default: the file's "
                        "loading.tolerance)")
    p.add_argument("--slip-axis", type=float, default=None, metavar="DEG",
                   help="+x of the assembly in the texture frame, deg (default: the file's "
                        "friction.slip_axis_deg, else the principal direction t_a)")
    p.add_argument("--textured", choices=["support", "part"], default=None,
                   help="which face carries the texture (default: the file's, else support)")
    p.add_argument("--max-marched", type=int, default=200, metavar="N",
                   help="cycles marched at most while looking for the stabilised cycle")
    p.add_argument("--dynamic", type=int, nargs="?", const=80000, default=None, metavar="STEPS",
                   help="also solve the assembly by Moreau time-stepping (small masses, slow "
                        "loading: STEPS steps per load segment, default 80000) over 3 cycles "
                        "and report its drift per cycle beside the quasi-static one (they "
                        "agree to first order in 1/STEPS: the two-node SPEC case to 1e-3 at "
                        "80000; the 201-node bushing strip to 0.54, 0.23, 0.095 at 8e4, 3.2e5, "
                        "1.28e6 steps)")
    p.add_argument("--map", nargs=2, metavar="P=LO:HI:N", default=None,
                   help="risk map over two wedge parameters, e.g. alpha=5:40:8 beta=5:40:8 "
                        "(the others from the texture or wedge flags)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png",
                   help="node displacement against cycles (and the strip's profiles), or the "
                        "risk map with --map")
    p.set_defaults(func=main)


def _texture_given(args) -> bool:
    return args.texture is not None or any(getattr(args, k) is not None for k in WEDGE_FLAGS)


def friction_for(args, asm):
    """(Friction, texture or None) from the command line's texture, else the file."""
    from ..assembly import friction_from_texture, resolve_friction
    from .derive import texture_from_args
    fr = asm.friction_table
    axis = args.slip_axis if args.slip_axis is not None else fr.get("slip_axis_deg")
    textured = args.textured or fr.get("textured", "support")
    if args.slip_axis is not None:
        from ..errors import check_range
        check_range("--slip-axis", args.slip_axis, -360.0, 360.0, unit="deg")
    if _texture_given(args):
        texture, _ = texture_from_args(args)
        name = args.texture or "wedge flags"
        f = friction_from_texture(texture, args.contact, axis, textured, name)
        if fr:
            f.detail["note"] = ("texture from the command line instead of the file's friction "
                                "source; its slip_axis_deg and textured still apply")
        return f, texture
    if args.slip_axis is not None or args.textured is not None:
        fr = dict(fr)
        if "mu_plus" in fr:
            raise InputError("--slip-axis and --textured apply to a texture or gauge, not to "
                             "explicit mu_plus/mu_minus")
        if args.slip_axis is not None:
            fr["slip_axis_deg"] = args.slip_axis
        if args.textured is not None:
            fr["textured"] = args.textured
        from dataclasses import replace
        asm = replace(asm, friction_table=fr)
    return resolve_friction(asm), None


def _settings(args, asm):
    from ..errors import check_range
    cycles = args.cycles if args.cycles is not None else (asm.cycles or 1e6)
    cycles = check_range("--cycles", cycles, 1.0, 1e15)
    if args.tolerance is not None:
        tol = check_range("--tolerance", args.tolerance, 0.0, None, low_open=True, unit="mm") * 1e-3
    else:
        tol = asm.tolerance
    from ..errors import check_int
    mm = check_int("--max-marched", args.max_marched, 2, 1_000_000)
    return cycles, tol, mm


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json (and, under the
    private key "_result", the simulation for plots)."""
    from .. import __version__
    from ..assembly import load_assembly
    from ..microslip import assess
    asm = load_assembly(args.assembly)
    cycles, tol, mm = _settings(args, asm)
    if args.map is not None:
        return run_map(args, asm, cycles, tol, mm)
    fr, _ = friction_for(args, asm)
    chain = asm.chain(fr.mu_plus, fr.mu_minus)
    out = {"asperity_version": __version__, "assembly": asm.to_dict(),
           "loading": _loading_dict(asm), "friction": fr.to_dict()}
    out.update(assess(chain, asm.loading, cycles, tol,
                      dT_c_closed_form=asm.dT_c_closed_form(fr.mu_plus, fr.mu_minus),
                      max_marched=mm))
    if args.dynamic is not None and out["verdict"] != "slides-off":
        out["dynamic"] = dynamic_check(chain, asm.loading, args.dynamic,
                                       out["drift_per_cycle_m"])
    out["_chain"] = chain
    return out


def dynamic_check(chain, loading, steps: int, drift_qs: float) -> dict:
    """Drift per cycle of the Moreau solution (3 cycles) against the quasi-static one."""
    from ..errors import check_int
    from ..microslip import simulate_dynamic
    steps = check_int("--dynamic", steps, 100, 10_000_000)
    r = simulate_dynamic(chain, loading, 3, steps_per_segment=steps)
    d = float(r.drift_per_cycle)
    scale = max(abs(drift_qs), 1e-12 * max(abs(x) for x in (d, drift_qs, 1.0)))
    return {"steps_per_segment": steps, "cycles": 3, "drift_per_cycle_m": d,
            "difference_m": d - drift_qs, "relative_difference":
            abs(d - drift_qs) / scale if drift_qs != 0.0 else None, "solver": r.solver}


def _loading_dict(asm) -> dict:
    L = asm.loading
    return {"history_K": [float(x) for x in L.dT], "force_history": [float(x) for x in L.F],
            "force_unit": "N/m" if asm.model == "strip" else "N", "force_at": asm.force_at,
            "substeps": L.substeps}


def parse_map_axis(text: str):
    """'alpha=5:40:8' -> ('alpha', values)."""
    import numpy as np
    from ..errors import check_int, check_range
    if "=" not in text:
        raise InputError(f"--map takes P=LO:HI:N with P one of {', '.join(MAP_PARAMS)}, "
                         f"got {text!r}")
    name, rng = text.split("=", 1)
    name = name.strip().replace("-", "_")
    if name not in MAP_PARAMS:
        raise InputError(f"--map parameter must be one of {', '.join(MAP_PARAMS)}, got {name!r}")
    parts = rng.split(":")
    if len(parts) != 3:
        raise InputError(f"--map {name} takes LO:HI:N, got {rng!r}")
    lo = check_range(f"--map {name} LO", parts[0])
    hi = check_range(f"--map {name} HI", parts[1])
    n = check_int(f"--map {name} N", parts[2], 2, 200)
    if not hi > lo:
        raise InputError(f"--map {name} needs LO < HI, got {lo:g}:{hi:g}")
    return name, np.linspace(lo, hi, n)


def run_map(args, asm, cycles, tol, max_marched) -> dict:
    """Verdict and drift per cycle over a grid of two wedge parameters."""
    from dataclasses import replace

    import numpy as np

    from .. import __version__
    from ..assembly import friction_from_texture
    from ..microslip import SlideOffError, long_life
    (px, xs), (py, ys) = (parse_map_axis(t) for t in args.map)
    if px == py:
        raise InputError(f"--map needs two different parameters, got {px} twice")
    if _texture_given(args):
        from .derive import texture_from_args
        base, _ = texture_from_args(args)
        contact = args.contact
    elif "texture" in asm.friction_table:
        from ..assembly import load_texture_or_surface
        base = load_texture_or_surface(asm.folder / asm.friction_table["texture"])
        contact = asm.friction_table.get("contact", "all-faces")
    else:
        raise InputError("--map needs a wedge texture: a texture file, the wedge flags, or a "
                         "texture in the assembly's [friction] table")
    if getattr(base, "kind", "") not in ("wedge", "gaussian-wedge"):
        raise InputError("--map varies wedge parameters: give a wedge texture, not a surface")
    fr = asm.friction_table
    axis = args.slip_axis if args.slip_axis is not None else fr.get("slip_axis_deg")
    textured = args.textured or fr.get("textured", "support")
    shape = (ys.size, xs.size)
    verdict = np.empty(shape, dtype=object)
    drift = np.full(shape, np.nan)
    mup = np.full(shape, np.nan)
    mum = np.full(shape, np.nan)
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            try:
                tex = replace(base, **{MAP_PARAMS[px]: float(x), MAP_PARAMS[py]: float(y)})
            except InputError as exc:
                raise InputError(f"--map: {exc}") from None
            f = friction_from_texture(tex, contact, axis, textured)
            mup[j, i], mum[j, i] = f.mu_plus, f.mu_minus
            try:
                r = long_life(asm.chain(f.mu_plus, f.mu_minus), asm.loading, cycles,
                              max_marched=max_marched)
            except SlideOffError:
                verdict[j, i] = "slides-off"
                continue
            verdict[j, i] = "ratchet" if r.ratchet else "shakedown"
            drift[j, i] = r.drift_per_cycle

    def grid(a):
        return [[(float(v) if np.isfinite(v) else None) for v in row] for row in a]
    return {"asperity_version": __version__, "assembly": asm.to_dict(),
            "loading": _loading_dict(asm), "contact": contact, "textured": textured,
            "slip_axis_deg": 0.0 if axis is None else float(axis),
            "base_texture": base.to_dict(),
            "map": {"x": {"parameter": px, "values": xs.tolist()},
                    "y": {"parameter": py, "values": ys.tolist()},
                    "verdict": verdict.tolist(), "drift_per_cycle_m": grid(drift),
                    "mu_plus": grid(mup), "mu_minus": grid(mum)},
            "cycles": cycles,
            "drift_after_cycles_m": grid(drift * cycles),
            "sign_convention": _sign()}


def _sign() -> str:
    from ..microslip import SIGN_CONVENTION
    return SIGN_CONVENTION


def _len(x) -> str:
    if x is None:
        return "-"
    a = abs(x)
    if a == 0:
        return "0 m"
    if a >= 1e-2:
        return f"{x:+.4g} m"
    if a >= 1e-5:
        return f"{x * 1e3:+.4g} mm"
    return f"{x * 1e6:+.4g} um"


def format_text(out: dict) -> str:
    a = out["assembly"]
    f = out["friction"]
    L = out["loading"]

    def mu(x):
        return "inf (self-locking)" if x is None else f"{x:.6f}"
    size = (f"strip, {a['n']} nodes, l = {a['l']:g} m" if a["model"] == "strip"
            else f"two-node, l0 = {a['l0']:g} m")
    src = {"explicit": "explicit coefficients",
           "gauge": f"gauge {f.get('gauge', '')}",
           "texture": f"texture {f.get('texture', '')} ({f.get('contact', '')})"}[f["source"]]
    lines = [f"assembly: {a['name']} ({size})", f"friction: {src}"]
    if f["source"] != "explicit":
        lines.append(f"  slip axis +x at {f['slip_axis_deg']:g} deg in the texture frame "
                     f"({f['slip_axis']}), texture on the {f['textured']}")
    if f.get("note"):
        lines.append(f"  ({f['note']})")
    lines.append(f"  mu+ (assembly sliding towards +x) = {mu(f['mu_plus'])}   "
                 f"mu- (towards -x) = {mu(f['mu_minus'])}")
    hist = " -> ".join(f"{x:g}" for x in L["history_K"])
    Fmax = out["max_tangential_load"]
    lines.append(f"loading: dT {hist} K per cycle, "
                 + (f"tangential load up to {Fmax:g} {L['force_unit']} ({L['force_at']})"
                    if Fmax else "no tangential load"))
    dc = out["dT_c_K"]
    cf = out["dT_c_closed_form_K"]
    lines.append("elastic limit dT_c = " + ("inf (no slider ever slips)" if dc is None else
                 f"{dc:.4g} K" + (f" (closed form {cf:.4g} K)" if cf is not None else ""))
                 + f"; dT range {out['dT_range_K']:g} K; margin dT_range / (2 dT_c) = "
                 f"{out['margin']:.3g}")
    v = out["verdict"]
    if v == "slides-off":
        lines.append(f"verdict: SLIDES OFF -- {out['reason']}")
    else:
        d = out["drift_per_cycle_m"]
        st = out["stabilised_at_cycle"]
        stab = f"stabilised from cycle {st}" if st else "NOT stabilised"
        if v == "ratchet":
            lines.append(f"verdict: RATCHET -- {_len(d)} per cycle (towards "
                         f"{out['drift_direction']}), {stab}")
        else:
            lines.append(f"verdict: SHAKEDOWN -- no drift per cycle ({out['regime']}, {stab})")
        how = (f"extrapolated from {out['cycles_marched']} marched cycles"
               if out.get("extrapolated") else "marched")
        lines.append(f"  displacement after {out['cycles']:g} cycles: "
                     f"{_len(out['drift_after_cycles_m'])} ({how})")
        if out["tolerance_m"] is not None:
            c = out["cycles_to_tolerance"]
            lines.append(f"  tolerance {out['tolerance_m'] * 1e3:g} mm: " +
                         ("never reached" if c is None else f"reached after {c:,} cycles"))
        if out.get("warning"):
            lines.append(f"  WARNING: {out['warning']}")
        if a["model"] == "strip" and v == "shakedown" and out["margin"] > 1:
            lines.append("  (for a strip, margin > 1 is necessary but not sufficient: its ends "
                         "slip back and forth while its middle sticks)")
    dyn = out.get("dynamic")
    if dyn:
        rel = dyn["relative_difference"]
        lines.append(f"Moreau time-stepping ({dyn['steps_per_segment']} steps per load segment, "
                     f"{dyn['cycles']} cycles): drift {_len(dyn['drift_per_cycle_m'])} per cycle"
                     + (f", {rel:.2g} from the quasi-static value" if rel is not None else
                        f" (quasi-static: none; difference {_len(dyn['difference_m'])})")
                     + f"; solver {dyn['solver'].get('status', '?')}")
    lines.append(f"sign convention: {out['sign_convention']}")
    return "\n".join(lines)


def format_map(out: dict) -> str:
    m = out["map"]
    px, py = m["x"]["parameter"], m["y"]["parameter"]
    head = f"{py} \\ {px}"
    lines = [f"risk map: {out['assembly']['name']}, drift per cycle (um; S = shakedown, "
             f"X = slides off), {out['contact']}, texture on the {out['textured']}",
             f"{head:>14s} " + " ".join(f"{x:>9.4g}" for x in m["x"]["values"])]
    for y, vs, ds in zip(m["y"]["values"], m["verdict"], m["drift_per_cycle_m"]):
        cells = []
        for v, d in zip(vs, ds):
            cells.append(f"{'S':>9s}" if v == "shakedown" else f"{'X':>9s}" if v != "ratchet"
                         else f"{d * 1e6:>+9.3g}")
        lines.append(f"{y:>14.4g} " + " ".join(cells))
    lines.append(f"sign convention: {out['sign_convention']}")
    return "\n".join(lines)


def _public(out: dict) -> dict:
    return {k: v for k, v in out.items() if not k.startswith("_")}


def main(args) -> int:
    out = run(args)
    if args.map is not None:
        if args.plot:
            from ..report_microslip import plot_risk_map
            plot_risk_map(out, args.plot)
        emit(args, out, format_map(out))
        return 0
    if args.plot:
        from ..report_microslip import plot_assembly_history
        plot_assembly_history(out["_chain"], _loading_from(args), args.plot,
                              title=out["assembly"]["name"])
    emit(args, _public(out), format_text(out))
    return 0


def _loading_from(args):
    from ..assembly import load_assembly
    return load_assembly(args.assembly).loading

