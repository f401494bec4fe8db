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

from ..errors import InputError, as_number, check_instance, check_int, check_range
from ..friction.reservoir import LEVEL_SLOPE_TOL, LOCK_TOL, check_contact

#: horizontal force of one tip, in units of k_n (z_max - z_r), above which the tip is
#: reported self-locking
LOCK_FORCE_RATIO = 1.0e4
#: run-in travel in units of the elastic slip length (1 + max|p_f| + max mu) k_n dz / k_f
RUN_IN_SLIP_LENGTHS = 20.0
#: physically meaningful ranges (SI units) of the spring model's inputs; k_f may also be
#: inf (rigid springs).  The friction depends only on k_f/k_n and preload/(k_n h); beyond
#: 1e12 the tips' elastic offsets k_n h/k_f fall below the round-off of their positions.
LIMITS = {"k_n": (1e-6, 1e12), "k_f": (1e-6, 1e12), "density": (1.0, 1e20),
          "preload": (-1e6, 1e6), "k_f/k_n": (1e-6, 1e12)}
#: most spring-tip updates (springs x steps, summed over the directions of one request):
#: one to three minutes on two cores of a 2020 laptop (rigid ~5e7/s, elastic ~2e6/s)
MAX_UPDATES = {"rigid": 5e9, "elastic": 2.5e8}
#: updates one direction costs whatever its size (set-up, kernel start)
DIRECTION_UPDATES = {"rigid": 2e4, "elastic": 1e3}


#: the textures the springs slide on (texture.wedges)
TEXTURE_KINDS = ("wedge", "gaussian-wedge")

_STATUS_TEXT = {
    1: "self-locking: a spring tip cannot climb its face",
    2: "the tip return mapping did not converge",
    3: "too many face changes in one step (reduce the step)",
}


@dataclass(frozen=True)
class SpringModel:
    """The springs carried by the sliding body in the spring-on-wedge simulation.

    Springs of normal stiffness ``k_n`` and flexural stiffness ``k_f``, uniformly spread
    (``density`` per unit area) and preloaded, with the numerics of the simulation (springs
    per wedge pitch, samples per pitch).  Ranges are in ``asperity.texture.spring_model.LIMITS``.

    Parameters
    ----------
    k_n : float, default 1e3
        Normal stiffness of one spring, N/m, in [1e-6, 1e12].
    k_f : float, default inf
        Flexural (tangential) stiffness of one spring, N/m, in [1e-6, 1e12] with ``k_f/k_n``
        in [1e-6, 1e12], or ``inf`` (the string "inf" in a file): rigid springs whose tips
        follow their bases, the limit the closed form describes.
    density : float, default 1e10
        Springs per m^2, in [1, 1e20]; stresses are ``density`` x the mean spring force.
    preload : float, default 0
        Force of a spring whose tip is at z = 0, N, in [-1e6, 1e6]; the rest level
        ``z_r = -preload / k_n`` must lie below the texture's highest point.
    n_springs : int, default 64
        Springs per wedge pitch (stratified along ``t_a``), in [1, 1e6].
    steps_per_period : int, default 8000
        Samples per wedge pitch of travel along ``t_a``, in [1, 1e8].

    Raises
    ------
    asperity.InputError
        A field that is not a real number or lies outside its range (one line naming it).

    See Also
    --------
    asperity.simulate_sliding, asperity.simulate_reservoir, asperity.simulate_loading_curve

    Notes
    -----
    The friction depends only on ``k_f/k_n`` and ``preload/(k_n h)``.  Before sliding the
    springs bend: ``k_t`` = ``density`` x ``k_f`` (Pa/m) is the tangential stiffness per unit
    area of Antoni et al. eq. 10-12 (SPEC.md section 2); ``rigid`` is True when ``k_f`` is
    infinite.

    Examples
    --------
    >>> model = asperity.SpringModel(k_f=1e5, preload=1e-3)
    >>> z_r = -model.preload / model.k_n
    >>> print(model.rigid, f"k_t = {model.k_t:.3g} Pa/m, rest level {z_r:g} m")
    False k_t = 1e+15 Pa/m, rest level -1e-06 m
    >>> asperity.SpringModel().rigid
    True
    """

    k_n: float = 1.0e3
    k_f: float = math.inf
    density: float = 1.0e10
    preload: float = 0.0
    n_springs: int = 64
    steps_per_period: int = 8000

    def __post_init__(self):
        kn = check_range("k_n", self.k_n, *LIMITS["k_n"], unit="N/m")
        object.__setattr__(self, "k_n", kn)
        object.__setattr__(self, "density", check_range("density", self.density,
                                                        *LIMITS["density"], unit="springs/m^2"))
        object.__setattr__(self, "k_f", _check_k_f(self.k_f, kn))
        object.__setattr__(self, "preload", check_range("preload", self.preload,
                                                        *LIMITS["preload"], unit="N"))
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
        try:
            return cls(**d)
        except InputError as exc:
            raise InputError(f"springs.{exc}") from None


