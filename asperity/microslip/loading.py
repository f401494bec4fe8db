"""Load cycles of an assembly: temperature change and tangential force, one closed cycle
of breakpoints repeated, with substeps per monotone segment.
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .limits import HISTORY_POINTS, POINTS_PER_CYCLE, check_dT, check_force, check_substeps


@dataclass(frozen=True)
class Loading:
    """One load cycle of an assembly, repeated: temperature change and tangential force.

    Breakpoints of the temperature change ``dT`` (K, from the assembly temperature) and
    the external tangential force ``F``, linear in between.  The assembly starts
    stress-free at ``dT = 0``, ``F = 0`` and is first brought to the cycle's first point;
    each cycle then runs through the breakpoints and ends where it started.
    ``Loading.cycles_between(dT_min, dT_max, force_min=0, force_max=None, substeps=1)``
    builds the cycle ``dT_min -> dT_max -> dT_min`` (the force in phase).

    Parameters
    ----------
    dT : array_like
        2 to 10000 breakpoints, K, each in [-5000, 5000]; ``dT[-1] == dT[0]`` (a closed
        cycle).
    F : float or array_like
        External tangential force, N (strip: N per m of width), each in [-1e12, 1e12]: one
        value (constant) or one per breakpoint, ``F[-1] == F[0]``.
    substeps : int, optional
        Load increments per segment, in [1, 1e5] (at most 1e7 load points a cycle);
        default 1.  They only add points to the trace (the march is exact).

    Attributes
    ----------
    dT_range : float
        ``max(dT) - min(dT)``, K.
    points_per_cycle : int
        Load points of one cycle.

    Raises
    ------
    InputError
        If a value is out of range, a series is not a flat list of numbers, or the cycle
        does not close.

    See Also
    --------
    asperity.simulate_microslip, asperity.assess : the assembly under these cycles.

    Examples
    --------
    >>> ld = asperity.Loading([0.0, 125.0, 0.0], [0.0, 5.0, 0.0], substeps=4)
    >>> ld.dT_range, ld.points_per_cycle
    (125.0, 8)
    >>> asperity.Loading.cycles_between(0.0, 125.0).dT
    array([  0., 125.,   0.])
    >>> asperity.Loading([0.0, 10.0, 5.0], 0.0)
    Traceback (most recent call last):
    ...
    asperity.errors.InputError: loading.history must end where it starts (a closed cycle),
    got 0 K ... 5 K
    """

    dT: np.ndarray
    F: np.ndarray
    substeps: int = 1

    def __post_init__(self):
        dT = _series("loading.history", self.dT, check_dT)
        F = _series("loading.force_history", self.F, check_force, scalar=True)
        if F.size == 1:
            F = np.full(dT.size, float(F[0]))
        if F.size != dT.size:
            raise InputError(f"loading.force_history must have as many points as "
                             f"loading.history ({dT.size}), got {F.size}")
        if dT[-1] != dT[0]:
            raise InputError(f"loading.history must end where it starts (a closed cycle), got "
                             f"{dT[0]:g} K ... {dT[-1]:g} K")
        if F[-1] != F[0]:
            raise InputError(f"loading.force_history must end where it starts (a closed "
                             f"cycle), got {F[0]:g} ... {F[-1]:g}")
        substeps = check_substeps("loading.substeps", self.substeps)
        points = (dT.size - 1) * substeps
        if points > POINTS_PER_CYCLE:
            raise InputError(f"loading has {dT.size - 1} segments x {substeps} substeps = "
                             f"{points:.3g} load points per cycle, at most "
                             f"{POINTS_PER_CYCLE:.0e}; lower loading.substeps")
        object.__setattr__(self, "dT", dT)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "substeps", substeps)

    @classmethod
    def cycles_between(cls, dT_min, dT_max, force_min=0.0, force_max=None, substeps=1):
        """Cycles dT_min -> dT_max -> dT_min; the force goes force_min -> force_max -> force_min
        in phase (constant force_min if force_max is None)."""
        lo = check_dT("dT_min", dT_min)
        hi = check_dT("dT_max", dT_max)
        if hi < lo:
            raise InputError(f"loading needs dT_min <= dT_max, got dT_min = {lo:g} K, "
                             f"dT_max = {hi:g} K")
        f0 = check_force("force_min", force_min)
        f1 = f0 if force_max is None else check_force("force_max", force_max)
        return cls(np.array([lo, hi, lo]), np.array([f0, f1, f0]), substeps)

    @property
    def dT_range(self) -> float:
        return float(self.dT.max() - self.dT.min())

    def _refine(self, a, b) -> np.ndarray:
        """``substeps`` points from each a[j] (excluded) to b[j] (included), in order."""
        m = self.substeps
        a, b = np.atleast_1d(a), np.atleast_1d(b)
        j = np.arange(1, m + 1, dtype=float)
        return (a[:, None] + (b - a)[:, None] * j[None, :] / m).ravel()

    def lead_in(self) -> tuple[np.ndarray, np.ndarray]:
        """Points from the stress-free state (0, 0) to the first point of the cycle."""
        if self.dT[0] == 0.0 and self.F[0] == 0.0:
            return np.zeros(0), np.zeros(0)
        return self._refine(0.0, self.dT[0]), self._refine(0.0, self.F[0])

    def cycle_points(self) -> tuple[np.ndarray, np.ndarray]:
        """Load points of one cycle (after its first point), ``substeps`` per segment."""
        return (self._refine(self.dT[:-1], self.dT[1:]), self._refine(self.F[:-1], self.F[1:]))

    @property
    def points_per_cycle(self) -> int:
        return (self.dT.size - 1) * self.substeps


def _series(name: str, value, check_one, scalar: bool = False) -> np.ndarray:
    """A 1-D series of real numbers (a scalar too if ``scalar``), each checked by
    ``check_one``; text, booleans, nested lists and too many points are refused."""
    lo, hi = HISTORY_POINTS
    if value is None or isinstance(value, (str, bytes, dict, bool)):
        raise InputError(f"{name} must be a list of numbers, got {_what(value)}")
    if isinstance(value, np.ma.MaskedArray):
        if np.ma.getmaskarray(value).any():
            raise InputError(f"{name} must be numbers, got "
                             f"{int(np.count_nonzero(np.ma.getmaskarray(value)))} masked values")
        value = np.ma.getdata(value)
    if isinstance(value, (list, tuple)):
        if len(value) > hi:
            raise InputError(f"{name} has {len(value)} points, at most {hi}")
        for i, x in enumerate(value):
            if isinstance(x, bool) or not isinstance(x, numbers.Real):
                raise InputError(f"{name}[{i}] must be a number, got {_what(x)}")
    try:
        a = np.asarray(value)
    except (ValueError, TypeError, OverflowError):
        raise InputError(f"{name} must be a flat list of numbers") from None
    if a.ndim == 0 and scalar:
        a = a.reshape(1)
    if a.ndim != 1:
        raise InputError(f"{name} must be a flat list of numbers, got "
                         f"{a.ndim} dimension(s) (shape {a.shape})")
    if a.dtype.kind not in "iuf":
        k = next((i for i, x in enumerate(a.tolist()) if isinstance(x, bool) or
                  not isinstance(x, (int, float))), 0)
        raise InputError(f"{name}[{k}] must be a number, got {_what(a.tolist()[k])}")
    if a.size > hi or a.size < (1 if scalar else lo):
        raise InputError(f"{name} must have {lo} to {hi} points, got {a.size}")
    out = np.empty(a.size)
    for i, x in enumerate(a.tolist()):
        out[i] = check_one(f"{name}[{i}]", x)
    return out


def _what(x) -> str:
    text = repr(x)
    text = text if len(text) <= 40 else text[:37] + "..."
    kind = ("a boolean" if isinstance(x, bool) else "text" if isinstance(x, str) else
            type(x).__name__)
    return f"{text} ({kind})"
