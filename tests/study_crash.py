"""A batch function that kills its worker process when it meets case CRASH_CASE, as an
out-of-memory kill or a crash in compiled code would (for tests of the study engine)."""
from __future__ import annotations

import os

from asperity.study.cases import run_batch

CRASH_CASE = 13


def crashing_batch(spec, names, ids, rows, files=None):
    if CRASH_CASE in ids:
        os._exit(1)
    return run_batch(spec, names, ids, rows, files)
