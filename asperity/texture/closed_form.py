"""Closed forms of the wedge texture (SPEC.md sections 1-2, Antoni et al.).

``H(x, y) = (x + tan y)/(1 - x tan y)`` is the tangential/normal force ratio of a tip
climbing a face of slope angle ``y`` with local friction ``x``; the all-faces wedge model's
``mu_a+``, ``mu_a-`` and ``mu_b`` follow from it (:func:`compute_wedge_axis_closed_form`).
The general homogenisation over any set of faces, of which these are the psi = 0 and
psi = 90 deg cases, is :mod:`asperity.friction.faces`.
"""
from __future__ import annotations

import math

import numpy as np

from ..friction.reservoir import LOCK_TOL


def compute_H(x, y):
    """Tangential/normal force ratio of a tip climbing a face of signed slope angle y.

    H(x, y) = (x + tan y) / (1 - x tan y)   (Antoni et al. eq. 8)

    x : local friction coefficient (>= 0); y : signed slope angle in radians, positive
    when the tip climbs.  Returns ``inf`` where ``x tan y >= 1`` (self-locking).
    """
    x = np.asarray(x, dtype=float)
    t = np.tan(np.asarray(y, dtype=float))
    den = 1.0 - x * t
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(den > LOCK_TOL, (x + t) / np.where(den > LOCK_TOL, den, 1.0), np.inf)
    return out[()] if out.ndim == 0 else out


def compute_wedge_axis_closed_form(alpha, beta, mu_alpha, mu_beta) -> dict:
    """mu_a+, mu_a-, mu_b (= mu_b+ = mu_b-) of the all-faces wedge model, SPEC.md section 2.

    Angles in radians.  Infinite where a face self-locks.
    """
    ta, tb = math.tan(alpha), math.tan(beta)
    ha = compute_H(mu_alpha, alpha)
    hb = compute_H(mu_beta, beta)
    mu_a_plus = (ha * tb + compute_H(mu_beta, -beta) * ta) / (ta + tb)
    mu_a_minus = (hb * ta + compute_H(mu_alpha, -alpha) * tb) / (ta + tb)
    mu_b = (mu_alpha * tb / math.cos(alpha) + mu_beta * ta / math.cos(beta)) / (ta + tb)
    return {"mu_a_plus": float(mu_a_plus), "mu_a_minus": float(mu_a_minus),
            "mu_b_plus": float(mu_b), "mu_b_minus": float(mu_b)}
