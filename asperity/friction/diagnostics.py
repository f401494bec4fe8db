"""Diagnostics of a directional friction result (SPEC.md section 1).

* self-locking: directions in which a loaded face cannot be climbed (a physical outcome:
  the macroscopic friction coefficient is infinite), with the face;
* thermodynamic admissibility: dissipation per unit normal load ``p . s >= 0`` for every
  sliding direction (Clausius-Duhem);
* associativity: for a law of maximum dissipation the lateral part equals the derivative
  of the tangential part, ``L(psi) = dT/dpsi``; the largest ``|L - dT/dpsi|`` measures
  how far the law is from associated.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .reservoir import Reservoir

#: p.s below -ADMISSIBILITY_TOL counts as negative dissipation
ADMISSIBILITY_TOL = 1e-12
#: |L - dT/dpsi| below this (relative to max |p|) counts as associated
ASSOCIATED_TOL = 1e-6
#: step of the central difference for dT/dpsi on closed forms (rad)
DERIVATIVE_STEP = 1e-6
#: the same for measured surfaces: in the windward regime every facet enters the loaded
#: set with a small jump of T as the direction turns past it; a step that spans many such
#: entries measures the derivative of the averaged law, not of one jump
SURFACE_DERIVATIVE_STEP = 1e-3


def find_self_locking(res: Reservoir, face_names=None) -> list[dict]:
    """One entry per self-locking direction: psi in degrees and the face that locks."""
    out = []
    for k in np.flatnonzero(res.locked):
        f = int(res.locked_face[k])
        name = face_names[f] if face_names is not None and 0 <= f < len(face_names) else str(f)
        out.append({"psi_deg": float(np.degrees(res.psi[k])), "face": name})
    return out


@dataclass(frozen=True)
class Admissibility:
    admissible: bool
    min_dissipation: float      # min over non-locking directions of p . s
    psi_min_deg: float          # where it occurs


def check_admissibility(res: Reservoir) -> Admissibility:
    """Clausius-Duhem check p(psi) . s(psi) >= 0 over the directions of ``res``.

    Self-locking directions dissipate without bound (p . s = +inf) and pass.
    """
    t = res.tangential
    ok = ~res.locked
    if not ok.any():
        return Admissibility(True, float("inf"), float("nan"))
    k = int(np.argmin(np.where(ok, t, np.inf)))
    dmin = float(t[k])
    return Admissibility(dmin >= -ADMISSIBILITY_TOL, dmin, float(np.degrees(res.psi[k])))


@dataclass(frozen=True)
class Associativity:
    associated: bool
    max_deviation: float        # max |L - dT/dpsi|
    max_lateral: float          # max |L|
    psi_max_deg: float          # direction of the largest deviation
    deviation: np.ndarray       # (m,) L - dT/dpsi (0 where undefined)
    defined: np.ndarray         # (m,) bool, where the derivative is defined


def check_associativity(res: Reservoir, dT_dpsi: np.ndarray | None = None,
                        defined: np.ndarray | None = None) -> Associativity:
    """Compare the lateral part with dT/dpsi.

    ``dT_dpsi`` is given by the caller when it can evaluate the law off the grid (closed
    forms: :func:`closed_form_dT_dpsi`); otherwise it is taken by periodic central
    differences over ``res.psi``, which must then be a uniform grid over a full turn.
    Directions that self-lock, are set-valued, or whose neighbours are (for the grid
    difference), are left out.
    """
    L = res.lateral
    T = res.tangential
    bad = res.locked | res.set_valued
    if dT_dpsi is None:
        m = res.psi.size
        if m < 8:
            raise ValueError("associativity by grid differences needs at least 8 directions")
        h = 2 * np.pi / m
        dT_dpsi = (np.roll(np.where(bad, 0, T), -1) - np.roll(np.where(bad, 0, T), 1)) / (2 * h)
        bad = bad | np.roll(bad, 1) | np.roll(bad, -1)
    ok = ~bad if defined is None else (~bad & defined)
    dev = np.where(ok, L - np.where(ok, dT_dpsi, 0.0), 0.0)
    if not ok.any():
        return Associativity(True, 0.0, 0.0, float("nan"), dev, ok)
    k = int(np.argmax(np.abs(dev)))
    pmax = float(np.max(np.hypot(res.p[ok, 0], res.p[ok, 1])))
    maxdev = float(abs(dev[k]))
    return Associativity(maxdev <= ASSOCIATED_TOL * max(pmax, 1e-300), maxdev,
                         float(np.max(np.abs(L[ok]))), float(np.degrees(res.psi[k])), dev, ok)


def closed_form_dT_dpsi(evaluate, psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """dT/dpsi of a closed-form law by a central difference of step DERIVATIVE_STEP.

    ``evaluate(psi) -> Reservoir``.  Returns (dT/dpsi, defined) where ``defined`` is
    False if either neighbour self-locks or is set-valued (a jump of the reservoir).
    """
    h = DERIVATIVE_STEP
    return dT_dpsi_from(evaluate(psi + h), evaluate(psi - h))


def dT_dpsi_from(rp: Reservoir, rm: Reservoir, h: float = DERIVATIVE_STEP
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Central difference of T between reservoirs at psi + h and psi - h."""
    defined = ~(rp.locked | rm.locked | rp.set_valued | rm.set_valued)
    dT = np.where(defined, (np.where(defined, rp.tangential, 0) - np.where(defined, rm.tangential, 0))
                  / (2 * h), 0.0)
    return dT, defined


