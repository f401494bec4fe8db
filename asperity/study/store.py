"""The result store of a study: one SQLite database in the study folder.

One row per case (``cases`` table): ``case_id``, the case's inputs (one column per
parameter, or ``file``), ``status`` (ok, failed, error), ``message``, ``seconds`` and one
column per output of the study's stages.  The client writes it, one transaction per
finished batch, so a kill at any moment loses at most the batches in flight and never
leaves half a row; ``case_id`` is the primary key, so no case is ever stored twice.  The
``meta`` table keeps the study (its file's text and parsed form) and its fingerprint:
the same folder resumes the same study only, and ``asperity study DIR`` summarises it
without the study file.

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
    """A study folder cannot be used (another study's, locked, damaged)."""


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
            return np.array([np.nan if r[0] is None else r[0] for r in cur], dtype=float)
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


def open_store(folder, study) -> Store:
    """Create the store of ``study`` in ``folder``, or reopen it to resume; refuses a folder
    that holds another study (or other files), in one line."""
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
        store = _open(db, folder, study)
    except BaseException:
        lock.close()
        raise
    store._lock = lock
    if store.created:
        store.created += made
    return store


def _open(db: Path, folder: Path, study) -> Store:
    fp = study.fingerprint()
    try:
        con = _connect(db)
        # no table yet: a new store, also when a run was killed before it made its tables
        # or a reader opened the file first (the lock is held: nobody else creates them)
        new = con.execute("SELECT 1 FROM sqlite_master WHERE type = 'table'").fetchone() is None
        if new:
            inputs = ["file"] if study.kind == "files" else study.parameter_names
            meta = {"schema": SCHEMA_VERSION, "fingerprint": fp, "study": study.to_dict(),
                    "study_text": study.text, "inputs": inputs,
                    "outputs": output_columns(study.spec["stages"]),
                    "n_cases": study.n_cases, "spec": study.spec}
            cols = [f"{_q(c)} {'TEXT' if c == 'file' else 'REAL'}" for c in inputs]
            cols += ["status TEXT NOT NULL", "message TEXT", "seconds REAL"]
            cols += [f"{_q(c)} {t}" for c, t in meta["outputs"]]
            with con:
                con.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)")
                con.execute(f"CREATE TABLE cases (case_id INTEGER PRIMARY KEY, {', '.join(cols)})")
                con.executemany("INSERT INTO meta VALUES (?, ?)",
                                [(k, json.dumps(v, default=repr)) for k, v in meta.items()])
            store = Store(con, folder, meta)
            store.created = [db]
            return store
        meta = _meta(con, db)
    except sqlite3.Error as exc:
        raise StoreError(f"{db}: not a usable study store ({exc})") from None
    if meta.get("fingerprint") != fp:
        con.close()
        raise StoreError(f"{folder}: holds a different study (the study file, a file it names "
                         f"or a scan changed); give -o a new folder, or delete this one to "
                         f"start again")
    return Store(con, folder, meta)


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


def export(store: Store, path) -> int:
    """Write every stored case to ``path`` (.parquet or .csv), atomically; row count."""
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
                for row in store.rows():
                    w.writerow(["" if v is None else v for v in row])
                    n += 1
            return n
        import pyarrow as pa
        import pyarrow.parquet as pq
        data = list(zip(*store.rows().fetchall())) or [()] * len(cols)
        types = {"case_id": pa.int64(), "status": pa.string(), "message": pa.string(),
                 "seconds": pa.float64(), "file": pa.string()}
        types.update({c: {"REAL": pa.float64(), "INTEGER": pa.int64(), "TEXT": pa.string()}[t]
                      for c, t in store.outputs})
        arrays = [pa.array(list(v), type=types.get(c, pa.float64())) for c, v in zip(cols, data)]
        pq.write_table(pa.table(arrays, names=cols), tmp)
        return len(data[0]) if data and data[0] else 0
