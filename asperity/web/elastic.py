"""The elastic-contact fields of the Surface page: load shares from a contact solution.

With *load shares* set to *elastic contact*, the texture or height map is pressed onto an
elastic half-space (E* given, or the materials E1, nu1 and optionally E2, nu2 of the
counterface) at one nominal pressure, a list of them or a range spaced in log, and each
facet weighs the normal force it carries (:mod:`asperity.surface.contact_facets`, as
``asperity derive --elastic E* --pressure P ...``).  Every refusal is one line in the
page's words, about one field (:class:`.forms.FormError`).

:func:`elastic_params` reads the fields into the job's ``params["elastic"]``:
``{"E_star", "pressures", "boundary", "hardness", "materials"}`` (None: area weighting).
"""
from __future__ import annotations

import math

from ..errors import InputError, check_range
from .forms import Form, FormError

LOADS = ("area", "elastic")
BOUNDARIES = ("", "periodic", "free")
#: form field -> label on the page
LABELS = {"load": "load shares", "E_star": "E* (Pa)", "E1": "E1 (Pa)", "nu1": "nu1",
          "E2": "E2 (Pa)", "nu2": "nu2", "pressure": "pressure (Pa)",
          "p_min": "pressures from (Pa)", "p_max": "pressures to (Pa)",
          "p_count": "number of pressures", "boundary": "boundary",
          "hardness": "hardness (Pa)"}
MATERIALS = ("E1", "nu1", "E2", "nu2")


def _positive(form: Form, name: str, required: bool = True) -> float | None:
    """A number above 0 (the modulus range of the solver for a modulus)."""
    from ..contact.solver import E_RANGE
    x = form.number(name, None, label=LABELS[name], required=required)
    if x is None:
        return None
    low, high = (E_RANGE if name.startswith("E") else (0.0, None))
    try:
        return check_range(LABELS[name], x, low, high, low_open=not name.startswith("E"),
                           unit="Pa")
    except InputError as exc:
        raise FormError(str(exc), name) from None


def modulus(form: Form) -> tuple[float, dict | None]:
    """(E*, the materials it comes from or None)."""
    from ..contact.solver import E_RANGE, effective_modulus
    given = [m for m in MATERIALS if form.text(m)]
    if not given:
        return _positive(form, "E_star"), None
    if form.text("E_star"):
        raise FormError(f"give E* (Pa) or the materials (E1, nu1 and E2, nu2), not both: "
                        f"leave E* (Pa) blank to use {given[0]}", given[0])
    mat = {m: (_positive(form, m, False) if m.startswith("E")
               else form.optional(m, label=LABELS[m])) for m in MATERIALS}
    for m in ("E1", "nu1"):
        if mat[m] is None:
            raise FormError(f"{LABELS[m]} is required with the materials (or give E* (Pa))",
                            m)
    if (mat["E2"] is None) != (mat["nu2"] is None):
        m = "nu2" if mat["nu2"] is None else "E2"
        raise FormError(f"{LABELS[m]} is required with {LABELS['E2' if m == 'nu2' else 'nu2']}"
                        " (leave both blank for a rigid counterface)", m)
    for m in ("nu1", "nu2"):
        if mat[m] is not None and not -1.0 < mat[m] <= 0.5:
            raise FormError(f"{m} must be in (-1, 0.5], got {mat[m]:g}", m)
    E = effective_modulus(mat["E1"], mat["nu1"], mat["E2"], mat["nu2"])
    if not E_RANGE[0] <= E <= E_RANGE[1]:
        raise FormError(f"the materials give E* = {E:.4g} Pa, outside [{E_RANGE[0]:g}, "
                        f"{E_RANGE[1]:g}]: check E1 (Pa)", "E1")
    return E, mat


def pressures(form: Form) -> list[float]:
    """The pressures: the range (from, to, number: spaced in log) when it is given, else
    the list of the pressure field (one number or several)."""
    from ..surface.contact_facets import MAX_PRESSURES
    rng = [n for n in ("p_min", "p_max", "p_count") if form.text(n)]
    if rng:
        for n in ("p_min", "p_max", "p_count"):
            if not form.text(n):
                raise FormError(f"{LABELS[n]} is required with {LABELS[rng[0]]} (a range "
                                f"needs from, to and the number of pressures)", rng[0])
        lo, hi = _positive(form, "p_min"), _positive(form, "p_max")
        n = form.whole("p_count", low=2, high=MAX_PRESSURES, label=LABELS["p_count"])
        if hi <= lo:
            raise FormError(f"pressures to (Pa) must be above pressures from (Pa) "
                            f"({lo:g} Pa), got {hi:g} Pa", "p_max")
        r = math.log(hi / lo)
        return [lo * math.exp(r * k / (n - 1)) for k in range(n)]
    parts = form.text("pressure").replace(",", " ").split()
    if not parts:
        raise FormError("pressure (Pa) is required (one number, several, or a range below)",
                        "pressure")
    if len(parts) > MAX_PRESSURES:
        raise FormError(f"pressure (Pa) takes at most {MAX_PRESSURES} numbers, got "
                        f"{len(parts)}", "pressure")
    return [_positive(Form({"pressure": p}), "pressure") for p in parts]


