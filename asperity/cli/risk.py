"""``asperity risk``: will an assembly creep, cycle after cycle, and how far?

texture (or gauge, or explicit coefficients) -> mu+ / mu- along the assembly's slip axis ->
quasi-static ratchet analysis of the assembly under its load cycles -> verdict.  With
``--map`` the verdict and drift per cycle over a grid of two wedge-texture parameters.
"""
from __future__ import annotations

from ..errors import InputError
from ..microslip.risk import MAP_PARAMS
from ..microslip.risk_text import format_map, format_text
from . import add_cluster_arguments, emit, whole_flag
from .parsing import DefaultsHelpFormatter
from .sources import (
    WEDGE_FLAGS,
    add_elastic_arguments,
    add_source_arguments,
    contact_failed,
    elastic_from_args,
    texture_from_args,
)


def add_parser(sub) -> None:
    p = sub.add_parser(
        "risk", help="ratchet verdict of an assembly under load cycles, from a texture",
        description="Cumulative microslip check (SPEC.md 5): the texture's friction along the "
                    "assembly's slip axis (mu+ resists sliding towards +x, mu- towards -x), "
                    "the assembly (two-node model or strip, see the documentation's file formats) marched through its "
                    "load cycles until the cycle is stabilised, and the verdict: shakedown (no "
                    "slip after the first cycles), alternating-slip (slip back and forth every "
                    "cycle, no drift), ratchet (a drift every cycle) or slides-off, with dT_c, the margin dT_range/(2 dT_c), the drift per cycle "
                    "(negative: towards -x), the drift after N cycles and the cycles until the "
                    "tolerance is reached.  Without a texture the assembly file's [friction] "
                    "table is used.  With --elastic and no --pressure the contact is solved at "
                    "the assembly's contact pressure (strip: p; two-node: N / contact_area); a "
                    "gauge file holding a law family ([friction] gauge) is taken at that pressure.  --map P=LO:HI:N P=LO:HI:N draws the verdict over a grid "
                    "of two wedge parameters (alpha, beta, mu_alpha, mu_beta).",
        formatter_class=DefaultsHelpFormatter)
    # --contact not given: the file's texture takes the file's contact (all-faces for a
    # texture given on the command line)
    add_source_arguments(p, contact_default=None, contact_note=(
        " (default: the assembly file's [friction] contact for its texture, else all-faces; "
        "refused when the file's friction is a gauge or mu_plus/mu_minus)"))
    add_elastic_arguments(p)
    p.add_argument("assembly", metavar="ASSEMBLY.toml", help="assembly file (see the documentation's file formats)")
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
    p.add_argument("--max-marched", default="200", metavar="N",
                   help="cycles marched at most while looking for the stabilised cycle "
                        "(2 to 1e6)")
    p.add_argument("--dynamic", nargs="?", const="80000", default=None, metavar="STEPS",
                   help="also solve the assembly by Moreau time-stepping (small masses, slow "
                        "loading: STEPS steps per load segment, default 80000) over 3 cycles "
                        "and report its drift per cycle beside the quasi-static one (100 to "
                        "1e7 steps; they "
                        "agree to first order in 1/STEPS: the two-node SPEC case to 1e-3 at "
                        "80000; the 201-node bushing strip to 0.54, 0.23, 0.095 at 8e4, 3.2e5, "
                        "1.28e6 steps)")
    p.add_argument("--fe", metavar="CODE", default=None,
                   help="also run the strip assembly in a finite-element code: getfem (2D "
                        "plane-stress body on the rigid textured support, the same law and "
                        "load history; needs apt-get install python3-getfem) and print its "
                        "drift per cycle beside the chain's, with the difference explained")
    p.add_argument("--fe-mesh", default=None, metavar="N",
                   help="--fe: elements along the length l (4 to 4000, default 200); "
                        "ceil(N h / l) through the height h, at least 2")
    p.add_argument("--map", nargs=2, metavar="P=LO:HI:N", default=None,
                   help="risk map over two wedge parameters, e.g. alpha=5:40:8 beta=5:40:8 "
                        "(the others from the texture or wedge flags)")
    add_cluster_arguments(p, "--map: run the grid on a local Dask cluster of N worker "
                             "processes (default: in this process)",
                          "--map: run the grid on an existing Dask cluster")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png",
                   help="node displacement against cycles (and the strip's profiles), or the "
                        "risk map with --map")
    p.set_defaults(func=main, outputs=[("--plot", "plot", True)],
                   inputs=["texture", "assembly", "friction_map"])


