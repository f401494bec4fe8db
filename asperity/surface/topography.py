"""The two kinds of surface a reader returns, in metres, and their units.

* :class:`HeightMap` -- heights on a regular grid, ``heights[i, j] = z(x_i, y_j)`` with
  ``x_i = i dx`` and ``y_j = j dy`` (the first index runs along x), NaN where the
  instrument recorded nothing;
* :class:`TriangleMesh` -- vertices and triangles of an open (or closed) sheet.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import (
    InputError,
    TextureFileError,
    _show,
    check_array,
    check_int,
    check_range,
    check_text,
)

#: length units accepted for ``unit`` (and in text headers): name -> metres
UNITS = {
    "m": 1.0, "metre": 1.0, "meter": 1.0, "metres": 1.0, "meters": 1.0,
    "mm": 1e-3, "millimetre": 1e-3, "millimeter": 1e-3, "millimetres": 1e-3,
    "millimeters": 1e-3,
    "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "micron": 1e-6, "microns": 1e-6,
    "micrometre": 1e-6, "micrometer": 1e-6, "micrometres": 1e-6, "micrometers": 1e-6,
    "nm": 1e-9, "nanometre": 1e-9, "nanometer": 1e-9, "nanometres": 1e-9,
    "nanometers": 1e-9,
}


UNIT_HELP = "m, mm, um (µm), nm"

#: physically meaningful ranges of a surface's numbers, in metres: a pixel finer than a
#: picometre is below any instrument (and below an atom); a pixel coarser than a metre, or a
#: coordinate beyond a kilometre, is no surface texture (usually a wrong --unit)
PIXEL_SIZE_RANGE = (1e-12, 1.0)
MAX_COORDINATE = 1e3
#: range of height_scale: enough to make nanometre AFM relief steep, or flatten a mesh
HEIGHT_SCALE_RANGE = (1e-6, 1e6)


@dataclass(frozen=True)
class HeightMap:
    """Heights on a regular grid, in metres.

    Attributes
    ----------
    heights : ndarray, shape (nx, ny)
        float64, ``heights[i, j] = z(x_i = i dx, y_j = j dy)``; NaN marks an
        undefined pixel.
    dx, dy : float
        Grid spacing along x and y, m (> 0).
    source : str
        File name (and channel) or a description.
    n_undefined : int
        Number of undefined pixels.
    """

    heights: np.ndarray
    dx: float
    dy: float
    source: str = ""
    n_undefined: int = 0

    def __post_init__(self):
        source = check_text("source", self.source)
        name = source or "height map"
        z = check_array(f"{name}: heights", self.heights, ndim=2, finite=False)
        if z.shape[0] < 1 or z.shape[1] < 1:
            raise InputError(f"{name}: heights must be a 2-D array, got shape {z.shape}")
        check_heights(z, name)
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "dx", pixel_length("dx", self.dx))
        object.__setattr__(self, "dy", pixel_length("dy", self.dy))
        object.__setattr__(self, "n_undefined", check_int("n_undefined", self.n_undefined, 0,
                                                          z.size))

    @property
    def nx(self) -> int:
        return int(self.heights.shape[0])

    @property
    def ny(self) -> int:
        return int(self.heights.shape[1])

    @property
    def physical_size(self) -> tuple[float, float]:
        """(lx, ly) = (nx dx, ny dy) in metres (the SurfaceTopography convention)."""
        return (self.nx * self.dx, self.ny * self.dy)


@dataclass(frozen=True)
class TriangleMesh:
    """A triangle mesh in metres.

    Attributes
    ----------
    vertices : ndarray, shape (nv, 3)
        float64, m.
    faces : ndarray, shape (nf, 3)
        int64 vertex indices; degenerate triangles already removed.
    source : str
        File name or a description.
    n_degenerate : int
        Number of degenerate triangles of the file that were dropped.
    kept_faces : ndarray, shape (nf,), or None
        int64, index of each face among the file's triangles (None:
        ``arange(nf)``); lets a friction map list one value per triangle of the file.
    """

    vertices: np.ndarray
    faces: np.ndarray
    source: str = ""
    n_degenerate: int = 0
    kept_faces: np.ndarray | None = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        name = check_text("source", self.source) or "mesh"
        v = check_array(f"{name}: vertices", self.vertices, shape=(None, 3))
        check_coordinates(v, f"{name}: vertex coordinates")
        f = check_array(f"{name}: faces", self.faces, shape=(None, 3))
        if f.size and not np.all(f == np.round(f)):
            raise InputError(f"{name}: faces must hold whole vertex indices")
        if f.size and (f.min() < 0 or f.max() >= v.shape[0]):
            raise InputError(f"{name}: face vertex indices must be in [0, {v.shape[0] - 1}]")
        f = f.astype(np.int64)
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)
        object.__setattr__(self, "n_degenerate", int(self.n_degenerate))
        if self.kept_faces is not None:
            k = np.asarray(self.kept_faces, dtype=np.int64)
            if k.shape != (f.shape[0],):
                raise InputError(f"{name}: kept_faces must have one index per face")
            object.__setattr__(self, "kept_faces", k)

    @property
    def n_faces(self) -> int:
        return int(self.faces.shape[0])


Surface = HeightMap | TriangleMesh


def positive_length(name: str, value) -> float:
    x = check_range(name, value, 0.0, None, low_open=True)
    if not math.isfinite(x):
        raise InputError(f"{name} must be finite, got {x:g}")
    return x


def pixel_length(name: str, value) -> float:
    """A grid spacing in metres within :data:`PIXEL_SIZE_RANGE`."""
    lo, hi = PIXEL_SIZE_RANGE
    return check_range(name, value, lo, hi, unit="m")


def check_coordinates(a: np.ndarray, what: str) -> None:
    """Finite values (NaN allowed: undefined) within +-:data:`MAX_COORDINATE` metres."""
    lo, hi = nan_range(a)
    if lo != lo:                                    # all NaN: the caller says what it means
        return
    big = max(abs(lo), abs(hi))
    if not big <= MAX_COORDINATE:
        kind = "infinite values" if math.isinf(big) else f"values up to {big:.3g} m"
        raise InputError(f"{what} must lie within +-{MAX_COORDINATE:g} m, got {kind}; check "
                         f"the unit (and height_scale)")


def nan_range(a: np.ndarray) -> tuple[float, float]:
    """(min, max) ignoring NaN; (nan, nan) for an empty or all-NaN array, silently."""
    import warnings
    if a.size == 0:
        return math.nan, math.nan
    with warnings.catch_warnings(), np.errstate(invalid="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        return float(np.nanmin(a)), float(np.nanmax(a))


def check_heights(z: np.ndarray, name: str) -> None:
    """Heights in metres: finite or NaN (undefined), within +-:data:`MAX_COORDINATE`."""
    check_coordinates(z, f"{name}: heights")


def unit_factor(unit, what: str = "unit") -> float:
    """Metres per ``unit`` (one of :data:`UNITS`), else InputError listing the allowed ones."""
    if isinstance(unit, str):
        key = unit.strip()
        f = UNITS.get(key, UNITS.get(key.lower()))
        if f is not None:
            return f
    raise InputError(f"{what} must be one of {UNIT_HELP}, got {unit!r}")


def pixel_pair(pixel_size, factor: float) -> tuple[float, float]:
    """(dx, dy) in metres from a number or a pair, given in a unit of ``factor`` metres;
    each within :data:`PIXEL_SIZE_RANGE` once in metres."""
    shape = None
    if not (isinstance(pixel_size, (str, bytes, dict)) or pixel_size is None):
        try:
            shape = np.shape(pixel_size)
        except ValueError:                # ragged
            pass
    if shape == ():
        vals = [pixel_size]
    elif shape == (2,):
        vals = list(pixel_size)
    else:
        got = _show(pixel_size) if shape is None else f"shape {shape}"
        raise InputError(f"pixel_size must be a number or a pair (dx, dy), got {got}")
    labels = ("pixel_size",) if len(vals) == 1 else ("pixel_size (dx)", "pixel_size (dy)")
    lo, hi = PIXEL_SIZE_RANGE
    out = []
    for label, v in zip(labels, vals):
        d = positive_length(label, v) * factor
        if not lo <= d <= hi:
            raise InputError(f"{label} must be in [{lo:g}, {hi:g}] m, got {d:g} m; check the "
                             f"value and its unit")
        out.append(d)
    return (out[0], out[-1])


def check_height_scale(value) -> float:
    """height_scale within :data:`HEIGHT_SCALE_RANGE`."""
    return check_range("height_scale", value, *HEIGHT_SCALE_RANGE)


def one_line(exc: BaseException, limit: int = 160) -> str:
    text = str(exc).strip().splitlines()
    msg = text[0].strip() if text else type(exc).__name__
    return msg if len(msg) <= limit else msg[: limit - 3] + "..."


def count_undefined(z: np.ndarray) -> int:
    return int(np.count_nonzero(np.isnan(z)))


def finish_heightmap(z: np.ndarray, dx: float, dy: float, source: str, height_scale: float,
                      name, copy: bool = True) -> HeightMap:
    """The HeightMap of heights ``z`` (m) read from file ``name``: a copy (``copy``) that
    owns its data, checked (finite or NaN, within range, pixel sizes within range)."""
    z = np.array(z, dtype=np.float64) if copy else np.asarray(z, dtype=np.float64)
    if z.ndim != 2 or z.shape[0] < 1 or z.shape[1] < 1:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got shape {z.shape}")
    lo, hi = nan_range(z)
    if math.isinf(lo) or math.isinf(hi):
        raise TextureFileError(f"{name}: the heights contain infinite values")
    n_undef = count_undefined(z)
    if n_undef == z.size:
        raise TextureFileError(f"{name}: every pixel is undefined")
    for label, d in (("pixel size dx", dx), ("pixel size dy", dy)):
        plo, phi = PIXEL_SIZE_RANGE
        if not plo <= d <= phi:
            raise TextureFileError(f"{name}: {label} {d:g} m is outside [{plo:g}, {phi:g}] m; "
                                   f"check the unit and pixel size")
    if height_scale != 1.0:
        z *= height_scale
    check_coordinates(np.array([lo * height_scale, hi * height_scale]), f"{name}: heights")
    return HeightMap(heights=z, dx=dx, dy=dy, source=source, n_undefined=n_undef)


def given_sizes(name, unit, pixel_size) -> tuple[float, tuple[float, float] | None]:
    """For a file that states its sizes (x3p, instrument files): (metres per number of the
    file, (dx, dy) in metres or None).  ``unit`` reads the file's numbers in that unit
    instead of the one it states (a file written in the wrong unit); ``pixel_size``, in
    ``unit``, replaces its spacing (and needs ``unit``)."""
    if pixel_size is not None and unit is None:
        raise InputError(f"{name}: a pixel size given for a file that states its own replaces "
                         f"it and needs its unit: pass unit too")
    f = None if unit is None else unit_factor(unit)
    return f, (None if pixel_size is None else pixel_pair(pixel_size, f))


def check_stated_pixel(name, dx: float, dy: float, stated_unit: str = "metres") -> None:
    """The spacing a file states, within :data:`PIXEL_SIZE_RANGE`; else one line that says
    how to read the file anyway (see :func:`given_sizes`)."""
    lo, hi = PIXEL_SIZE_RANGE
    for label, d in (("dx", dx), ("dy", dy)):
        if not lo <= d <= hi:
            raise TextureFileError(f"{name}: the file states a pixel size {label} of {d:g} m, "
                                   f"outside [{lo:g}, {hi:g}] m: if its numbers are not in "
                                   f"{stated_unit}, pass unit (the unit they are in; on the "
                                   f"command line --unit) and, to replace its spacing, "
                                   f"pixel_size (on the command line --pixel-size)")
