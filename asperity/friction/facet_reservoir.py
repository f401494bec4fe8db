"""Reservoir points of many plane facets (measured surfaces), memory-bounded.

:func:`compute_facet_reservoir` gives the same :class:`~asperity.friction.reservoir.Reservoir` as
the NumPy reference :func:`~asperity.friction.faces.compute_face_reservoir` (same formulas,
``LEVEL_SLOPE_TOL``/``LOCK_TOL`` semantics, windward fallback to the level faces,
``locked_face`` = the first self-locking facet in facet order), but never builds an
(n facets x m directions) array: a parallel numba kernel (:mod:`asperity.friction._facet_kernels`)
streams cache-sized chunks of facets through every direction of a batch; memory is
O(n + m * threads).  :func:`numpy_facet_reservoir` is the same computation in plain
streamed NumPy (blocks of directions x chunks of facets), the baseline of
``asperity bench --only facets`` and a second reference in the tests.

Results agree with the reference to rounding (~1e-15 relative for well-conditioned
facets; the summation order differs).  A facet whose vertical force share lies within
rounding of ``LOCK_TOL`` (or a slope within rounding of ``LEVEL_SLOPE_TOL``) may be
classified differently by the kernel, which evaluates ``fz`` as ``(a q - mu g.s)/q``.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError, check_array, check_int, check_mu, is_array
from .reservoir import (
    LEVEL_SLOPE_TOL,
    LOCK_TOL,
    MU_MAX,
    NO_WINDWARD_FACE,
    Reservoir,
    check_contact,
    check_progress,
    check_psi,
)

#: facets per cache chunk of the numba kernel (5 float64 streams of 1024 = 40 kB: L1/L2)
CHUNK = 1024
#: target facet-directions per kernel call when batching directions automatically
BATCH_WORK = 1 << 30
#: below this many facets per thread the kernel splits directions instead of facets
MIN_FACETS_PER_WORKER = 8192
#: most directions per kernel call a caller may ask for
MAX_BATCH = 1 << 31
#: facet-directions per kernel call (~0.05-0.2 s): a pass runs in pieces, and Ctrl-C is
#: honoured between them
PIECE_WORK = 1 << 26


class _Facets:
    """Validated, contiguous float64 facet data (zero-weight facets removed)."""

    __slots__ = ("gx", "gy", "a", "mu", "mu_uniform", "w", "idx", "wsum", "n_in")

    def __init__(self, gx, gy, mu, weight, engine="numba"):
        gx = _vector("gx", gx)
        gy = _vector("gy", gy)
        n = gx.shape[0]
        if gy.shape != (n,):
            raise InputError(f"gy must have the shape of gx ({n},), got {gy.shape}")
        w = _vector("weight", weight)
        if w.shape != (n,):
            raise InputError(f"weight must have shape ({n},), got {w.shape}")
        mu_uniform = not is_array(mu)
        if mu_uniform:
            mu_arr = np.array([check_mu("mu", mu, MU_MAX)])
        else:
            mu_arr = _vector("mu", mu)
            if mu_arr.shape != (n,):
                raise InputError(f"mu must be a number or an array of shape ({n},), "
                                 f"got shape {mu_arr.shape}")
        gx = np.ascontiguousarray(gx)
        gy = np.ascontiguousarray(gy)
        w = np.ascontiguousarray(w)
        mu_arr = np.ascontiguousarray(mu_arr)
        if engine == "numba":
            from ._facet_kernels import prepare
            a = np.empty(n)
            bad_g, bad_mu, bad_w, npos = prepare(gx, gy, mu_arr, w, a, MU_MAX)
        else:
            bad_g = int(np.count_nonzero(~(np.isfinite(gx) & np.isfinite(gy))))
            bad_mu = int(np.count_nonzero(~((mu_arr >= 0) & (mu_arr <= MU_MAX))))
            bad_w = int(np.count_nonzero(~(np.isfinite(w) & (w >= 0))))
            npos = int(np.count_nonzero(w > 0))
            a = np.empty(n)
            with np.errstate(all="ignore"):
                # the reference's 1/nrm, nrm = sqrt(1 + gx*gx + gy*gy), bitwise, in blocks
                for lo in range(0, n, 1 << 20):
                    hi = min(n, lo + (1 << 20))
                    x, y = gx[lo:hi], gy[lo:hi]
                    a[lo:hi] = 1.0 / np.sqrt(1.0 + x * x + y * y)
        if bad_g:
            raise InputError(f"gx and gy must be finite ({bad_g} facets are not)")
        if bad_mu:
            raise InputError(f"mu must be in [0, {MU_MAX:g}] ({bad_mu} facets are not)")
        if bad_w or npos == 0:
            raise InputError("weight must be finite, >= 0 and not all zero")
        if npos == n:
            idx = np.empty(0, dtype=np.int64)
        else:
            idx = np.flatnonzero(w > 0).astype(np.int64)
            gx, gy, w, a = gx[idx], gy[idx], w[idx], a[idx]
            if not mu_uniform:
                mu_arr = mu_arr[idx]
        self.gx, self.gy, self.w, self.a, self.mu = gx, gy, w, a, mu_arr
        self.mu_uniform = mu_uniform
        self.idx = idx
        self.wsum = float(self.w.sum())
        self.n_in = n

    @property
    def n(self) -> int:
        return self.gx.shape[0]

    def original(self, i):
        """Caller's facet numbers of compacted indices ``i`` (-1 stays -1)."""
        i = np.asarray(i, dtype=np.int64)
        if self.idx.size == 0:
            return i
        return np.where(i >= 0, self.idx[np.maximum(i, 0)], -1)


