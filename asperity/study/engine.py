"""The study engine: the cases of a study in batches on a Dask cluster, into the store.

* Where: ``workers=0`` runs in this process (no cluster: small sweeps, debugging);
  otherwise an embedded ``dask.distributed.LocalCluster`` (``workers`` processes, default
  one per core, on 127.0.0.1, stopped at the end), or an existing cluster given by its
  scheduler address (``tcp://HOST:PORT``) or scheduler file, e.g. from ``dask scheduler``
  / ``dask worker``, dask-jobqueue on SLURM or a Kubernetes deployment.  The same study
  gives the same results everywhere.
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

import logging
import os
import time
from dataclasses import dataclass

import numpy as np

from ..errors import AsperityError, InputError, check_int
from .cases import run_batch, warm_up

#: seconds of work per task the batch size aims at
TARGET_SECONDS = 1.0
#: cases in the first batches, before the cost per case is known
FIRST_BATCH = {"files": 1, "default": 16}
#: largest batch
MAX_BATCH = 20_000
#: batches in flight per worker
IN_FLIGHT_PER_WORKER = 3
#: environment variable naming a scheduler address (or scheduler file) for every study
SCHEDULER_ENV = "ASPERITY_SCHEDULER"


class EngineError(AsperityError):
    """The cluster cannot be reached or cannot run asperity's tasks."""


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


def resolve_scheduler(scheduler: str | None) -> str | None:
    """The scheduler to use: the argument, else $ASPERITY_SCHEDULER, else None (embedded)."""
    s = scheduler if scheduler is not None else os.environ.get(SCHEDULER_ENV) or None
    if s is not None and (not isinstance(s, str) or not s.strip()):
        raise InputError("--scheduler must be an address such as tcp://10.0.0.5:8786 or a "
                         "scheduler file")
    return s.strip() if s else None


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
    files = study.files if study.kind == "files" else None

    def inputs_of(cid):
        return (files[cid],) if files is not None else tuple(float(v) for v in matrix[cid])

    if workers is not None:
        workers = check_int("--workers", workers, 0, 4096)
    if not (workers == 0 and scheduler is None):     # --workers 0: in this process, always
        scheduler = resolve_scheduler(scheduler)
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
        store.write(results, inputs_of)
        stored += len(results)
        progress.report((stored - done.size) / todo.size, label)   # of this run: a true ETA

    def task_args(ids):
        rows = matrix[ids] if names else None
        fl = [files[i] for i in ids] if files is not None else None
        return (study.spec, names, ids.tolist(), rows, fl)

    timing = {"startup": 0.0}
    try:
        if scheduler is None and workers == 0:
            batcher = Batcher(todo, batch_size, first, 1)
            where, nw = "in-process", 1
            while (ids := batcher.next()) is not None:
                res = task(*task_args(ids))
                batcher.learn(len(res), sum(r[3] for r in res))
                finished(res)
        else:
            where, nw = _run_dask(todo, task_args, finished, scheduler, workers, batch_size,
                                  first, timing, task)
    except KeyboardInterrupt:
        raise StudyInterrupted(f"{stored} of {n} cases stored in {store.folder}; run the same "
                               f"command again to resume") from None
    return RunReport(n, stored - done.size, stored, time.perf_counter() - t0, where, nw,
                     timing["startup"])


def _connect(scheduler, workers):
    """(client, cluster or None, description, number of workers)."""
    import distributed
    logging.getLogger("distributed").setLevel(logging.ERROR)
    if scheduler is None:
        nw = workers or os.cpu_count() or 1
        import warnings
        try:
            # one core per worker: the numba kernels must not start a thread per core in
            # every worker (oversubscription)
            with warnings.catch_warnings():     # e.g. a note on a busy port: not the user's
                warnings.simplefilter("ignore")
                cluster = distributed.LocalCluster(
                    n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1",
                    dashboard_address=None, silence_logs=logging.ERROR,
                    env={"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"})
        except OSError as exc:
            raise EngineError(f"cannot start a local Dask cluster ({exc})") from None
        return distributed.Client(cluster), cluster, f"LocalCluster ({nw} workers)", nw
    _reachable(scheduler)
    try:
        if os.path.isfile(scheduler):
            client = distributed.Client(scheduler_file=scheduler, timeout="10s")
        else:
            client = distributed.Client(scheduler, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise EngineError(f"cannot reach the Dask scheduler at {scheduler!r} "
                          f"({' '.join(str(exc).split())[:200]})") from None
    try:
        client.wait_for_workers(1, timeout=60)
    except (TimeoutError, OSError):
        client.close()
        raise EngineError(f"the Dask scheduler at {scheduler!r} has no workers (waited 60 s); "
                          f"start some with: dask worker {scheduler}") from None
    nw = len(client.scheduler_info(n_workers=-1)["workers"])
    return client, None, scheduler, nw


class cluster:
    """A Dask client for other work than studies (e.g. the tiles of one huge scan): the
    same choice as :func:`run_study` -- ``scheduler`` (or $ASPERITY_SCHEDULER) an existing
    cluster, else a LocalCluster of ``workers`` single-threaded processes on 127.0.0.1 --
    closed at the end.  ``with cluster(None, 2) as (client, where, n_workers): ...``"""

    def __init__(self, scheduler: str | None = None, workers: int | None = None):
        self.scheduler = resolve_scheduler(scheduler)
        self.workers = None if workers is None else check_int("--workers", workers, 1, 4096)

    def __enter__(self):
        self.client, self.local, where, nw = _connect(self.scheduler, self.workers)
        return self.client, where, nw

    def __exit__(self, *exc):
        _close(self.client, self.local)
        return False


def _reachable(scheduler: str) -> None:
    """Fail at once, in one line, when a tcp:// scheduler address refuses connections
    (Dask itself retries until its timeout)."""
    import socket
    from urllib.parse import urlsplit
    if os.path.isfile(scheduler) or "://" not in scheduler:
        return
    u = urlsplit(scheduler)
    if u.scheme != "tcp" or not u.hostname or not u.port:
        return
    try:
        socket.create_connection((u.hostname, u.port), timeout=10).close()
    except OSError as exc:
        raise EngineError(f"cannot reach the Dask scheduler at {scheduler!r} "
                          f"({exc.strerror or type(exc).__name__}); start it with `dask "
                          f"scheduler` or check the address") from None


def _run_dask(todo, task_args, finished, scheduler, workers, batch_size, first, timing, task):
    from distributed import as_completed
    from distributed.client import FutureCancelledError
    try:
        from distributed.scheduler import KilledWorker
    except ImportError:                               # pragma: no cover
        from distributed import KilledWorker
    t0 = time.perf_counter()
    client, cluster, where, nw = _connect(scheduler, workers)
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
            batcher.learn(len(res), sum(r[3] for r in res))
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
        _close(client, cluster)
    return where, nw


def _close(client, cluster) -> None:
    import contextlib
    with contextlib.suppress(Exception):
        client.close(timeout=5)
    if cluster is not None:
        with contextlib.suppress(Exception):
            cluster.close(timeout=5)
