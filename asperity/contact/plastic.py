"""A plastic solve by an outer loop over the plastic set: the fallback of
:func:`asperity.contact.solver.solve_on` when the single Polonsky-Keer iteration with the
cap stalls (a cap close to the mean pressure: most of the contact at H, where the clipped
conjugate-gradient steps and the load control undo each other).

Outer iteration k, with P the plastic set (pressure H, fixed):

1. the elastic problem of the other pixels: heights h - K (H on P) (the displacement the
   plastic pixels cause), P undefined, load L - H |P|, no cap -- the plain elastic
   Polonsky-Keer solve (:func:`asperity.contact.solver._iterate`), started from the last
   outer iteration's pressures;
2. the pixels whose elastic pressure exceeds H join P; the pixels of P whose gap
   g = u - h + d (u of every pressure, d the elastic solve's approach) is positive leave
   it (they do not touch);
3. done when nothing moves and the elastic solve converged.

The elastic solves run to :data:`LOOSE_TOL` while the set moves, to the caller's tolerance
once it has settled; each starts from the last one's pressures.  The loop starts from the
plastic set of the single iteration that stalled (its pixels at H), without the least
penetrating ones when they alone carry the load, as after each update (the elastic solve
needs some load).

The plastic set grows from the highest loads outwards, so the loop ends after about as
many outer iterations as the plastic zones are pixels wide (measured: 10 to 60 for 10 %
to 99.9 % of the map at H, from an empty set; a few from the stalled iteration's set).
Complementarity of the result: pixels out of contact clear of the half-space and the free
ones on it (the elastic solve's), the plastic ones on or into it (step 2), each to the
solver's gap tolerance.
"""
from __future__ import annotations

import math

import numpy as np

from .gaps import reference_length

#: most outer iterations
MAX_OUTER = 10_000
#: the tolerance of the elastic solves while the plastic set still changes (the last
#: ones, on the final set, take the caller's): the set moves by whole pixels, and a
#: solve to 1e-8 of a set about to change is wasted (measured: the outer loop's
#: iterations cut 2 to 3 times)
LOOSE_TOL = 1e-4


def solve_plastic(iterate, gap_tol: float, space, z, pbar: float, H: float, n_def: int,
                  tol: float, maxit: int, progress, start=None) -> dict:
    """The fields and figures of ``iterate`` (:func:`asperity.contact.solver._iterate`, the
    elastic solve) for the capped problem, by the outer loop of the module's docstring
    (``maxit``: iterations of the elastic solves in all; ``gap_tol``: the gap, over the
    solver's reference length, beyond which a plastic pixel leaves the plastic set;
    ``start``: None or
    a pressure field whose pixels at H start the plastic set, the others the elastic
    solve)."""
    nx, ny = z.shape
    load = pbar * nx * ny
    undefined = np.isnan(z)
    span = reference_length(space, z, pbar)
    plastic = np.zeros(z.shape, dtype=bool)
    p0 = None
    if start is not None:
        plastic = _start_set(space, z, start, H, load)
        p0 = np.where(plastic | undefined, 0.0, start)
    p = np.zeros(z.shape)
    u = np.empty(z.shape)
    used, out = 0, None
    inner = max(tol, LOOSE_TOL)
    for _ in range(MAX_OUTER):
        p[...] = 0.0
        p[plastic] = H
        space.apply(p, u)                      # the plastic pixels' displacement
        h2 = z - u
        h2[plastic] = np.nan
        n_pl = int(np.count_nonzero(plastic))
        out = iterate(space, h2, (load - H * n_pl) / (nx * ny), math.inf, n_def - n_pl,
                      inner, maxit - used, p0, progress)
        used += out["iterations"]
        del h2
        pe = out.pop("pressure")
        np.nan_to_num(pe, copy=False)
        over = pe > H
        p += pe
        space.apply(p, u)
        d = out["approach"]
        release = plastic & (u - z + d > gap_tol * span)
        if not out["converged"] or used >= maxit:
            break
        moved = over.any() or release.any()
        if not moved and inner <= tol:
            break
        if not moved:                          # the set settled: the last solve to tol
            inner = tol
        plastic |= over
        plastic &= ~release
        _leave_load(plastic, u, z, H, load)
        pe[plastic | undefined] = 0.0
        p0 = pe
    converged = bool(out["converged"]) and inner <= tol and not over.any() \
        and not release.any()
    gap = u - z + d
    contact = p > 0.0
    gap[contact] = 0.0
    np.maximum(gap, 0.0, out=gap)
    p[undefined] = np.nan
    gap[undefined] = np.nan
    n_c = int(np.count_nonzero(contact))
    return dict(pressure=p, gap=gap, displacement=u, contact=contact, area_fraction=n_c / n_def,
                mean_pressure=float(np.nansum(p)) / (nx * ny), max_pressure=float(np.nanmax(p)),
                mean_gap=float(np.nansum(gap)) / n_def, iterations=used,
                residual=float(out["residual"]) if converged else max(float(out["residual"]),
                                                                      tol),
                converged=converged, plastic_fraction=int(np.count_nonzero(p >= H)) / n_def,
                approach=d)


def _start_set(space, z, start, H: float, load: float) -> np.ndarray:
    """The plastic set an outer loop starts from: the pixels of ``start`` at H (see
    :func:`_leave_load`)."""
    plastic = (start >= H) & ~np.isnan(z)
    u = np.empty(z.shape)
    space.apply(np.nan_to_num(start), u)
    _leave_load(plastic, u, z, H, load)
    return plastic


def _leave_load(plastic, u, z, H: float, load: float) -> None:
    """Without the least penetrating pixels of ``plastic`` (the largest u - z) when they
    alone carry the load (the elastic solve needs some of it)."""
    from .loads import at_most
    keep = at_most(load, H)
    if np.count_nonzero(plastic) > keep:
        idx = np.flatnonzero(plastic)
        w = (u - z).reshape(-1)[idx]
        drop = idx[np.argsort(w, kind="stable")[keep:]]
        plastic.reshape(-1)[drop] = False
