"""Triangle meshes (``.stl .obj .ply``), read by trimesh.

Mesh files carry no length unit, so ``unit`` is required.  Vertices with identical
coordinates are merged, and degenerate triangles (a repeated vertex or zero area) are
dropped and counted in :attr:`TriangleMesh.n_degenerate`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ..topography import UNIT_HELP, TriangleMesh, one_line, unit_factor


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
         height_scale: float, point_bytes: float = 0.0) -> TriangleMesh:
    """The mesh in ``data`` (``pixel_size`` does not apply to meshes: refused before)."""
    if unit is None:
        raise InputError(f"{name}: a {suffix} mesh file carries no length unit; pass unit "
                         f"(one of {UNIT_HELP}; on the command line --unit)")
    factor = unit_factor(unit)
    import io
    import logging

    import trimesh
    logging.getLogger("trimesh").setLevel(logging.ERROR)
    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=suffix[1:], process=False,
                            force="mesh")
        vertices = np.asarray(mesh.vertices, dtype=np.float64)
        faces = np.asarray(mesh.faces, dtype=np.int64)
    except Exception as exc:  # trimesh raises many kinds on a malformed file
        raise TextureFileError(f"{name}: not a readable {suffix} mesh ({one_line(exc)})") from None
    if faces.ndim != 2 or faces.shape[1] != 3 or faces.shape[0] == 0:
        raise TextureFileError(f"{name}: the {suffix} file holds no triangles")
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise TextureFileError(f"{name}: the {suffix} file holds no 3-D vertices")
    used = np.unique(faces)
    if used.size and (used[0] < 0 or used[-1] >= vertices.shape[0]):
        raise TextureFileError(f"{name}: a triangle refers to a vertex that does not exist")
    if not np.all(np.isfinite(vertices[used])):
        raise TextureFileError(f"{name}: vertex coordinates must be finite numbers")
    # merge vertices with identical coordinates (STL repeats them for every triangle),
    # numbered in order of first appearance
    uniq, first, inverse = np.unique(vertices, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    vertices = uniq[order]
    faces = rank[np.asarray(inverse).ravel()][faces]
    keep = ~_degenerate(vertices, faces)
    # drop vertices no kept triangle uses
    kept = faces[keep]
    used = np.unique(kept)
    remap = np.full(vertices.shape[0], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    vertices = vertices[used] * factor
    if height_scale != 1.0:
        vertices[:, 2] *= height_scale
    if kept.shape[0] == 0:
        raise TextureFileError(f"{name}: every triangle of the mesh is degenerate")
    return TriangleMesh(vertices=vertices, faces=remap[kept], source=name.name,
                        n_degenerate=int(np.count_nonzero(~keep)),
                        kept_faces=np.flatnonzero(keep).astype(np.int64))


def _degenerate(vertices: np.ndarray, faces: np.ndarray, rel: float = 1e-12) -> np.ndarray:
    """Triangles with a repeated vertex or (relative to their longest edge) zero area."""
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    repeated = (a == b) | (b == c) | (a == c)
    p0, p1, p2 = vertices[a], vertices[b], vertices[c]
    cross = np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)
    longest2 = np.max(np.stack([np.sum((p1 - p0) ** 2, axis=1), np.sum((p2 - p1) ** 2, axis=1),
                                np.sum((p0 - p2) ** 2, axis=1)]), axis=0)
    return repeated | (cross <= rel * longest2)
