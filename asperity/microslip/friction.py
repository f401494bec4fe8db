"""mu+ and mu- along an assembly's slip axis, from explicit coefficients, a gauge file or
a texture (wedge or surface).

Sign convention: ``mu_plus`` resists sliding of the assembly towards +x over the support,
``mu_minus`` towards -x.  With a texture on the support, ``mu_plus`` = T(psi) and
``mu_minus`` = T(psi + 180 deg) with psi = slip_axis_deg, T = p . s the tangential friction
of the texture; with the texture on the part the two swap.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..friction.sources import load_texture_or_surface
from ..paths import named_path
from .assembly import Assembly, AssemblyFileError


@dataclass(frozen=True)
class Friction:
    """mu+ and mu- along the slip axis and where they come from."""

    mu_plus: float
    mu_minus: float
    source: str                       # "explicit", "gauge", "texture"
    detail: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        def num(x):
            return float(x) if math.isfinite(x) else None
        return {"source": self.source, "mu_plus": num(self.mu_plus),
                "mu_minus": num(self.mu_minus),
                "self_locking": [d for d, x in (("+x", self.mu_plus), ("-x", self.mu_minus))
                                 if not math.isfinite(x)], **self.detail}


def friction_from_texture(texture, contact: str = "all-faces", slip_axis_deg=None,
                          textured: str = "support", source_name: str = "") -> Friction:
    """mu+ and mu- of ``texture`` (a wedge texture or a surface) along the slip axis.

    The axis: ``slip_axis_deg`` in the texture's frame (wedges: from t_a towards t_b;
    surfaces: from the file's +x towards +y), by default the principal direction t_a (wedges:
    0; surfaces: the principal axis found by ``derive``, in [0, 180) deg).
    mu+ = T(psi), mu- = T(psi + 180 deg) for a textured support (swapped for a textured
    part), T = p . s the tangential component of the friction force; the lateral component
    L = p . s_perp is carried by the assembly's guidance and reported only."""
    from ..friction.faces import compute_faces_reservoir
    surface = getattr(texture, "kind", "") == "surface"
    if slip_axis_deg is None:
        if surface:
            from ..friction.derive import derive
            psi_deg = derive(texture, contact).principal_direction_deg
        else:
            psi_deg = 0.0
        axis = "principal direction t_a"
    else:
        psi_deg = float(slip_axis_deg)
        axis = "given"
    psi = math.radians(psi_deg) + np.array([0.0, math.pi])
    res = compute_faces_reservoir(texture.faces(), psi, contact)
    T = np.where(res.locked, np.inf, res.tangential)
    L = np.where(res.locked, np.nan, res.lateral)
    plus, minus = (1, 0) if textured == "part" else (0, 1)
    _check_some_friction(T[plus], T[minus], source_name or "the texture")
    detail = {"slip_axis_deg": psi_deg, "slip_axis": axis, "textured": textured,
              "contact": contact, "texture": source_name or texture.to_dict().get("kind", ""),
              "lateral_plus": _num(L[plus]), "lateral_minus": _num(L[minus])}
    if getattr(texture, "elastic", None) is not None:   # load shares from an elastic contact
        detail["elastic_contact"] = dict(texture.elastic)
    return Friction(float(T[plus]), float(T[minus]), "texture", detail)


def _check_some_friction(mu_plus: float, mu_minus: float, name: str) -> None:
    """A texture without friction along the slip axis (local friction 0: its forces cancel
    to rounding, 1e-18 either side of 0) is refused as such, not as a coefficient out of
    range."""
    from ..errors import InputError
    from .limits import MU
    if min(mu_plus, mu_minus) < MU[0]:
        raise InputError(f"{name} gives no friction along the slip axis (mu+ = "
                         f"{max(mu_plus, 0.0):.3g}, mu- = {max(mu_minus, 0.0):.3g}, less than "
                         f"{MU[0]:g}): a part on it is held by nothing; give the faces a local "
                         f"friction mu above 0")


