"""The convex sliding set ``D`` of a Walker-Leine law, given by samples of its support
function ``h`` and of ``h'``.

Between samples ``h'/h`` is linear in ``psi`` (so ``ln h`` is the exact trapezoidal
integral of it); a repeated ``psi`` with two values of ``h'`` is a flat edge of ``D`` (a
set-valued sliding direction).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_array
from .geometry import TOL, TWO_PI, psi_array, tan_integral, unit
from .sets import RADIUS_MAX, RADIUS_MIN, StarSet


@dataclass(frozen=True)
class ConvexSet:
    """Convex set ``D`` from samples of its support function.

    psi : (n,) float, non-decreasing sliding directions (rad), psi[-1] < psi[0] + 2 pi;
          a value may appear twice (a flat edge of D: h' jumps there)
    h   : (n,) float, support function h_D(psi) > 0
    dh  : (n,) float, h'(psi) (left and right values at a flat edge)

    The boundary point with outward normal s(psi) is ``y = h s + h' s_perp``; its polar
    angle is ``psi + delta`` with ``delta = atan(h'/h)``.  Between distinct samples delta is
    linear in psi and ``ln h`` its exact integral ``int tan(delta) dpsi``, so the samples must
    satisfy ``ln h[k+1] - ln h[k] = tan_integral(...)`` (also across the wrap to
    psi[0] + 2 pi).  D is convex iff h + h'' = h (1 + g^2)(1 + delta') >= 0, i.e. iff the
    polar angle of y never decreases: delta' >= -1 on every interval and delta does not
    drop at a flat edge.
    """

    psi: np.ndarray
    h: np.ndarray
    dh: np.ndarray
    boundary: StarSet = field(init=False, repr=False, compare=False)
    edges: np.ndarray = field(init=False, repr=False, compare=False)

    #: boundary samples per interval for the radial function of D
    SUBDIVISIONS = 4

    def __post_init__(self):
        psi = np.array(check_array("psi", self.psi), dtype=float)
        h = np.array(check_array("h", self.h), dtype=float)
        dh = np.array(check_array("dh", self.dh), dtype=float)
        n = psi.size
        if psi.ndim != 1 or n < 3 or h.shape != psi.shape or dh.shape != psi.shape:
            raise InputError(f"psi, h and dh must have the same shape (n,), n >= 3, got "
                             f"{psi.shape}, {h.shape}, {dh.shape}")
        for name, a in (("psi", psi), ("h", h), ("dh", dh)):
            if not np.all(np.isfinite(a)):
                raise InputError(f"{name} must be finite (index {int(np.argmin(np.isfinite(a)))})")
        if np.any(h <= 0):
            raise InputError(f"h must be > 0, got {h.min():g} at index {int(np.argmin(h))}")
        if np.any((h < RADIUS_MIN) | (h > RADIUS_MAX)) or np.any(np.abs(dh) > RADIUS_MAX):
            raise InputError(f"h and |dh| must lie in [{RADIUS_MIN:g}, {RADIUS_MAX:g}], got h in "
                             f"[{h.min():g}, {h.max():g}], max |dh| {np.abs(dh).max():g}")
        if np.any(np.abs(psi) > 4 * TWO_PI):
            raise InputError(f"psi must be angles within +-{4 * TWO_PI:.4g} rad, got "
                             f"{np.abs(psi).max():g}")
        step = np.diff(psi)
        if np.any(step < 0) or not psi[-1] < psi[0] + TWO_PI:
            raise InputError("psi must be non-decreasing over less than a full turn")
        if np.any((step[1:] == 0) & (step[:-1] == 0)):
            raise InputError("psi may repeat a value at most twice (a flat edge)")
        for a in (psi, h, dh):
            a.setflags(write=False)
        object.__setattr__(self, "psi", psi)
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "dh", dh)
        lnh, delta = self.ln_h, self.delta
        k0, k1, d = self._intervals()
        integral = tan_integral(delta[k0], delta[k1], d, d)
        jump = lnh[k1] - lnh[k0] - integral
        bad = np.abs(jump) > TOL.support_consistency * (1.0 + np.abs(lnh[k0]))
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise InputError(
                f"h and dh are not a consistent support function: ln h changes by "
                f"{lnh[k1[k]] - lnh[k0[k]]:.6g} from psi = {math.degrees(psi[k0[k]]):.6g} deg to "
                f"{math.degrees(psi[k1[k]]):.6g} deg, the integral of h'/h gives {integral[k]:.6g}")
        same = step == 0
        edges = psi[:-1][same]
        edges.setflags(write=False)
        object.__setattr__(self, "edges", edges)
        if self.min_turn_rate() < -TOL.curvature:
            raise InputError(f"D is not convex: the polar angle of its boundary point turns back "
                             f"(d angle / d psi = {self.min_turn_rate():.6g} < 0)")
        # boundary polygon (inscribed) for the radial function and gauge of D
        m = self.SUBDIVISIONS
        t = (np.arange(m) / m)[None, :] * d[:, None]                      # (intervals, m)
        q = (psi[k0][:, None] + t).ravel()
        pts = self._point(np.repeat(k0, m), t.ravel(), q)
        # the near end of a flat edge (left value of h') ends the interval before it
        ends = np.flatnonzero(same)
        if ends.size:
            pe = self._point(ends, np.zeros(ends.size), psi[ends])
            pts = np.insert(pts, np.searchsorted(q, psi[ends], side="left"), pe, axis=0)
        object.__setattr__(self, "boundary", StarSet(_dedupe(pts)))

    @property
    def g(self) -> np.ndarray:
        """(n,) h'/h at the samples."""
        return self.dh / self.h

    @property
    def delta(self) -> np.ndarray:
        """(n,) atan(h'/h): angle from s(psi) to the boundary point with that normal."""
        return np.arctan2(self.dh, self.h)

    @property
    def ln_h(self) -> np.ndarray:
        return np.log(self.h)

    def _intervals(self):
        """(k0, k1, length) of the intervals between distinct consecutive samples, the last
        one wrapping round to psi[0] + 2 pi."""
        n = self.psi.size
        k0 = np.arange(n)
        k1 = (k0 + 1) % n
        d = np.where(k1 > k0, self.psi[k1] - self.psi[k0], self.psi[k1] + TWO_PI - self.psi[k0])
        keep = d > 0
        return k0[keep], k1[keep], d[keep]

    def _locate(self, psi):
        """Sample k at or before each psi (the right-hand one at a flat edge) and psi - psi_k."""
        p0 = self.psi[0]
        pm = p0 + np.mod(psi - p0, TWO_PI)
        k = np.clip(np.searchsorted(self.psi, pm, side="right") - 1, 0, self.psi.size - 1)
        return k, pm - self.psi[k]

    def _lnh_delta(self, k, t):
        n = self.psi.size
        k1 = (k + 1) % n
        d = np.where(k1 > k, self.psi[k1] - self.psi[k], self.psi[k1] + TWO_PI - self.psi[k])
        d0, d1 = self.delta[k], self.delta[k1]
        safe = np.where(d > 0, d, 1.0)
        return self.ln_h[k] + tan_integral(d0, d1, safe, t), d0 + (d1 - d0) * t / safe

    def _point(self, k, t, psi):
        lnh, delta = self._lnh_delta(k, t)
        return (np.exp(lnh) / np.cos(delta))[:, None] * unit(psi + delta)

    def support(self, psi) -> np.ndarray:
        psi = psi_array(psi)
        k, t = self._locate(psi)
        return np.exp(self._lnh_delta(k, t)[0])

    def normal_point(self, psi):
        """(y, y_minus, y_plus): the boundary point(s) with outward normal s(psi).

        Away from a flat edge the three are equal; on one (|psi - edge| <= TOL.edge) the
        normal cone holds the whole edge from y_minus to y_plus and y is its midpoint."""
        psi = psi_array(psi)
        k, t = self._locate(psi)
        y = self._point(k, t, psi)
        ym, yp = y.copy(), y.copy()
        if self.edges.size:
            p0 = self.psi[0]
            diff = np.mod(psi[:, None] - self.edges[None, :] + math.pi, TWO_PI) - math.pi
            hit = np.abs(diff) <= TOL.edge
            for i in np.flatnonzero(hit.any(axis=1)):
                e = self.edges[int(np.argmax(hit[i]))]
                j = int(np.searchsorted(self.psi, p0 + np.mod(e - p0, TWO_PI), side="left"))
                ym[i] = self._point(np.array([j]), np.zeros(1), self.psi[j:j + 1])[0]
                yp[i] = self._point(np.array([j + 1]), np.zeros(1), self.psi[j + 1:j + 2])[0]
                y[i] = 0.5 * (ym[i] + yp[i])
        return y, ym, yp

    def radial(self, phi) -> np.ndarray:
        return self.boundary.radial(phi)

    def gauge(self, x) -> np.ndarray:
        return self.boundary.gauge(x)

    def min_turn_rate(self) -> float:
        """min of d(polar angle of the boundary point)/dpsi = 1 + delta' over the intervals,
        and of the jump of delta at the flat edges: >= 0 for a convex D (h + h'' >= 0)."""
        k0, k1, d = self._intervals()
        rate = 1.0 + (self.delta[k1] - self.delta[k0]) / d
        same = np.flatnonzero(np.diff(self.psi) == 0)
        jumps = self.delta[same + 1] - self.delta[same]
        return float(min(rate.min(), jumps.min() if jumps.size else np.inf))

    def is_convex(self, tol: float = TOL.curvature) -> bool:
        return self.min_turn_rate() >= -tol


def _dedupe(pts: np.ndarray) -> np.ndarray:
    """Drop consecutive (cyclic) repeats of the same point."""
    d = np.hypot(*(pts - np.roll(pts, 1, axis=0)).T)
    scale = np.hypot(pts[:, 0], pts[:, 1]).max()
    keep = d > 1e-14 * scale
    if not keep.any():
        keep[0] = True
    return pts[keep]
