"""What every height map read in lines offers (:mod:`._streams`, :mod:`.text`,
:mod:`asperity.surface.tiles`)."""
from __future__ import annotations

from pathlib import Path

import numpy as np


class LineSource:
    """Lines of a height map (or of a per-pixel map) on disk.

    shape  : (nx, ny) of the map; ``axis``: 0 if a line is heights[i, :], 1 if heights[:, j]
    dx, dy : pixel size, m (None for a friction map); ``source``: the name shown
    """

    axis = 0
    streams = True                 # tiles are read from the file (workers can read them)

    def __init__(self, path, shape, dx, dy, source):
        self.path = str(Path(path).resolve())
        self.shape = (int(shape[0]), int(shape[1]))
        self.dx, self.dy = dx, dy
        self.source = source

    @property
    def n_lines(self) -> int:
        return self.shape[self.axis]

    def close(self) -> None:
        """Close the file handles kept between reads (none here; a later read reopens)."""

    def lines(self, a: int, b: int) -> np.ndarray:
        """float64 heights[a:b, :] (axis 0) or heights[:, a:b] (axis 1), m, NaN undefined."""
        raise NotImplementedError

    def block(self, axis: int, a: int, b: int) -> np.ndarray:
        """heights[a:b, :] (``axis`` 0) or heights[:, a:b] (``axis`` 1), whatever the
        file's own lines (across them: read in pieces of lines)."""
        if axis == self.axis:
            return self.lines(a, b)
        n = self.n_lines
        out = np.empty((b - a, self.shape[1]) if axis == 0 else (self.shape[0], b - a))
        step = max(1, (4 << 20) // max(1, self.shape[1 - self.axis]))
        for s in range(0, n, step):
            e = min(n, s + step)
            part = self.lines(s, e)
            if axis == 0:
                out[:, s:e] = part[a:b, :]
            else:
                out[s:e, :] = part[:, a:b]
        return out

    def __getstate__(self):
        return {k: v for k, v in self.__dict__.items() if not k.startswith("_h")}
