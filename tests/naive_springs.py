"""Slow, obviously-correct NumPy references for the spring kernels (tests only).

naive_rigid_p : k_f = inf -- every tip sits under its base, its force ratio on face f is
the closed-form per-face point p_f; p = -sum(R_h)/sum(R_z) over springs and steps.
"""
from __future__ import annotations

import numpy as np


def naive_rigid_p(profile, psi, X0, ux, k_n, z_rest):
    """p (2,) for tips at X0 + ux (all combinations), all faces loaded."""
    x = (np.asarray(X0)[:, None] + np.asarray(ux)[None, :]).ravel()
    L = profile.period
    xm = np.mod(x, L)
    seg = np.clip(np.searchsorted(profile.x, xm, side="right") - 1, 0, profile.mu.size - 1)
    z = profile.height(xm)
    g = np.diff(profile.z) / np.diff(profile.x)
    c, s = np.cos(psi), np.sin(psi)
    num = np.zeros(2)
    den = 0.0
    for xi, j, zi in zip(xm, seg, z):
        if zi <= z_rest:
            continue
        gj, mu = g[j], profile.mu[j]
        m = np.array([-gj, 0.0, 1.0]) / np.sqrt(1 + gj * gj)
        v = np.array([c, s, gj * c])
        F = m - mu * v / np.linalg.norm(v)     # contact force direction on a sliding tip
        Rz = k_n * (zi - z_rest)
        num += Rz * F[:2] / F[2]
        den += Rz
    return -num / den
