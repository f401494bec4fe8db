"""The progress of a job of ``asperity serve``: what the worker writes to its
``progress.json`` for the job's page to poll (:class:`JobProgress`), and how a task gives
each piece of its work a share of the bar (:func:`phase`, :func:`part`)."""
from __future__ import annotations

import contextlib
import json
import math
import time
from pathlib import Path

from ..io import write_text_atomic
from ..progress import progress_bar

#: seconds between two writes of progress.json
PROGRESS_EVERY = 0.2
#: the fraction shown before the job is done (100 % only once it is)
BEFORE_DONE = 0.99
#: time constant (s) of the smoothing of the time left; the fraction and the running
#: time at least needed for a first estimate
SMOOTH_S = 10.0
FIRST_ESTIMATE = (0.02, 2.0)


class JobProgress(progress_bar):
    """A progress bar that writes ``{"fraction", "label", "updated", "left_s"}`` to a file
    (at most every :data:`PROGRESS_EVERY` s) for the job page to poll; library code reports
    to it through :func:`asperity.progress.report` or a ``progress`` callable.

    Every piece of library code counts its own work from 0 to 1 (reading a scan, each
    contact solve, each derivation): a task gives each its share of the job with
    :meth:`span` (and :meth:`part` for the k-th of n like pieces), and the fraction written
    never goes back (a piece without a share of its own only moves the bar past where it
    is) and stays below 1 until the job is done.  The time left is the running time scaled
    by the fraction left, smoothed over :data:`SMOOTH_S` s and counted down in between."""

    def __init__(self, path: Path):
        import io
        super().__init__("job", stream=io.StringIO())
        self.path = Path(path)
        self.last = 0.0
        self.stack = [(0.0, 1.0)]
        self.lo, self.hi = 0.0, 1.0
        self.top = 0.0
        self.t0 = time.time()
        self.left: float | None = None
        self.t_left = 0.0

    def __call__(self, fraction: float, label: str | None = None) -> None:
        try:
            f = min(max(float(fraction), 0.0), 1.0)
        except (TypeError, ValueError):
            return
        if math.isnan(f):
            return
        if label is not None:
            self.phase = str(label)
        self.top = max(self.top, min(self.lo + f * (self.hi - self.lo), BEFORE_DONE))
        now = time.monotonic()
        if now - self.last < PROGRESS_EVERY:
            return
        self.last = now
        self.write(self.top, self.phase)

    @contextlib.contextmanager
    def span(self, lo: float, hi: float):
        """Inside the block, a fraction f reported fills [lo, hi] of the current span."""
        a, b = self.lo, self.hi
        self.stack.append((a + lo * (b - a), a + hi * (b - a)))
        self.lo, self.hi = self.stack[-1]
        try:
            yield self
        finally:
            self.stack.pop()
            self.lo, self.hi = a, b

    def part(self, k: int, n: int) -> None:
        """From now on a fraction fills the k-th (from 0) of n equal parts of the span of
        the enclosing :meth:`span` (the k-th of n contact solves)."""
        a, b = self.stack[-1]
        k = min(max(int(k), 0), max(int(n), 1) - 1)
        self.lo, self.hi = a + (b - a) * k / n, a + (b - a) * (k + 1) / n

    def estimate(self, fraction: float, now: float) -> float | None:
        """The smoothed time left (s) at ``now`` (None: too early to tell)."""
        elapsed = now - self.t0
        if fraction >= 1.0:
            return 0.0
        if fraction < FIRST_ESTIMATE[0] or elapsed < FIRST_ESTIMATE[1]:
            return None
        raw = elapsed * (1.0 - fraction) / fraction
        if self.left is None:
            self.left = raw
        else:
            dt = max(now - self.t_left, 0.0)
            guess = max(self.left - dt, 0.0)
            self.left = guess + (1.0 - math.exp(-dt / SMOOTH_S)) * (raw - guess)
        self.t_left = now
        return self.left

    def write(self, fraction: float, label: str) -> None:
        try:
            now = time.time()
            left = self.estimate(fraction, now)
            write_text_atomic(self.path, json.dumps(
                {"fraction": fraction, "label": label, "updated": now,
                 "left_s": None if left is None else round(left, 2)}))
        except Exception:                     # progress must never stop the work
            pass


def phase(bar, lo: float, hi: float, label: str | None = None):
    """``bar.span(lo, hi)`` of a job's bar (a context manager; nothing for another
    callable), its label set."""
    if label is not None:
        bar(0.0, label)
    return bar.span(lo, hi) if hasattr(bar, "span") else contextlib.nullcontext(bar)


def part(bar, k: int, n: int) -> None:
    """``bar.part(k, n)`` of a job's bar (nothing for another callable)."""
    if hasattr(bar, "part"):
        bar.part(k, n)
