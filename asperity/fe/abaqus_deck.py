"""The input-deck lines that go with the generated Abaqus routines (``asperity law
--abaqus-user FILE.inp``), and the header comment of each routine (the same lines, the
state variables, what the routine assumes).

Keywords (Abaqus Keywords Reference): ``*FRICTION, USER`` on a contact-pair interaction
selects FRIC (Standard) or VFRIC (Explicit); ``*FRICTION, USER=FRICTION`` selects
VFRICTION (Explicit general contact), whose interaction is assigned with ``*CONTACT
PROPERTY ASSIGNMENT`` and needs ``*CONTACT FORMULATION, TYPE=PURE MASTER-SLAVE`` (with
balanced weighting each pair is seen from both sides, and the side of the texture has no
single meaning). The first surface of a ``*CONTACT PAIR`` data line is the secondary
(slave) surface.
"""
from __future__ import annotations

#: Abaqus routine -> (solver, how the deck selects it)
SOLVERS = {"fric": "Abaqus/Standard, contact pairs",
           "vfric": "Abaqus/Explicit, contact pairs",
           "vfriction": "Abaqus/Explicit, general contact"}
#: the elastic slip stiffness written in the FRIC data line: a placeholder to replace
K_PLACEHOLDER = "1.0E+10"

FRIC_STATE = (("STATEV(1)", "accumulated frictional slip (path length)"),
              ("STATEV(2)", ("increments at which the pressure lay outside the law "
                            "family's pressures (the law clamped)")),
              ("STATEV(3)", "1 if the point slipped in the increment, 0 if it stuck"))
EXPLICIT_STATE = (("1", ("increments at which the pressure lay outside the law family's "
                        "pressures (the law clamped)")),
                  ("2", "1 if the law held the node at the last increment, 0 if it slid"))


EXPLICIT_PROPS = ("** props(1:3) the law's +x axis in global coordinates",
                  "**   (projected on the tangent plane)",
                  "** props(4) +1 texture on the main (master) surface, -1 on",
                  "**   the secondary (slave) surface")


def _g(x: float) -> str:
    """A deck number: 6 significant digits, a decimal point when it has no exponent."""
    s = f"{x:.6G}"
    return s if "." in s or "E" in s else s + ".0"


def deck_lines(routine: str, name: str = "TEXTURED", props=None) -> list[str]:
    """The deck snippet for ``routine`` ("fric", "vfric" or "vfriction"): keyword lines,
    ``**`` comment lines saying what to replace.  ``props``: {"stiffness": PROPS(1) or
    None (a placeholder), "angle_deg": PROPS(2), "side": +1/-1, "axis": (x, y, z)}."""
    pr = {"stiffness": None, "angle_deg": 0.0, "side": 1, "axis": (1.0, 0.0, 0.0),
          **(props or {})}
    side = _g(float(pr["side"]))
    if routine == "fric":
        k = K_PLACEHOLDER if pr["stiffness"] is None else _g(pr["stiffness"])
        return [f"** {SOLVERS['fric']}: user subroutine FRIC",
                f"*SURFACE INTERACTION, NAME={name}",
                "*FRICTION, USER, DEPVAR=3, PROPERTIES=3",
                f"{k}, {_g(pr['angle_deg'])}, {side}",
                *(["** PROPS(1) elastic slip stiffness, stress per unit slip:",
                   "**   replace the placeholder (e.g. the friction stress over",
                   "**   the slip accepted before sliding; --slip-stiffness)"]
                  if pr["stiffness"] is None else
                  ["** PROPS(1) elastic slip stiffness, stress per unit slip"]),
                "** PROPS(2) angle (deg) from local slip direction 1 to the",
                "**   law's +x axis",
                "** PROPS(3) +1 texture on the main (master) surface, -1 on",
                "**   the secondary (slave) surface",
                f"*CONTACT PAIR, INTERACTION={name}",
                "SECONDARY_SURFACE, MAIN_SURFACE",
                "** in every step (asymmetric and star laws have an",
                "** unsymmetric tangent):",
                "** *STEP, UNSYMM=YES"]
    if routine == "vfric":
        return [f"** {SOLVERS['vfric']}: user subroutine VFRIC",
                f"*SURFACE INTERACTION, NAME={name}",
                "*FRICTION, USER, DEPVAR=2, PROPERTIES=4",
                ", ".join(_g(float(v)) for v in pr["axis"]) + f", {side}",
                *EXPLICIT_PROPS,
                f"*CONTACT PAIR, INTERACTION={name}",
                "SECONDARY_SURFACE, MAIN_SURFACE"]
    if routine == "vfriction":
        return [f"** {SOLVERS['vfriction']}: user subroutine VFRICTION",
                f"*SURFACE INTERACTION, NAME={name}",
                "*FRICTION, USER=FRICTION, DEPVAR=2, PROPERTIES=4",
                ", ".join(_g(float(v)) for v in pr["axis"]) + f", {side}",
                *EXPLICIT_PROPS,
                "*CONTACT",
                "*CONTACT INCLUSIONS, ALL EXTERIOR",
                "*CONTACT PROPERTY ASSIGNMENT",
                f"SECONDARY_SURFACE, MAIN_SURFACE, {name}",
                "** one role per surface (else the side means nothing):",
                "*CONTACT FORMULATION, TYPE=PURE MASTER-SLAVE",
                "MAIN_SURFACE, SECONDARY_SURFACE, MASTER"]
    raise ValueError(f"routine must be fric, vfric or vfriction, got {routine!r}")


