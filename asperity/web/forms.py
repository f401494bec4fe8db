"""Form fields to values, each refusal one line naming the field (a 400 on the page).

The ranges of the physics are the library's to check (a wedge angle of 95 deg is refused
by :class:`asperity.WedgeTexture` with its own message); here only the form is: a field
that must be a number, a choice among the offered ones, a file of the right size.
"""
from __future__ import annotations

from ..errors import InputError, check_choice, number_from_text


class FormError(InputError):
    """A form field that cannot be read (HTTP 400)."""


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
        """The field as a float (``1e-3``, ``0.2``); blank gives ``default`` (or a
        FormError when required and there is no default)."""
        t = self.text(name)
        if t == "":
            if default is None and required:
                raise FormError(f"{label or name} is required")
            return default
        try:
            return number_from_text(label or name, t)
        except InputError as exc:
            raise FormError(str(exc)) from None

    def optional(self, name: str, *, label: str | None = None) -> float | None:
        return self.number(name, None, label=label, required=False)

    def whole(self, name: str, default: int | None = None, *, low: int = 0,
              high: int = 10 ** 9, label: str | None = None) -> int | None:
        x = self.number(name, None if default is None else float(default), label=label,
                        required=default is not None)
        if x is None:
            return None
        if x != int(x) or not low <= x <= high:
            raise FormError(f"{label or name} must be a whole number in [{low}, {high}], got "
                            f"{self.text(name)!r}")
        return int(x)

    def choice(self, name: str, choices, default: str | None = None, *,
               label: str | None = None) -> str:
        t = self.text(name) or default
        try:
            return check_choice(label or name, t, tuple(choices))
        except InputError as exc:
            raise FormError(str(exc)) from None

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
