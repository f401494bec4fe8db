"""The small hierarchy of user-facing errors, and the checks that raise them.

Every error a user can cause (bad input, unreadable file, unwritable output, a request too
large for the machine) derives from :class:`AsperityError`; the command line prints its
message on one line and exits with status 1, never with a traceback.  Messages name the
field, the allowed range and what arrived.

The checks accept real numbers only: a string such as ``"30"`` from a file, a boolean, a
NaN or (unless ``allow_inf``) an infinity is refused, whatever the range.
"""
from __future__ import annotations

import math
import numbers


class AsperityError(Exception):
    """Base class of the errors the command line reports in one line.

    Every error a user can cause (bad input, an unreadable file, an unwritable output, a
    request too large for the machine) derives from it; the command line prints its
    message on one line and exits with status 1, never with a traceback.  The message
    names the field, the allowed range and what arrived.

    See Also
    --------
    asperity.InputError

    Examples
    --------
    >>> try:
    ...     asperity.read_body("no-such-body.toml")
    ... except asperity.AsperityError as exc:
    ...     print(exc)
    body file 'no-such-body.toml' does not exist
    """


class InputError(AsperityError, ValueError):
    """A parameter is missing, of the wrong type, or outside its allowed range.

    Also a ``ValueError``.  The message names the field, the allowed range and what
    arrived.

    See Also
    --------
    asperity.AsperityError

    Examples
    --------
    >>> try:
    ...     asperity.disc_footprint(-0.05)
    ... except asperity.InputError as exc:
    ...     print(exc)
    radius must be in [1e-09, 1000] m, got -0.05
    >>> issubclass(asperity.InputError, ValueError)
    True
    """


class TextureFileError(InputError):
    """A texture file cannot be read or does not follow the documented format."""


class OutputError(AsperityError, OSError):
    """An output file cannot be written (missing folder, permissions, full disk)."""


class ResourceError(InputError):
    """A request needs more memory (or work) than this machine can give."""


def one_line(text, limit: int = 400) -> str:
    """``text`` (a message or an exception) on one line, at most ``limit`` characters."""
    t = " ".join(str(text).split())
    return t if len(t) <= limit else t[: limit - 3] + "..."


def _kind(value) -> str:
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, str):
        return "text"
    if value is None:
        return "nothing (None)"
    if isinstance(value, (list, tuple, dict)):
        return f"a {type(value).__name__}"
    return type(value).__name__


def _show(value) -> str:
    text = " ".join(repr(value).split())          # an array's repr spans lines
    return text if len(text) <= 40 else text[:37] + "..."


def as_number(name: str, value) -> float:
    """``value`` as a float if it is a real number (not text, not a boolean), else
    InputError naming ``name``."""
    if type(value) is float:                      # the common case, without the ABC check
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be a number, got {_show(value)} ({_kind(value)})")
    try:
        return float(value)
    except OverflowError:
        raise InputError(f"{name} is too large a number, got {_show(value)}") from None


def number_from_text(name: str, text: str) -> float:
    """A number typed on the command line (``'5'``, ``'1e-3'``), else InputError."""
    try:
        return float(str(text).strip())
    except ValueError:
        raise InputError(f"{name} must be a number, got {_show(text)}") from None


def check_range(name: str, value, low: float | None = None, high: float | None = None, *,
                low_open: bool = False, high_open: bool = False, unit: str = "",
                allow_inf: bool = False) -> float:
    """Return ``value`` as a float if it lies in the given range, else raise InputError.

    NaN is always refused, infinities unless ``allow_inf`` (and the range reaches them).
    The message names the field, the allowed range and the value that arrived.
    """
    x = as_number(name, value)
    if x == x and (allow_inf or x - x == 0.0) \
            and (low is None or x > low or (x == low and not low_open)) \
            and (high is None or x < high or (x == high and not high_open)) \
            and not (x - x != 0.0 and ((x > 0 and high is not None) or (x < 0 and low is not None))):
        return x                              # in range: no message to build
    lo = "(" if low_open or low is None else "["
    hi = ")" if high_open or high is None else "]"
    rng = f"{lo}{'-inf' if low is None else _fmt(low)}, {'inf' if high is None else _fmt(high)}{hi}"
    u = f" {unit}" if unit else ""
    if x != x:  # NaN
        raise InputError(f"{name} must be in {rng}{u}, got NaN")
    if math.isinf(x) and not allow_inf:
        raise InputError(f"{name} must be a finite number in {rng}{u}, got {_fmt(x)}")
    raise InputError(f"{name} must be in {rng}{u}, got {_got(x, low, high)}")


