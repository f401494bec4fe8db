"""Assembly files: the TOML description of an assembly for the microslip analysis.

Layout (every length in m, force in N, temperature change in K; the strip is per metre of
width, so its pressure is in Pa, its bed stiffness in Pa/m and its force in N/m)::

    name = "bushing-strip"              # optional
    description = "..."                 # optional

    [assembly]
    model = "strip"                     # "strip" or "two-node"
    # strip: h (thickness), E (modulus), p (contact pressure), l (length along the slip
    #        axis), k_t (tangential bed stiffness per unit area), alpha_T (expansion relative
    #        to the support, 1/K, signed: < 0 if the part expands less), n (nodes,
    #        default 201), nu (Poisson's ratio, optional: only the FE run uses it)
    # two-node: k (bar stiffness, N/m), l0 (length), alpha_T, k_t (contact stiffness of
    #        one node, N/m), N (normal force on each node), contact_area (optional:
    #        the nominal contact area of one node, m^2; its contact pressure N /
    #        contact_area picks the law of a law family)
    # (ranges: asperity.microslip.limits)

    [friction]                          # optional when a texture is given on the command line
    mu_plus = 0.2                       # explicit coefficients, or
    mu_minus = 0.1
    # gauge = "law.json"                # a gauge file written by `asperity fit`, or
    # texture = "wedge.toml"            # a texture or surface file (relative to this file)
    # slip_axis_deg = 0.0               # +x of the assembly in the texture/gauge frame
    #                                   # (default: the principal direction t_a)
    # textured = "support"              # which face carries the texture: support or part
    # contact = "all-faces"             # contact regime of the texture: all-faces, windward

    [loading]
    dT_min = 0.0                        # cycles dT_min -> dT_max -> dT_min, or
    dT_max = 80.0
    # history = [0.0, 80.0, 20.0, 80.0, 0.0]   # one cycle's breakpoints (closed)
    # force = 0.0                       # constant tangential force, or
    # force_min = 0.0, force_max = 50.0 # in phase with the temperature, or
    # force_history = [...]             # one value per history point
    # force_at = "uniform"              # uniform (by contact area), "start" (x = 0), "end"
    # substeps = 1                      # load increments per segment
    # cycles = 1e6                      # life to assess (the command line overrides)
    # tolerance = 1e-4                  # displacement tolerance, m (the command line overrides)

Sign convention: x is the slip axis of the assembly; a positive displacement is towards
+x; ``mu_plus`` resists sliding of the assembly towards +x over the support, ``mu_minus``
towards -x.  With a texture on the support, ``mu_plus`` = T(psi) and ``mu_minus`` =
T(psi + 180 deg) with psi = slip_axis_deg, T = p . s the tangential friction of the
texture; with the texture on the part the two swap (the support slides the other way over
it).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, check_choice, check_range, check_text
from ..io import read_toml
from .limits import (
    CONTACT_AREA,
    MU_FILE,
    STRIP,
    TWO_NODE,
    check_alpha_T,
    check_cycles,
    check_dT,
    check_force,
    check_mu,
    check_nodes,
    check_param,
    check_substeps,
    check_tolerance,
)

MODELS = ("strip", "two-node")
_TOP = {"name", "description", "assembly", "friction", "loading"}


_MODEL_KEYS = {"strip": {"h": "m", "E": "Pa", "p": "Pa", "l": "m", "k_t": "Pa/m",
                         "alpha_T": "1/K"},
               "two-node": {"k": "N/m", "l0": "m", "alpha_T": "1/K", "k_t": "N/m", "N": "N"}}


_FRICTION_KEYS = {"mu_plus", "mu_minus", "gauge", "texture", "slip_axis_deg", "textured",
                  "contact"}


_LOADING_KEYS = {"dT_min", "dT_max", "history", "force", "force_min", "force_max",
                 "force_history", "force_at", "substeps", "cycles", "tolerance"}


class AssemblyFileError(InputError):
    """An assembly file cannot be read or does not follow the format."""


@dataclass(frozen=True)
class Assembly:
    """A parsed assembly file: the model parameters, the friction table (unresolved: a
    gauge or texture is read by :func:`resolve_friction`), the loading."""

    name: str
    description: str
    model: str
    params: dict
    friction_table: dict
    loading: object                   # microslip.Loading
    force_at: str
    cycles: float | None
    tolerance: float | None
    folder: Path

    def chain(self, mu_plus: float, mu_minus: float):
        """The slider chain of this assembly with the given coefficients."""
        from dataclasses import replace

        from .chains import strip_chain, two_node_chain
        p = self.params
        if self.model == "strip":
            c = strip_chain(p["h"], p["E"], p["p"], p["l"], p["k_t"], p["alpha_T"], p["n"],
                            mu_plus, mu_minus)
        else:
            c = two_node_chain(p["k"], p["l0"], p["alpha_T"], p["k_t"], p["N"], mu_plus,
                               mu_minus)
        if self.force_at != "uniform":
            fw = np.zeros(c.n)
            fw[0 if self.force_at == "start" else -1] = 1.0
            c = replace(c, fw=fw)
        return c

    def dT_c_closed_form(self, mu_plus: float, mu_minus: float) -> float:
        """The closed-form elastic limit (SPEC.md 5) of this assembly, K."""
        from .closed_forms import strip_dT_c, two_node_dT_c
        p = self.params
        if self.model == "strip":
            return strip_dT_c(p["h"], p["E"], p["p"], p["l"], p["k_t"], mu_plus, mu_minus,
                              p["alpha_T"])
        return two_node_dT_c(p["k"], p["k_t"], p["N"], mu_plus, mu_minus, p["alpha_T"],
                             p["l0"])

    def contact_pressure(self) -> tuple[float | None, str]:
        """(nominal contact pressure in Pa, where it comes from): the strip's p; the
        two-node model's N / contact_area, None when the file gives no contact_area."""
        if self.model == "strip":
            return float(self.params["p"]), "assembly.p"
        area = self.params.get("contact_area")
        where = "assembly.N / assembly.contact_area"
        return (None, where) if area is None else (self.params["N"] / area, where)

    def to_dict(self) -> dict:
        return {"name": self.name, "model": self.model,
                **{k: v for k, v in self.params.items()}, "force_at": self.force_at}


