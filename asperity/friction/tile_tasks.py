"""The work on one tile of a scan, for every pass of :mod:`asperity.friction.tiled`: run in
this process or as Dask tasks (:func:`run_tiles` is what a worker runs; it reads its tiles
from the file path itself).

Passes (``kind``):

* ``prep`` -- spikes found, undefined pixels counted, height range, the normal equations of
  a least-squares form, the facet gradient sums of the mean-slope removal, the friction
  map's largest value (and its bad values);
* ``zrange`` / ``zhist`` / ``zcollect`` -- the centroid heights of the facets that can
  carry load, to place the rest level of a bearing fraction exactly;
* ``sweep`` -- the facets with their weights, then *jobs*: facet-kernel sums for a set of
  directions in a contact mode, or the locked weight for the load share; with the
  facets' figures (counts per cell row, slope statistics, preview) when asked.

Each tile's kernel calls use :data:`TILE_WORKERS` accumulators whatever the threads
(:func:`asperity.friction.facet_reservoir._numba_pass`), so a tile's sums are the same in
this process and on a single-threaded worker: the tiled result does not depend on where
it ran.
"""
from __future__ import annotations

import numpy as np

from ..surface import tiles as T
from ..surface.friction_map import bad_mu

#: accumulators of a tile's kernel calls (the threads share them out)
TILE_WORKERS = 32
#: directions per kernel call at most (the accumulators: TILE_WORKERS x this x 48 bytes)
MAX_BATCH_DIRECTIONS = 16384


def run_tiles(kind: str, plan, tiles, args=(), tick=None) -> list:
    """Results of pass ``kind`` for the tiles ``tiles`` of ``plan``, in order.
    ``tick(fraction)`` reports progress within the tiles (in-process runs)."""
    fn = PASSES[kind]
    out = []
    for i, t in enumerate(tiles):
        sub = None if tick is None else \
            (lambda f, i=i: tick((i + f) / len(tiles)))
        out.append(fn(plan, t, *args, tick=sub))
    return out


def prep_tile(plan, t, degree, want_slope, tick=None) -> dict:
    r = T.read_tile(plan, t, judge=True)
    z = r.pop("z")
    src = plan.heights
    l0, l1 = plan.bounds(t)
    if degree is not None:
        from ..surface.detrend import FormFit
        fit = FormFit(degree, *src.shape)
        own = z[:l1 - l0] if src.axis == 0 else z[:, :l1 - l0]
        fit.add(own, *T.tile_origin(plan, t))
        r.update(gram=fit.gram, rhs=fit.rhs, count=fit.count)
    g, ok = T.gradients(plan, z)
    r["n_ok"] = int(np.count_nonzero(ok))
    if want_slope:
        r["sum_g"] = (float(g[0][ok].sum()), float(g[1][ok].sum()))
    m = T.mu_block(plan, t)
    if m is not None:
        from ..surface.grid_facets import facet_mu
        r["bad_mu"] = bad_mu(m)
        fm = facet_mu(m)[ok]
        r["mu_max"] = float(fm.max()) if fm.size else 0.0
    return r


def _candidates(plan, t) -> np.ndarray:
    """Centroid heights of tile t's facets that can carry load (defined, not too steep)."""
    from ..surface.quality import steep_facets
    z = T.read_tile(plan, t)["z"]
    g, ok = T.gradients(plan, z)
    steep = steep_facets(g[0], g[1], plan.max_slope)
    if steep is not None:
        ok &= ~steep
    return T.centroids(plan, t, z)[ok]


def zrange_tile(plan, t, tick=None) -> tuple:
    zc = _candidates(plan, t)
    return (zc.size, float(zc.min()) if zc.size else np.inf,
            float(zc.max()) if zc.size else -np.inf)


def bin_index(zc: np.ndarray, levels) -> np.ndarray | None:
    """Bin of each value at the last of ``levels`` [(lo, hi, nbins, b0, b1), ...], -1 where
    a value falls outside the selected bins b0..b1 of an earlier level."""
    keep = np.ones(zc.size, dtype=bool)
    idx = None
    for k, (lo, hi, nb, b0, b1) in enumerate(levels):
        span = hi - lo
        idx = np.clip(((zc - lo) * (nb / span)).astype(np.int64) if span > 0 else
                      np.zeros(zc.size, np.int64), 0, nb - 1)
        if k < len(levels) - 1:
            keep &= (idx >= b0) & (idx <= b1)
    return np.where(keep, idx, -1)


def zhist_tile(plan, t, levels, tick=None) -> np.ndarray:
    idx = bin_index(_candidates(plan, t), levels)
    return np.bincount(idx[idx >= 0], minlength=levels[-1][2])


def zcollect_tile(plan, t, levels, tick=None) -> np.ndarray:
    zc = _candidates(plan, t)
    idx = bin_index(zc, levels)
    b0, b1 = levels[-1][3], levels[-1][4]
    return np.sort(zc[(idx >= b0) & (idx <= b1)])


def sweep_tile(plan, t, jobs, figures=False, tick=None) -> dict:
    """Facets of tile t, then each job: ("sweep", mode, psi) -> (sums, first) or
    ("lockw", windward, psi) -> (m, 2) locked and loaded weights."""
    r = T.read_tile(plan, t)
    z = r["z"]
    tf = T.tile_facets(plan, t, z, T.mu_block(plan, t))
    out = {"n": tf.w.size, "counts": tf.counts, "row0": tf.row0}
    if figures:
        out.update(n_ok=tf.n_ok, n_unloaded=tf.n_unloaded, stats=tf.stats,
                   wsum=float(tf.w.sum()), preview=T.preview_part(plan, t, z),
                   zc_max=tf.zc_max)
    del r, z
    fac = None
    if tf.w.size:
        from .facet_reservoir import _Facets
        fac = _Facets(tf.g[0], tf.g[1], tf.mu, tf.w)
    del tf
    out["jobs"] = [_job(fac, job, None if tick is None else
                        (lambda f, k=k: tick((k + f) / len(jobs))))
                   for k, job in enumerate(jobs)]
    return out


def _job(fac, job, tick):
    kind, mode, psi = job
    m = psi.size
    if kind == "lockw":
        if fac is None:
            return np.zeros((m, 2))
        from .diagnostics import locked_weights
        return locked_weights(fac.gx, fac.gy, fac.mu, fac.mu_uniform, fac.w, psi, mode, tick)
    from ._facet_kernels import N_ACC
    from .facet_reservoir import _auto_batch, _numba_pass
    sums = np.zeros((m, N_ACC))
    first = np.full(m, -1, dtype=np.int64)
    if fac is None:
        return sums, first
    cs, ss = np.cos(psi), np.sin(psi)
    b = min(_auto_batch(fac.n, m), MAX_BATCH_DIRECTIONS)
    for s in range(0, m, b):
        e = min(m, s + b)
        sub = None if tick is None else (lambda f, s=s, e=e: tick((s + f * (e - s)) / m))
        sums[s:e], first[s:e] = _numba_pass(fac, cs[s:e], ss[s:e], mode, sub,
                                            workers=TILE_WORKERS)
    return sums, first


PASSES = {"prep": prep_tile, "zrange": zrange_tile, "zhist": zhist_tile,
          "zcollect": zcollect_tile, "sweep": sweep_tile}
