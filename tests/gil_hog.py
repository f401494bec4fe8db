"""A batch function that first holds the interpreter lock for a long time, as a compiled
kernel does (for the tests of workers that must die with their parent even then: a watch
thread cannot run while another thread holds the lock; the kernel's parent-death signal
still ends the process)."""
from __future__ import annotations

import os
from pathlib import Path

from asperity.study.cases import run_batch

#: the builtin sum over a range runs in C without releasing the lock (about a minute)
HOG = 3 * 10 ** 9
#: folder where each worker notes its process id before it starts hogging
MARKS_ENV = "ASPERITY_TEST_MARKS"


def hogging_batch(spec, names, ids, rows, files=None):
    marks = os.environ.get(MARKS_ENV)
    if marks:
        Path(marks, str(os.getpid())).write_text("hogging")
    sum(range(HOG))
    return run_batch(spec, names, ids, rows, files)