#: self-locking directions on which :func:`locking_share` is evaluated, at most
MAX_SHARE_DIRECTIONS = 64


def share_directions(res: Reservoir) -> tuple[np.ndarray, np.ndarray]:
    """(shares: zeros, NaN on the self-locking directions left out; the indices of the
    self-locking directions on which :func:`locking_share` is evaluated)."""
    out = np.zeros(res.psi.shape)
    k = np.flatnonzero(res.locked)
    if k.size > MAX_SHARE_DIRECTIONS:
        out[k] = np.nan
        k = k[np.linspace(0, k.size - 1, MAX_SHARE_DIRECTIONS).round().astype(int)]
    return out, k


def locking_share(faces, res: Reservoir) -> np.ndarray:
    """For each direction of ``res``: the share of the load (weight) carried by faces that
    cannot be climbed (0 where the direction does not self-lock).  Tells whether a
    self-locking surface locks on a few steep outlier facets or on much of its area.
    Evaluated on at most MAX_SHARE_DIRECTIONS of the self-locking directions, evenly
    spread (NaN on the others)."""
    from ..progress import report
    out, k = share_directions(res)
    if k.size == 0:
        return out
    g = faces.gradient
    mu = np.asarray(faces.mu, dtype=float)
    uniform = mu.strides == (0,)
    lw = locked_weights(np.ascontiguousarray(g[:, 0]), np.ascontiguousarray(g[:, 1]),
                        np.ascontiguousarray(mu[:1] if uniform else mu), uniform,
                        np.ascontiguousarray(faces.weight, dtype=float), res.psi[k],
                        res.contact == "windward", report)
    out[k] = share_of(lw)
    return out


def locked_weights(gx, gy, mu, uniform, w, psi, windward: bool, tick=None) -> np.ndarray:
    """(m, 2): the weight of the facets that lock and of all loaded facets, for each
    direction psi; in pieces of ~PIECE_WORK facet-directions (Ctrl-C is honoured between
    them), ``tick(fraction done)`` after each."""
    from ._facet_kernels import locked_weight
    from .facet_reservoir import PIECE_WORK
    from .reservoir import LEVEL_SLOPE_TOL, LOCK_TOL
    m = psi.size
    out = np.empty((m, 2))
    step = max(1, PIECE_WORK // max(1, gx.size))
    for a in range(0, m, step):
        b = min(m, a + step)
        out[a:b] = locked_weight(gx, gy, mu, uniform, w, np.cos(psi[a:b]), np.sin(psi[a:b]),
                                 windward, LOCK_TOL, LEVEL_SLOPE_TOL)
        if tick is not None:
            tick(b / m)
    return out


def share_of(lw: np.ndarray) -> np.ndarray:
    """Locked share of the load from :func:`locked_weights`."""
    return lw[:, 0] / np.where(lw[:, 1] > 0, lw[:, 1], 1.0)
