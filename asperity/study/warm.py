"""Warming a worker for a scan library (``kind = "files"``) before its first batch.

A worker's first derive of a scan loads the facet kernels from numba's cache (the
parallel sweep and its OpenMP set-up: about 0.6 s of CPU, more than ten cases of a
256 x 256 scan), which the first batch would otherwise pay and the batch sizes would
learn from.  :func:`warm_scan` runs the study's stages once on a small synthetic height
map (:data:`SIDE` x :data:`SIDE`, a random walk, in a temporary ``.npy``) read with the
study's own options (``unit`` and ``pixel_size`` set when the study leaves them to the
files): the same reader, preparation, facet and derive kernels as a real case, for a few
milliseconds and whatever the size of the library's scans.  The result is thrown away;
a synthetic map the options refuse (a despike window wider than it, say) only warms less.
"""
from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

#: pixels on a side of the synthetic height map
SIDE = 48


def warm_scan(spec: dict, values: dict | None = None) -> str:
    """Run one case of ``spec`` on a synthetic scan; its status ("ok", "failed", ...)."""
    import warnings

    from ..progress import silenced
    from .cases import run_case
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
        return run_case({**spec, "surface": opts}, dict(values or {}), str(path))[0]
