"""Closed forms of the slider chains (SPEC.md section 5), beside the numerics: the
elastic limit dT_c of the two-node model and of the strip (shear lag), and the two-node
drift per cycle.

``alpha_T`` is signed (the part's expansion relative to its support).  Its sign decides
which end slips first on heating, not the drift: turning the sign of alpha_T is the same as
mirroring the chain end for end (u_i -> u_{n-1-i}), so under thermal cycles the drift per
cycle depends only on |alpha_T| and goes towards the side of the smaller coefficient.
Inputs are checked against :mod:`asperity.microslip.limits` (one-line InputError).
"""
from __future__ import annotations

import math

from ..errors import InputError
from .limits import (
    STRIP,
    TWO_NODE,
    check_alpha_T,
    check_dT,
    check_mu,
    check_param,
    same_friction,
)


def _two_node(k, k_t, N, mu_plus, mu_minus, alpha_T, l0):
    return (check_param("k", k, TWO_NODE["k"]), check_param("k_t", k_t, TWO_NODE["k_t"]),
            check_param("N", N, TWO_NODE["N"]), check_mu("mu_plus", mu_plus),
            check_mu("mu_minus", mu_minus), check_alpha_T("alpha_T", alpha_T),
            check_param("l0", l0, TWO_NODE["l0"]))


def two_node_dT_c(k, k_t, N, mu_plus, mu_minus, alpha_T, l0) -> float:
    """Elastic limit of the two-node model (SPEC.md 5):
    ``dT_c = min(mu+, mu-) N (1/k + 2/k_t) / (|alpha_T| l0)`` (K; inf if both directions
    are self-locking)."""
    k, k_t, N, mp, mm, aT, l0 = _two_node(k, k_t, N, mu_plus, mu_minus, alpha_T, l0)
    return min(mp, mm) * N * (1.0 / k + 2.0 / k_t) / (abs(aT) * l0)


def two_node_drift_per_cycle(k, k_t, N, mu_plus, mu_minus, alpha_T, l0, dT_min, dT_max) -> float:
    """Displacement of both nodes per full cycle once stabilised (m, SPEC.md 5):
    ``|alpha_T| l0 (dT_max - dT_min - 2 dT_c)`` towards the side of the smaller coefficient
    (-x if mu+ > mu-, whatever the sign of alpha_T), zero if the range is at most 2 dT_c
    or if mu+ = mu- (to within :data:`limits.SAME_FRICTION`)."""
    k, k_t, N, mp, mm, aT, l0 = _two_node(k, k_t, N, mu_plus, mu_minus, alpha_T, l0)
    lo, hi = check_dT("dT_min", dT_min), check_dT("dT_max", dT_max)
    if hi < lo:
        raise InputError(f"needs dT_min <= dT_max, got dT_min = {lo:g} K, dT_max = {hi:g} K")
    if same_friction(mp, mm):                       # the same coefficient but for rounding
        return 0.0
    dT_c = two_node_dT_c(k, k_t, N, mp, mm, aT, l0)
    excess = max(0.0, (hi - lo) - 2.0 * dT_c)
    return (-1.0 if mp > mm else 1.0) * abs(aT) * l0 * excess


def strip_dT_c(h, E, p, l, k_t, mu_plus, mu_minus, alpha_T) -> float:
    """Shear-lag elastic limit of the free strip on its elastic bed (SPEC.md 5):
    ``dT_c = mu p lam coth(lam l / 2) / (|alpha_T| k_t)``, ``lam = sqrt(k_t / (E h))``,
    ``mu = min(mu+, mu-)`` (with mu- < mu+ the end that moves towards -x slips first:
    x = 0 on heating if alpha_T > 0, x = l if alpha_T < 0)."""
    h, E, p, l, k_t = (check_param(name, v, STRIP[name]) for name, v in
                       (("h", h), ("E", E), ("p", p), ("l", l), ("k_t", k_t)))
    mp, mm = check_mu("mu_plus", mu_plus), check_mu("mu_minus", mu_minus)
    aT = check_alpha_T("alpha_T", alpha_T)
    lam = math.sqrt(k_t / E) / math.sqrt(h)
    return min(mp, mm) * p * lam / (abs(aT) * k_t * math.tanh(0.5 * lam * l))
