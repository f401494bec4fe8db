"""The spring model of the spring-on-wedge simulation and its results.

:class:`SpringModel` holds the springs' stiffnesses, density and preload and the numerics
(springs per pitch, steps per period); :class:`SlidingResult` and :class:`LoadingCurve`
are what :mod:`asperity.texture.springs` returns.  ``_setup`` turns a texture and a sliding
direction into the profile arrays the kernels read (with the closed-form per-face
reservoir points of the rigid regime).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ..errors import InputError, check_int, check_range
from ..friction.reservoir import LEVEL_SLOPE_TOL, LOCK_TOL, check_contact

#: horizontal force of one tip, in units of k_n (z_max - z_r), above which the tip is
#: reported self-locking
LOCK_FORCE_RATIO = 1.0e4
#: run-in travel in units of the elastic slip length (1 + max|p_f| + max mu) k_n dz / k_f
RUN_IN_SLIP_LENGTHS = 20.0


_STATUS_TEXT = {
    1: "self-locking: a spring tip cannot climb its face",
    2: "the tip return mapping did not converge",
    3: "too many face changes in one step (reduce the step)",
}


@dataclass(frozen=True)
class SpringModel:
    """Springs carried by the sliding body (see module docstring).

    k_n      : N/m, normal stiffness of one spring, (0, inf)
    k_f      : N/m, flexural (tangential) stiffness of one spring, (0, inf]; inf = rigid
    density  : springs per m^2, (0, inf); stresses = density x mean spring force
    preload  : N, force of a spring whose tip is at z = 0; rest level z_r = -preload/k_n
    n_springs: springs per wedge pitch (stratified along t_a), [1, 1e6]
    steps_per_period : samples per wedge pitch of travel along t_a, [1, 1e8]
    """

    k_n: float = 1.0e3
    k_f: float = math.inf
    density: float = 1.0e10
    preload: float = 0.0
    n_springs: int = 64
    steps_per_period: int = 8000

    def __post_init__(self):
        def finite_pos(name):
            x = check_range(name, getattr(self, name), 0.0, None, low_open=True)
            if not math.isfinite(x):
                raise InputError(f"{name} must be in (0, inf) and finite, got {x:g}")
            object.__setattr__(self, name, x)

        finite_pos("k_n")
        finite_pos("density")
        kf = self.k_f
        if isinstance(kf, str) and kf.strip().lower() in ("inf", "infinity"):
            kf = math.inf
        object.__setattr__(self, "k_f", check_range("k_f", kf, 0.0, None, low_open=True,
                                                       allow_inf=True))
        pre = check_range("preload", self.preload)
        if not math.isfinite(pre):
            raise InputError(f"preload must be finite, got {pre:g}")
        object.__setattr__(self, "preload", pre)
        object.__setattr__(self, "n_springs", check_int("n_springs", self.n_springs, 1, 1_000_000))
        object.__setattr__(self, "steps_per_period",
                           check_int("steps_per_period", self.steps_per_period, 1, 100_000_000))

    @property
    def rigid(self) -> bool:
        """True when k_f = inf (tips follow their bases)."""
        return math.isinf(self.k_f)

    @property
    def k_t(self) -> float:
        """Tangential stiffness per unit area, density x k_f (Pa/m)."""
        return self.density * self.k_f

    @classmethod
    def from_dict(cls, d: dict) -> "SpringModel":
        """From the ``[springs]`` table of a texture file (k_f may be the string "inf")."""
        if not isinstance(d, dict):
            raise InputError("springs must be a table")
        allowed = [f.name for f in fields(cls)]
        for key in d:
            if key not in allowed:
                raise InputError(f"unknown key springs.{key}; allowed: {', '.join(allowed)}")
        from .wedges import build_from_table
        return build_from_table(cls, d, "springs")


@dataclass(frozen=True)
class SlidingResult:
    """Steady sliding in direction psi.

    p : (2,) averaged -lambda_T/lambda_N in (t_a, t_b) (inf entries if locked)
    tangential, lateral : p . s and p . s_perp
    normal_stress : Pa, density x mean vertical spring force
    sliding_fraction : fraction of tip-steps in contact that were sliding (window)
    """

    psi: float
    p: np.ndarray
    tangential: float
    lateral: float
    normal_stress: float
    locked: bool
    locked_face: int
    n_springs: int
    n_steps: int
    sliding_fraction: float
    set_valued: bool = False
    message: str = ""


@dataclass(frozen=True)
class LoadingCurve:
    """Tangential loading from rest to full sliding (finite k_f)."""

    psi: float
    displacement: np.ndarray
    tangential_stress: np.ndarray
    lateral_stress: np.ndarray
    normal_stress: np.ndarray
    sliding_fraction: np.ndarray
    k_t: float
    k_t_measured: float
    mu_steady: float
    locked: bool = False
    locked_face: int = -1


@dataclass(frozen=True)
class _Setup:
    xs: np.ndarray
    zs: np.ndarray
    seg_mu: np.ndarray
    seg_face: np.ndarray
    seg_g: np.ndarray
    seg_loaded: np.ndarray
    seg_px: np.ndarray
    seg_py: np.ndarray
    seg_lock: np.ndarray
    period: float
    n_pitch: int
    z_rest: float
    set_valued: bool
    c: float
    sn: float


def _check_model(model) -> SpringModel:
    if not isinstance(model, SpringModel):
        raise InputError(f"model must be a SpringModel, got {type(model).__name__}")
    return model


def _check_psi(psi) -> float:
    x = check_range("psi", psi)
    if not math.isfinite(x):
        raise InputError(f"psi must be finite (radians), got {x:g}")
    return x


def _setup(texture, psi: float, model: SpringModel, contact: str) -> _Setup:
    check_contact(contact)
    if not hasattr(texture, "profile"):
        raise InputError(f"texture must be a WedgeTexture or GaussianWedgeTexture, "
                         f"got {type(texture).__name__}")
    prof = texture.profile()
    xs = np.ascontiguousarray(prof.x, dtype=np.float64)
    zs = np.ascontiguousarray(prof.z, dtype=np.float64)
    dx = np.diff(xs)
    if np.any(dx <= 0):
        raise InputError("texture profile nodes must be strictly increasing")
    seg_mu = np.ascontiguousarray(prof.mu, dtype=np.float64)
    seg_face = np.asarray(prof.face, dtype=np.int64)
    g = np.diff(zs) / dx
    z_rest = -model.preload / model.k_n
    zmax = float(zs.max())
    if not z_rest < zmax:
        raise InputError(
            f"preload must exceed {-model.k_n * zmax:g} N (rest level z_r = -preload/k_n "
            f"= {z_rest:g} m must lie below the highest point {zmax:g} m), got {model.preload:g}")
    c, sn = math.cos(psi), math.sin(psi)
    slope = g * c
    set_valued = False
    if contact == "all-faces":
        loaded = np.ones(g.size, dtype=np.int8)
    else:
        windward = slope > LEVEL_SLOPE_TOL
        if windward.any():
            loaded = windward.astype(np.int8)
        else:
            level = np.abs(slope) <= LEVEL_SLOPE_TOL
            loaded = level.astype(np.int8)
            set_valued = bool(np.any(level & (np.abs(g) > LEVEL_SLOPE_TOL)))
    # closed-form per-face reservoir point (friction.faces.compute_face_reservoir)
    nrm = np.sqrt(1.0 + g * g)
    vlen = np.sqrt(1.0 + slope * slope)
    fz = 1.0 / nrm - seg_mu * slope / vlen
    hx = g / nrm + seg_mu * c / vlen
    hy = seg_mu * sn / vlen
    lock = fz <= LOCK_TOL
    safe = np.where(lock, 1.0, fz)
    n_pitch = max(1, int(np.count_nonzero(seg_face == 0)))
    return _Setup(xs, zs, seg_mu, seg_face, g, loaded, hx / safe, hy / safe,
                  lock.astype(np.int8), float(xs[-1]), n_pitch, z_rest, set_valued, c, sn)


def _slip_length(st: _Setup, model: SpringModel) -> float:
    """Elastic slip length (1 + max|p_f| + max mu) k_n (z_max - z_r) / k_f, m."""
    pf = np.hypot(st.seg_px, st.seg_py)[st.seg_lock == 0]
    pmax = float(pf.max()) if pf.size else 1.0
    return (1.0 + pmax + float(st.seg_mu.max())) * model.k_n * (st.zs.max() - st.z_rest) / model.k_f


def _face_of_segment(st: _Setup, seg: np.ndarray) -> int:
    seg = seg[seg >= 0]
    if seg.size == 0:
        return -1
    return int(st.seg_face[int(seg[0])])
