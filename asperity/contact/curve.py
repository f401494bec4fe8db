"""Load curves: one contact solve per pressure, each started from the previous solution.

The pressures are solved in increasing order on one half-space (its spectrum computed
once); each solve starts from the previous pressure field, scaled to its own load by the
solver's load control.  The results come back in the order the pressures were given.

What the warm start buys is bounded, and measured (``python benchmarks/load_curve_bound.py
--n 512 [--plain]``; the benchmark's map and 8 pressures p/E* = 0.00125 .. 0.005, ratio
1.22 between neighbours, tolerance 1e-8; iterations, which do not depend on the machine):

* the iteration converges linearly at the same rate from a cold or a warm start: 4.1
  iterations a decade of the tolerance with the preconditioner (10.5 without), cold and
  warm alike, because the contact set keeps changing by a few pixels an iteration until
  the last decades;
* the start is one decade or less closer than a cold one: the previous solution scaled
  to the load is off by sum |p_start - p| / sum p = 0.19 at every step, a secant
  extrapolation of p / p_bar in log p_bar from the two previous solutions by 0.13 (and
  takes about as many iterations), since 16 % of each step's contact pixels were out of
  contact at the previous pressure: no field predicted from earlier solutions carries
  pressure there;
* so a warm solve takes 28 to 35 iterations where the cold one at the same pressure takes
  34 to 39 (plain: 65 to 85 for 75 to 95), and the 8 pressures cost 254 iterations, 7.1
  cold single solves of 36 at p/E* = 0.0025 (plain: 589, 7.2 of 82).  At 1024^2
  (``--n 1024``): 5.0 iterations a decade cold and warm, starts 0.21 off (secant 0.15),
  17 % new contact pixels a step, 313 iterations = 7.1 single solves of 44.

At most 3 single solves would leave the 7 warm solves, after the first (cold) one, 2
single solves: about 10 iterations each, 2.5 decades, hence a start within about 1e-5.5
of the solution, four to five decades closer than the 0.13 to 0.19 that the new contact
pixels leave.  The preconditioner (:data:`.solver.PRECONDITION`) takes 2.3 times fewer
iterations (1.7 times less time at 1024^2), cold and warm alike, so it does not change
the ratio.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError, check_array, check_int, check_range
from . import elastic
from .solver import PRESSURE_OVER_E, ContactResult, check_inputs, check_options, solve_on

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
    """Contacts at several pressures: a load curve, each solve started from the previous one.

    The pressures are solved in increasing order on one half-space (its spectrum computed
    once), each from the previous pressure field scaled to its load; the results come back
    in the order the pressures were given.

    Parameters
    ----------
    heights, pixel_size, E_star : array_like, float
        As for :func:`asperity.solve_contact`.
    pressures : sequence of float
        Nominal pressures, Pa, 1 to 1000 of them, each > 0 with ``pressure / E_star`` in
        [1e-12, 10].
    boundary, hardness, tol, max_iterations, progress, workers : optional
        As for :func:`asperity.solve_contact` (the hardness must exceed the largest
        pressure's mean over the defined pixels).

    Returns
    -------
    list of ContactResult
        One result per pressure, in the order given (see :func:`asperity.solve_contact`).

    Raises
    ------
    asperity.InputError
        An argument out of range (one line naming it).
    asperity.AsperityError
        ``ContactNotConverged`` when a solve reaches its iteration limit (its pressure in
        ``.result.pressure_asked``).

    See Also
    --------
    asperity.solve_contact, asperity.ElasticContact

    Examples
    --------
    Westergaard's wavy surface (:func:`asperity.solve_contact`): the contact fraction
    ``(2/pi) asin(sqrt(p/p*))`` is 1/3, 1/2 and full contact at p/p* = 0.25, 0.5, 1.2:

    >>> n, lam, delta, E = 128, 128e-6, 1e-7, 1e9
    >>> x = np.arange(n) * lam / n
    >>> h = np.tile(delta * np.cos(2 * np.pi * x / lam)[:, None], (1, 4))
    >>> p_star = np.pi * E * delta / lam
    >>> curve = asperity.solve_load_curve(h, lam / n, E, [0.25 * p_star, 0.5 * p_star,
    ...                                                   1.2 * p_star])
    >>> print(" ".join(f"{r.area_fraction:.4f}" for r in curve))
    0.3359 0.5078 1.0000
    """
    if pressures is None or isinstance(pressures, (str, bytes)):
        raise InputError(f"pressures must be a sequence of pressures in Pa, got "
                         f"{type(pressures).__name__}")
    return list(iter_load_curve(heights, pixel_size, E_star, pressures, boundary=boundary,
                                hardness=hardness, tol=tol, max_iterations=max_iterations,
                                progress=progress, workers=workers))
