"""Wedge textures: the periodic sawtooth and the Gaussian-height wedge texture.

Frame (SPEC.md section 1): ``t_a`` across the ridges (x), ``t_b`` along the ridges (y),
heights z above the wedges' common base line (the mean line, z = 0).  One wedge has a
face of slope angle ``alpha`` rising towards ``+t_a`` with local friction ``mu_alpha``
and a face of slope angle ``beta`` falling towards ``+t_a`` with ``mu_beta``.

A texture gives :meth:`faces` (gradient, friction, horizontal-area weight: all the closed
form needs) and :meth:`profile` (z(x) over one period, which the springs slide over).

Angles in degrees at the interface (files, CLI), in radians inside; lengths in metres.
"""
from __future__ import annotations

import math
from os import PathLike
from dataclasses import MISSING as _MISSING
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..errors import (
    InputError,
    TextureFileError,
    check_instance,
    check_int,
    check_mu,
    check_range,
    check_text,
)
from ..friction.reservoir import Faces
from ..io import read_toml


@dataclass(frozen=True)
class Profile:
    """A periodic piecewise-linear profile z(x) along t_a, uniform along t_b.

    x : (k+1,) float, nodes from 0 to ``period`` (x[0] = 0, x[-1] = period), metres
    z : (k+1,) float, heights at the nodes (z[0] == z[-1]), metres
    mu : (k,) float, friction of segment i (between nodes i and i+1)
    face : (k,) int, index into :meth:`faces` of segment i (-1 for a flat gap)
    """

    x: np.ndarray
    z: np.ndarray
    mu: np.ndarray
    face: np.ndarray

    @property
    def period(self) -> float:
        return float(self.x[-1])

    def height(self, xq) -> np.ndarray:
        """Heights at the points ``xq`` (any shape), the profile repeated periodically."""
        xq = np.mod(np.asarray(xq, dtype=float), self.period)
        return np.interp(xq, self.x, self.z)


#: physically meaningful ranges: face angles (deg; a flatter face is level), wedge heights
#: (m, from an atom to a hundred metres), the mean gap between Gaussian wedges in mean
#: base widths (sparser wedges are not sampled by the springs)
LIMITS = {"angle": (1e-6, 90.0), "height": (1e-10, 100.0), "gap_widths": (0.0, 100.0)}
#: bytes of memory per wedge of a Gaussian texture's profile and its spring set-up
BYTES_PER_WEDGE = 600


def _check_angle(name: str, value) -> float:
    x = check_range(name, value, 0.0, 90.0, low_open=True, high_open=True, unit="deg")
    if x < LIMITS["angle"][0]:
        raise InputError(f"{name} must be at least {LIMITS['angle'][0]:g} deg (a flatter face "
                         f"is level), got {x:g}")
    return x


def _check_length(name: str, value, allow_zero: bool = False) -> float:
    lo, hi = LIMITS["height"]
    return check_range(name, value, 0.0 if allow_zero else lo, hi, unit="m")