def _settings(args, asm):
    """(cycles, tolerance in m, max marched, dynamic steps) from the flags, checked with
    the flags' names before any work."""
    from ..errors import check_range
    from ..microslip.limits import check_cycles, check_tolerance
    cycles = check_cycles("--cycles", args.cycles) if args.cycles is not None else (
        asm.cycles or 1e6)
    if args.tolerance is not None:
        tol = check_tolerance("--tolerance", args.tolerance, scale=1e-3, unit="mm")
    else:
        tol = asm.tolerance
    mm = whole_flag("--max-marched", args.max_marched, 2, 1_000_000)
    if args.slip_axis is not None:
        check_range("--slip-axis", args.slip_axis, -360.0, 360.0, unit="deg")
    dyn = whole_flag("--dynamic", args.dynamic, 100, 10_000_000)
    return cycles, tol, mm, dyn


def _texture_given(args) -> bool:
    return args.texture is not None or any(getattr(args, k) is not None for k in WEDGE_FLAGS)


def run(args) -> dict:
    """Python API of the command: the JSON object it prints with --json (and, under the
    private key "_chain", the slider chain for plots)."""
    from ..microslip.assembly import load_assembly
    from ..microslip.risk import assembly_friction, assess_assembly
    if args.texture is not None and str(args.texture).lower().endswith(".json"):
        raise InputError(f"{args.texture}: a gauge file goes in the assembly file ([friction] "
                         "gauge = \"law.json\"); the argument before ASSEMBLY.toml is a "
                         "texture or surface file")
    asm = load_assembly(args.assembly)
    cycles, tol, mm, dyn = _settings(args, asm)
    pressure = _elastic_pressure(args, asm)
    if elastic_from_args(args, several=False) is not None:
        if not _texture_given(args):
            raise InputError("--elastic weights the faces of a texture or surface: give one "
                             "(the assembly file's friction table has none)")
        if args.map is not None:
            raise InputError("--map varies the wedge's parameters; not with --elastic")
    fe_mesh = _fe_settings(args, asm)
    texture = texture_from_args(args)[0] if _texture_given(args) else None
    if args.map is not None:
        x, y = (parse_map_axis(t) for t in args.map)
        if x[0] == y[0]:
            raise InputError(f"--map needs two different parameters, got {x[0]} twice")
        from ..study.maps import risk_map
        workers = whole_flag("--workers", args.workers, 0, 4096)
        return risk_map(asm, x, y, texture, contact=args.contact,
                        slip_axis_deg=args.slip_axis, textured=args.textured, cycles=cycles,
                        max_marched=mm, workers=0 if workers is None and not args.scheduler
                        else workers, scheduler=args.scheduler)
    friction = assembly_friction(asm, texture, texture_name=args.texture or "wedge flags",
                                 contact=args.contact, slip_axis_deg=args.slip_axis,
                                 textured=args.textured)
    if pressure is not None:
        friction.detail["contact_pressure"] = pressure
    out = assess_assembly(asm, friction, cycles=cycles, tolerance=tol, max_marched=mm,
                          dynamic_steps=dyn)
    if fe_mesh is not None:
        out["fe"] = _fe_block(asm, friction, out, fe_mesh)
    return out


