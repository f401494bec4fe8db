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

import json
from pathlib import Path

from ..io import json_ready, write_text_atomic
from .job_progress import JobProgress
from .results import one_line

#: for older imports: the job's progress bar lives in .job_progress
__all__ = ["JobProgress", "main", "run_job"]


def needs_units(message: str) -> bool:
    """Does the message ask for the length unit or the pixel size of a file?"""
    m = message.lower()
    return ("pass unit" in m or "pass pixel_size" in m or "no length unit" in m
            or "states no height unit" in m)


def tasks() -> dict:
    from . import tasks_contact, tasks_crawl, tasks_motion, tasks_study, tasks_surface
    return {**tasks_surface.TASKS, **tasks_contact.TASKS, **tasks_motion.TASKS,
            **tasks_crawl.TASKS, **tasks_study.TASKS}


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