def check_int(name: str, value, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as an int within [low, high], else raise InputError.  A float with
    an integral value (``1e6``) is accepted; text and booleans are not."""
    rng = "" if low is None and high is None else \
        f" in [{low if low is not None else '-inf'}, {high if high is not None else 'inf'}]"
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be a whole number{rng}, got {_show(value)} "
                         f"({_kind(value)})")
    if isinstance(value, numbers.Integral):
        n = int(value)
    else:
        x = float(value)
        if not (math.isfinite(x) and x.is_integer()):
            raise InputError(f"{name} must be a whole number{rng}, got {_fmt(x)}")
        n = int(x)
    if (low is not None and n < low) or (high is not None and n > high):
        raise InputError(f"{name} must be a whole number{rng}, got {_fmt_int(n)}")
    return n


def check_mu(name: str, value, high: float = 100.0) -> float:
    """A local friction coefficient: a finite number in [0, high]."""
    return check_range(name, value, 0.0, high)


def check_choice(name: str, value, choices) -> str:
    """``value`` if it is one of the strings ``choices``, else InputError listing them."""
    if not isinstance(value, str) or value not in choices:
        got = _show(value) if isinstance(value, str) else f"{_show(value)} ({_kind(value)})"
        raise InputError(f"{name} must be one of {', '.join(choices)}, got {got}")
    return value


def check_flag(name: str, value) -> bool:
    """``value`` if it is True or False (a NumPy bool too), else InputError."""
    import numpy as np
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be True or False, got {_show(value)} ({_kind(value)})")
    return bool(value)


def check_text(name: str, value, max_len: int = 4096) -> str:
    """A string field of a file (a name, a file name)."""
    if not isinstance(value, str):
        raise InputError(f"{name} must be text, got {_show(value)} ({_kind(value)})")
    if len(value) > max_len:
        raise InputError(f"{name} is too long ({len(value)} characters, at most {max_len})")
    return value


def check_table(where: str, value, allowed=None, required=()) -> dict:
    """A TOML table (dict) with keys in ``allowed`` and every key of ``required``."""
    if not isinstance(value, dict):
        raise InputError(f"{where} must be a table, got {_show(value)} ({_kind(value)})")
    if allowed is not None:
        unknown = sorted(set(value) - set(allowed))
        if unknown:
            raise InputError(f"unknown key {where}.{unknown[0]}; allowed: "
                             f"{', '.join(sorted(allowed))}")
    for k in required:
        if k not in value:
            raise InputError(f"missing key {where}.{k}")
    return value


def check_instance(name: str, value, cls, what: str | None = None):
    """``value`` if it is an instance of ``cls``, else InputError naming what was expected."""
    if not isinstance(value, cls):
        names = what or (" or ".join(c.__name__ for c in cls) if isinstance(cls, tuple)
                         else cls.__name__)
        raise InputError(f"{name} must be a {names}, got {_show(value)} ({_kind(value)})")
    return value


def check_array(name: str, value, ndim: int | None = None, shape=None, *,
                finite: bool = True, min_size: int = 0, dtype=float):
    """``value`` as a NumPy array of ``dtype`` with the given ``ndim``/``shape`` (None in
    ``shape`` matches any length), finite unless told otherwise; else one InputError line."""
    import numpy as np
    if value is None or isinstance(value, (str, bytes, dict)):
        raise InputError(f"{name} must be an array, got {_show(value)} ({_kind(value)})")
    masked = None
    if isinstance(value, np.ma.MaskedArray):    # masked: undefined (NaN) where allowed
        masked, value = np.ma.getmaskarray(value), np.ma.getdata(value)
    kind = getattr(getattr(value, "dtype", None), "kind", "")
    if kind == "c":
        raise InputError(f"{name} must be real numbers, got complex values ({value.dtype})")
    if kind == "b" and np.dtype(dtype).kind != "b":
        raise InputError(f"{name} must be numbers, got booleans (a {value.dtype} array)")
    if isinstance(value, np.ndarray):           # a copy of it at least: does it fit?
        _check_fits(name, value.shape, value.size * max(8, np.dtype(dtype).itemsize))
    try:
        a = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"{name} must be an array of numbers, got {_show(value)}") from None
    except MemoryError:
        raise ResourceError(f"{name} of shape {np.shape(value)} does not fit in memory; "
                            f"pass a smaller array") from None
    if masked is not None and masked.any():
        if finite or a.dtype.kind != "f":
            raise InputError(f"{name} must be finite numbers, got "
                             f"{int(np.count_nonzero(masked))} masked values")
        a = np.where(masked, np.nan, a)         # the masked pixels undefined, as NaN
    want = len(shape) if shape is not None else ndim
    if want is not None and a.ndim != want:
        raise InputError(f"{name} must have {want} dimension(s), got shape {a.shape}")
    if shape is not None and any(s is not None and s != n for s, n in zip(shape, a.shape)):
        exp = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
        raise InputError(f"{name} must have shape {exp}, got {a.shape}")
    if a.size < min_size:
        raise InputError(f"{name} must hold at least {min_size} value{'s' * (min_size != 1)}, "
                         f"got {a.size}")
    if finite and a.dtype.kind == "f" and not np.all(np.isfinite(a)):
        k = int(np.flatnonzero(~np.isfinite(a.ravel()))[0])
        raise InputError(f"{name} must be finite, got {a.ravel()[k]} at index {k}")
    return a


def _check_fits(name: str, shape, need: float) -> None:
    """Refuse an array whose copy cannot fit in this machine's memory (a broadcast view
    of 200000 x 200000 values holds none itself), in one line: the rule of
    :func:`asperity.resources.check_memory` (which imports this module) against the
    physical memory; what copies large arrays checks the memory free for it with that."""
    import os
    if need <= 2 ** 28:                        # a small array: no look at the machine
        return
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, OSError, ValueError):
        return
    if need > 0.8 * total:
        dims = " x ".join(str(n) for n in shape)
        raise ResourceError(f"{name} ({dims} values) needs about {need / 2 ** 30:.3g} GiB of "
                            f"memory, more than this machine's {total / 2 ** 30:.3g} GiB; "
                            f"pass a smaller array")


def is_array(value) -> bool:
    """``value`` is meant as an array (a list, a tuple or an array of one dimension or
    more), not as one number: to choose between :func:`check_array` and a number check."""
    import numpy as np
    return isinstance(value, (list, tuple)) or (isinstance(value, np.ndarray) and value.ndim > 0)


def _fmt(x: float) -> str:
    return f"{x:g}"


def _got(x: float, *bounds) -> str:
    """The value refused, in %g unless that reads as one of the range's bounds: then with
    the digits that tell it from them ('got 1.0000001e+13' beside the bound 1e+13, not
    'got 1e+13'; 'got 1e+291', not 'got 1.0000000000000001e+291')."""
    shown = {_fmt(b) for b in bounds if b is not None and b != x}
    for digits in (6, 9, 12, 17):
        t = f"{x:.{digits}g}"
        if t not in shown:
            return t
    return repr(x)


def _fmt_int(n: int) -> str:
    if abs(n) < 10**30:
        return str(n)
    digits = str(abs(n))                  # as %g would, beyond a float's range too (10**400)
    frac = digits[1:6].rstrip("0")
    return f"{'-' if n < 0 else ''}{digits[0]}{'.' + frac if frac else ''}e+{len(digits) - 1}"
