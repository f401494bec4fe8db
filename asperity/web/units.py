"""Units on the pages: one function chooses the engineering unit of a quantity from the
magnitude of its values, so that every page shows ``0.2748 um``, ``274.8 mm`` and ``5 MPa``
instead of ``2.748e-07 m``.

:func:`choose` takes all the values of one quantity shown on a page (a drift over the life
and the tolerance it is compared with; every height of a colour bar) and gives one unit for
all of them: the largest prefix that keeps the largest magnitude at or above 1.
:func:`show` formats a value in a unit so chosen.  The figures, the result pages and the
job lists all call these two (registered as the Jinja globals ``unit_of``, ``in_unit``,
``number_in`` and the filters ``cycles``, ``fixed`` and ``article``).
"""
from __future__ import annotations

import math

#: prefixes a base unit may take on the pages (a length in km or a pressure in uPa is
#: never what an engineer wants to read), smallest first
PREFIXES = {"m": ("n", "u", "m", ""), "Pa": ("", "k", "M", "G"), "N": ("m", "", "k", "M"),
            "N/m": ("", "k", "M", "G"), "s": ("",)}
SCALE = {"n": 1e-9, "u": 1e-6, "m": 1e-3, "": 1.0, "k": 1e3, "M": 1e6, "G": 1e9}


class Unit:
    """A unit chosen for a quantity: its name (``"um"``) and the factor of its base unit
    (``1e-6``): a value in the base unit is ``value / factor`` in this one."""

    __slots__ = ("name", "factor")

    def __init__(self, name: str, factor: float):
        self.name, self.factor = name, factor

    def __call__(self, x):
        """``x`` (base unit: a number or a NumPy array) in this unit; None stays None."""
        if x is None:
            return None
        return x / self.factor if hasattr(x, "shape") else float(x) / self.factor

    def __repr__(self) -> str:
        return f"Unit({self.name!r}, {self.factor:g})"


def _magnitudes(values):
    if values is None:
        return []
    if isinstance(values, (int, float)):
        values = [values]
    out = []
    for v in values:
        if isinstance(v, (list, tuple)):
            out += _magnitudes(v)
        elif v is not None:
            try:
                a = abs(float(v))
            except (TypeError, ValueError):
                continue
            if math.isfinite(a) and a > 0:
                out.append(a)
    return out


def choose(values, base: str = "m", smallest: bool = False) -> Unit:
    """The unit for every value of one quantity (``values``: a number, or numbers nested
    in lists; None, NaN and 0 ignored): the largest prefix of ``base`` in which the largest
    magnitude is at least 1 (to 4 digits; the smallest prefix when none is); ``base``
    itself when there is no finite non-zero value.  ``smallest``: the smallest magnitude
    instead (a list of pressures typed, 50 MPa to 1 GPa, reads 50 to 1000 MPa)."""
    prefixes = PREFIXES.get(base, ("",))
    mags = _magnitudes(values)
    if not mags:
        return Unit(base, 1.0)
    top = min(mags) if smallest else max(mags)
    pick = prefixes[0]
    for p in prefixes:
        if top / SCALE[p] >= 0.99995:          # what rounds to 1 at 4 digits
            pick = p
    return Unit(pick + base, SCALE[pick])


def number(x, unit: Unit, digits: int = 4, sign: bool = False) -> str:
    """``x`` (base unit) as a number in ``unit`` (``digits`` significant digits; ``sign``:
    a + before positive values), without the unit's name; None is ``-``."""
    if x is None:
        return "-"
    v = unit(x)
    if not math.isfinite(v):
        return ("+" if sign and v > 0 else "-" if v < 0 else "") + "infinity"
    text = f"{v:{'+' if sign else ''}.{digits}g}"
    if "e" in text:                           # a value far below the unit chosen for others
        mant, exp = text.split("e")
        text = f"{mant} x 10^{int(exp)}"
    return text


def show(x, unit: Unit, digits: int = 4, sign: bool = False) -> str:
    """``x`` (base unit) as ``"274.8 mm"`` in ``unit`` (see :func:`number`)."""
    return "-" if x is None else f"{number(x, unit, digits, sign)} {unit.name}"


def cycles(n) -> str:
    """A number of cycles as people write it: ``1 000 000``, ``364``, ``2.5 x 10^9``."""
    if n is None:
        return "-"
    x = float(n)
    if not math.isfinite(x):
        return "infinitely many"
    if x == int(x) and abs(x) < 1e9:
        return f"{int(x):,}".replace(",", "\u202f")
    mant, exp = f"{x:.3e}".split("e")
    return f"{float(mant):g} x 10^{int(exp)}"


def fixed(x, digits: int = 4) -> str:
    """A number without an exponent, to ``digits`` significant digits (a fraction of
    8.011e-05 is ``0.00008011``; at most 12 decimals); None is ``-``."""
    if x is None:
        return "-"
    v = float(x)
    if not math.isfinite(v):
        return "infinity" if v > 0 else "-infinity" if v < 0 else "-"
    if v == 0:
        return "0"
    decimals = min(12, max(0, digits - 1 - math.floor(math.log10(abs(v)))))
    return f"{v:.{decimals}f}"


def article(word, capital: bool = False) -> str:
    """``word`` after its indefinite article: ``an ellipse``, ``a star`` (``capital``:
    ``An ellipse``)."""
    text = str(word)
    low = text.lower()
    an = low[:1] in "aeio" or (low[:1] == "u" and not low.startswith(("uni", "use", "usu")))
    a = "an" if an and low else "a"
    return f"{a.capitalize() if capital else a} {text}"


def register(env) -> None:
    """The Jinja globals and filters of this module."""
    env.globals.update(unit_of=choose, in_unit=show, number_in=number)
    env.filters["cycles"] = cycles
    env.filters["fixed"] = fixed
    env.filters["article"] = article
