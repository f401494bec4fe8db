"""The small hierarchy of user-facing errors.

Every error a user can cause (bad input, unreadable file) derives from
:class:`AsperityError`; the command line prints its message on one line and exits
with status 1, never with a traceback.  Messages name the field, the allowed range
and what arrived.
"""
from __future__ import annotations

import math


class AsperityError(Exception):
    """Base class of the errors the command line reports in one line."""


class InputError(AsperityError, ValueError):
    """A parameter is missing, of the wrong type, or outside its allowed range."""


class TextureFileError(InputError):
    """A texture file cannot be read or does not follow the documented format."""


def check_range(name: str, value, low: float | None = None, high: float | None = None, *,
                low_open: bool = False, high_open: bool = False, unit: str = "") -> float:
    """Return ``value`` as a float if it lies in the given range, else raise InputError.

    The message names the field, the allowed range and the value that arrived.
    """
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if isinstance(value, bool):
        raise InputError(f"{name} must be a number, got {value!r}")
    lo = "(" if low_open or low is None else "["
    hi = ")" if high_open or high is None else "]"
    rng = f"{lo}{'-inf' if low is None else _fmt(low)}, {'inf' if high is None else _fmt(high)}{hi}"
    u = f" {unit}" if unit else ""
    if x != x:  # NaN
        raise InputError(f"{name} must be in {rng}{u}, got NaN")
    bad = False
    if low is not None and (x < low or (low_open and x == low)):
        bad = True
    if high is not None and (x > high or (high_open and x == high)):
        bad = True
    if (low is not None or high is not None) and x in (float("inf"), float("-inf")):
        if not (high is None and x > 0) and not (low is None and x < 0):
            bad = True
    if bad:
        raise InputError(f"{name} must be in {rng}{u}, got {_fmt(x)}")
    return x


def check_int(name: str, value, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as an int within [low, high], else raise InputError."""
    if isinstance(value, bool) or not isinstance(value, (int,)) and not (
        isinstance(value, float) and value.is_integer()
    ):
        try:
            if isinstance(value, str) and value.strip().lstrip("+-").isdigit():
                value = int(value)
            else:
                raise ValueError
        except ValueError:
            raise InputError(f"{name} must be a whole number, got {value!r}") from None
    n = int(value)
    if (low is not None and n < low) or (high is not None and n > high):
        rng = f"[{low if low is not None else '-inf'}, {high if high is not None else 'inf'}]"
        raise InputError(f"{name} must be a whole number in {rng}, got {n}")
    return n


def _fmt(x: float) -> str:
    return f"{x:g}"


def check_mu(name: str, value) -> float:
    x = check_range(name, value, 0.0, None)
    if not math.isfinite(x):
        raise InputError(f"{name} must be in [0, inf) and finite, got {x:g}")
    return x