def deck_text(routines, name: str = "TEXTURED", what: str = "", props=None) -> str:
    """The ``--abaqus-user`` file: the snippet of each routine in ``routines``."""
    lines = [("** Abaqus input-deck lines for the friction user routines written by "
             "asperity"), *(f"** {x}" for x in what.splitlines() if x)]
    for r in routines:
        lines += ["**", *deck_lines(r, name, props)]
    return "\n".join(lines) + "\n"


def assumptions(routine: str) -> list[str]:
    """What the routine assumes, for its header comment."""
    common = [("The law is a table of the force per unit normal load p(psi) of the "
              "gauge file (piecewise linear in psi), within the stated error of "
              "`asperity law --psi`. A law family is blended linearly in ln(pressure) "
              "between its levels and clamped outside them (counted in a state "
              "variable).")]
    if routine == "fric":
        return common + [
            ("TAU and STATEV come in as the start-of-increment values at every "
            "iteration and DGAM is the slip of the whole increment: the routine is a "
            "pure function of them (iterations leave no trace). It returns LM = 0 "
            "(slip or elastic stick; LM = 2 on entry returns at once; PROPS(1) <= 0 "
            "asks for Lagrange stick, LM = 1)."),
            ("Elastic predictor with PROPS(1); stick while the trial stress lies in "
            "PRESS C; otherwise the stress on PRESS x the boundary of C whose sliding "
            "direction (the law's own rule) is the plastic slip. DDTDDG and DDTDDP are "
            "the exact derivatives (unsymmetric: use *STEP, UNSYMM=YES)."),
            ("Local slip direction 1 is Abaqus's (the projection of the global x axis "
            "on the surface, unless an orientation is given); no state is a vector, "
            "so DROT is not used. NFDIR = 1 (2D) uses the law along +-x of the "
            "turned law.")]
    return common + [
        ("No iterations in Abaqus/Explicit: one call per increment, the state is "
        "written directly. t1 = dirCosSl is the slip direction of the increment (the "
        "predicted slip for kinematic contact), n = dirCosN, t2 = n x t1."),
        ("The law holds the node when the stick force lies in fNormal C: then "
        "fTangential = (-fStickForce, 0); otherwise the law's force for sliding along "
        "t1, first component clipped to [-fStickForce, 0]. Pressure = fNormal / area "
        "of the node. Single or double precision (implicit typing)."),
        *([("VFRIC works on contact pairs only (not general contact); its state "
           "variables belong to the secondary surface's nodes (jConSlvid).")]
          if routine == "vfric" else
          [("VFRICTION: general contact with PURE MASTER-SLAVE; state(:, 1, k) of "
           "each contact point (node-to-face: nNodState = 1).")])]


def header_lines(routine: str, what: str, name: str = "TEXTURED", props=None) -> list[str]:
    """The header comment of a generated routine (lines without the leading ``C``)."""
    state = FRIC_STATE if routine == "fric" else EXPLICIT_STATE
    var = "STATEV" if routine == "fric" else ("statev(i, node)" if routine == "vfric"
                                               else "state(i, 1, point)")
    out = [f"{routine.upper()} ({SOLVERS[routine]}) written by asperity", *what.splitlines(),
           "", "Input deck:", *(f"  {x}" for x in deck_lines(routine, name, props)), "",
           f"State variables ({var}; each written only if DEPVAR provides it):",
           *(f"  {k}: {v}" for k, v in state), "", "Assumptions:"]
    for a in assumptions(routine):
        out += [f"- {a}"]
    return out
