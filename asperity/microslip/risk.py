"""The risk analysis of an assembly as a library API (``asperity risk`` and the report
call it): friction along the slip axis -> quasi-static ratchet analysis -> verdict, and
the Moreau cross-check.  The risk map over two wedge parameters is a grid study:
:func:`asperity.study.maps.risk_map`.

The results are the JSON objects that ``asperity risk --json`` prints (keys documented in
README); :mod:`asperity.microslip.risk_text` turns them into the terminal text.
"""
from __future__ import annotations

from dataclasses import replace

from ..errors import InputError, check_choice, check_instance, check_int, check_text
from .assembly import Assembly
from .friction import Friction, friction_from_texture, resolve_friction
from .limits import check_cycles, check_tolerance

#: wedge parameters a risk map may vary -> field of the wedge texture
MAP_PARAMS = {"alpha": "alpha_deg", "beta": "beta_deg", "mu_alpha": "mu_alpha",
              "mu_beta": "mu_beta"}
#: cycles of the Moreau cross-check
DYNAMIC_CYCLES = 3
CONTACTS = ("all-faces", "windward")
FACES = ("support", "part")


def check_risk_texture(texture):
    if texture is not None and not (callable(getattr(texture, "faces", None))
                                    and callable(getattr(texture, "to_dict", None))):
        raise InputError(f"texture must be a wedge texture or a surface (load_texture, "
                         f"load_surface), got {type(texture).__name__}")
    return texture


def check_axis_and_face(slip_axis_deg, textured):
    from ..errors import check_range
    if slip_axis_deg is not None:
        slip_axis_deg = check_range("slip_axis_deg", slip_axis_deg, -360.0, 360.0, unit="deg")
    if textured is not None:
        check_choice("textured", textured, FACES)
    return slip_axis_deg, textured


def assembly_friction(asm: Assembly, texture=None, *, texture_name: str = "",
                      contact: str = "all-faces", slip_axis_deg: float | None = None,
                      textured: str | None = None) -> Friction:
    """mu+ and mu- along the slip axis of ``asm``.

    With ``texture`` (a wedge texture or a surface) its friction replaces the source of the
    file's ``[friction]`` table, whose ``slip_axis_deg`` and ``textured`` still apply unless
    given here; without it the table's source is used (explicit coefficients, a gauge or a
    texture file).  ``slip_axis_deg`` and ``textured`` override the table's.
    """
    check_instance("asm", asm, Assembly, "parsed assembly (load_assembly)")
    check_risk_texture(texture)
    check_text("texture_name", texture_name, 4096)
    check_choice("contact", contact, CONTACTS)
    slip_axis_deg, textured = check_axis_and_face(slip_axis_deg, textured)
    fr = asm.friction_table
    axis = slip_axis_deg if slip_axis_deg is not None else fr.get("slip_axis_deg")
    face = textured or fr.get("textured", "support")
    if texture is not None:
        f = friction_from_texture(texture, contact, axis, face, texture_name)
        if fr:
            f.detail["note"] = ("texture from the command line instead of the file's friction "
                                "source; its slip_axis_deg and textured still apply")
        return f
    if slip_axis_deg is not None or textured is not None:
        if "mu_plus" in fr:
            raise InputError("a slip axis or textured face (--slip-axis, --textured) applies "
                             "to a texture or gauge, not to explicit mu_plus/mu_minus")
        fr = dict(fr)
        if slip_axis_deg is not None:
            fr["slip_axis_deg"] = slip_axis_deg
        if textured is not None:
            fr["textured"] = textured
        asm = replace(asm, friction_table=fr)
    return resolve_friction(asm)


def life_settings(asm: Assembly, cycles, tolerance) -> tuple[float, float | None]:
    check_instance("asm", asm, Assembly, "parsed assembly (load_assembly)")
    cycles = check_cycles("cycles", asm.cycles or 1e6 if cycles is None else cycles)
    if tolerance is not None:
        tolerance = check_tolerance("tolerance", tolerance)
    else:
        tolerance = asm.tolerance
    return cycles, tolerance


def assess_assembly(asm: Assembly, friction: Friction, *, cycles: float | None = None,
                    tolerance: float | None = None, max_marched: int = 200,
                    dynamic_steps: int | None = None) -> dict:
    """The verdict of ``asm`` with ``friction``: the JSON object of ``asperity risk --json``.

    cycles        : life to assess (default: the file's ``loading.cycles``, else 1e6)
    tolerance     : displacement the assembly may drift, m (default: the file's)
    max_marched   : cycles marched at most while looking for the stabilised cycle
    dynamic_steps : also solve the assembly by Moreau time-stepping with this many steps
                    per load segment and report it under ``dynamic``

    The private key ``_chain`` holds the slider chain (for plots); drop the keys starting
    with ``_`` before writing JSON.
    """
    from .. import __version__
    from .verdict import assess
    cycles, tolerance = life_settings(asm, cycles, tolerance)
    check_instance("friction", friction, Friction, "Friction (from assembly_friction)")
    max_marched = check_int("max_marched", max_marched, 2, 1_000_000)
    if dynamic_steps is not None:
        dynamic_steps = check_int("dynamic_steps", dynamic_steps, 100, 10_000_000)
    chain = asm.chain(friction.mu_plus, friction.mu_minus)
    out = {"asperity_version": __version__, "assembly": asm.to_dict(),
           "loading": loading_dict(asm), "friction": friction.to_dict()}
    out.update(assess(chain, asm.loading, cycles, tolerance,
                      dT_c_closed_form=asm.dT_c_closed_form(friction.mu_plus,
                                                            friction.mu_minus),
                      max_marched=max_marched))
    if dynamic_steps is not None and out["verdict"] != "slides-off":
        out["dynamic"] = dynamic_check(chain, asm.loading, dynamic_steps,
                                       out["drift_per_cycle_m"])
    out["_chain"] = chain
    return out


def dynamic_check(chain, loading, steps: int, drift_qs: float) -> dict:
    """Drift per cycle of the Moreau solution (3 cycles) against the quasi-static one."""
    from .dynamic import simulate_dynamic
    steps = check_int("dynamic_steps", steps, 100, 10_000_000)
    r = simulate_dynamic(chain, loading, DYNAMIC_CYCLES, steps_per_segment=steps)
    d = float(r.drift_per_cycle)
    scale = max(abs(drift_qs), 1e-12 * max(abs(x) for x in (d, drift_qs, 1.0)))
    return {"steps_per_segment": steps, "cycles": DYNAMIC_CYCLES, "drift_per_cycle_m": d,
            "difference_m": d - drift_qs, "relative_difference":
            abs(d - drift_qs) / scale if drift_qs != 0.0 else None, "solver": r.solver}


def loading_dict(asm: Assembly) -> dict:
    """The JSON description of an assembly's load cycle."""
    L = asm.loading
    return {"history_K": [float(x) for x in L.dT], "force_history": [float(x) for x in L.F],
            "force_unit": "N/m" if asm.model == "strip" else "N", "force_at": asm.force_at,
            "substeps": L.substeps}