@dataclass(frozen=True)
class WedgeTexture:
    r"""Periodic sawtooth of identical wedges (Antoni et al. section 3.1, SPEC.md section 2).

    Ridges run along ``t_b``; across them a wedge of height ``h`` has a face of slope angle
    ``alpha`` rising towards ``+t_a`` (local friction ``mu_alpha``) and one of slope angle
    ``beta`` falling towards ``+t_a`` (``mu_beta``); the period is :math:`h(\cot\alpha +
    \cot\beta)`.  ``faces()`` gives the two faces (gradients ``(tan alpha, 0)`` and
    ``(-tan beta, 0)``, weighted by their horizontal lengths), ``profile()`` the height
    profile z(x) over one period (m) that the springs slide over.

    Parameters
    ----------
    alpha_deg, beta_deg : float
        Slope angles of the alpha and beta faces, degrees, in [1e-6, 90).
    mu_alpha, mu_beta : float
        Local (isotropic) friction coefficients of the alpha and beta faces, in [0, 100].
    height : float, default 1e-6
        Wedge height ``h``, m, in [1e-10, 100]; the homogenised friction does not depend on it.

    Raises
    ------
    asperity.InputError
        A field that is not a real number or lies outside its range (one line naming it).

    See Also
    --------
    asperity.GaussianWedgeTexture, asperity.load_texture, asperity.compute_axis_coefficients

    Examples
    --------
    >>> tex = asperity.WedgeTexture(alpha_deg=30.0, beta_deg=10.0, mu_alpha=0.1, mu_beta=0.2)
    >>> mu = asperity.compute_axis_coefficients(tex)
    >>> print(f"mu_a+ = {mu['mu_a_plus']:.6f}, mu_a- = {mu['mu_a_minus']:.6f}")
    mu_a+ = 0.185697, mu_a- = 0.193238
    >>> print(f"period {tex.profile().period * 1e6:.4f} um for h = {tex.height * 1e6:g} um")
    period 7.4033 um for h = 1 um
    """

    alpha_deg: float
    beta_deg: float
    mu_alpha: float
    mu_beta: float
    height: float = 1e-6
    kind = "wedge"

    def __post_init__(self):
        object.__setattr__(self, "alpha_deg", _check_angle("alpha_deg", self.alpha_deg))
        object.__setattr__(self, "beta_deg", _check_angle("beta_deg", self.beta_deg))
        object.__setattr__(self, "mu_alpha", check_mu("mu_alpha", self.mu_alpha))
        object.__setattr__(self, "mu_beta", check_mu("mu_beta", self.mu_beta))
        object.__setattr__(self, "height", _check_length("height", self.height))

    @property
    def alpha(self) -> float:
        """alpha in radians."""
        return math.radians(self.alpha_deg)

    @property
    def beta(self) -> float:
        """beta in radians."""
        return math.radians(self.beta_deg)

    def faces(self) -> Faces:
        ta, tb = math.tan(self.alpha), math.tan(self.beta)
        return Faces(
            gradient=np.array([[ta, 0.0], [-tb, 0.0]]),
            mu=np.array([self.mu_alpha, self.mu_beta]),
            weight=np.array([tb / (ta + tb), ta / (ta + tb)]),
            names=("alpha", "beta"),
        )

    def profile(self) -> Profile:
        h = self.height
        xa = h / math.tan(self.alpha)
        period = xa + h / math.tan(self.beta)
        return Profile(
            x=np.array([0.0, xa, period]),
            z=np.array([0.0, h, 0.0]),
            mu=np.array([self.mu_alpha, self.mu_beta]),
            face=np.array([0, 1]),
        )

    def to_dict(self) -> dict:
        return {"kind": self.kind, **{f.name: getattr(self, f.name) for f in fields(self)}}


