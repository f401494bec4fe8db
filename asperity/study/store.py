"""The result store of a study: one SQLite database in the study folder.

One row per case (``cases`` table): ``case_id``, the case's inputs (one column per
parameter, or ``file``), ``status`` (ok, failed, error), ``message``, ``seconds`` and one
column per output of the study's stages.  The client writes it, one transaction per
finished batch, so a kill at any moment loses at most the batches in flight and never
leaves half a row; ``case_id`` is the primary key, so no case is ever stored twice.  The
``meta`` table keeps the study (its file's text and parsed form), its fingerprint and the
SHA-256 of the content of every file it names (``input_digests``): the same folder resumes
the same study on the same inputs only -- a changed study file, or a scan, texture,
assembly or gauge file rewritten since (even at the same size and time stamp), is refused
naming it, unless the run asks to start over (``restart``: the stored cases are discarded
in one transaction, so an interrupted restart leaves the old store or the new one, never
a mix).  ``asperity study DIR`` summarises a store without the study file.

Export: Parquet (pyarrow) or CSV, one row per case, for pandas, duckdb or a spreadsheet.
"""
from __future__ import annotations

import json
import os
import sqlite3
from pathlib import Path

from ..errors import InputError, OutputError
from .cases import output_columns

DB_NAME = "study.sqlite"
SCHEMA_VERSION = 1


class StoreError(InputError):
    """A study folder cannot be used (another study's, locked, damaged).  ``changed``: what
    changed, for a store whose study or inputs changed since it was started."""

    changed: str | None = None


def _q(name: str) -> str:
    return '"' + name.replace('"', '""') + '"'


class Store:
    """An open study store.  Use :func:`open_store` (new or resumed) or :func:`read_store`
    (read only, for summaries and exports)."""

    def __init__(self, con: sqlite3.Connection, folder: Path, meta: dict):
        self.con = con
        self.folder = folder
        self.meta = meta
        self.inputs = meta["inputs"]
        self.outputs = [tuple(c) for c in meta["outputs"]]
        self._lock = None
        self.discarded = 0            # stored cases a restart discarded
        self.created: list[Path] = []      # what open_store created (discard() removes it)

    @property
    def path(self) -> Path:
        return self.folder / DB_NAME

    def columns(self) -> list[str]:
        return (["case_id", *self.inputs, "status", "message", "seconds"]
                + [c for c, _ in self.outputs])

    def done_ids(self):
        """Sorted case ids already stored (NumPy int64 array)."""
        import numpy as np
        cur = self.con.execute("SELECT case_id FROM cases ORDER BY case_id")
        return np.fromiter((r[0] for r in cur), dtype=np.int64)

    def count(self) -> dict:
        cur = self.con.execute("SELECT status, COUNT(*) FROM cases GROUP BY status")
        return {s: n for s, n in cur}

    def write(self, results, inputs_of) -> None:
        """Store finished cases in one transaction.  results: (case_id, status, message,
        seconds, outputs) tuples; inputs_of(case_id) -> the case's input values."""
        cols = self.columns()
        names = [c for c, _ in self.outputs]
        sql = (f"INSERT OR IGNORE INTO cases ({', '.join(map(_q, cols))}) VALUES "
               f"({', '.join('?' * len(cols))})")
        if hasattr(results, "outputs"):          # a block, by column: no dict per case
            ins = getattr(results, "inputs", None)
            if ins is None:
                ins = [inputs_of(cid) for cid in results.ids] if self.inputs else []
            empty = [None] * len(results)
            rows = zip(results.ids, *(zip(*ins) if ins else ()), results.status,
                       results.message, results.seconds,
                       *[results.outputs.get(n, empty) for n in names])
        else:
            rows = [(cid, *inputs_of(cid), status, msg, float(sec),
                     *[out.get(n) for n in names]) for cid, status, msg, sec, out in results]
        try:
            with self.con:
                self.con.executemany(sql, rows)
        except sqlite3.Error as exc:
            raise OutputError(f"{self.path}: cannot store results ({exc})") from None

    def forget_failed(self) -> int:
        """Delete the failed and error rows (so that they run again); their number."""
        with self.con:
            cur = self.con.execute("DELETE FROM cases WHERE status != 'ok'")
        return cur.rowcount

    def column(self, name: str, dtype=float):
        """One column over the stored cases, in case order (None -> NaN for floats)."""
        import numpy as np
        cur = self.con.execute(f"SELECT {_q(name)} FROM cases ORDER BY case_id")
        if dtype is float:
            return np.fromiter((np.nan if r[0] is None else r[0] for r in cur), dtype=float)
        return np.array([r[0] for r in cur], dtype=object)

    def rows(self):
        """Cursor over whole rows in case order."""
        return self.con.execute("SELECT * FROM cases ORDER BY case_id")

    def close(self) -> None:
        self.con.close()
        if self._lock is not None:
            self._lock.close()
            self._lock = None

    def discard(self) -> bool:
        """Close, and remove what :func:`open_store` created if no case was stored (a run
        that failed before its first case leaves nothing behind); True if removed."""
        try:
            empty = self.con.execute("SELECT COUNT(*) FROM cases").fetchone()[0] == 0
        except sqlite3.Error:
            empty = False
        if not (self.created and empty):
            self.close()
            return False
        self.con.close()
        import contextlib
        for name in (DB_NAME, DB_NAME + "-wal", DB_NAME + "-shm", ".lock"):
            with contextlib.suppress(OSError):
                (self.folder / name).unlink()
        if self._lock is not None:
            self._lock.close()
            self._lock = None
        for folder in reversed(self.created[1:]):          # the folders mkdir made
            with contextlib.suppress(OSError):
                folder.rmdir()
        return True


