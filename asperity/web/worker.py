"""What a worker process of ``asperity serve`` runs: one job at a time, through the library.

The server starts a few worker processes (:mod:`.runner`) and sends each a job: its kind,
its folder and its parameters.  The worker runs the task of that kind (in
:mod:`.tasks_surface`, :mod:`.tasks_motion`, :mod:`.tasks_study`) inside a
:class:`JobProgress` -- the library's progress bar (:mod:`asperity.progress`) pointed at
the job's ``progress.json`` instead of a terminal -- writes ``result.json`` and answers
with a short status.  A user error is one line (the upload's name instead of its stored
path), a bug is one line too (the traceback goes to ``traceback.txt`` in the job folder).
"""
from __future__ import annotations

import contextlib
import json
import math
import time
from pathlib import Path

from ..io import json_ready, write_text_atomic
from ..progress import progress_bar
from .results import one_line

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


def needs_units(message: str) -> bool:
    """Does the message ask for the length unit or the pixel size of a file?"""
    m = message.lower()
    return ("pass unit" in m or "pass pixel_size" in m or "no length unit" in m
            or "states no height unit" in m)


def tasks() -> dict:
    from . import tasks_contact, tasks_motion, tasks_study, tasks_surface
    return {**tasks_surface.TASKS, **tasks_contact.TASKS, **tasks_motion.TASKS,
            **tasks_study.TASKS}


def run_job(kind: str, job_dir: str, params: dict, uploads: str) -> dict:
    """Run one job; its answer: ``{"ok": True, "files": [...]}`` or ``{"ok": False,
    "status": 422 | 500, "error": one line, "needs_units": bool}``."""
    from ..errors import AsperityError
    folder = Path(job_dir)
    ctx = {"job_dir": folder, "uploads": Path(uploads), "jobs": folder.parent, "names": {}}
    bar = JobProgress(folder / "progress.json")
    try:
        task = tasks().get(kind)
        if task is None:
            raise AsperityError(f"unknown job kind {kind!r}")
        with bar:
            bar.write(0.0, "starting")
            result = task(params, ctx, bar)
        result = json_ready(result)
        write_text_atomic(folder / "result.json", json.dumps(result, allow_nan=False))
        bar.write(1.0, "done")
        return {"ok": True, "files": result.get("files", [])}
    except AsperityError as exc:
        msg = one_line(exc, ctx["names"])
        return {"ok": False, "status": 422, "error": msg, "needs_units": needs_units(msg)}
    except MemoryError:
        return {"ok": False, "status": 422, "error": "out of memory: ask for less (fewer "
                "directions, a smaller scan, fewer cases)", "needs_units": False}
    except RecursionError:
        return {"ok": False, "status": 422, "error": "input nested too deeply to be "
                "processed", "needs_units": False}
    except Exception as exc:                       # a bug: one line, traceback to a file
        import traceback
        try:
            write_text_atomic(folder / "traceback.txt", traceback.format_exc())
        except Exception:
            pass
        return {"ok": False, "status": 500, "needs_units": False,
                "error": f"internal error: {type(exc).__name__}: {one_line(exc, ctx['names'])} "
                         f"(please report it; the traceback is in the job's folder)"}


def warm_up() -> None:
    """Load the compiled kernels once, so that the first job does not wait for them."""
    try:
        from .. import WedgeTexture, derive
        derive(WedgeTexture(alpha_deg=30.0, beta_deg=10.0, mu_alpha=0.1, mu_beta=0.2),
               n_directions=8)
    except Exception:                              # pragma: no cover - never fatal
        pass


def main(conn, parent: int | None = None) -> None:
    """A worker process: jobs from ``conn`` until it closes (or None arrives); it ends
    when the server (process ``parent``) ends, however the server ends, and with it the
    processes of the job it runs (a study's local cluster)."""
    import os
    import signal

    from ..lifeline import die_with_parent
    die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # the server stops its workers itself
    os.environ.setdefault("MPLBACKEND", "Agg")
    warm_up()
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        if msg is None:
            return
        try:
            conn.send(run_job(*msg))
        except (BrokenPipeError, OSError):
            return
