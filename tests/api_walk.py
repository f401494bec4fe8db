"""The hostile-argument walker of the public API (tests/test_hostile_api.py): what an
argument may hold (its *kind*: a number in a range, a whole number, an array, a choice, a
file, an object of a class ...) and, from the kind alone, the bad values a careless or
hostile caller may pass in its place, each one a value the function must refuse.

Every kind's bad values are grouped in classes (the issue's: wrong type, wrong shape,
NaN, infinity, overflow, out of range, missing file ...), so that the walker can count the
calls of each class.  :func:`judge` runs one call and says what is wrong with how it
failed (None: a one-line InputError, no warning on the way)."""
from __future__ import annotations

import cmath
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


# ---- NumPy's own arrays (issue 25, item 3) --------------------------------------------------
#
# A list of numbers is not all a caller passes: a masked array, complex or boolean values,
# an object array, a 0-d array, a broadcast view of 200000 x 200000 values that holds no
# memory itself, a strided view, big-endian or integer values.  :func:`array_variants`
# derives them from an argument's valid value; each says what the function must do with
# it: refuse it in one line ("refuse"), take masked values as undefined or refuse them
# ("nan"), or give exactly what the same values as a plain float64 array give ("same").

#: a request far beyond any machine's memory (a float64 copy: 298 GiB)
HUGE = {1: (40_000_000_000,), 2: (200_000, 200_000)}


def array_variants(kind: Kind, valid):
    """(the plain float64 array, [(class, label, value, how) of the NumPy arrays built
    from it]): ``valid`` is the argument's value in a valid call (None: a small array of
    the kind's dimensions)."""
    import numpy as np
    nd = kind.ndim
    if valid is None:
        t = np.full((3, 2) if nd == 2 else (3,), 0.5)
    else:
        try:
            t = np.array(valid, dtype=float)
        except (TypeError, ValueError):
            return None, []
    if t.ndim == 0 or t.size == 0:
        return None, []
    x = float(t.flat[0])
    out = [("type", "complex array", t.astype(complex), "refuse"),
           ("type", "complex array with imaginary parts", t + 1j, "refuse"),
           ("type", "boolean array", np.ones(t.shape, dtype=bool), "refuse"),
           ("type", "object array holding text", _with(t.astype(object), "abc"), "refuse"),
           ("NaN", "object array holding None", _with(t.astype(object), None), "nan"),
           ("NaN", "masked array", np.ma.masked_array(t, mask=_first(t.shape)), "nan"),
           ("huge", "broadcast view of 4e10 values",
            np.broadcast_to(x, HUGE[2] if nd in (None, 2) else HUGE[1]), "refuse")]
    out.append(("shape", "0-d array", np.array(x), "scalar"))
    if nd is not None and "empty" not in kind.skip:
        out.append(("shape", "empty array", np.zeros((0,) * nd), "refuse"))
    out += [("layout", "strided view", np.repeat(t, 2, axis=-1)[..., ::2], "same"),
            ("layout", "big-endian", t.astype(">f8"), "same"),
            ("layout", "read-only", _read_only(t), "same")]
    if t.ndim == 2:
        out.append(("layout", "Fortran order", np.asfortranarray(t), "same"))
    if np.all(t == np.round(t)) and np.all(np.abs(t) < 2 ** 52):
        out.append(("layout", "integers", t.astype(np.int64), "same"))
    return t, [v for v in out if v[1] not in kind.skip]


def number_variants(kind: Kind, valid):
    """(the float, [(class, label, value, how)]) of the NumPy scalars a caller may pass
    for a number (``valid``: its value in a valid call; not a number: none)."""
    import numbers

    import numpy as np
    if isinstance(valid, bool) or not isinstance(valid, numbers.Real):
        return None, []
    x = float(valid)
    out = [("type", "NumPy complex", np.complex128(x), "refuse"),
           ("type", "NumPy bool", np.bool_(True), "refuse"),
           ("NaN", "masked constant", np.ma.masked, "refuse"),
           ("shape", "0-d array", np.array(x), "scalar")]
    if abs(x) < 2 ** 52 and x == round(x):
        out.append(("layout", "NumPy int64", np.int64(round(x)), "same"))
    return x, [v for v in out if v[1] not in kind.skip]


def _first(shape):
    import numpy as np
    m = np.zeros(shape, dtype=bool)
    m.flat[0] = True
    return m


def _with(a, item):
    a.flat[0] = item
    return a