def _connect(path: Path) -> sqlite3.Connection:
    con = sqlite3.connect(str(path), timeout=30.0, isolation_level="DEFERRED")
    con.execute("PRAGMA journal_mode=WAL")
    con.execute("PRAGMA synchronous=NORMAL")
    return con


def _lock(folder: Path):
    """An exclusive lock on the folder: two runs on one store would race."""
    from ..locks import lock_file
    return lock_file(folder / ".lock", StoreError(
        f"{folder}: another asperity study is running on this folder; wait for it or stop "
        f"it"))


def open_store(folder, study, restart: bool = False) -> Store:
    """Create the store of ``study`` in ``folder``, or reopen it to resume; refuses a folder
    that holds another study, or this study on inputs that changed since (or other files),
    in one line.  ``restart``: discard what the folder's store holds and start over
    (``Store.discarded`` says how many cases)."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise StoreError(f"{folder}: exists and is not a folder (give -o a folder name)")
    made = [p for p in (folder, *folder.parents) if not p.exists()][::-1]
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{folder}: cannot create the study folder ({exc.strerror})") from None
    db = folder / DB_NAME
    if not db.exists():
        others = [p.name for p in folder.iterdir() if p.name not in (".lock",)]
        if others:
            raise StoreError(f"{folder}: not empty and holds no study ({others[0]}, ...); give "
                             f"-o a new or empty folder")
    if not os.access(folder, os.W_OK):
        raise OutputError(f"{folder}: permission denied (the study folder must be writable)")
    lock = _lock(folder)
    try:
        store = _open(db, folder, study, restart)
    except BaseException:
        lock.close()
        raise
    store._lock = lock
    if store.created:
        store.created += made
    return store


def _open(db: Path, folder: Path, study, restart: bool = False) -> Store:
    fp, digests = study.fingerprint(), study.input_digests()
    n = 0
    try:
        con = _connect(db)
        # no table yet: a new store, also when a run was killed before it made its tables
        # or a reader opened the file first (the lock is held: nobody else creates them)
        new = con.execute("SELECT 1 FROM sqlite_master WHERE type = 'table'").fetchone() is None
        if not new:
            meta = _meta(con, db)
            same = meta.get("fingerprint") == fp and meta.get("input_digests") == digests
            if same and not restart:
                return Store(con, folder, meta)
            n = con.execute("SELECT COUNT(*) FROM cases").fetchone()[0]
            if not restart:
                con.close()
                what = _changed(folder, meta, fp, digests)
                err = StoreError(f"{what}; run again with --restart to discard the {n} "
                                 f"stored cases and start over (or give -o a new folder)")
                err.changed = what
                raise err
            _forget_summary(folder)
        inputs = (["file"] if study.kind == "files" else []) + study.parameter_names
        meta = {"schema": SCHEMA_VERSION, "fingerprint": fp, "input_digests": digests,
                "study": study.to_dict(), "study_text": study.text, "inputs": inputs,
                "outputs": output_columns(study.spec["stages"],
                                          study.spec.get("elastic") is not None),
                "n_cases": study.n_cases, "spec": study.spec}
        _create(con, meta, replace=not new)
    except sqlite3.Error as exc:
        raise StoreError(f"{db}: not a usable study store ({exc})") from None
    store = Store(con, folder, meta)
    store.discarded = n
    if new:
        store.created = [db]
    return store


def _create(con, meta: dict, replace: bool) -> None:
    """Write the tables of a new store in one transaction (``replace``: dropping the old
    ones in the same transaction, so that a restart interrupted at any point leaves the
    old store or the new one, never a mix)."""
    cols = [f"{_q(c)} {'TEXT' if c == 'file' else 'REAL'}" for c in meta["inputs"]]
    cols += ["status TEXT NOT NULL", "message TEXT", "seconds REAL"]
    cols += [f"{_q(c)} {t}" for c, t in meta["outputs"]]
    con.execute("BEGIN IMMEDIATE")
    try:
        if replace:
            con.execute("DROP TABLE IF EXISTS cases")
            con.execute("DROP TABLE IF EXISTS meta")
        con.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)")
        con.execute(f"CREATE TABLE cases (case_id INTEGER PRIMARY KEY, {', '.join(cols)})")
        con.executemany("INSERT INTO meta VALUES (?, ?)",
                        [(k, json.dumps(v, default=repr)) for k, v in meta.items()])
    except BaseException:
        con.rollback()
        raise
    con.commit()


def _changed(folder: Path, meta: dict, fp: str, digests: dict) -> str:
    """What changed in a store's study or inputs since it was started (a file first: its
    change shows in the parsed study too)."""
    old = meta.get("input_digests")
    if not isinstance(old, dict):
        return (f"{folder}: holds a study started by an earlier asperity, which did not "
                f"record the content of its input files")
    for path, digest in digests.items():
        if path not in old:
            return f"{path} is new since the study in {folder} was started"
        if old[path] != digest:
            return (f"{path} changed since the study in {folder} was started (SHA-256 "
                    f"{old[path][:12]}... then, {digest[:12]}... now)")
    gone = sorted(set(old) - set(digests))
    if gone:
        return f"{gone[0]} is gone since the study in {folder} was started"
    return f"{folder}: holds a different study (the study file changed since it was started)"


def _forget_summary(folder: Path) -> None:
    """Remove the summary files and figures of the run a restart discards."""
    try:
        figs = json.loads((folder / "summary.json").read_text(encoding="utf-8"))["figures"]
    except (OSError, ValueError, KeyError, TypeError):
        figs = []
    for f in [*(x for x in figs if isinstance(x, str)), "summary.json", "summary.md"]:
        try:
            (folder / Path(f).name).unlink()
        except OSError:
            pass


def _meta(con, db) -> dict:
    try:
        meta = {k: json.loads(v) for k, v in con.execute("SELECT key, value FROM meta")}
    except (sqlite3.Error, ValueError) as exc:
        raise StoreError(f"{db}: not a usable study store ({exc})") from None
    if meta.get("schema") != SCHEMA_VERSION:
        raise StoreError(f"{db}: store schema {meta.get('schema')!r}, this asperity reads "
                         f"{SCHEMA_VERSION}")
    return meta


def read_store(folder) -> Store:
    """Open a finished or interrupted study's store for reading."""
    folder = Path(folder)
    db = folder / DB_NAME
    if not folder.is_dir():
        raise StoreError(f"{folder}: not a folder (give a study file or a study folder)")
    if not db.is_file():
        raise StoreError(f"{folder}: holds no study ({DB_NAME} missing)")
    try:
        con = sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=30.0)
        meta = _meta(con, db)
    except sqlite3.Error as exc:
        raise StoreError(f"{db}: not a usable study store ({exc})") from None
    return Store(con, folder, meta)


