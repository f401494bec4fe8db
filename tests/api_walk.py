"""The hostile-argument walker of the public API (tests/test_hostile_api.py): what an
argument may hold (its *kind*: a number in a range, a whole number, an array, a choice, a
file, an object of a class ...) and, from the kind alone, the bad values a careless or
hostile caller may pass in its place, each one a value the function must refuse.

Every kind's bad values are grouped in classes (the issue's: wrong type, wrong shape,
NaN, infinity, overflow, out of range, missing file ...), so that the walker can count the
calls of each class.  :func:`judge` runs one call and says what is wrong with how it
failed (None: a one-line InputError, no warning on the way)."""
from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

from asperity.errors import AsperityError, InputError, OutputError

NAN, INF = math.nan, math.inf
BIG_INT = 10 ** 400                     # no float holds it: float(BIG_INT) overflows

#: wrong types: what a caller may pass where a number, an array or an object belongs
TYPES = [("type", "text", "abc"), ("type", "None", None), ("type", "list of text", ["a", "b"]),
         ("type", "dict", {"a": 1}), ("type", "bool", True), ("type", "object", object())]
#: numbers outside every range, and the numbers an out-of-range test picks from
NON_FINITE = [("NaN", "NaN", NAN), ("inf", "+inf", INF), ("inf", "-inf", -INF),
              ("overflow", "10**400", BIG_INT), ("overflow", "-10**400", -BIG_INT)]
PROBES = [("range", "negative", -1.0), ("range", "zero", 0.0), ("range", "huge", 1e300),
          ("range", "-huge", -1e300), ("range", "subnormal", 5e-324)]


@dataclass
class Kind:
    """What an argument holds.  ``bad()`` lists (class, label, value) to refuse."""

    what: str = "any"
    lo: float | None = None              # numbers, elements of arrays
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    none: bool = False                   # None is a valid value (a default)
    inf: bool = False                    # +inf is a valid value (rigid springs, self-locking)
    ndim: int | None = None              # arrays: dimensions (None: any shape)
    extra: list = field(default_factory=list)   # more bad values: (class, label, value)
    skip: tuple = ()                     # labels that are valid for this argument

    def inside(self, x: float) -> bool:
        if x != x:
            return False
        if math.isinf(x):
            return self.inf and x > 0
        above = self.lo is None or x > self.lo or (x == self.lo and not self.lo_open)
        below = self.hi is None or x < self.hi or (x == self.hi and not self.hi_open)
        return above and below

    def bad(self) -> list:
        out = [t for t in TYPES if not (t[2] is None and self.none)]
        if self.what in ("number", "int"):
            out += [("shape", "1-d", [1.0, 2.0]), ("shape", "2-d", [[1.0]]),
                    ("shape", "empty", []), ("shape", "ragged", [[1.0], [1.0, 2.0]])]
            out += [t for t in NON_FINITE + PROBES
                    if not (isinstance(t[2], float) and self.inside(t[2]))]
            if self.what == "int":
                out += [("type", "fraction", 2.5)]
        elif self.what == "array":               # ndim None: any shape (elementwise)
            nd = self.ndim
            out += [("shape", "ragged", [[0.1], [0.1, 0.2]])]
            if nd is not None:
                out += [("shape", f"{nd + 1}-d", [[[0.1]]] if nd == 2 else [[0.1, 0.2]]),
                        ("shape", "empty", [])]
            if nd == 2:
                out += [("shape", "1-d", [0.1, 0.2])]
            out += [(c, label + " inside", [0.1, x]) for c, label, x in NON_FINITE + PROBES
                    if not (isinstance(x, float) and self.inside(x))]
        elif self.what == "choice":
            out = [t for t in out if t[1] != "text"] + [("choice", "unknown name", "no-such"),
                                                        ("type", "number", 1.5)]
        elif self.what == "flag":
            out = [t for t in out if t[1] != "bool"] + [("type", "number", 2),
                                                        ("type", "text 'yes'", "yes")]
        elif self.what == "callable":
            out = [t for t in out if t[1] != "object"] + [("type", "number", 1.5)]
        elif self.what == "object":
            out += [("type", "number", 1.5), ("type", "a class", int)]
        elif self.what in ("file", "output"):
            out = [t for t in out if t[1] != "text"] + [("type", "number", 1.5)]
        elif self.what == "text":
            out = [t for t in out if t[1] != "text"] + [("type", "number", 1.5),
                                                        ("range", "too long", "x" * 100_000)]
        return [t for t in out + self.extra if t[1] not in self.skip]


