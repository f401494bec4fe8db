"""Local friction maps: one coefficient per pixel of a height map (same grid) or per
triangle of a mesh, read from ``.npy`` or a text matrix.
"""
from __future__ import annotations


import numpy as np

from ..errors import InputError, check_array
from .readers import READERS, reader_for
from .readers._files import read_bytes, surface_path
from .readers.array import load_array
from .readers.text import parse_text_matrix
from .topography import HeightMap, Surface


class GridShape(tuple):
    """(nx, ny) of a height map known by its shape only (a scan read in tiles)."""

    source = ""

    @property
    def nx(self) -> int:
        return self[0]

    @property
    def ny(self) -> int:
        return self[1]


#: largest local friction coefficient (as for --mu)
MAX_MU = 100.0


def read_friction_map(path, surface: Surface) -> np.ndarray:
    """Local friction coefficients matching ``surface``.

    For a :class:`HeightMap`: one value per pixel, shape (nx, ny), in the orientation
    rules of the heights (a ``.npy`` holds ``mu[i, j]`` with i along x; a text matrix has
    one line per y and one column per x; '#' header lines are skipped).  For a
    :class:`TriangleMesh`: one value per kept triangle (``.npy`` or text, any layout,
    read in order), or one per triangle of the mesh file (the values of the dropped
    degenerate ones are then discarded).  Values must be finite and >= 0.
    """
    p = surface_path(path)
    reader, suffix, gz = reader_for(p)
    if reader.name not in ("array", "text"):
        text = next(r for r in READERS if r.name == "text")
        raise InputError(f"{p}: a friction map must be .npy, .npz or a text matrix "
                         f"({' '.join(text.suffixes)}), optionally .gz; got suffix "
                         f"{suffix or '(none)'!r}")
    data = read_bytes(p, gz)
    is_map = isinstance(surface, (HeightMap, GridShape))
    if reader.name == "array":
        m = load_array(data, suffix, p)
    else:
        m, _, _ = parse_text_matrix(data, p)
        if is_map:
            m = m.T
    if is_map:
        expected = (surface.nx, surface.ny)
        if m.shape != expected:
            raise InputError(f"{p}: friction map has shape {m.shape}, expected {expected} "
                             f"(nx, ny) like the heights of {surface.source or 'the surface'}"
                             f" (a text matrix: {surface.ny} lines of {surface.nx} values)")
    else:
        m = m.ravel()
        nf = surface.n_faces
        n_file = nf + surface.n_degenerate
        if m.size == n_file and surface.n_degenerate and surface.kept_faces is not None:
            m = m[surface.kept_faces]
        elif m.size != nf:
            also = (f" (or {n_file}, one per triangle of the file)"
                    if surface.n_degenerate and surface.kept_faces is not None else "")
            raise InputError(f"{p}: friction map has {m.size} values, expected {nf}{also}, one "
                             f"per triangle of {surface.source or 'the mesh'}")
    n, first = bad_mu(m)
    if n:
        raise bad_mu_error(n, first, f"{p}: ")
    return np.array(m, dtype=np.float64)


def bad_mu(m: np.ndarray) -> tuple[int, float]:
    """(number of friction values that are not finite in [0, MAX_MU], the first one)."""
    bad = ~np.isfinite(m) | (m < 0) | (m > MAX_MU)
    n = int(np.count_nonzero(bad))
    return n, (float(m.ravel()[np.flatnonzero(bad.ravel())[0]]) if n else 0.0)


def bad_mu_error(n: int, first: float, where: str = "") -> InputError:
    """The one-line error of a friction map with ``n`` bad values, the first ``first``."""
    return InputError(f"{where}friction map values must be finite and >= 0 (at most "
                      f"{MAX_MU:g}); found {first:g} ({n} bad values)")


def check_friction_map(friction_map) -> np.ndarray:
    """An array of local friction coefficients: finite, in [0, MAX_MU]."""
    m = check_array("friction map", friction_map, finite=False)
    n, first = bad_mu(m)
    if n:
        raise bad_mu_error(n, first)
    return m