def named_file(path: str, source: str) -> str:
    """A scan library's file as its study names it: relative to the study file's folder
    when it lies in it (the folder as the study was given, or its real path), else as
    stored (an absolute pattern of the study).  Lexical: the files need not exist."""
    folder = os.path.dirname(str(source))
    if not folder:                        # a study file in the current folder
        return path if os.path.isabs(path) else os.path.normpath(path)
    for base in dict.fromkeys((folder, os.path.realpath(folder)) if os.path.isabs(folder)
                              else (folder,)):
        try:
            return str(Path(path).relative_to(base))
        except ValueError:
            continue
    return path


def _rows(store: Store):
    """Whole rows in case order, with a files study's file as its study names it."""
    rows = store.rows()
    if "file" not in store.inputs:
        return rows
    j = store.columns().index("file")
    src = store.meta["study"].get("source", "")
    return (r[:j] + (None if r[j] is None else named_file(r[j], src),) + r[j + 1:]
            for r in rows)


def export(store: Store, path) -> int:
    """Write every stored case to ``path`` (.parquet or .csv), atomically; row count.  A
    scan library's ``file`` column holds each file as the study names it (relative to the
    study file), one row per file."""
    from ..io import atomic_path
    suffix = Path(str(path)).suffix.lower()
    if suffix not in (".parquet", ".csv"):
        raise InputError(f"--export writes .parquet or .csv, got {Path(str(path)).name!r}")
    cols = store.columns()
    with atomic_path(path) as tmp:
        if suffix == ".csv":
            import csv
            n = 0
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                w = csv.writer(fh)
                w.writerow(cols)
                for row in _rows(store):
                    w.writerow(["" if v is None else v for v in row])
                    n += 1
            return n
        import pyarrow as pa
        import pyarrow.parquet as pq
        data = list(zip(*_rows(store))) or [()] * len(cols)
        types = {"case_id": pa.int64(), "status": pa.string(), "message": pa.string(),
                 "seconds": pa.float64(), "file": pa.string()}
        types.update({c: {"REAL": pa.float64(), "INTEGER": pa.int64(), "TEXT": pa.string()}[t]
                      for c, t in store.outputs})
        arrays = [pa.array(list(v), type=types.get(c, pa.float64())) for c, v in zip(cols, data)]
        pq.write_table(pa.table(arrays, names=cols), tmp)
        return len(data[0]) if data and data[0] else 0


