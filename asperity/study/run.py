"""A study from file to summary: the library API behind ``asperity study``.

>>> s = run_study_file("surfaces/two-node-tolerance.toml", "out.study", workers=2)  # doctest: +SKIP
>>> s["p_ratchet"]                                                                   # doctest: +SKIP
"""
from __future__ import annotations

import json
from pathlib import Path

from ..errors import InputError


def default_folder(study_file) -> Path:
    """Where a study's results go without -o: ``<study name>-study`` in the current folder."""
    return Path(f"{Path(str(study_file)).stem}-study")


def run_study_file(path, folder=None, *, scheduler: str | None = None,
                   workers: int | None = None, batch_size: int | None = None,
                   retry_failed: bool = False, plot: bool = False,
                   restart: bool = False) -> dict:
    """Run (or resume) the study of file ``path`` into ``folder``; its summary.

    workers: local worker processes (default one per core; 0: in this process);
    scheduler: an existing Dask cluster's scheduler address or scheduler file (default
    $ASPERITY_SCHEDULER, else a LocalCluster); retry_failed: run the failed cases again;
    restart: discard the cases the folder holds (of this study or of another, or of inputs
    that changed since) and start over -- without it such a folder is refused.
    Writes ``study.sqlite``, ``summary.json``, ``summary.md`` (and with ``plot`` the
    figures) into the folder."""
    from .engine import resolve_scheduler, run_study
    from .spec import Study, load_study
    from .store import open_store
    study = path if isinstance(path, Study) else load_study(path)
    if scheduler is not None and workers is not None:
        raise InputError("give --scheduler (an existing cluster) or --workers (a local one), "
                         "not both")
    if scheduler is not None or workers is None:    # checked before anything is created
        scheduler = resolve_scheduler(scheduler)
    store = open_store(folder or default_folder(study.source), study, restart=restart)
    try:
        if retry_failed:
            store.forget_failed()
        report = run_study(study, store, scheduler=scheduler, workers=workers,
                           batch_size=batch_size)
        summary = finish(store, plot)
        summary["run"] = {"ran": report.ran, "seconds": report.seconds, "where": report.where,
                          "workers": report.workers, "discarded": store.discarded}
    except BaseException as exc:
        if store.discard() and isinstance(exc, KeyboardInterrupt):  # the folder as it was
            raise type(exc)("stopped before its first case was stored; nothing written") \
                from None
        raise
    store.close()
    return summary


def finish(store, plot: bool = False) -> dict:
    """Summarise ``store`` and write summary.json, summary.md (and the figures)."""
    from ..io import json_ready, outside_transaction, write_text_atomic
    from .summary import summarise
    from .text import markdown
    summary = json_ready(summarise(store))
    figs = []
    with outside_transaction():        # the study folder is a working store: written now
        if plot:
            from .plot import figures
            figs = figures(store, summary, store.folder)
        summary["figures"] = [str(store.folder / f) for f in figs]
        if _writable(store.folder):
            write_text_atomic(store.folder / "summary.json",
                              json.dumps(summary, indent=2, allow_nan=False) + "\n")
            write_text_atomic(store.folder / "summary.md", markdown(summary, figs))
    return summary


def _writable(folder: Path) -> bool:
    import os
    return os.access(folder, os.W_OK)


def summarise_folder(folder, *, plot: bool = False) -> dict:
    """The summary of a finished or interrupted study in ``folder`` (rewrites its
    summary files when the folder is writable)."""
    from .store import read_store
    store = read_store(folder)
    try:
        return finish(store, plot)
    finally:
        store.close()


def export_folder(folder, path) -> int:
    """Write the cases of the study in ``folder`` to ``path`` (.parquet or .csv); a scan
    library's files as its study names them."""
    from .store import export, read_store
    store = read_store(folder)
    try:
        return export(store, path)
    finally:
        store.close()
