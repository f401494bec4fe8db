"""The checks of the arguments of :func:`asperity.contact.solve_contact` and
:func:`asperity.contact.solve_load_curve`: every bad value refused in one line naming the
argument and its allowed range (:mod:`asperity.errors`)."""
from __future__ import annotations

import numpy as np

from ..errors import InputError, check_array, check_choice, check_range
from . import elastic

#: range of the nominal pressure over E* a solve accepts (beyond: the map is flattened
#: flat many times over, or nothing is loaded)
PRESSURE_OVER_E = (1e-12, 10.0)
#: range of E* in Pa (a gel to diamond, with margin)
E_RANGE = (1.0, 1e13)


def effective_modulus(E1, nu1, E2=None, nu2=None) -> float:
    r"""Effective modulus E* of two elastic bodies in contact (SPEC.md section 7).

    Parameters
    ----------
    E1 : float
        Young's modulus of the first body, Pa, > 0.
    nu1 : float
        Poisson's ratio of the first body, in (-1, 0.5].
    E2 : float or None, default None
        Young's modulus of the second body, Pa, > 0; None (with ``nu2``): a rigid
        counterface.
    nu2 : float or None, default None
        Poisson's ratio of the second body, in (-1, 0.5].

    Returns
    -------
    float
        :math:`E^* = 1 / ((1 - \nu_1^2)/E_1 + (1 - \nu_2^2)/E_2)`, Pa.

    Raises
    ------
    asperity.InputError
        A value out of range, or one of ``E2`` and ``nu2`` without the other.

    See Also
    --------
    asperity.solve_contact, asperity.ElasticContact

    Examples
    --------
    Steel on a rigid counterface, and steel on aluminium:

    >>> print(f"{asperity.effective_modulus(210e9, 0.3) / 1e9:.2f} GPa")
    230.77 GPa
    >>> print(f"{asperity.effective_modulus(210e9, 0.3, 70e9, 0.33) / 1e9:.2f} GPa")
    58.61 GPa
    """
    E1 = check_range("E1", E1, 0.0, None, low_open=True, unit="Pa")
    nu1 = check_range("nu1", nu1, -1.0, 0.5, low_open=True)
    c = (1.0 - nu1 * nu1) / E1
    if (E2 is None) != (nu2 is None):
        raise InputError("give E2 and nu2 together (or neither: a rigid counterface)")
    if E2 is not None:
        E2 = check_range("E2", E2, 0.0, None, low_open=True, unit="Pa")
        nu2 = check_range("nu2", nu2, -1.0, 0.5, low_open=True)
        c += (1.0 - nu2 * nu2) / E2
    return 1.0 / c


def _pixel_size(pixel_size) -> tuple[float, float]:
    from ..surface.topography import pixel_length
    if not isinstance(pixel_size, (list, tuple, np.ndarray)) or (
            isinstance(pixel_size, np.ndarray) and pixel_size.ndim == 0):
        d = pixel_length("pixel_size", pixel_size)
        return d, d
    a = check_array("pixel_size", pixel_size, shape=(2,))
    return pixel_length("pixel_size dx", float(a[0])), pixel_length("pixel_size dy",
                                                                     float(a[1]))


def check_inputs(heights, pixel_size, E_star, pressure, boundary, hardness):
    """The checked arguments of :func:`solve_contact`: (heights as float64, (dx, dy),
    E*, pressure, boundary, hardness or None, number of defined pixels)."""
    if isinstance(heights, np.ndarray) and heights.ndim == 2 and \
            check_choice("boundary", boundary, elastic.BOUNDARIES):
        check_solver_memory(heights.shape, boundary)     # before any copy, a view's too
    z = check_array("heights", heights, ndim=2, finite=False)
    if z.shape[0] < 2 or z.shape[1] < 2:
        raise InputError(f"heights must have at least 2 x 2 pixels, got shape {z.shape}")
    boundary = check_choice("boundary", boundary, elastic.BOUNDARIES)
    check_solver_memory(z.shape, boundary)     # before any copy of the heights
    # C order: the kernels work on flat views (a Fortran-ordered map would be copied)
    z = np.ascontiguousarray(z)
    if np.isinf(z).any():
        raise InputError("heights must be finite or NaN (undefined), got an infinity")
    defined = int(np.count_nonzero(~np.isnan(z)))
    if defined == 0:
        raise InputError("heights has no defined (finite) pixel: nothing can carry the load")
    from ..surface.topography import MAX_COORDINATE
    big = float(np.nanmax(np.abs(z)))
    if big > MAX_COORDINATE:
        raise InputError(f"heights must lie within +-{MAX_COORDINATE:g} m, got values up to "
                         f"{big:.3g} m; check the unit (heights in metres)")
    dx, dy = _pixel_size(pixel_size)
    E_star = check_range("E_star", E_star, *E_RANGE, unit="Pa")
    p = check_range("pressure", pressure, 0.0, None, low_open=True, unit="Pa")
    lo, hi = PRESSURE_OVER_E
    check_range("pressure / E_star", p / E_star, lo, hi)
    if hardness is not None:
        mean_defined = p * z.size / defined
        hardness = check_range("hardness", hardness, mean_defined, None, low_open=True,
                               unit="Pa (above the mean pressure over the defined pixels)")
    return z, (dx, dy), E_star, p, boundary, hardness, defined


def check_solver_memory(shape, boundary: str) -> None:
    """Refuse a solve whose arrays do not fit in the free memory, in one line."""
    from ..resources import check_memory
    check_memory(elastic.solver_bytes(shape, boundary),
                 f"the {boundary} contact solve of heights of {shape[0]} x {shape[1]} "
                 f"pixels",
                 "crop or resample the map to fewer pixels")
