"""Gauge files: a fitted friction law as versioned JSON (format "asperity-gauge", version 1).

The layout is the JSON Schema shipped with the package, ``asperity/schemas/gauge-1.schema.json``
(:func:`schema`).  :func:`write_gauge` writes atomically; :func:`read_gauge` refuses an
unknown format or version, then checks the file against the schema (by hand, for the
schema keywords the file uses: one error line naming the field) and rebuilds the law, whose
own checks (polygon order, support-function consistency, convexity of D) follow.

Floats are written with ``repr`` (shortest round-trip form), so a law reloads bit for bit.
Non-finite numbers (``NaN``, ``Infinity``, ``1e999``) are refused.
"""
from __future__ import annotations

import json
import math
from functools import lru_cache
from pathlib import Path

import numpy as np

from . import __version__
from .errors import InputError
from .gauges import (ConvexSet, FitReport, GaugeLaw, ReservoirData, StarSet, TruncatedEllipse,
                     WalkerLeineLaw, associated)

FORMAT = "asperity-gauge"
VERSION = 1
SCHEMA_NAME = f"gauge-{VERSION}.schema.json"

UNITS = {"force": "per unit normal load (dimensionless): p = -lambda_T / lambda_N",
         "angles": "rad in *_rad fields (sliding direction psi from the x axis of the force "
                   "frame towards y), deg in *_deg fields"}


class GaugeFileError(InputError):
    """A gauge file cannot be read or does not follow the format."""


@lru_cache(maxsize=1)
def schema() -> dict:
    """The JSON Schema of gauge files (shipped as package data)."""
    from importlib.resources import files
    return json.loads(files("asperity").joinpath("schemas", SCHEMA_NAME).read_text("utf-8"))


# ----------------------------------------------------------------------------- writing

def to_dict(gl: GaugeLaw) -> dict:
    """The JSON object of a gauge file."""
    law = gl.law
    if gl.kind == "truncated-ellipse":
        e = law.C
        params = {**e.axes, "theta_rad": float(e.theta)}
    else:
        params = {"C": {"points": law.C.points.tolist()},
                  "D": {"psi_rad": law.D.psi.tolist(), "h": law.D.h.tolist(),
                        "dh_dpsi": law.D.dh.tolist()}}
    return {
        "format": FORMAT,
        "version": VERSION,
        "asperity_version": __version__,
        "law": gl.kind,
        "units": dict(UNITS),
        "frame": {"principal_direction_deg": float(gl.principal_direction_deg),
                  "description": "forces and directions in the frame of the source: wedge "
                                 "textures t_a (across the ridges), t_b (along them); "
                                 "surfaces x, y of the file, t_a at principal_direction_deg"},
        "parameters": params,
        "data": {"psi_rad": gl.data.psi.tolist(), "p": gl.data.p.tolist(),
                 "limit": [int(v) for v in gl.data.limit]},
        "fit": gl.fit.to_dict(),
        "source": gl.source,
    }


def dumps(obj) -> str:
    """JSON text: objects indented, arrays of numbers (and of number pairs) on one line."""
    def enc(x, ind):
        pad = "  " * ind
        if isinstance(x, dict):
            if not x:
                return "{}"
            items = [f'{pad}  {json.dumps(k)}: {enc(v, ind + 1)}' for k, v in x.items()]
            return "{\n" + ",\n".join(items) + "\n" + pad + "}"
        if isinstance(x, list):
            if all(not isinstance(v, (dict, list)) for v in x) or all(
                    isinstance(v, list) and all(not isinstance(w, (dict, list)) for w in v)
                    for v in x):
                return json.dumps(x, allow_nan=False, separators=(", ", ": "))
            return "[\n" + ",\n".join(f"{pad}  {enc(v, ind + 1)}" for v in x) + "\n" + pad + "]"
        return json.dumps(x, allow_nan=False)
    return enc(obj, 0) + "\n"


def write_gauge(path, gl: GaugeLaw) -> dict:
    """Write the gauge file of ``gl`` atomically; returns its JSON object."""
    from .io import write_text_atomic
    obj = to_dict(gl)
    try:
        text = dumps(obj)
    except ValueError as exc:                                   # a non-finite number
        raise GaugeFileError(f"cannot write {path}: {exc}") from None
    validate(obj)
    write_text_atomic(path, text)
    return obj


# ----------------------------------------------------------------------------- reading

class _NonFinite:
    def __init__(self, text):
        self.text = text


def _parse_constant(text):
    return _NonFinite(text)


