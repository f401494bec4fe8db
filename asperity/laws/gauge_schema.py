"""Checking a gauge-file object against the shipped JSON Schema, by hand, for the schema
keywords the format uses: one error line naming the first offending field (no jsonschema
dependency at run time; the tests also check the files with jsonschema).
"""
from __future__ import annotations

import json
import math
from functools import lru_cache

from .. import __version__
from ..errors import InputError

FORMAT = "asperity-gauge"
VERSION = 1
#: a law family over the nominal pressure (asperity.laws.family); one law is still version 1
FAMILY_VERSION = 2
VERSIONS = (VERSION, FAMILY_VERSION)
SCHEMA_NAME = f"gauge-{VERSION}.schema.json"


@lru_cache(maxsize=2)
def schema(version: int = VERSION) -> dict:
    """The JSON Schema of gauge files of ``version`` (1: one law, 2: a law family; shipped
    as package data)."""
    from importlib.resources import files
    name = f"gauge-{version}.schema.json"
    return json.loads(files("asperity").joinpath("schemas", name).read_text("utf-8"))


class _NonFinite:
    def __init__(self, text):
        self.text = text


def parse_constant(text):
    return _NonFinite(text)


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
    if v not in VERSIONS or isinstance(v, bool) or not isinstance(v, int):
        raise InputError(f"field version: unknown gauge-file version {_show(v)}; this asperity "
                         f"({__version__}) reads versions {VERSION} and {FAMILY_VERSION}: "
                         "upgrade asperity, or refit with `asperity fit`")
    _check_finite(obj, "")
    sch = schema(v)
    _check(obj, sch, sch, "")


def _check_finite(x, path: str) -> None:
    if isinstance(x, _NonFinite) or (isinstance(x, float) and not math.isfinite(x)):
        raise InputError(f"field {_field(path)} must be a finite number, got {_show(x)}")
    if isinstance(x, int) and not isinstance(x, bool) and abs(x) > 2 ** 1000:
        raise InputError(f"field {_field(path)} must be a finite number, got an integer of "
                         f"{len(str(abs(x)))} digits")
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
    """The subset of JSON Schema 2020-12 that the gauge schemas use."""
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
        if "maximum" in sch and x > sch["maximum"]:
            raise InputError(f"field {where} must be <= {sch['maximum']}, got {_show(x)}")
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
