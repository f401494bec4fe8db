"""Form fields to values, each refusal one line naming the field (a 400 on the page).

The ranges of the physics are the library's to check (a wedge angle of 95 deg is refused
by :class:`asperity.WedgeTexture` with its own message); here only the form is: a field
that must be a number, a choice among the offered ones, a file of the right size.
"""
from __future__ import annotations

import contextlib
import math

from ..errors import AsperityError, InputError, check_choice, check_int, number_from_text
from .security import TooLarge


class FormError(InputError):
    """A form field that cannot be read (HTTP 400)."""

    def __init__(self, message: str, field: str | None = None):
        super().__init__(message)
        self.field = field


def field_of(exc: BaseException) -> str | None:
    """The form field an error is about (set where the form was read), else None."""
    return getattr(exc, "field", None)


@contextlib.contextmanager
def at(field: str):
    """Errors raised inside are about form field ``field`` (unless they already name one)."""
    try:
        yield
    except (AsperityError, TooLarge) as exc:
        if field_of(exc) is None:
            exc.field = field
        raise


def _read(field: str, check, *args):
    """``check(*args)``; its refusal as a FormError about ``field`` (HTTP 400)."""
    try:
        return check(*args)
    except InputError as exc:
        raise FormError(str(exc), field) from None


class Form:
    """The fields of a submitted form (text fields and uploaded files)."""

    def __init__(self, form):
        self.form = form

    def text(self, name: str, default: str = "") -> str:
        v = self.form.get(name)
        if v is None or hasattr(v, "filename"):
            return default
        return str(v).strip()

    def number(self, name: str, default: float | None = None, *, label: str | None = None,
               required: bool = True) -> float | None:
        """The field as a finite float (``1e-3``, ``0.2``); blank gives ``default`` (or a
        FormError when required and there is no default)."""
        t = self.text(name)
        label = label or name
        if t == "":
            if default is None and required:
                raise FormError(f"{label} is required", name)
            return default
        x = _read(name, number_from_text, label, t)
        if not math.isfinite(x):
            raise FormError(f"{label} must be a finite number, got {t[:40]!r}", name)
        return x

    def optional(self, name: str, *, label: str | None = None) -> float | None:
        return self.number(name, None, label=label, required=False)

    def whole(self, name: str, default: int | None = None, *, low: int | None = None,
              high: int | None = None, label: str | None = None) -> int | None:
        """The field as a whole number in [low, high] (None: the library checks that
        side), through :func:`asperity.errors.check_int`; blank gives ``default``."""
        t = self.text(name)
        if t == "":
            return default
        label = label or name
        return _read(name, check_int, label, _read(name, number_from_text, label, t), low, high)

    def choice(self, name: str, choices, default: str | None = None, *,
               label: str | None = None) -> str:
        t = self.text(name) or default
        return _read(name, check_choice, label or name, t, tuple(choices))

    def file(self, name: str):
        """The uploaded file of field ``name`` (None if no file was chosen)."""
        v = self.form.get(name)
        if v is None or not hasattr(v, "filename") or not v.filename:
            return None
        return v

    def files(self, name: str) -> list:
        return [v for v in self.form.getlist(name) if hasattr(v, "filename") and v.filename]

    def values(self) -> dict:
        """The text fields as submitted (to fill the form again after an error)."""
        return {k: str(v) for k, v in self.form.multi_items() if not hasattr(v, "filename")}