def _fe_settings(args, asm):
    """--fe and --fe-mesh checked before any work: the mesh (elements along l), or None."""
    if args.fe is None:
        if args.fe_mesh is not None:
            raise InputError("--fe-mesh sets the mesh of --fe getfem; give --fe getfem")
        return None
    from ..fe.strip import MESH_DEFAULT, MESH_RANGE, check_fe_assembly, fe_mesh
    if args.fe != "getfem":
        raise InputError(f"--fe must be getfem (the FE code asperity runs), got {args.fe!r}")
    if args.map is not None:
        raise InputError("--fe runs one assembly; not with --map")
    check_fe_assembly(asm)
    n = whole_flag("--fe-mesh", args.fe_mesh, *MESH_RANGE) if args.fe_mesh else MESH_DEFAULT
    fe_mesh(asm, n)
    return n


def _fe_block(asm, friction, out, mesh):
    from ..fe.strip import run_strip_fe
    if out["verdict"] == "slides-off":
        return {"skipped": "the assembly slides off: no cycle to compare"}
    return run_strip_fe(asm, friction.mu_plus, friction.mu_minus, mesh=mesh,
                        chain_drift_m=out["drift_per_cycle_m"])


def _elastic_pressure(args, asm):
    """With --elastic: the block ``contact_pressure`` of the friction's JSON.  Without
    --pressure the contact is solved at the assembly's contact pressure (``args.pressure``
    set to it); a --pressure other than the assembly's is used as asked, with a note."""
    import math
    if args.elastic is None:
        return None
    p, where = asm.contact_pressure()
    if args.pressure is None:
        if p is None:
            raise InputError("--elastic without --pressure solves the contact at the "
                             "assembly's contact pressure, and this two-node assembly gives "
                             "none: add assembly.contact_area (m^2, the nominal contact area "
                             "of one node) to the assembly file, or give --pressure")
        args.pressure = [p]
        return {"pressure_Pa": p, "from": where, "solved": True}
    if len(args.pressure) != 1:
        return None                      # refused by elastic_from_args
    x = args.pressure[0]
    out = {"pressure_Pa": x, "from": "--pressure", "solved": True}
    if p is not None and not math.isclose(x, p, rel_tol=1e-9):
        out["note"] = (f"--pressure {x:g} Pa is not the assembly's contact pressure {p:g} Pa "
                       f"({where}): the contact is solved at --pressure, as asked")
    return out


def parse_map_axis(text: str):
    """'alpha=5:40:8' -> ('alpha', values)."""
    import numpy as np

    from ..errors import check_int, check_range, number_from_text
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
    lo = check_range(f"--map {name} LO", number_from_text(f"--map {name} LO", parts[0]))
    hi = check_range(f"--map {name} HI", number_from_text(f"--map {name} HI", parts[1]))
    n = check_int(f"--map {name} N", number_from_text(f"--map {name} N", parts[2]), 2, 200)
    if not hi > lo:
        raise InputError(f"--map {name} needs LO < HI, got {lo:g}:{hi:g}")
    return name, np.linspace(lo, hi, n)


def _public(out: dict) -> dict:
    pub = {k: v for k, v in out.items() if not k.startswith("_")}
    if isinstance(pub.get("fe"), dict):
        pub["fe"] = _public(pub["fe"])
    return pub


def main(args) -> int:
    from ..contact.solver import ContactNotConverged
    try:
        out = run(args)
    except ContactNotConverged as exc:
        return contact_failed("risk", exc)
    if args.map is not None:
        if args.plot:
            from ..microslip.plot import plot_risk_map
            plot_risk_map(out, args.plot)
        emit(args, out, format_map(out))
        return 0
    if args.plot:
        from ..microslip.plot import plot_assembly_history
        plot_assembly_history(out["_chain"], _loading_from(args), args.plot,
                              title=out["assembly"]["name"], fe=out.get("fe"))
    text = format_text(out)
    if out.get("fe"):
        from ..fe.strip import fe_lines
        text += "\n" + "\n".join(fe_lines(out["fe"]))
    emit(args, _public(out), text)
    return 0


def _loading_from(args):
    from ..microslip.assembly import load_assembly
    return load_assembly(args.assembly).loading
