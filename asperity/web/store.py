"""The data folder of ``asperity serve``: uploads and jobs, on disk, surviving a restart.

::

    DATA/uploads/<32 hex><suffix>        an uploaded file under a generated name
    DATA/uploads/<32 hex><suffix>.json   what it was called (shown, never opened)
    DATA/jobs/<id>/job.json              the job's record (the server writes it)
    DATA/jobs/<id>/progress.json         fraction done (the worker writes it)
    DATA/jobs/<id>/result.json           the result (the worker writes it)
    DATA/jobs/<id>/...                   files to download (gauge.json, figures, ...)
    DATA/jobs/.deleted-<id>-<hex>/       a job being deleted (renamed first, then removed)

Every file is written atomically (:func:`asperity.io.write_text_atomic`): a kill at any
moment leaves the old record or the new one.  Names that come from a request (job ids,
upload ids, file names) are matched against strict patterns before any path is built;
a client's file name is never used as a path.
"""
from __future__ import annotations

import json
import math
import re
import secrets
import time
from pathlib import Path

from ..errors import InputError
from ..io import write_text_atomic

JOB_ID = re.compile(r"^[0-9]{8}-[0-9]{6}-[0-9a-f]{6}$")
UPLOAD_ID = re.compile(r"^[0-9a-f]{32}(\.[a-z0-9]{1,10}){1,2}$")
#: suffixes an upload may keep (its format is read from it); a trailing .gz is allowed
SUFFIX = re.compile(r"^\.[a-z0-9]{1,10}$")
#: names of companion files (a study's texture and assembly files): plain file names
PLAIN_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,127}$")
STATUSES = ("queued", "running", "done", "failed", "cancelled")
FINISHED = ("done", "failed", "cancelled")


class UploadError(InputError):
    """An upload that cannot be taken (name, size, format)."""


def now_iso() -> str:
    return time.strftime("%Y-%m-%d %H:%M:%S", time.localtime())


def display_name(name) -> str:
    """A client's file name as shown on a page (the last part, printable, at most 100
    characters); never used as a path."""
    text = str(name or "").replace("\\", "/").rsplit("/", 1)[-1]
    text = "".join(c for c in text if c.isprintable()).strip()
    return (text[:97] + "...") if len(text) > 100 else (text or "unnamed")


def check_plain_name(name, what: str = "file name") -> str:
    """``name`` if it is a plain file name (no folder, no leading dot), else UploadError."""
    text = str(name or "")
    if "/" in text or "\\" in text or ".." in text:
        raise UploadError(f"{what} {display_name_raw(text)!r} is not a plain file name "
                          f"(folders are not allowed)")
    if not PLAIN_NAME.match(text):
        raise UploadError(f"{what} {display_name_raw(text)!r} is not a plain file name: use "
                          f"letters, digits, '.', '_' and '-', starting with a letter or digit")
    return text


def display_name_raw(text: str) -> str:
    text = "".join(c for c in str(text) if c.isprintable())
    return text if len(text) <= 60 else text[:57] + "..."


def upload_suffix(name) -> str:
    """The format suffix of a client's file name: ``.x3p``, ``.txt.gz``; UploadError if
    the name holds a folder or has no usable suffix."""
    text = str(name or "")
    if not text:
        raise UploadError("the file has no name; its format is read from its suffix "
                          "(.x3p, .stl, .txt, .toml, ...)")
    if "/" in text or "\\" in text or text.startswith(".") or ".." in text:
        raise UploadError(f"file name {display_name_raw(text)!r} is not a plain file name "
                          f"(folders are not allowed)")
    parts = text.lower().rsplit(".", 2)
    if len(parts) < 2:
        raise UploadError(f"file name {display_name_raw(text)!r} has no suffix; the format "
                          f"is read from it (.x3p, .stl, .txt, .npy, .toml, ...)")
    suffix = "." + parts[-1]
    if parts[-1] == "gz" and len(parts) == 3:
        suffix = "." + parts[-2] + suffix
    if not all(SUFFIX.match("." + s) for s in suffix.split(".")[1:]):
        raise UploadError(f"file name {display_name_raw(text)!r}: the suffix {suffix!r} is "
                          f"not a file format suffix")
    return suffix