def _err(where: str, exc: InputError) -> AssemblyFileError:
    msg = str(exc)
    return AssemblyFileError(msg if msg.startswith(f"{where}.") else f"{where}.{msg}")


def _table(data: dict, key: str, allowed: set, path) -> dict:
    t = data.get(key, {})
    if not isinstance(t, dict):
        raise AssemblyFileError(f"{path}: {key} must be a table [{key}], got "
                                f"{type(t).__name__} {_short(t)}")
    unknown = sorted(set(t) - allowed)
    if unknown:
        raise AssemblyFileError(f"{path}: unknown key {key}.{unknown[0]}; allowed: "
                                f"{', '.join(sorted(allowed))}")
    return t


def _short(x) -> str:
    text = repr(x)
    return text if len(text) <= 40 else text[:37] + "..."


def _field(where: str, check, *args):
    """check(*args) with a failure reported as ``where.message``."""
    try:
        return check(*args)
    except AssemblyFileError:
        raise
    except InputError as exc:
        raise _err(where, exc) from None


def load_assembly(path) -> Assembly:
    """Read an assembly TOML file: the model, its friction and its load cycle.

    Parameters
    ----------
    path : str or os.PathLike
        The assembly file (layout: the module's docstring, ``asperity.microslip.assembly``;
        lengths in m, forces in N, temperature changes in K, the strip per metre of width).
        The files it names (gauge, texture) are relative to its folder.

    Returns
    -------
    Assembly
        A frozen record: ``name``, ``description``, ``model`` ("strip" or "two-node"),
        ``params`` (the model's numbers, SI), ``friction_table`` (the ``[friction]`` table,
        unresolved: :func:`asperity.assembly_friction` reads its gauge or texture),
        ``loading`` (:class:`asperity.Loading`), ``force_at``, ``cycles`` and ``tolerance``
        (None when the file gives none) and ``folder``.  ``dT_c_closed_form(mu_plus,
        mu_minus)`` gives the elastic limit of SPEC.md 5, K.

    Raises
    ------
    InputError
        An ``AssemblyFileError`` (an InputError) naming the file and the field: every
        number is checked against its physical range (``asperity.microslip.limits``);
        ``alpha_T`` is signed (< 0: the part expands less than its support), never 0.

    See Also
    --------
    asperity.assembly_friction, asperity.assess_assembly, asperity.risk_map

    Examples
    --------
    The two-node bar of SPEC.md 5, whose elastic limit is
    dT_c = mu- N (1/k + 2/k_t) / (alpha_T l0) = 41.67 K:

    >>> asm = asperity.load_assembly("surfaces/two-node-spec.toml")
    >>> asm.name, asm.model, asm.params["k"], asm.friction_table
    ('two-node-spec', 'two-node', 1000000.0, {'mu_plus': 0.2, 'mu_minus': 0.1})
    >>> print(f"{asm.dT_c_closed_form(0.2, 0.1):.2f}")                  # K
    41.67
    """
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        raise AssemblyFileError(f"an assembly file must be a path, got {_short(path)}")
    p = Path(path)
    return assembly_from_dict(read_toml(p, "assembly file", _TOP, AssemblyFileError), p)


