"""``asperity law``'s Abaqus user routines: --fric, --vfric, --vfriction FILE.f and
--abaqus-user FILE.inp (issue 27). The flags, the outputs they declare, and the writer
called by :mod:`asperity.cli.law` once the law is read."""
from __future__ import annotations

#: flag, args attribute, routine
ROUTINE_FLAGS = (("--fric", "fric", "fric"), ("--vfric", "vfric", "vfric"),
                 ("--vfriction", "vfriction", "vfriction"))
#: the outputs the flags declare (checked before any work: folder exists, not an input)
FE_OUTPUTS = [(flag, dest, False) for flag, dest, _ in ROUTINE_FLAGS] + [
    ("--abaqus-user", "abaqus_user", False)]


def add_fe_flags(p) -> None:
    p.add_argument("--fric", metavar="FILE.f",
                   help="write the Abaqus/Standard user subroutine FRIC of the law (fixed-"
                        "form Fortran, the law's table baked in within 1e-4 of --psi; "
                        "PROPS: elastic slip stiffness, angle of the law's +x from local "
                        "direction 1 in deg, +1/-1 texture on the main/secondary surface)")
    p.add_argument("--vfric", metavar="FILE.f",
                   help="write the Abaqus/Explicit user subroutine VFRIC (contact pairs; "
                        "props: the law's +x axis in global coordinates, +1/-1 side)")
    p.add_argument("--vfriction", metavar="FILE.f",
                   help="write the Abaqus/Explicit user subroutine VFRICTION (general "
                        "contact, PURE MASTER-SLAVE; props as --vfric)")
    p.add_argument("--slip-stiffness", type=float, metavar="PA_PER_M",
                   help="FRIC's PROPS(1) in the deck lines: the elastic slip stiffness, shear "
                        "stress per unit slip (1 to 1e20; without it a placeholder to "
                        "replace)")
    p.add_argument("--law-angle", type=float, default=0.0, metavar="DEG",
                   help="FRIC's PROPS(2) in the deck lines: the angle from the local slip "
                        "direction 1 to the law's +x axis (-360 to 360 deg)")
    p.add_argument("--law-axis", type=float, nargs=3, default=(1.0, 0.0, 0.0),
                   metavar=("X", "Y", "Z"),
                   help="VFRIC/VFRICTION's props(1:3) in the deck lines: the law's +x axis in "
                        "global coordinates (not zero)")
    p.add_argument("--texture-side", choices=("main", "secondary"), default="main",
                   help="the surface that carries the texture: PROPS(3) / props(4) = +1 "
                        "(main, master) or -1 (secondary, slave) in the deck lines")
    p.add_argument("--abaqus-user", metavar="FILE.inp",
                   help="write the input-deck lines of the routines asked for (of FRIC "
                        "when none is): *SURFACE INTERACTION, *FRICTION, USER with its "
                        "data line, the contact pair or general-contact lines")


def deck_props(args) -> dict:
    """The properties the deck lines carry, checked (one line naming the flag)."""
    import math

    from ..errors import InputError, check_range
    k = getattr(args, "slip_stiffness", None)
    if k is not None:
        k = check_range("--slip-stiffness", k, 1.0, 1e20, unit="Pa/m")
    angle = check_range("--law-angle", getattr(args, "law_angle", 0.0), -360.0, 360.0,
                        unit="deg")
    axis = [float(v) for v in getattr(args, "law_axis", (1.0, 0.0, 0.0))]
    if not all(math.isfinite(v) for v in axis) or math.hypot(*axis) == 0.0:
        raise InputError(f"--law-axis must be a finite, non-zero vector, got "
                         f"{' '.join(f'{v:g}' for v in axis)}")
    side = -1 if getattr(args, "texture_side", "main") == "secondary" else 1
    return {"stiffness": k, "angle_deg": angle, "side": side, "axis": axis}


def wanted(args) -> list[tuple[str, str]]:
    """(routine, path) of the routine files asked for."""
    return [(r, getattr(args, dest)) for _, dest, r in ROUTINE_FLAGS if getattr(args, dest, None)]


def write_fe(args, gauge, what: str) -> dict | None:
    """Write the routines and the deck snippet asked for; the JSON record of what was
    written (None when nothing was asked). ``gauge``: a GaugeLaw or GaugeFamily."""
    import time

    from ..fe.abaqus_deck import deck_text, header_lines
    from ..fe.abaqus_fric import law_table_of, routine_source
    from ..io import write_text_atomic
    routines = wanted(args)
    if not routines and not getattr(args, "abaqus_user", None):
        return None
    props = deck_props(args)
    t0 = time.perf_counter()
    table = law_table_of(gauge)                     # TableError (one line) if 1e-4 fails
    t_table = time.perf_counter() - t0
    levels = getattr(table, "pressures", None)
    about = (f"law: {what}\ntable: {table.n} directions"
             + (f" x {len(levels)} pressure levels" if levels is not None else "")
             + f", max force error {table.max_error:.2e} (per unit normal load)")
    out = {"table_nodes": table.n, "max_table_error": float(table.max_error),
           "table_seconds": t_table, "routines": []}
    if levels is not None:
        out["table_pressure_levels_Pa"] = [float(x) for x in levels]
    for routine, path in routines:
        t1 = time.perf_counter()
        text = routine_source(gauge, routine, header=header_lines(routine, about,
                                                                  props=props),
                              table=table)
        write_text_atomic(path, text)
        out["routines"].append({"routine": routine.upper(), "file": str(path),
                                "lines": text.count("\n"),
                                "seconds": t_table + time.perf_counter() - t1})
    if getattr(args, "abaqus_user", None):
        names = [r for r, _ in routines] or ["fric"]
        write_text_atomic(args.abaqus_user, deck_text(names, what=about, props=props))
        out["deck"] = {"file": str(args.abaqus_user), "routines": [r.upper() for r in names]}
    return out


def written(args) -> list[tuple[str, str]]:
    """(what, path) lines for the terminal."""
    out = [(f"Abaqus {r.upper()} routine", p) for r, p in wanted(args)]
    if getattr(args, "abaqus_user", None):
        out.append(("Abaqus input-deck lines", args.abaqus_user))
    return out
