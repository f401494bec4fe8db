"""The risk analysis of an assembly as a library API (``asperity risk`` and the report
call it): friction along the slip axis -> quasi-static ratchet analysis -> verdict, and
the Moreau cross-check.  The risk map over two wedge parameters is a grid study:
:func:`asperity.study.maps.risk_map`.

The results are the JSON objects that ``asperity risk --json`` prints (keys documented in
the file formats' outputs); :mod:`asperity.microslip.risk_text` turns them into the terminal text.
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
                      contact: str | None = None, slip_axis_deg: float | None = None,
                      textured: str | None = None) -> Friction:
    """The friction coefficients mu+ and mu- along an assembly's slip axis.

    Parameters
    ----------
    asm : Assembly
        An assembly read by :func:`asperity.load_assembly`.
    texture : texture, surface or None, optional
        A wedge texture or a surface (:func:`asperity.load_texture`,
        :func:`asperity.load_surface`) whose friction replaces the source of the file's
        ``[friction]`` table (whose ``slip_axis_deg`` and ``textured`` still apply unless
        given here).  None (default): the table's source (explicit coefficients, a gauge
        or a texture file).
    texture_name : str, optional
        The texture's name in the result's ``detail`` (default: its kind).
    contact : str or None, optional
        Contact regime of the texture: "all-faces" or "windward".  It applies to
        ``texture``, or else to the texture file of the table (in place of the table's
        ``contact``); a table with a gauge or explicit coefficients refuses it.  None
        (default): the table's ``contact`` for its texture file, "all-faces" for
        ``texture``.
    slip_axis_deg : float or None, optional
        The assembly's +x in the texture's (or gauge's) frame, deg, in [-360, 360]; None:
        the table's, else the principal direction t_a.  Not with explicit coefficients.
    textured : str or None, optional
        Which face carries the texture: "support" or "part" (mu+ and mu- swap); None: the
        table's, else "support".

    Returns
    -------
    Friction
        ``mu_plus`` (resists sliding of the assembly towards +x over the support),
        ``mu_minus`` (towards -x), ``source`` ("explicit", "gauge" or "texture") and
        ``detail``; ``to_dict()`` is the ``friction`` object of ``asperity risk --json``.

    Raises
    ------
    InputError
        A value outside its range; a slip axis or textured face with explicit
        coefficients; an unreadable gauge or texture file.

    See Also
    --------
    asperity.load_assembly, asperity.assess_assembly, asperity.compute_reservoir

    Notes
    -----
    With a texture on the support, mu+ = T(psi) and mu- = T(psi + 180 deg), psi the slip
    axis and T = p . s the tangential friction of the texture; with the texture on the
    part the two swap (the support slides the other way over it).

    Examples
    --------
    The bushing's file names the SPEC.md wedge on its housing (mu_a+ = 0.185697,
    mu_a- = 0.193238); on the bushing itself the two swap:

    >>> asm = asperity.load_assembly("surfaces/bushing-strip.toml")
    >>> f = asperity.assembly_friction(asm)
    >>> print(f.source, f"{f.mu_plus:.6f} {f.mu_minus:.6f}")
    texture 0.185697 0.193238
    >>> f = asperity.assembly_friction(asm, textured="part")
    >>> print(f"{f.mu_plus:.6f} {f.mu_minus:.6f}")
    0.193238 0.185697
    """
    check_instance("asm", asm, Assembly, "parsed assembly (load_assembly)")
    check_risk_texture(texture)
    check_text("texture_name", texture_name, 4096)
    if contact is not None:
        check_choice("contact", contact, CONTACTS)
    slip_axis_deg, textured = check_axis_and_face(slip_axis_deg, textured)
    fr = asm.friction_table
    axis = slip_axis_deg if slip_axis_deg is not None else fr.get("slip_axis_deg")
    face = textured or fr.get("textured", "support")
    if texture is not None:
        f = friction_from_texture(texture, contact or "all-faces", axis, face, texture_name)
        if fr:
            f.detail["note"] = ("texture from the command line instead of the file's friction "
                                "source; its slip_axis_deg and textured still apply")
        return f
    if contact is not None:
        if "texture" not in fr:
            raise InputError("a contact regime (--contact) applies to a texture; the assembly's "
                             "friction is " + ("a gauge file" if "gauge" in fr else
                                               "given as mu_plus/mu_minus"))
        asm = replace(asm, friction_table=dict(fr, contact=contact))
        fr = asm.friction_table
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
    """The ratchet verdict of an assembly with given friction: the JSON object of
    ``asperity risk --json``.

    Parameters
    ----------
    asm : Assembly
        An assembly read by :func:`asperity.load_assembly`.
    friction : Friction
        Its friction along the slip axis, from :func:`asperity.assembly_friction`.
    cycles : float or None, optional
        Life to assess, in [1, 1e15]; None: the file's ``loading.cycles``, else 1e6.
    tolerance : float or None, optional
        Displacement the assembly may drift, m, in [1e-9, 1e3]; None: the file's (or
        none).
    max_marched : int, optional
        Cycles marched at most while looking for the stabilised cycle, in [2, 1e6]
        (default 200).
    dynamic_steps : int or None, optional
        Also solve the assembly by Moreau time-stepping (3 cycles) with this many steps
        per load segment, in [100, 1e7], and report it under ``dynamic``; None (default):
        not.

    Returns
    -------
    dict
        ``verdict`` ("shakedown", "alternating-slip", "ratchet" or "slides-off"),
        ``dT_c_K`` and ``dT_c_closed_form_K`` (the elastic limit, K), ``margin``,
        ``drift_per_cycle_m`` (m, positive towards +x), ``drift_after_cycles_m``,
        ``cycles_to_tolerance``, the ``assembly``, ``loading`` and ``friction`` it was
        given and the ``sign_convention``; keys in the file formats' outputs.  The private
        key ``_chain`` holds the slider chain (for plots): drop the keys starting with
        ``_`` before writing JSON.

    Raises
    ------
    InputError
        A value outside its range.

    See Also
    --------
    asperity.load_assembly, asperity.assembly_friction, asperity.assess,
    asperity.risk_map

    Notes
    -----
    The quasi-static ratchet analysis of SPEC.md 5 (:func:`asperity.assess` on the
    assembly's slider chain).  With mu+ > mu- the assembly creeps towards -x: the two-node
    bar iff the temperature range exceeds 2 dT_c; for a strip that is necessary, not
    sufficient (its ends may slip back and forth while its middle sticks).

    Examples
    --------
    The two-node bar of SPEC.md 5 cycled over 3 dT_c drifts -5.0e-5 m per cycle:

    >>> asm = asperity.load_assembly("surfaces/two-node-spec.toml")
    >>> out = asperity.assess_assembly(asm, asperity.assembly_friction(asm), cycles=1000)
    >>> out["verdict"], round(out["dT_c_K"], 2), round(out["margin"], 3)
    ('ratchet', 41.67, 1.5)
    >>> print(f"{out['drift_per_cycle_m']:.4e} m per cycle, towards {out['drift_direction']}")
    -5.0000e-05 m per cycle, towards -x
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
