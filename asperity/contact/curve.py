"""Load curves: one contact solve per pressure, each started from the previous solution.

The pressures are solved in increasing order on one half-space (its spectrum computed
once); each solve starts from the previous pressure field, scaled to its own load by the
solver's load control.  The results come back in the order the pressures were given.

What the warm start buys is bounded: the Polonsky-Keer iteration converges linearly (a
decade of the residual every few iterations, set by the conditioning of the contact set),
so a start from the previous solution saves the decades it starts closer by -- about one
for neighbouring pressures -- and each further solve costs most of a cold one (the
figures: ``asperity bench --only contact``).
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError, check_array, check_int, check_range
from . import elastic
from .solver import (
    PRESSURE_OVER_E,
    ContactResult,
    check_inputs,
    check_options,
    check_solver_memory,
    solve_on,
)

#: most pressures of one load curve
MAX_PRESSURES = 1000


def iter_load_curve(heights, pixel_size, E_star, pressures, *, boundary="periodic",
                    hardness=None, tol=1e-8, max_iterations=None, progress=None,
                    workers=None):
    """Yield the :class:`ContactResult` at each of ``pressures`` in the order given (see
    :func:`solve_load_curve`); a result out of order waits for its turn, so pressures given
    in increasing order keep one result at a time."""
    values = check_array("pressures", pressures, ndim=1, finite=False)
    check_int("pressures (number of values)", values.size, 1, MAX_PRESSURES)
    for p in values:
        check_range("pressures", p, 0.0, None, low_open=True, unit="Pa")
    z, (dx, dy), E, _, boundary, H, n_def = check_inputs(heights, pixel_size, E_star,
                                                         float(values.max()), boundary,
                                                         hardness)
    check_range("pressures / E_star", float(values.min()) / E, *PRESSURE_OVER_E)
    tol, maxit, workers = check_options(tol, max_iterations, progress, workers)
    check_solver_memory(z.shape, boundary)
    space = elastic.HalfSpace(z.shape, dx, dy, E, boundary, workers=workers)
    order = np.argsort(values, kind="stable")
    waiting: dict[int, ContactResult] = {}
    previous = None
    nxt = 0
    for k in order:
        res = solve_on(space, z, float(values[k]), H, n_def, tol, maxit, previous, progress)
        previous = res.pressure
        waiting[int(k)] = res
        del res
        while nxt in waiting:
            yield waiting.pop(nxt)
            nxt += 1


def solve_load_curve(heights, pixel_size, E_star, pressures, *, boundary="periodic",
                     hardness=None, tol=1e-8, max_iterations=None, progress=None,
                     workers=None) -> list[ContactResult]:
    """One :class:`ContactResult` per pressure of ``pressures`` (Pa, nominal, as
    :func:`solve_contact`'s ``pressure``), in the order given.

    The pressures are solved in increasing order, each from the previous solution (scaled
    to its load) on one half-space; the other arguments are :func:`solve_contact`'s (the
    hardness must exceed the largest pressure's mean over the defined pixels).  A solve
    that reaches its iteration limit raises :class:`ContactNotConverged` (its pressure in
    ``.result.pressure_asked``).
    """
    if pressures is None or isinstance(pressures, (str, bytes)):
        raise InputError(f"pressures must be a sequence of pressures in Pa, got "
                         f"{type(pressures).__name__}")
    return list(iter_load_curve(heights, pixel_size, E_star, pressures, boundary=boundary,
                                hardness=hardness, tol=tol, max_iterations=max_iterations,
                                progress=progress, workers=workers))