def assembly_from_dict(data: dict, path) -> Assembly:
    """An assembly from the tables of an assembly file (as :func:`load_assembly` reads
    them); ``path`` names it in messages, and its folder resolves the files it names."""
    p = Path(path)
    if not isinstance(data, dict):
        raise AssemblyFileError(f"{p}: an assembly must be a table, got {_short(data)}")
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise AssemblyFileError(f"{p}: unknown key {unknown[0]!r}; allowed top-level keys: "
                                f"{', '.join(sorted(_TOP))}")
    if "assembly" not in data:
        raise AssemblyFileError(f"{p}: missing table [assembly]")
    a = data["assembly"]
    if not isinstance(a, dict):
        raise AssemblyFileError(f"{p}: assembly must be a table [assembly]")
    model = a.get("model")
    if not isinstance(model, str) or model not in MODELS:
        raise AssemblyFileError(f"{p}: assembly.model must be one of {', '.join(MODELS)}, "
                                f"got {_short(model)}")
    keys = _MODEL_KEYS[model]
    allowed = set(keys) | {"model"} | ({"n", "nu"} if model == "strip" else {"contact_area"})
    a = _table(data, "assembly", allowed, p)
    missing = [k for k in keys if k not in a]
    if missing:
        raise AssemblyFileError(f"{p}: missing key assembly.{missing[0]} (model {model!r} "
                                f"needs {', '.join(keys)})")
    ranges = STRIP if model == "strip" else TWO_NODE
    try:
        meta = {k: _field("", check_text, k, data.get(k, d), 4096)
                for k, d in (("name", p.stem), ("description", ""))}
        params = {k: (_field("assembly", check_alpha_T, k, a[k]) if k == "alpha_T" else
                      _field("assembly", check_param, k, a[k], ranges[k])) for k in keys}
        if model == "strip":
            params["n"] = _field("assembly", check_nodes, "n", a.get("n", 201))
            if "nu" in a:                  # Poisson's ratio: the FE run's (asperity.fe)
                params["nu"] = _field("assembly", _check_nu, "nu", a["nu"])
        elif "contact_area" in a:
            params["contact_area"] = _field("assembly", check_param, "contact_area",
                                            a["contact_area"], CONTACT_AREA)
        fr = _table(data, "friction", _FRICTION_KEYS, p)
        lo = _table(data, "loading", _LOADING_KEYS, p)
        loading, force_at, cycles, tolerance = _loading(lo)
        fr = _check_friction_table(fr)
    except AssemblyFileError as exc:
        msg = str(exc).lstrip(".")
        raise AssemblyFileError(f"{p}: {msg}") from None
    return Assembly(meta["name"], meta["description"], model, params, fr, loading, force_at,
                    cycles, tolerance, p.parent)


def with_loading(asm: Assembly, table: dict, path) -> Assembly:
    """``asm`` with its ``[loading]`` table replaced by ``table`` (checked exactly as
    :func:`assembly_from_dict` checks it): the same Assembly that parsing the whole file
    with that table gives, for studies that vary the loading only."""
    from dataclasses import replace
    p = Path(path)
    try:
        lo = _table({"loading": table}, "loading", _LOADING_KEYS, p)
        loading, force_at, cycles, tolerance = _loading(lo)
    except AssemblyFileError as exc:
        msg = str(exc).lstrip(".")
        raise AssemblyFileError(f"{p}: {msg}") from None
    return replace(asm, loading=loading, force_at=force_at, cycles=cycles, tolerance=tolerance)


def _check_nu(name: str, value) -> float:
    return check_range(name, value, 0.0, 0.5, high_open=True)


