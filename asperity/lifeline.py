"""Child processes that end when their parent ends, however it ends.

A process that asperity starts (a worker of ``asperity serve``, a Dask worker of a local
cluster) calls :func:`die_with_parent` first thing.  The child watches, not the parent: a
parent killed with SIGKILL (the out-of-memory killer, a crash) can do nothing, so

* on Linux the kernel sends the child SIGKILL when its parent dies (``prctl``
  ``PR_SET_PDEATHSIG``, set through ctypes), even while the child runs a compiled kernel
  that holds the interpreter lock; the parent must start the child from a thread that
  lives as long as the child (the signal follows the thread that forked);
* everywhere, a watch thread sees the child re-parented (its parent id changes) within
  :data:`POLL_SECONDS`, stops the child's own children and ends the child.

Each level watches its own parent, so a whole tree goes: the server's workers die with the
server, the Dask workers of a study a worker runs die with that worker.  A study store
loses nothing by it: its rows are written in transactions, and the store's lock (an
``flock``) is released by the kernel with the last process holding it.

Dask: ``preload=[PRELOAD]`` makes every worker of a ``LocalCluster`` call
:func:`die_with_parent` (its nanny lives in the client, so the client is its parent).
"""
from __future__ import annotations

import os
import signal
import sys
import threading

#: seconds between two looks of the watch thread at the parent
POLL_SECONDS = 0.25
#: the module Dask workers preload (its :func:`dask_setup` runs in each new worker)
PRELOAD = "asperity.lifeline"
PR_SET_PDEATHSIG = 1

_watching: list[int] = []


def _prctl():
    if not sys.platform.startswith("linux"):
        return None
    try:
        import ctypes
        return ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None


def parent_death_signal(sig: int = signal.SIGKILL) -> bool:
    """Ask the kernel to send ``sig`` to this process when its parent dies (Linux only);
    True when it is set."""
    prctl = _prctl()
    return prctl is not None and prctl(PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0


def preexec():
    """A ``preexec_fn`` for :mod:`subprocess`: the child gets SIGKILL when the thread that
    starts it ends (start it from the main thread); None where that is not available."""
    prctl = _prctl()                           # looked up here, not in the forked child
    if prctl is None:
        return None
    return lambda: prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)


def original_parent() -> int:
    """The id of the process that started this one: multiprocessing's parent when this is
    a multiprocessing child (the id is known even if the parent died already), else the
    current parent."""
    import multiprocessing
    parent = multiprocessing.parent_process()
    return parent.pid if parent is not None and parent.pid else os.getppid()


def children_of(pid: int) -> list[int]:
    """Every descendant of process ``pid`` (Linux /proc; empty elsewhere)."""
    out, todo = [], [pid]
    while todo:
        q = todo.pop()
        try:
            tasks = os.listdir(f"/proc/{q}/task")
        except OSError:
            continue
        for t in tasks:
            try:
                with open(f"/proc/{q}/task/{t}/children", encoding="ascii") as fh:
                    kids = [int(x) for x in fh.read().split()]
            except (OSError, ValueError):
                continue
            out += kids
            todo += kids
    return out


def _end(code: int = 1) -> None:
    """End this process now, and its children first (they would only be orphaned)."""
    for pid in children_of(os.getpid()):
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    os._exit(code)


def die_with_parent(parent: int | None = None) -> None:
    """End this process (and its children) as soon as process ``parent`` (default: the one
    that started it) is gone.  Idempotent; call it from the main thread."""
    parent = original_parent() if parent is None else int(parent)
    if parent in _watching:
        return
    _watching.append(parent)
    parent_death_signal()
    if os.getppid() != parent:                 # gone before the signal was asked for
        _end()

    def watch():
        import time
        while True:
            time.sleep(POLL_SECONDS)
            if os.getppid() != parent:
                _end()

    threading.Thread(target=watch, name="asperity-lifeline", daemon=True).start()


def dask_setup(worker=None) -> None:
    """Dask preload hook: a worker of a local cluster dies with the process that started
    it (the client, where its nanny runs), and ignores Ctrl-C: a terminal sends SIGINT to
    the whole foreground group, and the worker would die with a traceback of its event
    loop while its client is still closing it (the client stops its workers itself)."""
    die_with_parent()
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:                         # not the main thread: nothing to undo
        pass