def _read_only(t):
    a = t.copy()
    a.flags.writeable = False
    return a


def nan_first(plain):
    """``plain`` with NaN in the place :func:`array_variants` masks."""
    a = plain.copy()
    a.flat[0] = math.nan
    return a


#: attributes whose values differ between two identical calls (clocks, caches)
VOLATILE = re.compile(r"time|elapsed|seconds|wall|cpu|created|date|duration")


def outcome(call):
    """("value", result) or ("error", type name, message) of ``call()``, and the warnings
    it raised on the way."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            res = ("value", call())
        except AsperityError as exc:
            res = ("error", type(exc).__name__, str(exc))
        except Exception as exc:           # noqa: BLE001 -- the finding
            res = ("raw", type(exc).__name__, str(exc).replace("\n", "\\n")[:160])
    return res, [str(w.message)[:100] for w in caught]


def differ(a, b, path="", depth=0) -> str | None:
    """Where two results differ (None: the same values, to 1e-12, NaN equal to NaN)."""
    import dataclasses

    import numpy as np
    if depth > 8 or a is b:
        return None
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape:
            return f"{path}: shape {a.shape} != {b.shape}"
        if "O" in a.dtype.kind + b.dtype.kind:
            ok = all(differ(x, y) is None for x, y in zip(a.flat, b.flat))
        elif a.dtype.kind in "fc" or b.dtype.kind in "fc":
            ok = np.allclose(a, b, rtol=1e-12, atol=0.0, equal_nan=True)
        else:
            ok = np.array_equal(a, b)
        return None if ok else f"{path}: arrays differ"
    if isinstance(a, (bool, str, bytes, type(None))) or isinstance(b, (bool, str, bytes)):
        return None if a == b else f"{path}: {a!r} != {b!r}"
    if isinstance(a, (int, float, np.number)) and isinstance(b, (int, float, np.number)):
        fa, fb = complex(a), complex(b)
        same = fa == fb or (cmath.isnan(fa) and cmath.isnan(fb)) or \
            abs(fa - fb) <= 1e-12 * abs(fa)
        return None if same else f"{path}: {a!r} != {b!r}"
    if type(a) is not type(b):
        return f"{path}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, dict):
        if set(a) != set(b):
            return f"{path}: keys {sorted(map(str, set(a) ^ set(b)))}"
        items = [(k, a[k], b[k]) for k in a]
    elif isinstance(a, (list, tuple)):
        if len(a) != len(b):
            return f"{path}: length {len(a)} != {len(b)}"
        items = list(zip(range(len(a)), a, b))
    elif dataclasses.is_dataclass(a):
        items = [(f.name, getattr(a, f.name), getattr(b, f.name))
                 for f in dataclasses.fields(a)]
    elif hasattr(a, "__dict__") and not callable(a):
        items = [(k, v, vars(b).get(k)) for k, v in vars(a).items()]
    else:
        return None                           # functions, modules, kernels: not values
    for k, x, y in items:
        if isinstance(k, str) and (k.startswith("_") or VOLATILE.search(k)):
            continue
        why = differ(x, y, f"{path}.{k}", depth + 1)
        if why:
            return why
    return None


def judge_variant(call, expected, kind: Kind, names, how: str) -> str | None:
    """What is wrong with how ``call`` (a NumPy variant of an argument) ended: "refuse":
    a one-line InputError naming the argument (:func:`judge`); "nan": that, or what the
    values with NaN in the masked places give; "scalar" (a 0-d array): that, or what its
    value as a float gives; "same": what the plain float64 array of the same values gives,
    a refusal or a result.  ``expected(how)``: the :func:`outcome` of that other call."""
    if how == "refuse":
        return judge(call, kind, names)
    if how in ("nan", "scalar") and judge(call, kind, names) is None:
        return None
    got, warned = outcome(call)
    want, _ = expected(how)
    if warned:
        return f"warning on the way: {warned[0]}"
    if got[0] == "raw":
        return f"{got[1]}: {got[2]}"
    if got[0] != want[0]:
        return (f"{got[0]} {got[1:] if got[0] != 'value' else ''} where the plain array "
                f"gives {want[0]} {want[1:] if want[0] != 'value' else ''}")[:300]
    if got[0] == "error":
        return None if got[1:] == want[1:] else f"a different refusal: {got[2][:120]}"
    why = differ(got[1], want[1])
    return None if why is None else f"another result than the plain array's ({why})"
