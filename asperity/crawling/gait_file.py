"""Gait files (TOML): a curvature gait as a Fourier series, or a table of joint angles.

::

    name = "wave and bend"                  # optional
    description = "..."                     # optional

    [gait]
    kind = "fourier"                        # fourier | joints
    length = 1.0                            # m
    period = 1.0                            # s

    [[gait.terms]]                          # kappa L += cos * cos 2 pi (m s / L + n t / T)
    m = 1                                   #           + sin * sin 2 pi (m s / L + n t / T)
    n = 1                                   # whole numbers in [-50, 50]; n = 0: static
    cos = 7.0                               # in [-100, 100]; cos or sin may be left out
    sin = 0.0

or, for a chain of ``links`` rigid links (joints counted from the tail, see
:mod:`.gait_chain`)::

    [gait]
    kind = "joints"
    length = 0.8
    period = 2.0
    links = 8
    unit = "deg"                            # rad (default) | deg
    angles = [[...7 angles...], ...]        # rows: equally spaced times over one period

or a serpenoid chain (phi_j = a sin(2 pi t / T - j b) + c, joints counted from the tail:
b < 0 runs the wave from the head to the tail, see :class:`.gait_chain.SerpenoidChain`)::

    [gait]
    kind = "serpenoid"
    length = 0.8
    period = 2.0
    links = 8
    unit = "deg"                            # rad (default) | deg: a, b and c
    amplitude = 40.0                        # a in [0, 180] deg
    phase = -51.43                          # b in [-360, 360] deg
    offset = 0.0                            # c in [-180, 180] deg (optional: a steady turn)

The table's rows are the times k T / rows (k = 0..rows-1; at least 4 rows), its columns
the links - 1 joint angles; a periodic cubic spline interpolates them.  Every missing,
unknown or bad field is one InputError line naming the file and the field
(``gait.terms[2].cos``) and its range.  Shipped examples: ``surfaces/gaits/``.
"""
from __future__ import annotations

import math
from os import PathLike
from pathlib import Path

from ..errors import (
    InputError,
    check_choice,
    check_instance,
    check_int,
    check_range,
    check_table,
    check_text,
)
from . import gait as gm
from . import gait_chain as gc

KINDS = ("fourier", "joints", "serpenoid")
_TOP = {"name", "description", "gait"}
_KEYS = {"fourier": {"kind", "length", "period", "terms"},
         "joints": {"kind", "length", "period", "links", "unit", "angles"},
         "serpenoid": {"kind", "length", "period", "links", "unit", "amplitude", "phase",
                       "offset"}}
_TERM_KEYS = {"m", "n", "cos", "sin"}


def read_gait(path) -> gm.Gait:
    """The gait of a TOML gait file (format in the module docstring)."""
    from ..io import read_toml
    p = Path(check_instance("path", path, (str, PathLike), "file name (text or a Path)"))
    data = read_toml(p, "gait file", _TOP, InputError)
    try:
        return gait_from_dict(data, str(p), p.stem)
    except InputError as exc:
        msg = str(exc)
        raise type(exc)(msg if msg.startswith(str(p)) else f"{p}: {msg}") from None


def gait_from_dict(data: dict, source: str = "", default_name: str = "gait") -> gm.Gait:
    """A gait from the parsed file (a dict with the table ``gait``)."""
    if not isinstance(data, dict):
        raise InputError("a gait file must hold a table [gait]")
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r}; allowed top-level keys: "
                         f"{', '.join(sorted(_TOP))}")
    if "gait" not in data:
        raise InputError("missing table [gait]")
    g = check_table("gait", data["gait"], None, ("kind", "length", "period"))
    kind = check_choice("gait.kind", g["kind"], KINDS)
    check_table("gait", g, _KEYS[kind])
    length = check_range("gait.length", g["length"], *gm.LENGTH_RANGE, unit="m")
    period = check_range("gait.period", g["period"], *gm.PERIOD_RANGE, unit="s")
    name = check_text("name", data.get("name", default_name), 200)
    check_text("description", data.get("description", ""))
    if kind == "fourier":
        return gm.FourierGait(_terms(g), period, length, name)
    if kind == "serpenoid":
        return _serpenoid(g, period, length)
    return _joints(g, period, length, name, source)


def _serpenoid(g: dict, period: float, length: float) -> gc.SerpenoidChain:
    for k in ("links", "amplitude", "phase"):
        if k not in g:
            raise InputError(f"missing key gait.{k}")
    deg = check_choice("gait.unit", g.get("unit", "rad"), ("rad", "deg")) == "deg"
    scale, unit = (math.pi / 180, "deg") if deg else (1.0, "rad")
    values = {}
    for key, (lo, hi) in (("amplitude", gc.JOINT_AMPLITUDE_RANGE), ("phase", gc.PHASE_RANGE),
                          ("offset", gc.OFFSET_RANGE)):
        v = check_range(f"gait.{key}", g.get(key, 0.0), lo / scale, hi / scale, unit=unit)
        values[key] = min(max(v * scale, lo), hi)      # the range's ends exactly
    return gc.SerpenoidChain(check_int("gait.links", g["links"], *gc.LINKS_RANGE),
                             values["amplitude"], values["phase"], values["offset"],
                             period, length)


def _terms(g: dict) -> list[tuple]:
    if "terms" not in g:
        raise InputError("missing key gait.terms (one [[gait.terms]] table a term)")
    terms = g["terms"]
    if not isinstance(terms, list) or not terms:
        raise InputError("gait.terms must be a list of tables ([[gait.terms]]), one a term")
    for i, term in enumerate(terms):
        check_table(f"gait.terms[{i}]", term, _TERM_KEYS, ("m", "n"))
    return gm.fourier_terms(terms, "gait.")


def _joints(g: dict, period: float, length: float, name: str, source: str) -> gc.JointTable:
    for k in ("links", "angles"):
        if k not in g:
            raise InputError(f"missing key gait.{k}")
    links = check_int("gait.links", g["links"], *gc.LINKS_RANGE)
    unit = check_choice("gait.unit", g.get("unit", "rad"), ("rad", "deg"))
    scale, top = (math.pi / 180, 180.0) if unit == "deg" else (1.0, math.pi)
    rows = g["angles"]
    if not isinstance(rows, list):
        raise InputError("gait.angles must be a table of rows (a list of lists of numbers)")
    lo, hi = gc.ROWS_RANGE
    if not lo <= len(rows) <= hi:
        raise InputError(f"gait.angles must have {lo} to {hi} rows (times over one "
                         f"period), got {len(rows)}")
    table = []
    for i, row in enumerate(rows):
        if not isinstance(row, list):
            raise InputError(f"gait.angles[{i}] must be a row of {links - 1} joint angles, "
                             f"got a single value")
        if len(row) != links - 1:
            raise InputError(f"gait.angles[{i}] has {len(row)} values, expected "
                             f"{links - 1} (gait.links - 1)")
        table.append([scale * check_range(f"gait.angles[{i}][{j}]", x, -top, top,
                                          unit=unit) for j, x in enumerate(row)])
    return gc.JointTable(table, period, length, name, source)
