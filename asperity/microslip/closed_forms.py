"""Closed forms of the slider chains (SPEC.md section 5), beside the numerics: the
elastic limit dT_c of the two-node model and of the strip (shear lag), and the two-node
drift per cycle.
"""
from __future__ import annotations

import math


def two_node_dT_c(k, k_t, N, mu_plus, mu_minus, alpha_T, l0) -> float:
    """Elastic limit of the two-node model (SPEC.md 5):
    ``dT_c = min(mu+, mu-) N (1/k + 2/k_t) / (alpha_T l0)`` (K)."""
    return min(mu_plus, mu_minus) * N * (1.0 / k + 2.0 / k_t) / (alpha_T * l0)


def two_node_drift_per_cycle(k, k_t, N, mu_plus, mu_minus, alpha_T, l0, dT_min, dT_max) -> float:
    """Displacement of both nodes per full cycle once stabilised (m, SPEC.md 5):
    ``-alpha_T l0 (dT_max - dT_min - 2 dT_c)`` towards the side of the smaller coefficient
    (-x if mu+ > mu-), zero if the range is at most 2 dT_c or if mu+ = mu-."""
    if mu_plus == mu_minus:
        return 0.0
    dT_c = two_node_dT_c(k, k_t, N, mu_plus, mu_minus, alpha_T, l0)
    excess = max(0.0, (dT_max - dT_min) - 2.0 * dT_c)
    return (-1.0 if mu_plus > mu_minus else 1.0) * alpha_T * l0 * excess


def strip_dT_c(h, E, p, l, k_t, mu_plus, mu_minus, alpha_T) -> float:
    """Shear-lag elastic limit of the free strip on its elastic bed (SPEC.md 5):
    ``dT_c = mu p lam coth(lam l / 2) / (alpha_T k_t)``, ``lam = sqrt(k_t / (E h))``,
    ``mu = min(mu+, mu-)`` (the end x = 0 slips towards -x first when mu- < mu+)."""
    lam = math.sqrt(k_t / (E * h))
    return min(mu_plus, mu_minus) * p * lam / (alpha_T * k_t * math.tanh(0.5 * lam * l))
