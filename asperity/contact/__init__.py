"""Elastic contact: the load a rough surface's pixels carry under a nominal pressure.

* :mod:`.elastic` -- the elastic half-space u = K p (periodic: 2/(E*|q|) in Fourier space;
  free: Love's rectangular-patch coefficients, DC-FFT on a grid padded to twice the size);
* :mod:`.solver` -- the Polonsky-Keer constrained conjugate gradient with exact load
  control and an optional plastic cap (:func:`solve_contact`, :class:`ContactResult`);
  its fused loops in :mod:`._pk_kernels`;
* :mod:`.curve` -- load curves (:func:`solve_load_curve`): the pressures in increasing
  order on one half-space, each solve started from the previous solution.

The rigid surface is the height map (its highest points touch first); the elastic
half-space of effective modulus E* comes down onto it (SPEC.md section 7).
"""
from __future__ import annotations

from .solver import (  # noqa: F401  (the room's API)
    ContactNotConverged,
    ContactResult,
    effective_modulus,
    solve_contact,
)
from .curve import iter_load_curve, solve_load_curve  # noqa: F401


__all__ = ["ContactNotConverged", "ContactResult", "effective_modulus", "iter_load_curve",
           "solve_contact", "solve_load_curve"]