def _loading(lo: dict):
    from .loading import Loading
    substeps = _field("loading", check_substeps, "substeps", lo.get("substeps", 1))
    has_range = "dT_min" in lo or "dT_max" in lo
    if has_range and "history" in lo:
        raise AssemblyFileError("loading: give dT_min/dT_max or history, not both")
    forces = [k for k in ("force", "force_min", "force_history") if k in lo]
    if len(forces) > 1:
        raise AssemblyFileError(f"loading: give one of force, force_min/force_max, "
                                f"force_history, not {forces[0]} and {forces[1]}")
    if "force_max" in lo and "force_min" not in lo:
        raise AssemblyFileError("loading.force_max needs loading.force_min")
    if "history" in lo:
        if not isinstance(lo["history"], list):
            raise AssemblyFileError(f"loading.history must be a list of numbers (K), got "
                                    f"{_short(lo['history'])}")
        dT = lo["history"]
    elif has_range:
        for k in ("dT_min", "dT_max"):
            if k not in lo:
                raise AssemblyFileError(f"loading.{k} missing (cycles need dT_min and dT_max)")
        lo_, hi_ = (_field("loading", check_dT, k, lo[k]) for k in ("dT_min", "dT_max"))
        if hi_ < lo_:
            raise AssemblyFileError(f"loading needs dT_min <= dT_max, got dT_min = {lo_:g} K, "
                                    f"dT_max = {hi_:g} K")
        dT = [lo_, hi_, lo_]
    else:
        raise AssemblyFileError("loading: missing dT_min/dT_max or history (K)")
    if "force_history" in lo:
        F = lo["force_history"]
        if not isinstance(F, list):
            raise AssemblyFileError(f"loading.force_history must be a list of numbers, got "
                                    f"{_short(F)}")
    elif "force_min" in lo:
        f0 = _field("loading", check_force, "force_min", lo["force_min"])
        f1 = _field("loading", check_force, "force_max", lo.get("force_max", f0))
        if len(dT) != 3:
            raise AssemblyFileError("loading.force_min/force_max follow dT_min/dT_max; "
                                    "with a history give force_history")
        F = [f0, f1, f0]
    else:
        F = _field("loading", check_force, "force", lo.get("force", 0.0))
    loading = _field("loading", Loading, dT, F, substeps)
    at = _field("loading", check_choice, "force_at", lo.get("force_at", "uniform"),
                ("uniform", "start", "end"))
    cycles = tol = None
    if "cycles" in lo:
        cycles = _field("loading", check_cycles, "cycles", lo["cycles"])
    if "tolerance" in lo:
        tol = _field("loading", check_tolerance, "tolerance", lo["tolerance"])
    return loading, at, cycles, tol


def _check_friction_table(fr: dict) -> dict:
    fr = dict(fr)
    sources = [k for k in ("mu_plus", "gauge", "texture") if k in fr]
    if "mu_minus" in fr and "mu_plus" not in fr:
        sources.append("mu_minus")
    if len(sources) > 1:
        raise AssemblyFileError(f"friction: give mu_plus/mu_minus, gauge or texture, not "
                                f"{sources[0]} and {sources[1]}")
    if "mu_plus" in fr or "mu_minus" in fr:
        for k in ("mu_plus", "mu_minus"):
            if k not in fr:
                raise AssemblyFileError(f"friction.{k} missing (explicit friction needs "
                                        "mu_plus and mu_minus)")
            fr[k] = _field("friction", check_mu, k, fr[k], MU_FILE, False)
        extra = [k for k in ("slip_axis_deg", "textured", "contact") if k in fr]
        if extra:
            raise AssemblyFileError(f"friction.{extra[0]} applies to a gauge or texture, not "
                                    "to explicit mu_plus/mu_minus")
    if "slip_axis_deg" in fr:
        fr["slip_axis_deg"] = _field("friction", check_range, "slip_axis_deg",
                                     fr["slip_axis_deg"], -360.0, 360.0)
    for k, choices in (("textured", ("support", "part")), ("contact", ("all-faces", "windward"))):
        if k in fr:
            _field("friction", check_choice, k, fr[k], choices)
    for k in ("gauge", "texture"):
        if k in fr:
            if not isinstance(fr[k], str) or not fr[k]:
                raise AssemblyFileError(f"friction.{k} must be a file name (text), got "
                                        f"{_short(fr[k])}")
            _field("friction", check_text, k, fr[k], 4096)
    return fr