@dataclass(frozen=True)
class GaussianWedgeTexture:
    """Wedges of fixed angles whose heights follow a normal distribution.

    The wedges stand on one base line (z = 0) at random positions: consecutive wedges are
    separated by flat gaps drawn from an exponential distribution of mean ``mean_gap``.
    Heights are drawn from N(height_mean, height_std) truncated to positive values
    (non-positive draws are drawn again).  The profile repeats with the total length.  The
    closed form is the periodic :class:`asperity.WedgeTexture`'s (SPEC.md section 2).

    Parameters
    ----------
    alpha_deg, beta_deg, mu_alpha, mu_beta : float
        As for :class:`asperity.WedgeTexture`.
    height_mean : float
        Mean wedge height, m, in [1e-10, 100].
    height_std : float
        Standard deviation of the heights, m, in [0, 3 ``height_mean``].
    n_wedges : int, default 200
        Number of wedges in one period of the texture, in [1, 1e7].
    seed : int, default 0
        Random seed (>= 0), so that a texture file always gives the same profile.
    mean_gap : float or None, default None
        Mean flat gap between wedges, m, in [0, 100 mean base widths]; None: half the mean
        base width ``height_mean (cot alpha + cot beta)``.

    Raises
    ------
    asperity.InputError
        A field that is not a real number or lies outside its range (one line naming it).

    Examples
    --------
    >>> tex = asperity.GaussianWedgeTexture(30.0, 10.0, 0.1, 0.2, height_mean=5e-6,
    ...                                     height_std=1.5e-6, n_wedges=100, seed=7)
    >>> h = tex.heights()
    >>> print(h.size, bool((h > 0).all()), f"mean gap {tex.mean_gap * 1e6:.4f} um")
    100 True mean gap 18.5083 um
    >>> round(asperity.compute_axis_coefficients(tex)["mu_a_plus"], 6)
    0.185697
    """

    alpha_deg: float
    beta_deg: float
    mu_alpha: float
    mu_beta: float
    height_mean: float
    height_std: float
    n_wedges: int = 200
    seed: int = 0
    mean_gap: float | None = None
    kind = "gaussian-wedge"
    _profile: Profile | None = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "alpha_deg", _check_angle("alpha_deg", self.alpha_deg))
        object.__setattr__(self, "beta_deg", _check_angle("beta_deg", self.beta_deg))
        object.__setattr__(self, "mu_alpha", check_mu("mu_alpha", self.mu_alpha))
        object.__setattr__(self, "mu_beta", check_mu("mu_beta", self.mu_beta))
        object.__setattr__(self, "height_mean", _check_length("height_mean", self.height_mean))
        object.__setattr__(self, "height_std",
                           _check_length("height_std", self.height_std, allow_zero=True))
        object.__setattr__(self, "n_wedges", check_int("n_wedges", self.n_wedges, 1, 10_000_000))
        object.__setattr__(self, "seed", check_int("seed", self.seed, 0, 2**63 - 1))
        width = self.height_mean * (1 / math.tan(self.alpha) + 1 / math.tan(self.beta))
        if self.mean_gap is None:
            object.__setattr__(self, "mean_gap", 0.5 * width)
        else:
            gap = check_range("mean_gap", self.mean_gap, 0.0, None, unit="m")
            most = LIMITS["gap_widths"][1]
            if gap > most * width:
                raise InputError(f"mean_gap must be at most {most:g} mean base widths "
                                 f"({most * width:g} m; sparser wedges are not sampled), got "
                                 f"{gap:g}")
            object.__setattr__(self, "mean_gap", gap)
        if self.height_std > 3.0 * self.height_mean:
            raise InputError(
                f"height_std must be at most 3 x height_mean ({3 * self.height_mean:g} m) "
                f"so that positive heights can be drawn, got {self.height_std:g}"
            )

    alpha = WedgeTexture.alpha
    beta = WedgeTexture.beta

    def faces(self) -> Faces:
        # Every wedge, whatever its height, has the same two faces in the same
        # proportion of horizontal length; the flat gaps carry no load once the
        # springs' rest level is above the base line.
        return WedgeTexture.faces(self)  # type: ignore[arg-type]

    def heights(self) -> np.ndarray:
        """The n_wedges drawn heights (m), reproducible from ``seed``."""
        rng = np.random.default_rng(self.seed)
        h = rng.normal(self.height_mean, self.height_std, self.n_wedges)
        for _ in range(1000):
            bad = h <= 0.0
            if not bad.any():
                break
            h[bad] = rng.normal(self.height_mean, self.height_std, int(bad.sum()))
        return h

    def profile(self) -> Profile:
        if self._profile is not None:
            return self._profile
        from ..resources import check_memory
        n = self.n_wedges
        check_memory(BYTES_PER_WEDGE * float(n), f"a profile of {n} wedges", "use fewer wedges")
        rng = np.random.default_rng([self.seed, 1])
        h = self.heights()
        gaps = rng.exponential(self.mean_gap, n) if self.mean_gap > 0 else np.zeros(n)
        ca, cb = 1 / math.tan(self.alpha), 1 / math.tan(self.beta)
        # nodes per wedge: ridge, valley, then the end of the gap to the next valley (if
        # any); x by a running sum of the steps, as one would add them one by one
        keep = np.column_stack([np.ones((n, 2), bool), gaps > 0]).ravel()
        step = np.column_stack([h * ca, h * cb, gaps]).ravel()[keep]
        xs = np.concatenate([[0.0], np.cumsum(step)])
        zs = np.concatenate([[0.0], np.column_stack([h, np.zeros((n, 2))]).ravel()[keep]])
        mus = np.tile([self.mu_alpha, self.mu_beta, self.mu_alpha], n)[keep]
        face = np.tile(np.array([0, 1, -1], dtype=np.int64), n)[keep]
        prof = Profile(xs, zs, mus, face)
        object.__setattr__(self, "_profile", prof)
        return prof

    def to_dict(self) -> dict:
        return {"kind": self.kind, **{f.name: getattr(self, f.name) for f in fields(self)
                                      if not f.name.startswith("_")}}