def _check_k_f(value, k_n: float) -> float:
    """k_f: a number in LIMITS["k_f"] with k_f/k_n in LIMITS["k_f/k_n"], or inf ("inf" in a
    file) for rigid springs."""
    if isinstance(value, str) and value.strip().lower() in ("inf", "infinity"):
        return math.inf
    kf = as_number("k_f", value)
    if kf == math.inf:
        return kf
    lo, hi = LIMITS["k_f"]
    if not lo <= kf <= hi:
        got = "NaN" if kf != kf else f"{kf:g}"
        raise InputError(f"k_f must be in [{lo:g}, {hi:g}] N/m or inf (rigid springs), got {got}")
    lo, hi = LIMITS["k_f/k_n"]
    if not lo <= kf / k_n <= hi:
        why = ("above it the tips' elastic offsets fall below round-off: use k_f = inf, the "
               "rigid limit" if kf / k_n > hi else "below it a tip is dragged over a million "
               "wedge heights before it slides")
        raise InputError(f"k_f / k_n must be in [{lo:g}, {hi:g}], got {kf / k_n:.3g} "
                         f"(k_f = {kf:g}, k_n = {k_n:g} N/m): {why}")
    return kf


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
    zref: float   # m, the highest point: the kernels' unit of length


def _check_model(model) -> SpringModel:
    return check_instance("model", model, SpringModel)


def _check_psi(psi) -> float:
    return check_range("psi", psi, -1e3, 1e3, unit="rad")


def _check_texture(texture):
    """A wedge texture (texture.wedges, which reads this module's [springs] tables)."""
    if isinstance(texture, type) or getattr(texture, "kind", None) not in TEXTURE_KINDS:
        check_instance("texture", texture, (), "WedgeTexture or GaussianWedgeTexture")
    return texture


def _face_points(g, mu, c: float, sn: float):
    """Closed-form reservoir point (px, py) of a tip sliding in s = (c, sn) on faces of
    slope g and friction mu (friction.faces.compute_face_reservoir), and their
    self-locking flags; inf-free (locked faces get the point of F_z = 1)."""
    slope = g * c
    nrm = np.sqrt(1.0 + g * g)
    vlen = np.sqrt(1.0 + slope * slope)
    fz = 1.0 / nrm - mu * slope / vlen
    hx = g / nrm + mu * c / vlen
    hy = mu * sn / vlen
    lock = fz <= LOCK_TOL
    safe = np.where(lock, 1.0, fz)
    return hx / safe, hy / safe, lock


def _setup(texture, psi: float, model: SpringModel, contact: str) -> _Setup:
    check_contact(contact)
    prof = _check_texture(texture).profile()
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
    px, py, lock = _face_points(g, seg_mu, c, sn)
    n_pitch = max(1, int(np.count_nonzero(seg_face == 0)))
    return _Setup(xs, zs, seg_mu, seg_face, g, loaded, px, py, lock.astype(np.int8),
                  float(xs[-1]), n_pitch, z_rest, set_valued, c, sn, zmax)


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
