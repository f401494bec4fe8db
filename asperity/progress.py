"""Progress on long work, and long work that Ctrl-C can stop.

A numba kernel does not return to Python until it is done, so Python cannot act on Ctrl-C
while it runs.  Long computations therefore run in pieces (:func:`chunks`): between two
pieces Python raises KeyboardInterrupt if Ctrl-C was pressed, and reports progress.  A
piece should take well under a second.

Progress goes to whatever :class:`progress_bar` is active (the command line opens one per
command, ``--quiet`` silences it): on a terminal, a one-line bar on stderr with the
fraction done and the time left, drawn once the work has taken more than half a second;
when stderr is not a terminal (a log file, a pipe, a batch job), a plain line every
:data:`LINE_SECONDS` seconds (``$ASPERITY_PROGRESS_EVERY`` seconds when set; 0: none), the
first once the work has taken that long, so short work stays silent.  A bar opened inside
another (a command's phase) reports through the outer one, under its own label.  Library
code calls :func:`report` and does not care whether anyone listens.
"""
from __future__ import annotations

import contextvars
import math
import os
import time

_current: contextvars.ContextVar[progress_bar | None] = contextvars.ContextVar(
    "progress_bar", default=None)

#: seconds of work before a bar is drawn (short work stays silent)
QUIET_SECONDS = 0.5
#: seconds between two progress lines when stderr is not a terminal
LINE_SECONDS = 5.0
#: environment variable overriding :data:`LINE_SECONDS` (0: no lines)
LINE_ENV = "ASPERITY_PROGRESS_EVERY"


def line_seconds() -> float:
    """Seconds between two progress lines off a terminal (0: none)."""
    text = os.environ.get(LINE_ENV)
    if text is None:
        return LINE_SECONDS
    try:
        x = float(text)
    except ValueError:
        return LINE_SECONDS
    return x if math.isfinite(x) and x > 0 else 0.0


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.0f} s"
    return f"{s / 60:.1f} min" if s < 7200 else f"{s / 3600:.1f} h"


class progress_bar:
    """Progress of the work inside the block on stderr (``stream``): a one-line bar on a
    terminal, a line every few seconds elsewhere, nothing with ``quiet``.

    Use as a context manager: inside it, :func:`report` draws on it.  Calling the bar with
    a fraction draws too (the older interface, still used by callbacks).  Opened inside
    another bar (no ``stream`` given), it passes its reports to that one.
    """

    def __init__(self, label: str, stream=None, quiet: bool = False):
        import sys
        self.label = label
        self.outer = _current.get() if stream is None else None
        self.stream = stream or sys.stderr
        try:
            tty = self.stream.isatty()
        except (AttributeError, ValueError):
            tty = False
        self.every = 0.0 if tty or quiet else line_seconds()
        self.on = tty and not quiet                  # the terminal's bar
        self.shown = False
        self.start = time.perf_counter()
        self.last_line = self.start
        self.phase = ""
        self.phase_start = self.start
        self.phase_f0 = 0.0
        self._token = None

    def __call__(self, fraction: float, label: str | None = None) -> None:
        if self.outer is not None:
            self.outer(fraction, self.label if label is None else label)
            return
        if not (self.on or self.every):
            return
        try:
            f = min(max(float(fraction), 0.0), 1.0)
        except (TypeError, ValueError):
            return
        now = time.perf_counter()
        if (label is not None and label != self.phase) or f < self.phase_f0:
            self.phase = self.phase if label is None else label
            self.phase_start, self.phase_f0 = now, f
        left = self._left(now, f)
        if not self.on:
            if now - self.last_line >= self.every:
                self.last_line = now
                eta = "" if left is None else f", about {_duration(left)} left"
                what = "" if self.label.split()[-1:] == [self.phase] or not self.phase \
                    else f"{self.phase} "            # not 'asperity study: study 5 %'
                self._write(f"{self.label}: {what}{100 * f:.1f} % after "
                            f"{_duration(now - self.start)}{eta}\n")
            return
        if not self.shown and now - self.start < QUIET_SECONDS:
            return
        n = round(30 * f)
        eta = " " * 12 if left is None else f" {left:6.0f} s left"
        name = self.phase or self.label
        self._write(f"\r{name[:28]:<28} [{'#' * n}{'.' * (30 - n)}] {100 * f:5.1f} %{eta}")
        self.shown = True

    def _left(self, now: float, f: float) -> float | None:
        """Seconds left in the phase at the pace since its first report (None until it has
        moved by 1 %, and at the end)."""
        done = f - self.phase_f0
        if done < 0.01 or f >= 1.0:
            return None
        return (now - self.phase_start) * (1.0 - f) / done

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):                # progress must never stop the work
            self.on, self.every = False, 0.0

    def __enter__(self):
        self._token = _current.set(self)
        return self

    def __exit__(self, *exc):
        if self._token is not None:
            _current.reset(self._token)
            self._token = None
        if self.shown:
            self._write("\r" + " " * 90 + "\r")
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


class _Silent:
    """The bar inside :class:`silenced`: reports (and bars opened inside) go nowhere."""

    def __call__(self, fraction: float, label: str | None = None) -> None:
        pass


class silenced:
    """No progress inside the block (work nested in a larger one, such as the cases of a
    study, must not draw over the study's bar nor print lines of its own)."""

    def __enter__(self):
        self._token = _current.set(_Silent())
        return self

    def __exit__(self, *exc):
        _current.reset(self._token)
        return False
