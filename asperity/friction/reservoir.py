"""The directional-friction result and what every friction computation shares.

:class:`Faces` is the input of the homogenisation (plane faces: gradient, local friction,
horizontal-area weight); wedge textures (:mod:`asperity.texture`) and surfaces
(:mod:`asperity.surface`) both produce it.  :class:`Reservoir` is its output: the reservoir
point ``p(psi) = -lambda_T / lambda_N`` for a set of sliding directions, with the
self-locking and set-valued flags.  The contact regimes and the tolerances that decide
"level" and "self-locking" sit here, once.
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, _kind, _show, check_array, check_choice, check_range


@dataclass(frozen=True)
class Faces:
    """The plane faces of a texture or the facets of a surface: what the homogenisation reads.

    gradient : (n, 2) float -- (dz/dx, dz/dy) of each face (dimensionless)
    mu       : (n,) float   -- local isotropic friction coefficient of each face
    weight   : (n,) float   -- horizontal (projected) area weight (wedges: fractions summing
               to 1; surfaces: area x contact weight, m^2)
    names    : tuple of n str, or None (facets of a surface are numbered)
    """

    gradient: np.ndarray
    mu: np.ndarray
    weight: np.ndarray
    names: tuple[str, ...]


CONTACT_REGIMES = ("all-faces", "windward")
#: slope g.s below which a face counts as level with the motion (windward regime)
LEVEL_SLOPE_TOL = 1e-12
#: message when, in the windward regime, every face descends in some sliding direction
NO_WINDWARD_FACE = ("windward contact: in some sliding direction every face descends, so nothing "
                    "is climbed (a tilted surface? remove the tilt, e.g. --detrend slope)")
#: vertical force share below which a face is taken as self-locking
LOCK_TOL = 1e-12
#: largest |psi| (rad) taken as a sliding direction (beyond, cos and sin lose precision)
MAX_PSI = 1e4
#: largest local friction coefficient of a face (as errors.check_mu)
MU_MAX = 100.0


@dataclass(frozen=True)
class Reservoir:
    """Reservoir points p(psi) of a texture for a set of sliding directions.

    Attributes
    ----------
    psi : ndarray, shape (m,)
        Sliding directions in radians (from t_a towards t_b).
    p : ndarray, shape (m, 2)
        ``p = -lambda_T/lambda_N`` in the (t_a, t_b) frame; rows of self-locking
        directions hold ``inf``.
    locked : ndarray of bool, shape (m,)
        Self-locking direction.
    locked_face : ndarray of int, shape (m,)
        Index of the first self-locking face (-1: none).
    set_valued : ndarray of bool, shape (m,)
        The reservoir is set-valued there (windward, along the ridges).
    contact : str
        The contact regime.
    """

    psi: np.ndarray
    p: np.ndarray
    locked: np.ndarray
    locked_face: np.ndarray
    set_valued: np.ndarray
    contact: str

    def take(self, index) -> "Reservoir":
        """The directions ``index`` (a slice or index array) of this reservoir."""
        return Reservoir(psi=self.psi[index], p=self.p[index], locked=self.locked[index],
                         locked_face=self.locked_face[index], set_valued=self.set_valued[index],
                         contact=self.contact)

    @property
    def s(self) -> np.ndarray:
        """(m, 2) unit sliding directions."""
        return np.column_stack([np.cos(self.psi), np.sin(self.psi)])

    @property
    def tangential(self) -> np.ndarray:
        """(m,) T = p . s (inf where self-locking)."""
        out = np.full(self.psi.shape, np.inf)
        ok = ~self.locked
        out[ok] = np.einsum("ij,ij->i", self.p[ok], self.s[ok])
        return out

    @property
    def lateral(self) -> np.ndarray:
        """(m,) L = p . s_perp, s_perp = s turned +90 deg (0 where self-locking)."""
        out = np.zeros(self.psi.shape)
        ok = ~self.locked
        s = self.s[ok]
        out[ok] = -self.p[ok, 0] * s[:, 1] + self.p[ok, 1] * s[:, 0]
        return out


def check_contact(contact: str, name: str = "contact") -> str:
    """Return ``contact`` if it is a known contact regime, else raise InputError."""
    return check_choice(name, contact, CONTACT_REGIMES)


def check_progress(progress):
    """``progress`` if it is None or a callable(fraction), else InputError."""
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be a callable or None, got {_show(progress)} "
                         f"({_kind(progress)})")
    return progress


def check_psi(psi, name: str = "psi") -> np.ndarray:
    """Sliding directions (rad): a number or a 1-d array of at least one finite angle within
    +-MAX_PSI, as a (m,) float array; else one InputError line naming ``name``."""
    if isinstance(psi, (numbers.Real, np.generic)):
        return np.array([check_range(name, psi, -MAX_PSI, MAX_PSI, unit="rad")])
    if psi is None or isinstance(psi, (str, bytes, dict)):
        raise InputError(f"{name} must be a number or a 1-d array of angles (rad), got "
                         f"{_show(psi)} ({_kind(psi)})")
    a = np.atleast_1d(check_array(name, psi, min_size=1))
    if a.ndim != 1:
        raise InputError(f"{name} must be a number or a 1-d array of angles, got shape {a.shape}")
    far = np.abs(a) > MAX_PSI
    if far.any():
        raise InputError(f"{name} must be angles within +-{MAX_PSI:g} rad, got "
                         f"{a[far][0]:g} at index {int(np.flatnonzero(far)[0])}")
    return a


def directions(n: int) -> np.ndarray:
    """n equally spaced sliding directions psi_k = 2 pi k / n (radians), psi_0 = 0."""
    return 2.0 * np.pi * np.arange(n) / n


def locked_runs(res: Reservoir) -> str:
    """Self-locking directions as circular runs: '[-40, 40] deg, [170, 190] deg'."""
    lk = res.locked
    n = lk.size
    deg = np.degrees(res.psi)
    if lk.all():
        return "all directions"
    start = int(np.flatnonzero(~lk)[0])          # begin scanning at a free direction
    runs, cur = [], None
    for j in range(1, n + 1):
        k = (start + j) % n
        if lk[k]:
            cur = [k, k] if cur is None else [cur[0], k]
        elif cur is not None:
            runs.append(cur)
            cur = None
    def ang(k):
        a = deg[k]
        return a - 360.0 if a > 180.0 else a
    out = []
    for a, b in runs:
        lo, hi = ang(a), ang(b)
        if hi < lo:
            lo, hi = deg[a], deg[b] + 360.0 if deg[b] < deg[a] else deg[b]
        out.append(f"[{lo:g}, {hi:g}] deg")
    return ", ".join(out)
