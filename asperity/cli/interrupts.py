"""SIGTERM handled as Ctrl-C is.

Python turns Ctrl-C (SIGINT) into KeyboardInterrupt, so a command stops between two
pieces of work, its outputs uncommitted, its Dask cluster closed, its study store
consistent, and :func:`asperity.cli.main.main` prints one line.  SIGTERM (``kill``, a
batch system, a container stopping) ends a Python process at once by default: no line,
outputs left as they were but the cluster's workers and semaphores leaked (the
multiprocessing resource tracker warns about them).  Inside :class:`terminate_as_interrupt`
SIGTERM raises :class:`Terminated`, a KeyboardInterrupt, so everything that cleans up on
Ctrl-C cleans up on SIGTERM too; the command exits with :data:`EXIT_TERMINATED`.  A second
SIGTERM during that cleanup is ignored (SIGKILL remains to force it).
"""
from __future__ import annotations

import signal
import threading

#: exit status after Ctrl-C (128 + SIGINT)
EXIT_INTERRUPTED = 130
#: exit status after SIGTERM (128 + SIGTERM)
EXIT_TERMINATED = 143


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived (raised where Ctrl-C would raise KeyboardInterrupt)."""


class terminate_as_interrupt:
    """Within the block SIGTERM raises :class:`Terminated`; ``received`` tells afterwards
    whether it came (library code may turn the KeyboardInterrupt into its own, such as a
    study's StudyInterrupted).  Outside the main thread (where no handler can be set) a
    no-op."""

    def __init__(self):
        self.received = False
        self._old = None

    def _handler(self, signum, frame):
        if self.received:
            return                               # cleaning up after the first one
        self.received = True
        raise Terminated("SIGTERM")

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            self._old = signal.signal(signal.SIGTERM, self._handler)
        return self

    def __exit__(self, *exc):
        if self._old is not None:
            signal.signal(signal.SIGTERM, self._old)
            self._old = None
        return False