Texture = WedgeTexture | GaussianWedgeTexture
_TEXTURE_KINDS = {"wedge": WedgeTexture, "gaussian-wedge": GaussianWedgeTexture}
_TOP_KEYS = {"name", "description", "texture", "springs"}


def _dataclass_keys(cls) -> set[str]:
    return {f.name for f in fields(cls) if not f.name.startswith("_")}


def texture_from_dict(d: dict, where: str = "texture") -> Texture:
    """Build a texture from the ``[texture]`` table of a texture file.

    Raises TextureFileError naming the missing or unknown key and the allowed ones.
    """
    if not isinstance(d, dict):
        raise TextureFileError(f"{where} must be a table")
    kind = d.get("kind", "wedge")
    if not isinstance(kind, str) or kind not in _TEXTURE_KINDS:
        raise TextureFileError(
            f"{where}.kind must be one of {', '.join(sorted(_TEXTURE_KINDS))}, got {kind!r}"[:300])
    cls = _TEXTURE_KINDS[kind]
    allowed = _dataclass_keys(cls) | {"kind"}
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise TextureFileError(
            f"unknown key {where}.{unknown[0]} for kind {kind!r}; allowed: {', '.join(sorted(allowed))}")
    required = [f.name for f in fields(cls)
                if not f.name.startswith("_") and f.default is _MISSING and f.default_factory is _MISSING]
    missing = [k for k in required if k not in d]
    if missing:
        raise TextureFileError(f"missing key {where}.{missing[0]} (kind {kind!r} needs "
                               f"{', '.join(required)})")
    return build_from_table(cls, {k: v for k, v in d.items() if k != "kind"}, where,
                            TextureFileError)


def build_from_table(cls, d: dict, where: str, error=InputError):
    """``cls(**d)``, with a field error re-raised as ``error`` prefixed by the table name."""
    try:
        return cls(**d)
    except InputError as exc:
        raise error(f"{where}.{exc}") from None


@dataclass(frozen=True)
class TextureFile:
    """A parsed texture file: the texture and the optional spring-model table."""

    texture: Texture
    springs: dict
    name: str
    description: str


def load_texture_file(path: str | Path) -> TextureFile:
    """Read a TOML texture file (the file formats: texture files); its ``[springs]`` table,
    if any, is checked too (keys and ranges of :class:`~.spring_model.SpringModel`)."""
    from .spring_model import SpringModel
    p = Path(check_instance("path", path, (str, PathLike), "file name (text or a Path)"))
    data = read_toml(p, "texture file", _TOP_KEYS, TextureFileError)
    if "texture" not in data:
        raise TextureFileError(f"{p}: missing table [texture]")
    try:
        tex = texture_from_dict(data["texture"])
        springs = data.get("springs", {})
        if not isinstance(springs, dict):
            raise TextureFileError("springs must be a table")
        SpringModel.from_dict(springs)
        name = check_text("name", data.get("name", p.stem), 200)
        description = check_text("description", data.get("description", ""))
    except InputError as exc:
        raise TextureFileError(f"{p}: {exc}") from None
    return TextureFile(tex, dict(springs), name, description)


def load_texture(path: str | Path) -> Texture:
    """Read the texture of a TOML texture file (format: the file-format reference, texture files).

    Parameters
    ----------
    path : str or os.PathLike
        The file: a ``[texture]`` table (``kind`` "wedge" or "gaussian-wedge" and the fields
        of that texture), optional ``name`` and ``description``, and an optional ``[springs]``
        table (the fields of :class:`asperity.SpringModel`), which is checked too.

    Returns
    -------
    WedgeTexture or GaussianWedgeTexture
        The texture of the ``[texture]`` table.

    Raises
    ------
    asperity.InputError
        A missing or unreadable file, a key missing, unknown or out of range (one line).

    Examples
    --------
    >>> tex = asperity.load_texture("surfaces/wedge-asymmetric.toml")
    >>> tex
    WedgeTexture(alpha_deg=30.0, beta_deg=10.0, mu_alpha=0.1, mu_beta=0.2, height=5e-06)
    >>> round(asperity.compute_axis_coefficients(tex)["mu_a_minus"], 6)
    0.193238
    """
    return load_texture_file(path).texture
