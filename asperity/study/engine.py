"""The study engine: the cases of a study in batches on a Dask cluster, into the store.

* Where: ``workers=0`` runs in this process (no cluster: small sweeps, debugging);
  otherwise an embedded ``dask.distributed.LocalCluster`` (``workers`` processes, default
  one per core, at most what the cores and the free memory allow, on 127.0.0.1, stopped
  at the end and dying with this process), or an existing cluster given by its scheduler
  address (``tcp://HOST:PORT``) or scheduler file, e.g. from ``dask scheduler`` / ``dask
  worker``, dask-jobqueue on SLURM or a Kubernetes deployment (:mod:`.clusters`).  The
  same study gives the same results everywhere.
* Batches: cases are grouped into tasks of about :data:`TARGET_SECONDS` each (the size
  adapts to the measured cost per case), so that microsecond cases are not dominated by
  the scheduler; at most a few batches per worker are in flight, so memory stays bounded
  for any number of cases.  Scans are read by the worker from their path.
* Faults: a batch whose worker dies is rerun by Dask on another worker (and the worker
  replaced by its nanny); a batch that kills its workers repeatedly is split until the
  case that does it is found; that case is run once more alone (it may only have shared a
  worker with the culprit) and stored as failed with the reason if it kills it again.
* Stores: the client writes each finished batch in one transaction; Ctrl-C or a kill
  loses at most the batches in flight, and the same command resumes.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import check_int
from .cases import run_batch, warm_up
from .clusters import SCHEDULER_ENV, EngineError, cluster, resolve_scheduler  # noqa: F401
from .clusters import close as _close
from .clusters import connect as _connect

#: seconds of work per task the batch size aims at
TARGET_SECONDS = 1.0
#: cases in the first batches, before the cost per case is known
FIRST_BATCH = {"files": 1, "default": 16}
#: largest batch
MAX_BATCH = 20_000
#: batches in flight per worker
IN_FLIGHT_PER_WORKER = 3
#: memory of a scan library's case per byte of its file: the facets of a height map with a
#: rest level (200 bytes a pixel) over the densest file format (4 bytes a pixel, float32)
SCAN_BYTES_PER_FILE_BYTE = 50


class StudyInterrupted(KeyboardInterrupt):
    """Ctrl-C during a study; the message says what the store holds."""


@dataclass
class RunReport:
    cases: int
    ran: int                   # cases run by this call
    stored: int                # cases in the store after it
    seconds: float
    where: str                 # "in-process", "LocalCluster (2 workers)", "tcp://..."
    workers: int
    startup_seconds: float = 0.0   # starting or reaching the cluster
    shutdown_seconds: float = 0.0  # closing it (a local cluster's workers exit: ~0.3-1 s)


class Batcher:
    """Hands out the case ids still to run, in batches sized from the measured cost."""

    def __init__(self, todo: np.ndarray, fixed: int | None, first: int, workers: int):
        self.todo = todo
        self.pos = 0
        self.fixed = fixed
        self.size = fixed or first
        self.workers = max(1, workers)
        self.per_case = None

    def left(self) -> int:
        return self.todo.size - self.pos

    def next(self) -> np.ndarray | None:
        if self.pos >= self.todo.size:
            return None
        n = self.size
        if not self.fixed:            # keep every worker busy until the end
            n = min(n, max(1, self.left() // (2 * self.workers)))
        ids = self.todo[self.pos:self.pos + n]
        self.pos += ids.size
        return ids

    def learn(self, n_cases: int, seconds: float) -> None:
        """A batch of ``n_cases`` took ``seconds`` of case time: resize."""
        if self.fixed or n_cases == 0:
            return
        c = max(seconds / n_cases, 1e-7)
        self.per_case = c if self.per_case is None else 0.7 * self.per_case + 0.3 * c
        self.size = int(min(MAX_BATCH, max(1, TARGET_SECONDS / self.per_case)))


def run_study(study, store, *, scheduler: str | None = None, workers: int | None = None,
              batch_size: int | None = None, task=None) -> RunReport:
    """Run every case of ``study`` missing from ``store``.  ``task``: the function a
    worker runs on a batch (default :func:`asperity.study.cases.run_batch`; tests give one
    that crashes its worker)."""
    task = task or run_batch
    from .. import progress
    t0 = time.perf_counter()
    n = study.n_cases
    done = store.done_ids()
    todo = np.setdiff1d(np.arange(n, dtype=np.int64), done, assume_unique=True)
    matrix = study.matrix()
    names = study.parameter_names
    files = study.case_files if study.kind == "files" else None

    def inputs_of(cid):
        values = tuple(float(v) for v in matrix[cid]) if names else ()
        return values if files is None else (files[cid], *values)

    if workers is not None:
        workers = check_int("--workers", workers, 0, 4096)
    if scheduler is not None or workers is None:     # --workers N: a local cluster (or,
        scheduler = resolve_scheduler(scheduler)     # 0, this process), never $ASPERITY_...
    if batch_size is None:
        batch_size = study.batch_size
    first = FIRST_BATCH["files" if files is not None else "default"]
    stored = done.size
    label = f"study ({done.size} stored before)" if done.size else "study"
    progress.report(0.0, label)
    if todo.size == 0:
        return RunReport(n, 0, stored, time.perf_counter() - t0, "nothing to run", 0)

    def finished(results):
        nonlocal stored
        if hasattr(results, "outputs") and names and files is None:
            results.inputs = matrix[np.asarray(results.ids, np.int64)].tolist()   # a block
        store.write(results, inputs_of)
        stored += len(results)
        progress.report((stored - done.size) / todo.size, label)   # of this run: a true ETA

    def task_args(ids):
        rows = matrix[ids] if names else None
        fl = [files[i] for i in ids] if files is not None else None
        return (study.spec, names, ids, rows, fl)    # an array: dask does not walk it

    timing = {"startup": 0.0}
    try:
        if scheduler is None and workers == 0:
            batcher = Batcher(todo, batch_size, first, 1)
            where, nw = "in-process", 1
            while (ids := batcher.next()) is not None:
                res = task(*task_args(ids))
                batcher.learn(len(res), case_seconds(res))
                finished(res)
        else:
            where, nw = _run_dask(todo, task_args, finished, scheduler, workers, batch_size,
                                  first, timing, task, worker_bytes(study))
    except KeyboardInterrupt:
        raise StudyInterrupted(f"{stored} of {n} cases stored in {store.folder}; run the same "
                               f"command again to resume") from None
    return RunReport(n, stored - done.size, stored, time.perf_counter() - t0, where, nw,
                     timing["startup"], timing.get("shutdown", 0.0))


def case_seconds(results) -> float:
    """The summed case seconds of a task's results (a block's by column)."""
    total = getattr(results, "total_seconds", None)
    return float(total) if total is not None else float(sum(r[3] for r in results))


def worker_bytes(study) -> float:
    """Memory of a local worker running ``study``'s cases: a warm worker, plus for a scan
    library its largest scan's facets (:data:`SCAN_BYTES_PER_FILE_BYTE`)."""
    from ..resources import WORKER_BYTES
    if study.kind != "files" or not study.files:
        return float(WORKER_BYTES)
    import os
    sizes = [os.stat(f).st_size if os.path.isfile(f) else 0 for f in study.files]
    return float(WORKER_BYTES + SCAN_BYTES_PER_FILE_BYTE * max(sizes))


