"""Warming a worker for a scan library (``kind = "files"``) before its first batch.

A worker's first derive of a scan loads the facet kernels from numba's cache (the
parallel sweep and its OpenMP set-up: about 0.6 s of CPU, more than ten cases of a
256 x 256 scan), which the first batch would otherwise pay and the batch sizes would
learn from.  :func:`synthetic_scan` gives a small synthetic height map (:data:`SIDE` x
:data:`SIDE`, a random walk, in a temporary ``.npy``) and the study's spec to read it
with its own options (``unit`` and ``pixel_size`` set when the study leaves them to the
files): one case on it runs the same reader, preparation, facet and derive kernels as a
real case, in a few milliseconds whatever the size of the library's scans.  Its result
is thrown away; a synthetic map the options refuse (a despike window wider than it, say)
only warms less.
"""
from __future__ import annotations

import contextlib
import tempfile
import warnings
from pathlib import Path

import numpy as np

#: pixels on a side of the synthetic height map
SIDE = 48


@contextlib.contextmanager
def synthetic_scan(spec: dict):
    """``with synthetic_scan(spec) as (scan_spec, path): run_case(scan_spec, {}, path)``;
    warnings and progress silenced inside, as in a batch."""
    from ..progress import silenced
    rng = np.random.default_rng(0)
    z = np.cumsum(rng.normal(size=(SIDE, SIDE)), axis=1) * 0.02
    z += np.cumsum(rng.normal(size=(SIDE, SIDE)), axis=0) * 0.01
    opts = dict(spec.get("surface") or {})
    if "unit" not in opts or "pixel_size" not in opts:
        opts.update(unit="um", pixel_size=1.0)
    with tempfile.TemporaryDirectory(prefix="asperity-warm-") as tmp, \
            warnings.catch_warnings(), silenced():
        warnings.simplefilter("ignore")            # as in a batch: they reach nobody
        path = Path(tmp) / "warm.npy"
        np.save(path, z.astype(np.float32))
        yield {**spec, "surface": opts}, str(path)