def number(lo=None, hi=None, **kw) -> Kind:
    return Kind("number", lo, hi, **kw)


def whole(lo=None, hi=None, **kw) -> Kind:
    return Kind("int", lo, hi, **kw)


def array(lo=None, hi=None, ndim=1, **kw) -> Kind:
    return Kind("array", lo, hi, ndim=ndim, **kw)


def choice(**kw) -> Kind:
    return Kind("choice", **kw)


def flag(**kw) -> Kind:
    return Kind("flag", **kw)


def callback(**kw) -> Kind:
    return Kind("callable", none=True, **kw)


def instance(**kw) -> Kind:
    return Kind("object", **kw)


def infile(folder, suffix, **kw) -> Kind:
    """A file to read: also missing, a folder, empty, or bytes that are not its format."""
    (folder / f"empty{suffix}").write_bytes(b"")
    (folder / f"garbage{suffix}").write_bytes(b"\x00\xff garbage \x01" * 7)
    extra = [("file", "missing file", folder / f"missing{suffix}"),
             ("file", "a folder", folder), ("file", "empty file", folder / f"empty{suffix}"),
             ("file", "not its format", folder / f"garbage{suffix}"),
             ("file", "empty text", "")]
    return Kind("file", extra=extra + kw.pop("extra", []), **kw)


def outfile(folder, **kw) -> Kind:
    """A file to write: also in a missing folder, or a folder."""
    extra = [("file", "missing folder", folder / "no-such-folder" / "out.json"),
             ("file", "a folder", folder), ("file", "empty text", "")]
    return Kind("output", extra=extra + kw.pop("extra", []), **kw)


def address(**kw) -> Kind:
    """Where to reach a service (a Dask scheduler): refused, or unreachable, in one line."""
    return Kind("address", none=True, extra=[("choice", "no address", "abc"),
                                            ("choice", "no port", "tcp://127.0.0.1:99999")],
                **kw)


def text(**kw) -> Kind:
    return Kind("text", **kw)


def outfolder(folder, **kw) -> Kind:
    """A folder to write in: also a file, or a folder that cannot be made."""
    (folder / "a-file").write_bytes(b"x")
    extra = [("file", "a file", folder / "a-file"),
             ("file", "below a file", folder / "a-file" / "sub")]
    return Kind("output", none=True, extra=extra, **kw)


def judge(call, kind: Kind, names, value=None) -> str | None:
    """Run ``call()``; None if it raised a one-line InputError (an OutputError for an
    output file, any AsperityError for an address to reach) whose message names one of
    ``names`` (or, for a file, the file given), with no warning on the way; else what went
    wrong."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            call()
        except AsperityError as exc:
            error = exc
        except Exception as exc:           # noqa: BLE001 -- the finding
            msg = str(exc).replace("\n", "\\n")[:160]
            return f"{type(exc).__name__}: {msg}"
        else:
            return "accepted"
    msg = str(error)
    want = {"output": (InputError, OutputError), "address": AsperityError}.get(kind.what,
                                                                             InputError)
    if not isinstance(error, want):
        return f"{type(error).__name__} (not InputError): {msg[:160]}"
    if not msg or "\n" in msg:
        return f"not one line: {msg[:160]!r}"
    if caught:
        w = caught[0]
        return f"{w.category.__name__} on the way: {str(w.message)[:100]}"
    if kind.what in ("file", "output") and isinstance(value, (str, Path)) and str(value):
        names = (*names, str(value))
    if not any(re.search(rf"(?<![\w]){re.escape(n)}(?![\w])", msg) for n in names):
        return f"message names none of {names}: {msg[:160]}"
    return None