def elastic_params(form: Form, texture: bool, method: str = "closed-form",
                   load_fields=()) -> dict | None:
    """The elastic contact of the form, or None (area weighting).  ``texture``: a wedge or
    a texture file (periodic by construction); ``load_fields``: the form's other load
    models that exclude it, (field, label) when given."""
    from ..contact.solver import PRESSURE_OVER_E
    from ..surface.contact_facets import ElasticContact
    if form.choice("load", LOADS, "area", label=LABELS["load"]) == "area":
        return None
    if method != "closed-form":
        raise FormError("the elastic contact weights the closed form: choose the closed-form "
                        "method (the spring simulation has its own load model)", "method")
    for name, label in load_fields:
        if form.text(name):
            raise FormError(f"the elastic contact sets the load shares: leave {label} blank",
                            name)
    E, mat = modulus(form)
    ps = pressures(form)
    boundary = form.choice("boundary", BOUNDARIES, "", label="boundary") or None
    if texture and boundary == "free":
        raise FormError("boundary of a wedge texture must be periodic (the texture repeats "
                        "by construction)", "boundary")
    lo, hi = PRESSURE_OVER_E
    for p in ps:
        if not lo <= p / E <= hi:
            where = "p_min" if form.text("p_min") else "pressure"
            raise FormError(f"pressure over E*, p/E* = {p / E:.3g}, must be in [{lo:g}, "
                            f"{hi:g}]: check pressure (Pa) and E* (Pa)", where)
    H = _positive(form, "hardness", required=False)
    if H is not None and H <= max(ps):
        raise FormError(f"hardness (Pa) must be above the pressure ({max(ps):g} Pa), got "
                        f"{H:g} Pa", "hardness")
    ElasticContact(E, tuple(ps), boundary=boundary, hardness=H)    # the library's checks
    return {"E_star": E, "pressures": ps, "boundary": boundary, "hardness": H,
            "materials": mat}


def contact_of(params: dict):
    """The ElasticContact of a job's ``params["elastic"]`` (several pressures: a family)."""
    from ..surface.contact_facets import ElasticContact
    e = params["elastic"]
    ps = e["pressures"]
    return ElasticContact(e["E_star"], ps[0] if len(ps) == 1 else tuple(ps),
                          boundary=e.get("boundary"), hardness=e.get("hardness"),
                          **({"max_iterations": e["max_iterations"]}
                             if e.get("max_iterations") else {}))


def describe(e: dict) -> str:
    """The settings line of an elastic contact: ``E* 115 GPa, 3 pressures 1 to 10 MPa``."""
    from .units import choose, show
    ps = e["pressures"]
    up = choose(ps, "Pa", smallest=True)
    out = f"elastic contact E* {show(e['E_star'], choose(e['E_star'], 'Pa'))}, "
    out += f"p {show(ps[0], up)}" if len(ps) == 1 else \
        f"{len(ps)} pressures {show(ps[0], up)} to {show(ps[-1], up)}"
    if e.get("boundary"):
        out += f", {e['boundary']} boundary"
    if e.get("hardness"):
        out += f", hardness {show(e['hardness'], choose(e['hardness'], 'Pa'))}"
    return out


#: the value of the Law page's choice "the law family" (``JOB:family``)
FAMILY = "family"


def pressure_choices(jobs: list[dict]) -> list[tuple[str, str, str]]:
    """The Law page's choice of pressure: (value ``JOB:k``, words, job) for every pressure
    of the finished Surface results with an elastic contact."""
    from .units import choose, show
    out = []
    for j in jobs:
        e = (j.get("params") or {}).get("elastic")
        if not isinstance(e, dict) or not isinstance(e.get("pressures"), list):
            continue
        try:
            ps = [float(p) for p in e["pressures"]]
        except (TypeError, ValueError):
            continue
        unit = choose(ps, "Pa", smallest=True)
        if len(ps) > 1:
            out.append((f"{j['id']}:{FAMILY}", f"the law family: one law at each of its "
                        f"{len(ps)} pressures, {show(ps[0], unit)} to {show(ps[-1], unit)}",
                        j["id"]))
        out += [(f"{j['id']}:{k}", f"p = {show(p, choose(p, 'Pa'))} alone" if len(ps) > 1
                 else f"its only pressure, p = {show(p, choose(p, 'Pa'))}", j["id"])
                for k, p in enumerate(ps)]
    return out


def chosen_pressure(form: Form, rec: dict) -> dict:
    """The Law job's ``elastic`` (the one pressure chosen of result ``rec``, or all of
    them for its law family) and ``family`` (how many pressures the result has, the index
    chosen: None for the family)."""
    e = rec["params"]["elastic"]
    ps = e["pressures"]
    t = form.text("pressure")
    if len(ps) > 1 and t == f"{rec['id']}:{FAMILY}":
        return {"elastic": e, "family": {"count": len(ps), "index": None}}
    if len(ps) == 1 and t in ("", f"{rec['id']}:0"):
        k = 0
    else:
        job, _, idx = t.partition(":")
        if job != rec["id"] or not idx.isdigit() or int(idx) >= len(ps):
            raise FormError(f"at the pressure: pick one of the {len(ps)} pressures of result "
                            f"{rec['id']} from the list", "pressure")
        k = int(idx)
    return {"elastic": {**e, "pressures": [ps[k]]}, "family": {"count": len(ps), "index": k}}