class Store:
    """The data folder (see the module docstring)."""

    def __init__(self, root: Path):
        self.root = Path(root)
        self.jobs_dir = self.root / "jobs"
        self.uploads_dir = self.root / "uploads"

    # ------------------------------------------------------------------ uploads
    def new_upload_path(self, filename) -> tuple[str, Path]:
        """(upload id, path to write) for a client's file name (only its suffix is kept)."""
        uid = secrets.token_hex(16) + upload_suffix(filename)
        return uid, self.uploads_dir / uid

    def finish_upload(self, uid: str, filename, size: int) -> dict:
        meta = {"id": uid, "name": display_name(filename), "size": int(size),
                "uploaded": now_iso()}
        write_text_atomic(self.uploads_dir / f"{uid}.json", json.dumps(meta))
        return meta

    def upload_path(self, uid) -> Path:
        if not isinstance(uid, str) or not UPLOAD_ID.match(uid):
            raise UploadError("no such upload (it may have been deleted); choose the file again")
        p = self.uploads_dir / uid
        if not p.is_file():
            raise UploadError("no such upload (it may have been deleted); choose the file again")
        return p

    def upload_meta(self, uid) -> dict:
        self.upload_path(uid)
        try:
            return json.loads((self.uploads_dir / f"{uid}.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return {"id": uid, "name": uid, "size": None}

    # ------------------------------------------------------------------ jobs
    def new_job(self, kind: str, params: dict, title: str) -> dict:
        stamp = time.strftime("%Y%m%d-%H%M%S", time.localtime())
        while True:
            jid = f"{stamp}-{secrets.token_hex(3)}"
            folder = self.jobs_dir / jid
            try:
                folder.mkdir(parents=True)
                break
            except FileExistsError:
                continue
        rec = {"id": jid, "kind": kind, "title": title, "status": "queued",
               "created": now_iso(), "created_at": time.time(), "started": None,
               "finished": None, "seconds": None,
               "params": params, "error": None, "error_status": None,
               "needs_units": False, "attempts": 0, "files": []}
        self.write(rec)
        return rec

    def job_dir(self, jid) -> Path:
        if not isinstance(jid, str) or not JOB_ID.match(jid):
            raise KeyError(jid)
        return self.jobs_dir / jid

    def read(self, jid) -> dict | None:
        try:
            return json.loads((self.job_dir(jid) / "job.json").read_text(encoding="utf-8"))
        except (KeyError, OSError, ValueError):
            return None

    def write(self, rec: dict) -> None:
        write_text_atomic(self.job_dir(rec["id"]) / "job.json", json.dumps(rec, indent=1))

    def update(self, jid: str, **changes) -> dict | None:
        rec = self.read(jid)
        if rec is None:
            return None
        rec.update(changes)
        self.write(rec)
        return rec

    def delete(self, jid: str) -> bool:
        """Remove job ``jid`` and all its files: its folder is first renamed out of the
        list in one step (a kill at any moment leaves the whole job or none of it listed),
        then removed.  False if there is no such job."""
        import shutil
        try:
            folder = self.job_dir(jid)
        except KeyError:
            return False
        trash = self.jobs_dir / f".deleted-{jid}-{secrets.token_hex(4)}"
        try:
            folder.rename(trash)
        except FileNotFoundError:
            return False
        shutil.rmtree(trash, ignore_errors=True)
        return True

    def sweep(self) -> None:
        """Finish deletions that a kill interrupted (folders renamed, not yet removed)."""
        import shutil
        try:
            for p in self.jobs_dir.glob(".deleted-*"):
                shutil.rmtree(p, ignore_errors=True)
        except OSError:
            pass

    def progress(self, jid) -> dict:
        try:
            return json.loads((self.job_dir(jid) / "progress.json").read_text(encoding="utf-8"))
        except (KeyError, OSError, ValueError):
            return {"fraction": 0.0, "label": ""}

    def result(self, jid) -> dict | None:
        try:
            return json.loads((self.job_dir(jid) / "result.json").read_text(encoding="utf-8"))
        except (KeyError, OSError, ValueError):
            return None

    def job_file(self, jid: str, name: str) -> Path | None:
        """A file the job declared for download (``rec["files"]``), else None."""
        rec = self.read(jid)
        if rec is None or name not in rec.get("files", []):
            return None
        p = self.job_dir(jid) / name
        return p if p.is_file() else None

    def jobs(self, kinds=None, status=None, limit: int = 50) -> list[dict]:
        """The newest jobs first (of ``kinds``, with ``status``)."""
        return self.select((kinds, status, limit))[0]

    def select(self, *queries) -> list[list[dict]]:
        """Several :meth:`jobs` lists, one per query ``(kinds, status, limit)``, from one
        pass over the records (a page lists jobs of several kinds)."""
        outs: list[list[dict]] = [[] for _ in queries]
        try:
            names = sorted((p.name for p in self.jobs_dir.iterdir() if JOB_ID.match(p.name)),
                           reverse=True)
        except OSError:
            return outs
        for jid in names:
            if all(len(o) >= q[2] for o, q in zip(outs, queries)):
                break
            rec = self.read(jid)
            if rec is None:
                continue
            for o, (kinds, status, limit) in zip(outs, queries):
                if len(o) < limit and (not kinds or rec["kind"] in kinds) and \
                        (not status or rec["status"] in status):
                    o.append(rec)
        return outs


def clock(rec: dict, progress: dict, now: float | None = None) -> dict:
    """How long job ``rec`` has waited or run, from the times stored in its record (so a
    page reloaded shows the same), and the time left: the worker's smoothed estimate
    (``left_s`` at ``updated`` in its progress, :class:`~.job_progress.JobProgress`)
    counted down since, None once spent; else the elapsed time scaled by what is left, once
    the job is 2 % done and ran 2 s.
    ``{"elapsed_s", "left_s" (None: no estimate), "since": "queued" | "running"}``."""
    now = time.time() if now is None else now
    running = rec.get("status") == "running" and rec.get("started_at")
    t0 = rec.get("started_at") if running else rec.get("created_at")
    if not isinstance(t0, (int, float)):
        try:
            t0 = time.mktime(time.strptime(str(rec.get("created")), "%Y-%m-%d %H:%M:%S"))
        except (TypeError, ValueError, OverflowError):
            t0 = now
    elapsed = max(0.0, now - float(t0))
    left = None
    try:
        f = float(progress.get("fraction") or 0.0)
    except (TypeError, ValueError):
        f = 0.0
    told, at = progress.get("left_s"), progress.get("updated")
    if running and "left_s" in progress:
        if isinstance(told, (int, float)) and isinstance(at, (int, float)) and \
                math.isfinite(told) and math.isfinite(at):
            left = told - max(0.0, now - at)
            left = left if left > 0.5 else None
    elif running and 0.02 <= f < 1.0 and elapsed >= 2.0:
        left = elapsed * (1.0 - f) / f
    return {"elapsed_s": round(elapsed, 1), "left_s": None if left is None else round(left, 1),
            "since": "running" if running else "queued"}


def duration(seconds) -> str:
    """``75`` -> ``1 min 15 s``; ``4000`` -> ``1 h 07 min``."""
    s = int(round(float(seconds or 0)))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"