def read_gauge(path) -> GaugeLaw:
    """Read and check a gauge file; raises GaugeFileError with one line naming the field."""
    p = Path(path)
    if not p.is_file():
        raise GaugeFileError(f"gauge file {str(p)!r} does not exist")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise GaugeFileError(f"{p}: cannot be read ({exc})") from None
    try:
        obj = json.loads(text, parse_constant=_parse_constant)
    except json.JSONDecodeError as exc:
        raise GaugeFileError(f"{p}: not valid JSON ({exc.msg} at line {exc.lineno}, "
                             f"column {exc.colno})") from None
    try:
        return from_dict(obj)
    except InputError as exc:
        raise GaugeFileError(f"{p}: {exc}") from None


def from_dict(obj) -> GaugeLaw:
    """Rebuild the law of a gauge-file object (checked first)."""
    validate(obj)
    kind = obj["law"]
    prm = obj["parameters"]
    if kind == "truncated-ellipse":
        e = TruncatedEllipse(prm["mu_a_plus"], prm["mu_a_minus"], prm["mu_b_plus"],
                             prm["mu_b_minus"], theta=prm["theta_rad"])
        law = associated(e)
    else:
        try:
            C = StarSet(np.array(prm["C"]["points"], dtype=float))
        except InputError as exc:
            raise InputError(f"field parameters.C.{exc}") from None
        D = prm["D"]
        n = {len(D["psi_rad"]), len(D["h"]), len(D["dh_dpsi"])}
        if len(n) != 1:
            raise InputError("field parameters.D: psi_rad, h and dh_dpsi must have the same "
                             f"length, got {len(D['psi_rad'])}, {len(D['h'])}, {len(D['dh_dpsi'])}")
        try:
            Dset = ConvexSet(np.array(D["psi_rad"], dtype=float), np.array(D["h"], dtype=float),
                             np.array(D["dh_dpsi"], dtype=float))
        except InputError as exc:
            raise InputError(f"field parameters.D: {exc}") from None
        law = WalkerLeineLaw(C, Dset)
    d = obj["data"]
    if not len(d["psi_rad"]) == len(d["p"]) == len(d["limit"]):
        raise InputError(f"field data: psi_rad, p and limit must have the same length, got "
                         f"{len(d['psi_rad'])}, {len(d['p'])}, {len(d['limit'])}")
    data = ReservoirData(np.array(d["psi_rad"], dtype=float), np.array(d["p"], dtype=float),
                         np.array(d["limit"], dtype=np.int64))
    fit = obj["fit"]
    known = set(FitReport.__dataclass_fields__)
    rep = FitReport(**{k: v for k, v in fit.items() if k in known})
    return GaugeLaw(kind, law, data, rep, obj["source"],
                    float(obj["frame"]["principal_direction_deg"]))


# ----------------------------------------------------------------------------- checking

def validate(obj) -> None:
    """Check a gauge-file object: format and version first, then the shipped schema.

    Raises InputError with one line naming the first offending field.
    """
    if not isinstance(obj, dict):
        raise InputError(f"a gauge file must hold a JSON object, got {_jtype(obj)}")
    fmt = obj.get("format")
    if fmt != FORMAT:
        raise InputError(f"field format must be {FORMAT!r}, got {_show(fmt)}: not a gauge file")
    if "version" not in obj:
        raise InputError("missing field version")
    v = obj["version"]
    if v != VERSION or isinstance(v, bool):
        raise InputError(f"field version: unknown gauge-file version {_show(v)}; this asperity "
                         f"({__version__}) reads version {VERSION}: upgrade asperity, or refit "
                         "with `asperity fit`")
    _check_finite(obj, "")
    sch = schema()
    _check(obj, sch, sch, "")


def _check_finite(x, path: str) -> None:
    if isinstance(x, _NonFinite) or (isinstance(x, float) and not math.isfinite(x)):
        raise InputError(f"field {_field(path)} must be a finite number, got {_show(x)}")
    if isinstance(x, dict):
        for k, v in x.items():
            _check_finite(v, f"{path}.{k}" if path else k)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            _check_finite(v, f"{path}[{i}]")


def _jtype(x) -> str:
    if x is None:
        return "null"
    if isinstance(x, bool):
        return "boolean"
    if isinstance(x, int):
        return "integer"
    if isinstance(x, float):
        return "number"
    if isinstance(x, _NonFinite):
        return x.text
    if isinstance(x, str):
        return "string"
    if isinstance(x, list):
        return "array"
    if isinstance(x, dict):
        return "object"
    return type(x).__name__


