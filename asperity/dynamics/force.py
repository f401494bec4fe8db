"""The external load on a sliding body (:class:`Force`, public as ``asperity.Force``):
a constant force and torque plus a periodic part, square or sine, in SI units."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_array, check_choice, check_range

#: waveform name -> its code in the step kernels
WAVEFORMS = {"none": 0, "square": 1, "sine": 2}


@dataclass(frozen=True)
class Force:
    """An external load on a sliding body: f(t) = constant + amplitude w(t), evaluated at
    the step midpoints.

    Passed as ``force=`` to :func:`asperity.slide_body` and :func:`asperity.simulate_body`
    (which then need ``t_end``: a loaded body need not come to rest).  Calling it,
    ``force(t)``, gives the (k, 3) load at the times t.

    Parameters
    ----------
    constant : array_like of float, optional
        1 to 3 numbers (fx, fy, torque), missing ones 0 (default all 0): the force in N
        along the world x and y axes (not the texture's: a ``texture_angle_deg`` turns the
        law, not the force) and the torque in N m about the body's centre,
        counter-clockwise positive; each within +-1e12.
    amplitude : array_like of float, optional
        The periodic part's amplitude, as ``constant`` (default all 0).
    period : float, optional
        T, s, in [1e-9, 1e9] (default 1).
    waveform : str, optional
        "none" (default; w = 0: the constant alone), "square" (w = +1 on the first half of
        each period, -1 on the second) or "sine" (w = sin(2 pi t / T)).

    Raises
    ------
    InputError
        A value outside its range, an unknown waveform.

    See Also
    --------
    asperity.slide_body, asperity.simulate_body

    Examples
    --------
    A disc of 2 kg at rest on Coulomb friction mu = 0.3, pushed along x by 1.5 times what
    friction holds, accelerates at F / m - mu g = 1.4715 m/s^2:

    >>> from asperity import Force, coulomb_law, disc_footprint, slide_body
    >>> push = Force(constant=(1.5 * 0.3 * 2.0 * 9.81, 0.0))          # N; torque 0
    >>> s = slide_body(coulomb_law(0.3), disc_footprint(0.05, contact_points=64), 0.0, 0.0,
    ...                mass=2.0, dt=1e-3, t_end=0.2, force=push)
    >>> round(float(s.result.u[-1, 0]), 4)                             # m/s after 0.2 s
    0.2943
    >>> Force(amplitude=(0.0, 0.0, 0.01), period=0.5, waveform="square")(0.3)   # N, N, N m
    array([[ 0.  ,  0.  , -0.01]])
    """

    constant: tuple = (0.0, 0.0, 0.0)
    amplitude: tuple = (0.0, 0.0, 0.0)
    period: float = 1.0
    waveform: str = "none"

    def __post_init__(self):
        check_choice("waveform", self.waveform, tuple(WAVEFORMS))
        check_range("period", self.period, 1e-9, 1e9, unit="s")
        for name in ("constant", "amplitude"):
            v = np.zeros(3)
            a = check_array(name, getattr(self, name), ndim=1)
            if not 1 <= a.size <= 3 or np.any(np.abs(a) > 1e12):
                raise InputError(f"{name} must be 1 to 3 numbers (fx, fy in N, torque in N m) "
                                 f"within +-1e12, got {a}")
            v[:a.size] = a
            object.__setattr__(self, name, tuple(float(x) for x in v))

    def params(self) -> np.ndarray:
        return np.array([WAVEFORMS[self.waveform], self.period, *self.constant, *self.amplitude])

    def __call__(self, t) -> np.ndarray:
        """(m, 3) force at the times t."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.waveform == "square":
            w = np.where(np.mod(t / self.period, 1.0) < 0.5, 1.0, -1.0)
        elif self.waveform == "sine":
            w = np.sin(2 * np.pi * t / self.period)
        else:
            w = np.zeros_like(t)
        return np.asarray(self.constant)[None, :] + w[:, None] * np.asarray(self.amplitude)[None, :]
