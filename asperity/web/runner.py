"""Jobs on worker processes: the page submits, a worker computes, the page polls.

The compiled kernels hold the interpreter lock while they run, so the computations run
in separate processes (``spawn``: the parent never forks a process with numba's threads
in it): one :class:`Slot` per worker, each a process fed one job at a time through a
pipe, that ends when the server ends, however it ends (:mod:`asperity.lifeline`: killed
with SIGKILL, the server takes its workers and their study clusters with it; the next
start runs their jobs again, a study resuming its store).  The server's event loop only
hands out jobs and reads records, so a page never waits for a computation.  Queued jobs wait in a first-in first-out queue; their records
say ``queued`` on disk, so a restart finds them and runs them (and the ones that were
running when the server stopped) again.  A worker that dies (out of memory, a crash, a
job stopped from its page) is replaced; its job is tried once more, then failed with
one line.
"""
from __future__ import annotations

import asyncio
import logging
import multiprocessing
import time

from .store import FINISHED, Store, now_iso

log = logging.getLogger("asperity.web")
#: tries of a job whose worker died
MAX_ATTEMPTS = 2


class WorkerDied(Exception):
    pass


class Slot:
    """One worker process and its pipe."""

    def __init__(self):
        self.proc = None
        self.conn = None
        self.start()

    def start(self) -> None:
        """Start the worker process.  Called from the server's main thread only: the worker
        dies with the thread that started it (asperity.lifeline)."""
        import os

        from . import worker
        ctx = multiprocessing.get_context("spawn")
        parent, child = ctx.Pipe()
        self.proc = ctx.Process(target=worker.main, args=(child, os.getpid()),
                                name="asperity-serve-worker", daemon=False)
        self.proc.start()
        child.close()
        self.conn = parent

    def call(self, task: tuple) -> dict:
        """Run ``task`` on the worker (blocking: called from a thread)."""
        try:
            self.conn.send(task)
            while True:
                if self.conn.poll(0.2):
                    return self.conn.recv()
                if not self.proc.is_alive():
                    raise WorkerDied(self.proc.exitcode)
        except (EOFError, OSError, BrokenPipeError):
            raise WorkerDied(self.proc.exitcode) from None

    def kill(self) -> None:
        if self.proc is not None and self.proc.is_alive():
            self.proc.kill()
        if self.proc is not None:
            self.proc.join(timeout=5)
        if self.conn is not None:
            self.conn.close()


class Runner:
    """Hands the jobs of ``store`` to ``workers`` worker processes."""

    def __init__(self, store: Store, workers: int = 2):
        self.store = store
        self.n = max(1, int(workers))
        self.queue: asyncio.Queue | None = None
        self.slots: list[Slot] = []
        self.tasks: list[asyncio.Task] = []
        self.running: dict[str, Slot] = {}
        self.cancelled: set[str] = set()
        self.events: dict[str, asyncio.Event] = {}
        self.stopping = False

    async def start(self) -> None:
        self.queue = asyncio.Queue()
        self.slots = [Slot() for _ in range(self.n)]
        self.tasks = [asyncio.create_task(self._loop(s)) for s in self.slots]
        self.recover()

    def recover(self) -> None:
        """Queue again the jobs that were queued or running when the server stopped (a
        job whose worker had written its result is done)."""
        for rec in reversed(self.store.jobs(status=("queued", "running"), limit=10 ** 6)):
            if rec["status"] == "running" and self.store.result(rec["id"]) is not None:
                res = self.store.result(rec["id"])
                self.store.update(rec["id"], status="done", finished=now_iso(),
                                  files=res.get("files", []))
                continue
            self.store.update(rec["id"], status="queued")
            self.submit(rec["id"])

    def submit(self, jid: str) -> None:
        self.events.setdefault(jid, asyncio.Event())
        self.queue.put_nowait(jid)

    async def wait(self, jid: str, timeout: float) -> dict | None:
        """The job's record once finished, or after ``timeout`` seconds."""
        ev = self.events.get(jid)
        if ev is not None:
            try:
                await asyncio.wait_for(asyncio.shield(ev.wait()), timeout)
            except asyncio.TimeoutError:
                pass
        return self.store.read(jid)

    def cancel(self, jid: str) -> bool:
        """Stop a queued or running job; False if it had finished."""
        rec = self.store.read(jid)
        if rec is None or rec["status"] in FINISHED:
            return False
        self.cancelled.add(jid)
        slot = self.running.get(jid)
        if slot is not None:
            slot.proc.kill()               # the loop sees the worker die and restarts it
        else:
            self._finish(jid, status="cancelled", error="stopped before it started")
        return True

    def _finish(self, jid: str, **changes) -> None:
        rec = self.store.read(jid)
        if rec is not None:
            started = rec.get("started_at") or time.time()
            self.store.update(jid, finished=now_iso(), seconds=round(time.time() - started, 3),
                              **changes)
        ev = self.events.pop(jid, None)
        if ev is not None:
            ev.set()

    async def _loop(self, slot: Slot) -> None:
        while not self.stopping:
            jid = await self.queue.get()
            rec = self.store.read(jid)
            if rec is None or rec["status"] != "queued" or jid in self.cancelled:
                continue
            rec = self.store.update(jid, status="running", started=now_iso(),
                                    started_at=time.time(), attempts=rec["attempts"] + 1)
            task = (rec["kind"], str(self.store.job_dir(jid)), rec["params"],
                    str(self.store.uploads_dir))
            self.running[jid] = slot
            try:
                out = await asyncio.to_thread(slot.call, task)
            except WorkerDied as exc:
                if self.stopping:
                    return
                await asyncio.to_thread(slot.kill)
                slot.start()                   # in the event loop's (main) thread
                if jid in self.cancelled:
                    self._finish(jid, status="cancelled", error="stopped from its page")
                elif rec["attempts"] >= MAX_ATTEMPTS:
                    self._finish(jid, status="failed", error_status=500, error=(
                        f"the process computing this job died (exit code {exc.args[0]}: out "
                        f"of memory, or a crash), twice; ask for less"))
                else:
                    self.store.update(jid, status="queued")
                    self.queue.put_nowait(jid)
                continue
            finally:
                self.running.pop(jid, None)
            if out.get("ok"):
                self._finish(jid, status="done", files=out.get("files", []))
            else:
                self._finish(jid, status="failed", error=out.get("error"),
                             error_status=out.get("status", 422),
                             needs_units=bool(out.get("needs_units")))

    async def stop(self) -> None:
        """Stop the workers (their jobs stay ``running`` on disk: the next start runs
        them again)."""
        self.stopping = True
        for t in self.tasks:
            t.cancel()
        for s in self.slots:
            s.kill()
        self.slots = []