def _vector(name, x) -> np.ndarray:
    return check_array(name, x, ndim=1, finite=False)      # the kernel counts non-finite


def _check_callables(progress, batch):
    check_progress(progress)
    return None if batch is None else check_int("batch", batch, 1, MAX_BATCH)


def _auto_batch(n: int, m: int) -> int:
    return max(1, min(m, BATCH_WORK // max(n, 1)))


def _assemble(fac: _Facets, psi, contact, sums, first, level_fn) -> Reservoir:
    """Reservoir from per-direction totals.

    sums  : (m, 6) totals (slots of asperity.friction._facet_kernels: px, py, w, nlock, nload, nsteep)
    first : (m,) compacted index of the first loaded self-locking facet (-1: none)
    level_fn(sel) -> (sums, first) of the level faces for the directions ``sel``
    """
    m = psi.shape[0]
    set_valued = np.zeros(m, dtype=bool)
    if contact == "all-faces":
        wsum = np.full(m, fac.wsum)
    else:
        wsum = sums[:, 2].copy()
        none = np.flatnonzero(sums[:, 4] == 0)
        if none.size:
            lsums, lfirst = level_fn(none)
            if np.any(lsums[:, 4] == 0):
                # cannot happen with weights > 0: some face is level or climbed in every direction
                raise InputError(NO_WINDWARD_FACE)
            sums = sums.copy()
            first = first.copy()
            sums[none] = lsums
            first[none] = lfirst
            wsum[none] = lsums[:, 2]
            set_valued[none] = lsums[:, 5] > 0
    locked = sums[:, 3] > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.column_stack([sums[:, 0] / wsum, sums[:, 1] / wsum])
    p[locked] = np.inf
    locked_face = np.where(locked, fac.original(first), -1).astype(np.int64)
    return Reservoir(psi=psi, p=p, locked=locked, locked_face=locked_face,
                     set_valued=set_valued, contact=contact)


# --------------------------------------------------------------------------- numba


def _plan(n: int, m: int, nthreads: int):
    """Worker facet/direction ranges: split facets when there are enough, else directions."""
    if nthreads <= 1 or (n < MIN_FACETS_PER_WORKER * nthreads and m >= nthreads):
        if nthreads <= 1 or m < 2:
            return (np.array([0]), np.array([n]), np.array([0]), np.array([m]))
        k = min(nthreads, m)
        d = (np.arange(k + 1) * m) // k
        return (np.zeros(k, np.int64), np.full(k, n, np.int64), d[:-1].astype(np.int64),
                d[1:].astype(np.int64))
    # facet split on chunk boundaries
    nch = -(-n // CHUNK)
    k = min(nthreads, nch)
    cb = (np.arange(k + 1) * nch) // k * CHUNK
    cb[-1] = n
    return (cb[:-1].astype(np.int64), np.minimum(cb[1:], n).astype(np.int64),
            np.zeros(k, np.int64), np.full(k, m, np.int64))


def _numba_pass(fac: _Facets, cs, ss, mode: int, tick=None, workers=None):
    """Sums of one batch of directions, in kernel calls of about :data:`PIECE_WORK`
    facet-directions.  Every worker advances through its facets by whole cache chunks,
    all workers in step, so the chunks and the order in which they are added are those of
    a single call: the result is the same bit for bit, and Ctrl-C (raised by Python
    between two calls) stops the pass within a fraction of a second.  ``workers``: the
    number of accumulators (default: one per thread; a fixed number makes the sums
    independent of the threads that run them)."""
    from numba import get_num_threads

    from ._facet_kernels import N_ACC, facet_sweep
    m = cs.shape[0]
    f0, f1, d0, d1 = _plan(fac.n, m, get_num_threads() if workers is None else workers)
    k = f0.shape[0]
    acc = np.zeros((k, m, N_ACC))
    first = np.full((k, m), -1, dtype=np.int64)
    span = int((f1 - f0).max())
    dirs = max(1, int((d1 - d0).max()))
    step = CHUNK * max(1, PIECE_WORK // (CHUNK * dirs * k))
    for lo in range(0, span, step):
        facet_sweep(fac.gx, fac.gy, fac.a, fac.mu, fac.mu_uniform, fac.w, cs, ss, mode,
                    LOCK_TOL, LEVEL_SLOPE_TOL, np.minimum(f0 + lo, f1),
                    np.minimum(f0 + lo + step, f1), d0, d1, CHUNK, acc, first)
        if tick is not None:
            tick(min(lo + step, span) / span)
    return _reduce(acc, first)


def _reduce(acc, first):
    sums = acc.sum(axis=0)
    found = first >= 0
    has = found.any(axis=0)
    first_t = np.argmax(found, axis=0)
    f = np.where(has, first[first_t, np.arange(first.shape[1])], -1)
    return sums, f


def compute_facet_reservoir(gx, gy, mu, weight, psi, contact: str = "all-faces", *,
                            progress=None, batch=None) -> Reservoir:
    """Reservoir points of n plane facets for the sliding directions ``psi`` (numba kernel).

    The same result as the NumPy reference of :func:`asperity.compute_reservoir` (to
    rounding: the sums are taken in another order), without ever building an (n facets x m
    directions) array: a parallel kernel streams cache-sized chunks of facets through every
    direction of a batch; memory O(n + m x threads).

    Parameters
    ----------
    gx, gy : (n,) array_like of float
        Facet gradients dz/dx and dz/dy, finite.
    mu : float or (n,) array_like of float
        Local friction coefficient, the same for every facet or one a facet, in [0, 100].
    weight : (n,) array_like of float
        Horizontal-area weights, finite, >= 0 and not all zero.
    psi : float or array_like
        Sliding directions, radians from +x towards +y, a number or a 1-d array within
        +-1e4.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.
    progress : callable or None, default None
        ``progress(fraction_done)``, called after each batch of directions.
    batch : int or None, default None
        Directions per kernel call, in [1, 2**31]; None: about 1e9 facet-directions a call.

    Returns
    -------
    Reservoir
        As :func:`asperity.compute_reservoir` returns it; ``locked_face`` is the first
        self-locking facet in facet order.

    Raises
    ------
    asperity.InputError
        Arrays of mismatched shapes, non-finite values, weights all zero, a friction
        coefficient or direction out of range, or an unknown contact regime.

    See Also
    --------
    asperity.compute_reservoir, asperity.FacetSurface, asperity.derive

    Examples
    --------
    The two faces of the SPEC.md wedge, along ``+t_a`` and ``-t_a``:

    >>> ta, tb = np.tan(np.radians([30.0, 10.0]))
    >>> r = asperity.compute_facet_reservoir([ta, -tb], [0.0, 0.0], [0.1, 0.2], [tb, ta],
    ...                                      np.radians([0.0, 180.0]))
    >>> print(" ".join(f"{t:.6f}" for t in r.tangential))
    0.185697 0.193238
    """
    check_contact(contact)
    b = _check_callables(progress, batch)
    fac = _Facets(gx, gy, mu, weight)
    psi = check_psi(psi)
    return _run(fac, psi, contact, progress, b, _numba_pass)


def _run(fac, psi, contact, progress, b, pass_fn) -> Reservoir:
    from ._facet_kernels import MODE_ALL, MODE_LEVEL, MODE_WINDWARD, N_ACC
    m = psi.shape[0]
    cs, ss = np.cos(psi), np.sin(psi)
    mode = MODE_ALL if contact == "all-faces" else MODE_WINDWARD
    if b is None:
        b = _auto_batch(fac.n, m)
    sums = np.zeros((m, N_ACC))
    first = np.full(m, -1, dtype=np.int64)
    for start in range(0, m, b):
        stop = min(m, start + b)
        tick = None if progress is None else \
            (lambda f, a=start, z=stop: progress((a + f * (z - a)) / m))
        sums[start:stop], first[start:stop] = pass_fn(fac, cs[start:stop], ss[start:stop], mode,
                                                      tick)

    def level(sel):
        return pass_fn(fac, cs[sel], ss[sel], MODE_LEVEL)

    return _assemble(fac, psi, contact, sums, first, level)


# --------------------------------------------------------------------------- numpy

#: elements (directions x facets) of one NumPy block
NUMPY_BLOCK = 1 << 16


def _numpy_pass(fac: _Facets, cs, ss, mode: int, tick=None):
    """Streamed NumPy sums of :func:`_numba_pass`, with the reference's formulas."""
    n, m = fac.n, cs.shape[0]
    sums = np.zeros((m, 6))
    first = np.full(m, -1, dtype=np.int64)
    fchunk = min(n, max(1024, NUMPY_BLOCK))
    dblock = max(1, NUMPY_BLOCK // fchunk)
    for j0 in range(0, m, dblock):
        j1 = min(m, j0 + dblock)
        sx, sy = cs[j0:j1, None], ss[j0:j1, None]
        for lo in range(0, n, fchunk):
            hi = min(n, lo + fchunk)
            gx, gy, a, w = fac.gx[lo:hi], fac.gy[lo:hi], fac.a[lo:hi], fac.w[lo:hi]
            mu = fac.mu[0] if fac.mu_uniform else fac.mu[lo:hi]
            slope = gx * sx + gy * sy
            vlen = np.sqrt(1.0 + slope * slope)
            fz = a - mu * slope / vlen
            if mode == 0:
                loaded = None
            elif mode == 1:
                loaded = slope > LEVEL_SLOPE_TOL
            else:
                loaded = np.abs(slope) <= LEVEL_SLOPE_TOL
            lk = fz <= LOCK_TOL
            if loaded is not None:
                lk &= loaded
            ok = ~lk if loaded is None else loaded & ~lk
            ww = np.where(ok, w, 0.0) / np.where(ok, fz, 1.0)
            hx = gx * a + mu * sx / vlen
            hy = gy * a + mu * sy / vlen
            blk = sums[j0:j1]
            blk[:, 0] += (ww * hx).sum(axis=1)
            blk[:, 1] += (ww * hy).sum(axis=1)
            nl = lk.sum(axis=1)
            blk[:, 3] += nl
            if loaded is None:
                blk[:, 4] += hi - lo
            else:
                blk[:, 2] += (loaded * w).sum(axis=1)
                blk[:, 4] += loaded.sum(axis=1)
                if mode == 2:
                    steep = np.hypot(gx, gy) > LEVEL_SLOPE_TOL
                    blk[:, 5] += (loaded & steep).sum(axis=1)
            fb = first[j0:j1]
            new = (fb < 0) & (nl > 0)
            if new.any():
                fb[new] = lo + np.argmax(lk[new], axis=1)
        if tick is not None:
            tick(j1 / m)
    return sums, first


def numpy_facet_reservoir(gx, gy, mu, weight, psi, contact: str = "all-faces", *,
                          progress=None, batch=None) -> Reservoir:
    """:func:`compute_facet_reservoir` in streamed NumPy (blocks of ~65k facet-directions).

    The comparison baseline of the facet benchmark and a second reference in the tests;
    memory O(n + m).
    """
    check_contact(contact)
    b = _check_callables(progress, batch)
    fac = _Facets(gx, gy, mu, weight, engine="numpy")
    psi = check_psi(psi)
    return _run(fac, psi, contact, progress, b, _numpy_pass)
