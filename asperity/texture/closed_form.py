"""Closed forms of the wedge texture (SPEC.md sections 1-2, Antoni et al.).

``H(x, y) = (x + tan y)/(1 - x tan y)`` is the tangential/normal force ratio of a tip
climbing a face of slope angle ``y`` with local friction ``x``; the all-faces wedge model's
``mu_a+``, ``mu_a-`` and ``mu_b`` follow from it (:func:`compute_wedge_axis_closed_form`).
The general homogenisation over any set of faces, of which these are the psi = 0 and
psi = 90 deg cases, is :mod:`asperity.friction.faces`.
"""
from __future__ import annotations

import math
import numbers

import numpy as np

from ..errors import InputError, check_array, check_mu, check_range
from ..friction.reservoir import LOCK_TOL


def compute_H(x, y):
    r"""Tangential/normal force ratio of a tip climbing a face of signed slope angle y.

    Parameters
    ----------
    x : float or array_like
        Local friction coefficient of the face, in [0, 100].
    y : float or array_like
        Signed slope angle of the face, radians, in (-pi/2, pi/2): positive when the tip
        climbs, negative when it descends.  ``x`` and ``y`` have one shape, or one of them
        is a number.

    Returns
    -------
    float or numpy.ndarray
        :math:`H(x, y)`, dimensionless, of the broadcast shape of ``x`` and ``y`` (a NumPy
        float for two numbers); ``inf`` where :math:`x \tan y \ge 1` (self-locking: the tip
        cannot climb), never NaN.

    Raises
    ------
    asperity.InputError
        A value outside its range, NaN, or shapes that do not broadcast.

    See Also
    --------
    asperity.compute_axis_coefficients : The wedge's mu_a+, mu_a-, mu_b+, mu_b- from it.
    asperity.WedgeTexture : The texture whose faces it describes.

    Notes
    -----
    Antoni et al. eq. 8 (SPEC.md section 2):

    .. math:: H(x, y) = \frac{x + \tan y}{1 - x \tan y}

    Averaged over one wedge period with the faces' horizontal lengths as weights it gives
    :math:`\mu_{a+} = (H(\mu_\alpha, \alpha)\tan\beta + H(\mu_\beta, -\beta)\tan\alpha) /
    (\tan\alpha + \tan\beta)` and :math:`\mu_{a-}` likewise, independent of the wedge
    height and of the springs' stiffness.

    Examples
    --------
    A tip climbing a 30 deg face with local friction 0.1, then descending it:

    >>> print(f"{asperity.compute_H(0.1, np.radians(30.0)):.6f}")
    0.718853
    >>> print(f"{asperity.compute_H(0.1, np.radians(-30.0)):.6f}")
    -0.451295
    >>> print(asperity.compute_H(0.3, np.radians(80.0)))  # 0.3 tan 80 deg > 1: self-locking
    inf
    >>> asperity.compute_H(0.2, np.radians([-10.0, 0.0, 10.0])).round(6)
    array([0.022867, 0.2     , 0.390083])
    """
    x = _check_values("x (local friction)", x, 0.0, 100.0)
    yv = _check_values("y (slope angle)", y, -0.5 * math.pi, 0.5 * math.pi, open_ends=True,
                       unit="rad")
    try:
        x, yv = np.broadcast_arrays(x, yv)
    except ValueError:
        raise InputError(f"x and y must have one shape (or one be a number), got "
                         f"{np.shape(x)} and {np.shape(yv)}") from None
    t = np.tan(yv)
    den = 1.0 - x * t
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        out = np.where(den > LOCK_TOL, (x + t) / np.where(den > LOCK_TOL, den, 1.0), np.inf)
    return out[()] if out.ndim == 0 else out


def _check_values(name: str, value, low: float, high: float, open_ends: bool = False,
                  unit: str = ""):
    """A number or an array of numbers within [low, high] ((low, high) if open_ends)."""
    if isinstance(value, numbers.Real) or isinstance(value, (str, bytes)) or value is None:
        return np.float64(check_range(name, value, low, high, low_open=open_ends,
                                      high_open=open_ends, unit=unit))
    a = check_array(name, value)
    inside = (a > low) & (a < high) if open_ends else (a >= low) & (a <= high)
    if not np.all(inside):
        k = int(np.flatnonzero(~inside.ravel())[0])
        lo, hi = ("(", ")") if open_ends else ("[", "]")
        raise InputError(f"{name} must be in {lo}{low:g}, {high:g}{hi}{' ' + unit if unit else ''}"
                         f", got {a.ravel()[k]:g} at index {k}")
    return a


def compute_wedge_axis_closed_form(alpha, beta, mu_alpha, mu_beta) -> dict:
    """mu_a+, mu_a-, mu_b (= mu_b+ = mu_b-) of the all-faces wedge model, SPEC.md section 2.

    Angles in radians, in (0, pi/2); local friction in [0, 100].  Infinite where a face
    self-locks.
    """
    alpha, beta = (check_range(n, v, 0.0, 0.5 * math.pi, low_open=True, high_open=True,
                               unit="rad") for n, v in (("alpha", alpha), ("beta", beta)))
    mu_alpha, mu_beta = check_mu("mu_alpha", mu_alpha), check_mu("mu_beta", mu_beta)
    ta, tb = math.tan(alpha), math.tan(beta)
    ha = compute_H(mu_alpha, alpha)
    hb = compute_H(mu_beta, beta)
    mu_a_plus = (ha * tb + compute_H(mu_beta, -beta) * ta) / (ta + tb)
    mu_a_minus = (hb * ta + compute_H(mu_alpha, -alpha) * tb) / (ta + tb)
    mu_b = (mu_alpha * tb / math.cos(alpha) + mu_beta * ta / math.cos(beta)) / (ta + tb)
    return {"mu_a_plus": float(mu_a_plus), "mu_a_minus": float(mu_a_minus),
            "mu_b_plus": float(mu_b), "mu_b_minus": float(mu_b)}