def friction_from_gauge(law, slip_axis_deg=None, textured: str = "support",
                        source_name: str = "") -> Friction:
    """mu+ and mu- of a fitted law (:class:`~asperity.laws.fitting.GaugeLaw`) along the slip axis
    (default: the law's principal direction t_a), as :func:`friction_from_texture`; a law
    family is refused (take its law at a pressure first: :func:`law_at_assembly`)."""
    from ..laws.family import GaugeFamily
    if isinstance(law, GaugeFamily):
        from ..errors import InputError
        raise InputError(f"{source_name or 'the gauge'} holds a law family over the pressures "
                         f"{law.pressures[0]:g} to {law.pressures[-1]:g} Pa: take its law at "
                         "the contact pressure first (GaugeFamily.at)")
    psi_deg = law.principal_direction_deg if slip_axis_deg is None else float(slip_axis_deg)
    psi = math.radians(psi_deg) + np.array([0.0, math.pi])
    f = law.force(psi)
    s = np.column_stack([np.cos(psi), np.sin(psi)])
    T = np.sum(f.p * s, axis=1)
    L = f.p[:, 1] * s[:, 0] - f.p[:, 0] * s[:, 1]
    plus, minus = (1, 0) if textured == "part" else (0, 1)
    return Friction(float(T[plus]), float(T[minus]), "gauge",
                    {"slip_axis_deg": psi_deg, "slip_axis": "principal direction t_a"
                     if slip_axis_deg is None else "given", "textured": textured,
                     "gauge": source_name, "lateral_plus": float(L[plus]),
                     "lateral_minus": float(L[minus])})


def resolve_friction(asm: Assembly) -> Friction:
    """The friction of an assembly file's [friction] table (file names relative to it,
    ``~`` expanded: :func:`asperity.paths.named_path`, as a study that names the assembly
    finds them)."""
    fr = asm.friction_table
    if "mu_plus" in fr:
        return Friction(float(fr["mu_plus"]), float(fr["mu_minus"]), "explicit")
    axis = fr.get("slip_axis_deg")
    textured = fr.get("textured", "support")
    if "gauge" in fr:
        from ..laws.gauge_file import read_gauge
        path = named_path(fr["gauge"], asm.folder)
        gl, block = law_at_assembly(read_gauge(path), asm, str(path))
        f = friction_from_gauge(gl, axis, textured, str(path))
        if block is not None:
            f.detail["contact_pressure"] = block
        return f
    if "texture" in fr:
        path = named_path(fr["texture"], asm.folder)
        return friction_from_texture(load_texture_or_surface(path), fr.get("contact", "all-faces"),
                                     axis, textured, str(path))
    raise AssemblyFileError("no friction: give a texture on the command line, or mu_plus and "
                            "mu_minus, a gauge or a texture in the assembly's [friction] table")


def law_at_assembly(gauge, asm: Assembly, name: str):
    """(GaugeLaw, the JSON block ``contact_pressure`` or None) of a gauge file's law or law
    family at the assembly's contact pressure (:meth:`Assembly.contact_pressure`): a family
    is taken at it (interpolated between its members, or refused outside their range); a
    single law derived from an elastic contact at another pressure is used as it is, with
    a note."""
    from ..errors import InputError
    from ..laws.family import GaugeFamily, law_at
    p, where = asm.contact_pressure()
    if isinstance(gauge, GaugeFamily):
        if p is None:
            raise InputError(f"{name} holds a law family (pressures {gauge.pressures[0]:g} to "
                             f"{gauge.pressures[-1]:g} Pa) and the two-node assembly gives no "
                             "contact pressure: add assembly.contact_area (m^2, the nominal "
                             "contact area of one node) to the assembly file")
        gl, how = law_at(gauge, p, where, name)
        return gl, {"from": where, **how}
    c = gauge.source.get("elastic_contact")
    if p is not None and isinstance(c, dict) and isinstance(c.get("pressure_Pa"), float) \
            and not math.isclose(c["pressure_Pa"], p, rel_tol=1e-6):
        return gauge, {"pressure_Pa": p, "from": where, "law_pressure_Pa": c["pressure_Pa"],
                       "note": f"the gauge's law was derived at p = {c['pressure_Pa']:g} Pa, "
                               f"not at the assembly's {p:g} Pa ({where}): fit a law family "
                               "(several --pressure) to take the law at the assembly's"}
    return gauge, None


def _num(x) -> float | None:
    return float(x) if np.isfinite(x) else None