def _run_dask(todo, task_args, finished, scheduler, workers, batch_size, first, timing, task,
              per_worker=None):
    from distributed import as_completed
    from distributed.client import FutureCancelledError
    try:
        from distributed.scheduler import KilledWorker
    except ImportError:                               # pragma: no cover
        from distributed import KilledWorker
    t0 = time.perf_counter()
    client, cluster, where, nw = _connect(scheduler, workers, per_worker)
    try:
        spec, names, ids, rows, fl = task_args(todo[:1])
        client.run(warm_up, spec, None if fl else dict(zip(names, map(float, rows[0])))
                   if names else {})
    except (ImportError, AttributeError) as exc:
        _close(client, cluster)
        raise EngineError(f"the workers cannot run asperity ({type(exc).__name__}: {exc}); "
                          f"install the same asperity on every worker") from None
    timing["startup"] = time.perf_counter() - t0
    batcher = Batcher(todo, batch_size, first, nw)
    ac = as_completed()
    in_flight = {}                    # future key -> (case ids, future)
    quarantine = []

    def submit(ids):
        fut = client.submit(task, *task_args(ids), pure=False)
        in_flight[fut.key] = (ids, fut)
        ac.add(fut)

    def refill():
        ids = batcher.next()
        if ids is not None:
            submit(ids)

    try:
        for _ in range(IN_FLIGHT_PER_WORKER * nw):
            refill()
        while not ac.is_empty():
            fut = next(ac)
            ids, _ = in_flight.pop(fut.key)
            try:
                res = fut.result()
            except KilledWorker:
                if ids.size > 1:                      # find the case that kills workers
                    half = ids.size // 2
                    submit(ids[:half])
                    submit(ids[half:])
                else:                                 # it may only have shared a worker
                    quarantine.append(ids)            # with the culprit: rerun it alone
                refill()
                continue
            except FutureCancelledError:
                raise EngineError("the cluster cancelled the study's tasks") from None
            except (ImportError, AttributeError) as exc:
                raise EngineError(f"the workers cannot run asperity ({type(exc).__name__}: "
                                  f"{exc}); install the same asperity on every worker") from None
            batcher.learn(len(res), case_seconds(res))
            finished(res)
            fut.release()
            refill()
        for ids in quarantine:        # each alone on the cluster: only a culprit dies now
            fut = client.submit(task, *task_args(ids), pure=False)
            try:
                res = fut.result()
            except KilledWorker:
                res = [(int(ids[0]), "failed", "the worker running this case died, also "
                        "when it ran alone (out of memory or a crash)", 0.0, {})]
            finished(res)
    finally:
        for _, f in in_flight.values():
            f.cancel()
        t1 = time.perf_counter()
        _close(client, cluster)
        timing["shutdown"] = time.perf_counter() - t1
    return where, nw
