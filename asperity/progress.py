"""Progress on long work, and long work that Ctrl-C can stop.

A numba kernel does not return to Python until it is done, so Python cannot act on Ctrl-C
while it runs.  Long computations therefore run in pieces (:func:`chunks`): between two
pieces Python raises KeyboardInterrupt if Ctrl-C was pressed, and reports progress.  A
piece should take well under a second.

Progress goes to whatever :class:`progress_bar` is active (the command line opens one per
command): a one-line bar with the fraction done and the time left, on stderr and only when
stderr is a terminal, drawn once the work has taken more than half a second.  Library code
calls :func:`report` and does not care whether anyone listens.
"""
from __future__ import annotations

import contextvars
import time

_current: contextvars.ContextVar["progress_bar | None"] = contextvars.ContextVar(
    "progress_bar", default=None)

#: seconds of work before a bar is drawn (short work stays silent)
QUIET_SECONDS = 0.5


class progress_bar:
    """A one-line progress bar on stderr when it is a terminal (a no-op otherwise).

    Use as a context manager: inside it, :func:`report` draws on it.  Calling the bar with
    a fraction draws too (the older interface, still used by callbacks).
    """

    def __init__(self, label: str, stream=None):
        import sys
        self.label = label
        self.stream = stream or sys.stderr
        try:
            self.on = self.stream.isatty()
        except (AttributeError, ValueError):
            self.on = False
        self.shown = False
        self.start = time.perf_counter()
        self.phase = ""
        self.phase_start = self.start
        self._token = None

    def __call__(self, fraction: float, label: str | None = None) -> None:
        if not self.on:
            return
        now = time.perf_counter()
        if label is not None and label != self.phase:
            self.phase, self.phase_start = label, now
        if not self.shown and now - self.start < QUIET_SECONDS:
            return
        f = min(max(float(fraction), 0.0), 1.0)
        n = int(round(30 * f))
        took = now - self.phase_start
        eta = f" {took * (1 - f) / f:6.0f} s left" if 0.02 < f < 1 else " " * 12
        name = self.phase or self.label
        self.stream.write(f"\r{name[:28]:<28} [{'#' * n}{'.' * (30 - n)}] {100 * f:5.1f} %{eta}")
        self.stream.flush()
        self.shown = True

    def __enter__(self):
        self._token = _current.set(self)
        return self

    def __exit__(self, *exc):
        if self._token is not None:
            _current.reset(self._token)
            self._token = None
        if self.shown:
            self.stream.write("\r" + " " * 90 + "\r")
            self.stream.flush()
        return False


def report(fraction: float, label: str | None = None) -> None:
    """Tell the active progress bar (if any) how far the work is, 0 to 1."""
    bar = _current.get()
    if bar is not None:
        bar(fraction, label)


def chunks(total: int, size: int, label: str | None = None):
    """Yield ``(start, stop)`` over ``range(total)`` in pieces of at most ``size``, reporting
    progress after each piece; Ctrl-C pressed during a piece stops the loop after it."""
    size = max(1, int(size))
    start = 0
    while start < total:
        stop = min(total, start + size)
        yield start, stop
        start = stop
        report(start / total if total else 1.0, label)


class silenced:
    """No progress bar inside the block (work nested in a larger one, such as the cases of
    a study, must not draw over the study's bar)."""

    def __enter__(self):
        self._token = _current.set(None)
        return self

    def __exit__(self, *exc):
        _current.reset(self._token)
        return False
