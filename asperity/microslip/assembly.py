"""Assembly files: the TOML description of an assembly for the microslip analysis.

Layout (every length in m, force in N, temperature change in K; the strip is per metre of
width, so its pressure is in Pa, its bed stiffness in Pa/m and its force in N/m)::

    name = "bushing-strip"              # optional
    description = "..."                 # optional

    [assembly]
    model = "strip"                     # "strip" or "two-node"
    # strip: h (thickness), E (modulus), p (contact pressure), l (length along the slip
    #        axis), k_t (tangential bed stiffness per unit area), alpha_T (expansion relative
    #        to the support, 1/K), n (nodes, default 201)
    # two-node: k (bar stiffness, N/m), l0 (length), alpha_T, k_t (contact stiffness of
    #        one node, N/m), N (normal force on each node)

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

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, check_int, check_range
from ..io import read_toml

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

    def to_dict(self) -> dict:
        return {"name": self.name, "model": self.model,
                **{k: v for k, v in self.params.items()}, "force_at": self.force_at}


def _err(where: str, exc: InputError) -> AssemblyFileError:
    return AssemblyFileError(f"{where}.{exc}")


def _table(data: dict, key: str, allowed: set, path) -> dict:
    t = data.get(key, {})
    if not isinstance(t, dict):
        raise AssemblyFileError(f"{path}: {key} must be a table [{key}]")
    unknown = sorted(set(t) - allowed)
    if unknown:
        raise AssemblyFileError(f"{path}: unknown key {key}.{unknown[0]}; allowed: "
                                f"{', '.join(sorted(allowed))}")
    return t


def _positive(where: str, name: str, value, unit: str) -> float:
    try:
        v = check_range(name, value, 0.0, None, low_open=True, unit=unit)
    except InputError as exc:
        raise _err(where, exc) from None
    if not math.isfinite(v):
        raise AssemblyFileError(f"{where}.{name} must be finite, got {v:g}")
    return v


def load_assembly(path) -> Assembly:
    """Read an assembly TOML file; one-line AssemblyFileError naming the field."""
    p = Path(path)
    data = read_toml(p, "assembly file", _TOP, AssemblyFileError)
    if "assembly" not in data:
        raise AssemblyFileError(f"{p}: missing table [assembly]")
    a = data["assembly"]
    if not isinstance(a, dict):
        raise AssemblyFileError(f"{p}: assembly must be a table [assembly]")
    model = a.get("model")
    if model not in MODELS:
        raise AssemblyFileError(f"{p}: assembly.model must be one of {', '.join(MODELS)}, "
                                f"got {model!r}")
    keys = _MODEL_KEYS[model]
    allowed = set(keys) | {"model"} | ({"n"} if model == "strip" else set())
    a = _table(data, "assembly", allowed, p)
    missing = [k for k in keys if k not in a]
    if missing:
        raise AssemblyFileError(f"{p}: missing key assembly.{missing[0]} (model {model!r} "
                                f"needs {', '.join(keys)})")
    try:
        params = {k: _positive("assembly", k, a[k], u) for k, u in keys.items()}
        if model == "strip":
            try:
                params["n"] = check_int("n", a.get("n", 201), 2, 10_000_000)
            except InputError as exc:
                raise _err("assembly", exc) from None
        fr = _table(data, "friction", _FRICTION_KEYS, p)
        lo = _table(data, "loading", _LOADING_KEYS, p)
        loading, force_at, cycles, tolerance = _loading(lo)
        _check_friction_table(fr)
    except AssemblyFileError as exc:
        raise AssemblyFileError(f"{p}: {exc}") from None
    return Assembly(str(data.get("name", p.stem)), str(data.get("description", "")), model,
                    params, dict(fr), loading, force_at, cycles, tolerance, p.parent)


def _loading(lo: dict):
    from .loading import Loading
    try:
        substeps = check_int("substeps", lo.get("substeps", 1), 1, 100_000)
    except InputError as exc:
        raise _err("loading", exc) from None
    has_range = "dT_min" in lo or "dT_max" in lo
    if has_range and "history" in lo:
        raise AssemblyFileError("loading: give dT_min/dT_max or history, not both")
    forces = [k for k in ("force", "force_min", "force_history") if k in lo]
    if len(forces) > 1:
        raise AssemblyFileError(f"loading: give one of force, force_min/force_max, "
                                f"force_history, not {forces[0]} and {forces[1]}")
    if "force_max" in lo and "force_min" not in lo:
        raise AssemblyFileError("loading.force_max needs loading.force_min")
    try:
        if "history" in lo:
            h = lo["history"]
            if not isinstance(h, list) or not all(isinstance(x, (int, float)) and
                                                  not isinstance(x, bool) for x in h):
                raise AssemblyFileError("loading.history must be a list of numbers (K)")
            dT = np.array(h, dtype=float)
        elif has_range:
            for k in ("dT_min", "dT_max"):
                if k not in lo:
                    raise AssemblyFileError(f"loading.{k} missing (cycles need dT_min and "
                                            "dT_max)")
            lo_, hi_ = (check_range(k, lo[k]) for k in ("dT_min", "dT_max"))
            if not (math.isfinite(lo_) and math.isfinite(hi_)) or hi_ < lo_:
                raise AssemblyFileError(f"loading needs finite dT_min <= dT_max, got "
                                        f"dT_min = {lo_:g} K, dT_max = {hi_:g} K")
            dT = np.array([lo_, hi_, lo_])
        else:
            raise AssemblyFileError("loading: missing dT_min/dT_max or history (K)")
        if "force_history" in lo:
            fh = lo["force_history"]
            if not isinstance(fh, list):
                raise AssemblyFileError("loading.force_history must be a list of numbers")
            F = np.array(fh, dtype=float)
        elif "force_min" in lo:
            f0 = check_range("force_min", lo["force_min"])
            f1 = check_range("force_max", lo.get("force_max", f0))
            if dT.size != 3:
                raise AssemblyFileError("loading.force_min/force_max follow dT_min/dT_max; "
                                        "with a history give force_history")
            F = np.array([f0, f1, f0])
        else:
            F = np.array([check_range("force", lo.get("force", 0.0))])
        loading = Loading(dT, F, substeps)
    except AssemblyFileError:
        raise
    except InputError as exc:
        msg = str(exc)
        raise AssemblyFileError(msg if msg.startswith("loading") else f"loading.{msg}") from None
    at = lo.get("force_at", "uniform")
    if at not in ("uniform", "start", "end"):
        raise AssemblyFileError(f"loading.force_at must be one of uniform, start, end, got {at!r}")
    cycles = tol = None
    try:
        if "cycles" in lo:
            cycles = check_range("cycles", lo["cycles"], 1.0, 1e15)
        if "tolerance" in lo:
            tol = check_range("tolerance", lo["tolerance"], 0.0, None, low_open=True, unit="m")
    except InputError as exc:
        raise _err("loading", exc) from None
    return loading, at, cycles, tol


def _check_friction_table(fr: dict) -> None:
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
            try:
                check_range(k, fr[k], 0.0, None)
            except InputError as exc:
                raise _err("friction", exc) from None
        extra = [k for k in ("slip_axis_deg", "textured", "contact") if k in fr]
        if extra:
            raise AssemblyFileError(f"friction.{extra[0]} applies to a gauge or texture, not "
                                    "to explicit mu_plus/mu_minus")
    if "slip_axis_deg" in fr:
        try:
            v = check_range("slip_axis_deg", fr["slip_axis_deg"], -360.0, 360.0, unit="deg")
        except InputError as exc:
            raise _err("friction", exc) from None
        fr["slip_axis_deg"] = v
    if fr.get("textured", "support") not in ("support", "part"):
        raise AssemblyFileError(f"friction.textured must be support or part, got "
                                f"{fr['textured']!r}")
    if fr.get("contact", "all-faces") not in ("all-faces", "windward"):
        raise AssemblyFileError(f"friction.contact must be all-faces or windward, got "
                                f"{fr['contact']!r}")
    for k in ("gauge", "texture"):
        if k in fr and not isinstance(fr[k], str):
            raise AssemblyFileError(f"friction.{k} must be a file name (string)")
