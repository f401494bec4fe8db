"""Gaits of a chain of rigid links (robots built of modules): the serpenoid and a table of
joint angles over one period (the gait files' "joints" kind).

A chain of n links of length L / n, counted from the tail: link 0 at the tail, link n - 1
at the head; joint j (j = 1..n-1) between links j - 1 and j, at s = j L / n.  The joint
angle phi_j is the angle of link j minus that of link j - 1 (positive: the body turns
left going head-wards, as a positive curvature does).  The link angles are
theta_j = sum_{i <= j} phi_i minus their mean (the body frame: the length-weighted mean
of the link angles is 0).  A point at s lies on link floor(s n / L) (the head-ward link
where s is a joint) and carries that link's angle as its tangent; positions and
velocities are exact sums over the links.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_array, check_int, check_range
from .gait import AMPLITUDE_RANGE, WAVES_RANGE, Gait, _check_size, check_times

LINKS_RANGE = (2, 1000)
JOINT_AMPLITUDE_RANGE = (0.0, math.pi)      #: rad
PHASE_RANGE = (-2 * math.pi, 2 * math.pi)   #: rad
OFFSET_RANGE = (-math.pi, math.pi)          #: rad
ROWS_RANGE = (4, 100_000)                   #: rows of a joint-angle table


class _ChainGait(Gait):
    """A chain of ``links`` links; subclasses give the joint angles and their rates."""

    def _joints(self, t: np.ndarray):          # pragma: no cover - every subclass has one
        raise NotImplementedError

    def link_angles(self, t) -> tuple[np.ndarray, np.ndarray]:
        """The links' angles in the body frame (rad, zero mean) and their rates (rad/s) at
        times ``t`` (nt,): (nt, links) each, link 0 at the tail."""
        phi, rate = self._joints(check_times(t))
        theta = np.zeros((phi.shape[0], self.links))
        omega = np.zeros_like(theta)
        np.cumsum(phi, axis=1, out=theta[:, 1:])
        np.cumsum(rate, axis=1, out=omega[:, 1:])
        theta -= theta.mean(axis=1, keepdims=True)
        omega -= omega.mean(axis=1, keepdims=True)
        return theta, omega

    def _frame(self, t: np.ndarray):
        """Link angles, rates, unit tangents (complex) and the joints' positions and
        velocities (nt, links + 1) complex, the tail at 0."""
        theta, omega = self.link_angles(t)
        e = np.exp(1j * theta)
        ell = self.length / self.links
        joints = np.zeros((theta.shape[0], self.links + 1), complex)
        rates = np.zeros_like(joints)
        np.cumsum(ell * e, axis=1, out=joints[:, 1:])
        np.cumsum(1j * ell * omega * e, axis=1, out=rates[:, 1:])
        return theta, omega, e, joints, rates

    def _curve(self, t: np.ndarray, s: np.ndarray, rates: bool = True, tol: float = 0.0):
        theta, omega, e, joints, joint_rates = self._frame(t)
        ell = self.length / self.links
        k = np.minimum(np.floor(np.round(s / ell, 9)).astype(np.int64), self.links - 1)
        along = s - k * ell
        z = joints[:, k] + along * e[:, k]
        zd = joint_rates[:, k] + along * 1j * omega[:, k] * e[:, k]
        return z, zd, theta[:, k]

    def _polyline(self, t: np.ndarray, segments: int):
        """The chain itself: its links are the polyline (exact), whatever ``segments``:
        joints x + i y (nt, links + 1) complex, and their arc lengths (m)."""
        return self._frame(t)[3], np.arange(self.links + 1) * (self.length / self.links)


class SerpenoidChain(_ChainGait):
    """The serpenoid of modular snake robots: joint angles
    phi_j(t) = a sin(2 pi t / T - j b) + c, j = 1..n-1, joints counted from the tail.

    **Direction**: joint j lags joint j - 1 by the phase b, so for b > 0 the wave runs
    from the tail to the head, for b < 0 from the head to the tail (the direction of the
    :class:`~.gait.CurvatureWave`, crawling head-wards with mu_t > mu_f).

    Correspondence: the joint angle is the curvature times the link length, so the chain
    with a = A / n, b = -2 pi k / n, c = 0 is the curvature wave A, k (whole k) sampled at
    the joints, a quarter period earlier: its shape at t approaches the wave's at t - T/4
    as n grows, the positions to O(n^-2) (:meth:`from_wave`).

    links : n in [2, 1000]; amplitude : a (rad) in [0, pi]; phase : b (rad) in
    [-2 pi, 2 pi]; offset : c (rad) in [-pi, pi] (a steady turn); period : T (s);
    length : L (m).
    """

    kind = "serpenoid"

    def __init__(self, links, amplitude, phase, offset=0.0, period=1.0, length=1.0):
        self.links = check_int("links", links, *LINKS_RANGE)
        self.amplitude = check_range("amplitude", amplitude, *JOINT_AMPLITUDE_RANGE,
                                     unit="rad")
        self.phase = check_range("phase", phase, *PHASE_RANGE, unit="rad")
        self.offset = check_range("offset", offset, *OFFSET_RANGE, unit="rad")
        self.length, self.period = _check_size(length, period)
        self.name = (f"serpenoid chain of {self.links} links, a = {self.amplitude:.4g} rad, "
                     f"b = {self.phase:.4g} rad")

    @classmethod
    def from_wave(cls, amplitude, waves, links, period=1.0, length=1.0) -> SerpenoidChain:
        """The chain of ``links`` links closest to the curvature wave A = ``amplitude``,
        k = ``waves`` (whole k): a = A / n, b = -2 pi k / n, its shape at t that of the
        wave at t - T / 4."""
        n = check_int("links", links, *LINKS_RANGE)
        k = check_range("waves", waves, *WAVES_RANGE, low_open=True)
        a = check_range("amplitude", amplitude, *AMPLITUDE_RANGE)
        return cls(n, a / n, -2 * math.pi * k / n, 0.0, period, length)

    def _joints(self, t: np.ndarray):
        j = np.arange(1, self.links)
        arg = 2 * math.pi * np.mod(t / self.period, 1.0)[:, None] - j * self.phase
        return (self.amplitude * np.sin(arg) + self.offset,
                (2 * math.pi / self.period) * self.amplitude * np.cos(arg))

    def params(self) -> dict:
        return {"kind": self.kind, "links": self.links, "amplitude": self.amplitude,
                "phase": self.phase, "offset": self.offset, "period": self.period,
                "length": self.length}


class JointTable(_ChainGait):
    """Joint angles tabulated over one period, interpolated by a periodic cubic spline.

    angles : (rows, links - 1) rad, rows at the equally spaced times k T / rows,
    k = 0..rows-1 (the first row is repeated at t = T), columns the joints j = 1..n-1
    counted from the tail, each in [-pi, pi]; at least 4 rows and 2 links.  The joints'
    rates are the spline's derivative.
    """

    kind = "joints"

    def __init__(self, angles, period=1.0, length=1.0, name: str | None = None,
                 source: str = ""):
        a = check_array("angles", angles, ndim=2)
        rows, cols = a.shape
        if rows < ROWS_RANGE[0] or rows > ROWS_RANGE[1]:
            raise InputError(f"angles must have {ROWS_RANGE[0]} to {ROWS_RANGE[1]} rows "
                             f"(times over one period), got {rows}")
        self.links = check_int("links", cols + 1, *LINKS_RANGE)
        bad = np.argwhere(np.abs(a) > math.pi * (1 + 1e-12))     # 180 deg in rad passes
        if bad.size:
            i, j = bad[0]
            raise InputError(f"angles[{i}][{j}] must be in [-pi, pi] rad, got {a[i, j]:g}")
        self.length, self.period = _check_size(length, period)
        from scipy.interpolate import CubicSpline
        times = np.arange(rows + 1) * (self.period / rows)
        self.angles = a
        self._spline = CubicSpline(times, np.vstack([a, a[:1]]), axis=0, bc_type="periodic")
        self._rate = self._spline.derivative()
        self.source = source
        self.name = name if name is not None else \
            f"joint table of {self.links} links, {rows} rows"

    def _joints(self, t: np.ndarray):
        tau = np.mod(t, self.period)
        return self._spline(tau), self._rate(tau)

    def params(self) -> dict:
        return {"kind": self.kind, "links": self.links, "rows": int(self.angles.shape[0]),
                "period": self.period, "length": self.length, "source": self.source}