def _show(x) -> str:
    if isinstance(x, _NonFinite):
        return x.text
    if isinstance(x, float) and not math.isfinite(x):
        return repr(x)
    if isinstance(x, (dict, list)):
        return _jtype(x)
    return json.dumps(x) if isinstance(x, (str, int, float, bool)) or x is None else repr(x)


def _is_type(x, t: str) -> bool:
    if t == "object":
        return isinstance(x, dict)
    if t == "array":
        return isinstance(x, list)
    if t == "string":
        return isinstance(x, str)
    if t == "boolean":
        return isinstance(x, bool)
    if t == "null":
        return x is None
    if t == "integer":
        return (isinstance(x, int) and not isinstance(x, bool)) or (
            isinstance(x, float) and math.isfinite(x) and x.is_integer())
    if t == "number":
        return isinstance(x, (int, float)) and not isinstance(x, bool)
    raise ValueError(f"schema type {t!r} not supported")      # pragma: no cover


def _field(path: str) -> str:
    return path or "(top level)"


def _resolve(ref: str, root: dict) -> dict:
    if not ref.startswith("#/"):
        raise ValueError(f"schema reference {ref!r} not supported")   # pragma: no cover
    node = root
    for part in ref[2:].split("/"):
        node = node[part]
    return node


def _matches(x, sch, root, path) -> bool:
    try:
        _check(x, sch, root, path)
        return True
    except InputError:
        return False


def _check(x, sch: dict, root: dict, path: str) -> None:
    """The subset of JSON Schema 2020-12 that gauge-1.schema.json uses."""
    if "$ref" in sch:
        _check(x, _resolve(sch["$ref"], root), root, path)
    where = _field(path)
    if isinstance(x, _NonFinite) or (isinstance(x, float) and not math.isfinite(x)):
        raise InputError(f"field {where} must be a finite number, got {_show(x)}")
    if "type" in sch:
        types = sch["type"] if isinstance(sch["type"], list) else [sch["type"]]
        if not any(_is_type(x, t) for t in types):
            raise InputError(f"field {where} must be of type {' or '.join(types)}, "
                             f"got {_jtype(x)} {_show(x) if not isinstance(x, (dict, list)) else ''}"
                             .rstrip())
    if "const" in sch and not (x == sch["const"] and type(x) is type(sch["const"])):
        raise InputError(f"field {where} must be {json.dumps(sch['const'])}, got {_show(x)}")
    if "enum" in sch and not any(x == e and type(x) is type(e) for e in sch["enum"]):
        raise InputError(f"field {where} must be one of "
                         f"{', '.join(json.dumps(e) for e in sch['enum'])}, got {_show(x)}")
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        if "minimum" in sch and x < sch["minimum"]:
            raise InputError(f"field {where} must be >= {sch['minimum']}, got {_show(x)}")
        if "exclusiveMinimum" in sch and x <= sch["exclusiveMinimum"]:
            raise InputError(f"field {where} must be > {sch['exclusiveMinimum']}, got {_show(x)}")
    if isinstance(x, dict):
        for k in sch.get("required", []):
            if k not in x:
                raise InputError(f"missing field {path + '.' if path else ''}{k}")
        props = sch.get("properties", {})
        extra = sch.get("additionalProperties", True)
        for k, v in x.items():
            sub = f"{path}.{k}" if path else k
            if k in props:
                _check(v, props[k], root, sub)
            elif extra is False:
                allowed = ", ".join(props)
                raise InputError(f"unknown field {sub} (allowed: {allowed})")
            elif isinstance(extra, dict):
                _check(v, extra, root, sub)
    if isinstance(x, list):
        if "minItems" in sch and len(x) < sch["minItems"]:
            raise InputError(f"field {where} must have at least {sch['minItems']} items, "
                             f"got {len(x)}")
        if "maxItems" in sch and len(x) > sch["maxItems"]:
            raise InputError(f"field {where} must have at most {sch['maxItems']} items, "
                             f"got {len(x)}")
        if "items" in sch:
            for i, v in enumerate(x):
                _check(v, sch["items"], root, f"{path}[{i}]")
    for sub in sch.get("allOf", []):
        _check(x, sub, root, path)
    if "if" in sch:
        if _matches(x, sch["if"], root, path):
            if "then" in sch:
                _check(x, sch["then"], root, path)
        elif "else" in sch:
            _check(x, sch["else"], root, path)
