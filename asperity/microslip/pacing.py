"""Pieces of a long kernel run: a numba kernel cannot be interrupted, so the chain solvers
march their load points or time steps in pieces, each aimed at :data:`TARGET_SECONDS`
(Python honours Ctrl-C and reports progress between two pieces).  The kernels carry their
whole state from one piece to the next, so the size of the pieces never changes a result.
"""
from __future__ import annotations

import time

#: aimed duration of one piece, s (Ctrl-C is honoured within about this)
TARGET_SECONDS = 0.1


class Pacer:
    """Sizes of consecutive pieces: the first ``first`` units, then as many as the measured
    rate fits in :data:`TARGET_SECONDS` (growing at most 4 x per piece).

    Use: ``k = pacer.size()``, run k units, ``pacer.done(k)``.
    """

    def __init__(self, first: int, most: int = 1 << 40):
        self.next = max(1, int(first))
        self.most = max(1, int(most))
        self.t0 = time.perf_counter()

    def size(self, left: int | None = None) -> int:
        k = min(self.next, self.most)
        self.t0 = time.perf_counter()
        return k if left is None else max(1, min(k, int(left)))

    def done(self, units: int) -> None:
        took = time.perf_counter() - self.t0
        units = max(1, int(units))
        if took <= 1e-4:
            grow = 4 * units
        else:
            grow = min(4 * units, int(units * TARGET_SECONDS / took))
        self.next = max(1, min(grow, self.most))
