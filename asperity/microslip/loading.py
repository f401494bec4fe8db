"""Load cycles of an assembly: temperature change and tangential force, one closed cycle
of breakpoints repeated, with substeps per monotone segment.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_int, check_range


@dataclass(frozen=True)
class Loading:
    """One load cycle, repeated: temperature change ``dT`` (K) and external tangential
    force ``F`` (N; strip: N per m of width) at breakpoints, linear in between.

    The assembly starts stress-free at dT = 0, F = 0 and is first brought to the cycle's
    first point; each cycle then runs through the breakpoints and ends where it started
    (``dT[-1] == dT[0]``, ``F[-1] == F[0]``).  ``substeps`` load increments per segment.
    """

    dT: np.ndarray
    F: np.ndarray
    substeps: int = 1

    def __post_init__(self):
        dT = np.asarray(self.dT, dtype=float).ravel()
        F = np.asarray(self.F, dtype=float).ravel()
        if dT.size < 2:
            raise InputError(f"loading.history needs at least 2 points, got {dT.size}")
        if not np.all(np.isfinite(dT)):
            raise InputError("loading.history must hold finite temperature changes (K)")
        if F.size == 1:
            F = np.full(dT.size, float(F[0]))
        if F.size != dT.size:
            raise InputError(f"loading.force_history must have as many points as "
                             f"loading.history ({dT.size}), got {F.size}")
        if not np.all(np.isfinite(F)):
            raise InputError("loading.force_history must hold finite forces")
        if dT[-1] != dT[0] or F[-1] != F[0]:
            raise InputError(f"loading.history must end where it starts (a closed cycle), got "
                             f"{dT[0]:g} K ... {dT[-1]:g} K")
        object.__setattr__(self, "dT", dT)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "substeps", check_int("substeps", self.substeps, 1, 100_000))

    @classmethod
    def cycles_between(cls, dT_min, dT_max, force_min=0.0, force_max=None, substeps=1):
        """Cycles dT_min -> dT_max -> dT_min; the force goes force_min -> force_max -> force_min
        in phase (constant force_min if force_max is None)."""
        lo = check_range("dT_min", dT_min)
        hi = check_range("dT_max", dT_max)
        if not math.isfinite(lo) or not math.isfinite(hi) or hi < lo:
            raise InputError(f"loading needs finite dT_min <= dT_max, got dT_min = {lo:g} K, "
                             f"dT_max = {hi:g} K")
        f0 = check_range("force_min", force_min)
        f1 = f0 if force_max is None else check_range("force_max", force_max)
        return cls(np.array([lo, hi, lo]), np.array([f0, f1, f0]), substeps)

    @property
    def dT_range(self) -> float:
        return float(self.dT.max() - self.dT.min())

    def _refine(self, a, b):
        m = self.substeps
        return [a + (b - a) * (j + 1) / m for j in range(m)]

    def lead_in(self) -> tuple[np.ndarray, np.ndarray]:
        """Points from the stress-free state (0, 0) to the first point of the cycle."""
        if self.dT[0] == 0.0 and self.F[0] == 0.0:
            return np.zeros(0), np.zeros(0)
        return np.array(self._refine(0.0, self.dT[0])), np.array(self._refine(0.0, self.F[0]))

    def cycle_points(self) -> tuple[np.ndarray, np.ndarray]:
        """Load points of one cycle (after its first point), ``substeps`` per segment."""
        dT, F = [], []
        for j in range(self.dT.size - 1):
            dT += self._refine(self.dT[j], self.dT[j + 1])
            F += self._refine(self.F[j], self.F[j + 1])
        return np.array(dT), np.array(F)
