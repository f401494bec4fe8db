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

from ..errors import InputError, TextureFileError, check_range

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


@dataclass(frozen=True)
class HeightMap:
    """Heights on a regular grid, in metres.

    heights     : (nx, ny) float64, ``heights[i, j] = z(x_i = i dx, y_j = j dy)``; NaN marks
                  an undefined pixel
    dx, dy      : grid spacing along x and y, m (> 0)
    source      : file name (and channel) or a description
    n_undefined : number of undefined pixels
    """

    heights: np.ndarray
    dx: float
    dy: float
    source: str = ""
    n_undefined: int = 0

    def __post_init__(self):
        z = np.asarray(self.heights, dtype=np.float64)
        if z.ndim != 2 or z.shape[0] < 1 or z.shape[1] < 1:
            raise InputError(f"{self.source or 'height map'}: heights must be a 2-D array, "
                             f"got shape {z.shape}")
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "dx", positive_length("dx", self.dx))
        object.__setattr__(self, "dy", positive_length("dy", self.dy))
        object.__setattr__(self, "n_undefined", int(self.n_undefined))

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

    vertices     : (nv, 3) float64, m
    faces        : (nf, 3) int64 vertex indices; degenerate triangles already removed
    source       : file name or a description
    n_degenerate : number of degenerate triangles of the file that were dropped
    kept_faces   : (nf,) int64, index of each face among the file's triangles (None:
                   ``arange(nf)``); lets a friction map list one value per triangle
                   of the file
    """

    vertices: np.ndarray
    faces: np.ndarray
    source: str = ""
    n_degenerate: int = 0
    kept_faces: np.ndarray | None = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        v = np.asarray(self.vertices, dtype=np.float64)
        f = np.asarray(self.faces)
        name = self.source or "mesh"
        if v.ndim != 2 or v.shape[1] != 3:
            raise InputError(f"{name}: vertices must have shape (nv, 3), got {v.shape}")
        if f.ndim != 2 or f.shape[1] != 3:
            raise InputError(f"{name}: faces must have shape (nf, 3), got {f.shape}")
        f = f.astype(np.int64)
        if f.size and (f.min() < 0 or f.max() >= v.shape[0]):
            raise InputError(f"{name}: face vertex indices must be in [0, {v.shape[0] - 1}]")
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


def unit_factor(unit, what: str = "unit") -> float:
    """Metres per ``unit`` (one of :data:`UNITS`), else InputError listing the allowed ones."""
    if isinstance(unit, str):
        key = unit.strip()
        f = UNITS.get(key, UNITS.get(key.lower()))
        if f is not None:
            return f
    raise InputError(f"{what} must be one of {UNIT_HELP}, got {unit!r}")


def pixel_pair(pixel_size, factor: float) -> tuple[float, float]:
    """(dx, dy) in metres from a number or a pair, given in a unit of ``factor`` metres."""
    if isinstance(pixel_size, (str, bytes)):
        raise InputError(f"pixel_size must be a number or a pair (dx, dy), got {pixel_size!r}")
    if np.ndim(pixel_size) == 0:
        d = positive_length("pixel_size", pixel_size)
        return d * factor, d * factor
    vals = list(np.asarray(pixel_size, dtype=object).ravel())
    if len(vals) != 2:
        raise InputError(f"pixel_size must be a number or a pair (dx, dy), got {pixel_size!r}")
    return (positive_length("pixel_size (dx)", vals[0]) * factor,
            positive_length("pixel_size (dy)", vals[1]) * factor)


def one_line(exc: BaseException, limit: int = 160) -> str:
    text = str(exc).strip().splitlines()
    msg = text[0].strip() if text else type(exc).__name__
    return msg if len(msg) <= limit else msg[: limit - 3] + "..."


def count_undefined(z: np.ndarray) -> int:
    return int(np.count_nonzero(np.isnan(z)))


def finish_heightmap(z: np.ndarray, dx: float, dy: float, source: str, height_scale: float,
                      name) -> HeightMap:
    z = np.array(z, dtype=np.float64)  # a copy that owns its data
    if np.isinf(z).any():
        raise TextureFileError(f"{name}: the heights contain infinite values")
    if z.ndim != 2 or z.shape[0] < 1 or z.shape[1] < 1:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got shape {z.shape}")
    n_undef = count_undefined(z)
    if n_undef == z.size:
        raise TextureFileError(f"{name}: every pixel is undefined")
    if height_scale != 1.0:
        z *= height_scale
    return HeightMap(heights=z, dx=dx, dy=dy, source=source, n_undefined=n_undef)
