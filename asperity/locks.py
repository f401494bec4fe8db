"""Exclusive locks on a study folder or a data folder that are never stuck.

:func:`lock_file` takes an ``flock`` on a lock file: the kernel frees it when the holder
ends, however it ends (SIGKILL included), so a crashed run never leaves a lock behind.
The file names its holder (process id and host), for the message a second run gets, and
so that a lock kept by a descriptor that outlived its holder (a forked child still
running) is recognised and taken over.
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path


#: seconds a lock held by another process is waited for before refusing (a holder whose
#: parent was killed ends within a fraction of this: see asperity.lifeline)
LOCK_WAIT_SECONDS = 3.0


def lock_file(path: str | Path, error: BaseException, wait: float | None = None):
    """An exclusive lock on ``path`` (created if missing), held as long as the returned
    handle is open; ``error`` (its message completed with the holder's process id) is
    raised when another process still holds it after ``wait`` seconds (default
    :data:`LOCK_WAIT_SECONDS`).

    The lock is an ``flock``: the kernel frees it when its holder ends, however it ends.
    The file names the holder (process id and host); a lock that another process holds
    through a descriptor inherited from a holder that has ended (a forked child left
    running) is taken over: the file is replaced by a new one, which is locked instead."""
    import fcntl
    import socket
    import time
    wait = LOCK_WAIT_SECONDS if wait is None else wait
    deadline = time.monotonic() + wait
    host = socket.gethostname()
    suspect = None
    while True:
        fh = open(path, "a+")                      # noqa: SIM115 - the caller holds it
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.seek(0)
            holder = fh.read(200).split()
            seen = (os.fstat(fh.fileno()).st_ino, tuple(holder))
            fh.close()
            ended = len(holder) == 2 and holder[1] == host and holder[0].isdigit() \
                and not _alive(int(holder[0]))
            if ended:
                if seen == suspect:                # the same ended holder twice, 50 ms
                    _replace_lock(path)            # apart: not a new holder about to
                    suspect = None                 # write its id
                    continue
                suspect = seen
            if time.monotonic() >= deadline:
                who = "" if not holder or not holder[0].isdigit() else \
                    f" (process {holder[0]}{', which has ended' if ended else ''})"
                raise type(error)(f"{error}{who}") from None
            time.sleep(0.05)
            continue
        try:
            same = os.fstat(fh.fileno()).st_ino == os.stat(path).st_ino
        except OSError:
            same = False
        if not same:                               # replaced or removed meanwhile: again
            fh.close()
            continue
        fh.truncate(0)
        fh.write(f"{os.getpid()} {host}\n")
        fh.flush()
        return fh


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:                                # another user's process: alive
        return True
    return True


def _replace_lock(path) -> None:
    fd, tmp = tempfile.mkstemp(prefix=".lock.", dir=os.path.dirname(os.path.abspath(path)))
    os.close(fd)
    try:
        os.replace(tmp, path)
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
