"""A triangle mesh's heights on a regular grid: the rigid surface an elastic contact meets.

The contact solver (:mod:`asperity.contact`) works on a regular grid of heights.  A mesh is
turned into one by :func:`mesh_heightmap`: the nodes ``(x0 + i h, y0 + j h)`` cover the
mesh's projected bounding box from its lowest x and y (``h`` the grid step, the same
along x and y), and each node takes the height of the highest triangle above it -- the
upper envelope, what a ray cast from above meets first (:mod:`._mesh_grid_kernels`).  A
node that no triangle covers (a hole, the outside of a round mesh) is undefined (NaN) and
carries no load.  Overhangs are hidden below the envelope, as they are from a counter-face
coming from above.

The default step is the mesh's median projected edge length over
:data:`NODES_PER_EDGE`, made finer when the grid would have fewer than
:data:`DEFAULT_MIN_NODES` nodes (a mesh of a few large triangles still gets a contact
resolved on some 256 x 256 nodes) and coarser when it would have more than
:data:`DEFAULT_MAX_NODES` (it is a default; ``grid_step`` sets any step memory allows).

:func:`face_forces` maps a pressure on that grid back to the mesh's own triangles: each
node carries ``p h^2`` (its pixel's force) and shares it equally between the triangles on
top there -- one inside a triangle, the two of an edge or all those of a vertex the node
lies on (a node on an edge given wholly to one side would shift the force across every
edge of a grid that is aligned with them, a bias that does not fall as ``h`` does).  The
forces sum to the load exactly; a triangle's force is the pressure integrated over the
pixels of the nodes it holds, right to a fraction of a pixel along its edges (an error of
order ``h`` over the triangle's size: keep several pixels a triangle -- the default's
four nodes an edge give about seven).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_range
from .topography import HeightMap, TriangleMesh

#: default grid step: the median projected edge length over this
NODES_PER_EDGE = 4
#: the default step is made finer so that the grid holds at least this many nodes, and
#: coarser so that it holds at most DEFAULT_MAX_NODES
DEFAULT_MIN_NODES = 1 << 16
DEFAULT_MAX_NODES = 1 << 22
#: barycentric tolerance: a node on an edge or a vertex belongs to each triangle there
EDGE_EPS = 1e-9
#: bytes a node of the grid itself: the heights, and the triangle count of face_forces
GRID_BYTES_PER_NODE = 16
#: a triangle is on top at a node when its height there is within this share of the
#: mesh's height range (and magnitude) of the envelope
TOP_TOL = 1e-9


@dataclass(frozen=True)
class MeshGrid:
    """heightmap: the grid's heights (HeightMap, NaN where no triangle is);
    origin: (x0, y0) of node (0, 0), m; step: the grid step, m; default_step: True when
    the step was chosen from the mesh's edges."""

    heightmap: HeightMap
    origin: tuple
    step: float
    default_step: bool

    def to_dict(self) -> dict:
        nx, ny = self.heightmap.heights.shape
        return {"grid": [nx, ny], "grid_step_m": self.step, "grid_origin_m": list(self.origin),
                "grid_step_default": self.default_step,
                "uncovered_nodes": int(self.heightmap.n_undefined)}


def _projected(mesh: TriangleMesh):
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    name = mesh.source or "mesh"
    if f.shape[0] == 0:
        raise InputError(f"{name}: the mesh has no triangle (nothing to press)")
    used = np.zeros(v.shape[0], dtype=bool)
    used[f.ravel()] = True
    vu = v[used]
    lo, hi = vu.min(axis=0), vu.max(axis=0)
    if not (hi[0] > lo[0] and hi[1] > lo[1]):
        raise InputError(f"{name}: the mesh has no projected area in x-y (it is a "
                         "vertical sheet or a line): no height grid")
    return v, f, lo, hi, name


#: nodes counted at most along a side (far beyond any memory)
MAX_NODES_PER_SIDE = 1e15


def default_step(mesh: TriangleMesh) -> float:
    """The median projected edge length over :data:`NODES_PER_EDGE`, refined so that the
    grid has at least :data:`DEFAULT_MIN_NODES` nodes and coarsened so that it has at
    most :data:`DEFAULT_MAX_NODES`."""
    v, f, lo, hi, _ = _projected(mesh)
    e = np.concatenate([np.hypot(*(v[f[:, b], :2] - v[f[:, a], :2]).T)
                        for a, b in ((0, 1), (1, 2), (2, 0))])
    e = e[e > 0]
    lx, ly = hi[0] - lo[0], hi[1] - lo[1]
    step = math.sqrt(lx * ly / DEFAULT_MIN_NODES)
    if e.size:
        step = min(step, float(np.median(e)) / NODES_PER_EDGE)
    return max(step, math.sqrt(lx * ly / DEFAULT_MAX_NODES))


def grid_shape(lo, hi, step: float) -> tuple[int, int]:
    """Nodes along x and y of a grid of ``step`` from ``lo`` covering up to ``hi`` (a count
    beyond :data:`MAX_NODES_PER_SIDE`, even an overflow of a step such as 5e-324 m, is
    capped there: the memory check then refuses the grid)."""
    counts = (float(hi[k] - lo[k]) / float(step) * (1 + 1e-12) for k in (0, 1))
    return tuple(math.floor(min(c, MAX_NODES_PER_SIDE)) + 1 for c in counts)


def mesh_heightmap(mesh: TriangleMesh, grid_step=None, node_bytes: float = 0.0) -> MeshGrid:
    """The upper envelope of ``mesh`` on a grid of step ``grid_step`` (m, > 0; None: the
    default, see the module's docstring).  ``node_bytes``: the memory each node will need
    afterwards (the contact solve's), for the check made before the grid is allocated."""
    from ..resources import check_memory
    if not isinstance(mesh, TriangleMesh):
        raise InputError(f"mesh must be a TriangleMesh, got {type(mesh).__name__}")
    v, f, lo, hi, name = _projected(mesh)
    given = grid_step is not None
    step = check_range("grid_step", grid_step, 0.0, None, low_open=True, unit="m") \
        if given else default_step(mesh)
    if not math.isfinite(step):
        raise InputError(f"grid_step must be a finite length in m, got {step}")
    nx, ny = grid_shape(lo, hi, step)
    if nx < 2 or ny < 2:
        top = min(hi[0] - lo[0], hi[1] - lo[1])
        raise InputError(f"grid_step {step:g} m gives a grid of {nx} x {ny} nodes over "
                         f"{name} ({hi[0] - lo[0]:.4g} x {hi[1] - lo[1]:.4g} m): at most "
                         f"{top:.4g} m")
    check_memory(float(nx) * float(ny) * (GRID_BYTES_PER_NODE + float(node_bytes)),
                 f"the height grid of {name} ({nx} x {ny} nodes of {step:.4g} m)",
                 "give a coarser grid_step (--grid-step)")
    from ._mesh_grid_kernels import _walk
    z = np.full((nx, ny), -np.inf)
    no = np.zeros((1, 1))
    _walk(np.ascontiguousarray(v), np.ascontiguousarray(f), float(lo[0]), float(lo[1]),
          float(step), z, EDGE_EPS, 0, 0.0, np.zeros((1, 1), dtype=np.int32), no, no[0])
    empty = np.isneginf(z)
    z[empty] = np.nan
    n_undef = int(np.count_nonzero(empty))
    if n_undef == z.size:
        raise InputError(f"{name}: no node of the height grid lies under a triangle")
    hm = HeightMap(z, step, step, source=f"{name} (height grid)", n_undefined=n_undef)
    return MeshGrid(hm, (float(lo[0]), float(lo[1])), float(step), not given)


def face_forces(mesh: TriangleMesh, mg: MeshGrid, pressure: np.ndarray) -> np.ndarray:
    """The normal force (N) on each triangle of ``mesh`` from the ``pressure`` (Pa) on the
    nodes of its grid ``mg``: each node's ``p h^2`` shared equally between the triangles
    on top there (see the module's docstring)."""
    from ._mesh_grid_kernels import _walk
    z = mg.heightmap.heights
    p = np.asarray(pressure, dtype=float)
    if p.shape != z.shape:
        raise InputError(f"pressure has shape {p.shape}, the grid {z.shape}")
    v = np.ascontiguousarray(mesh.vertices, dtype=float)
    f = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    fin = np.isfinite(z)
    zt = np.where(fin, z, np.inf)                  # no triangle is on top of an empty node
    ztol = TOP_TOL * float(np.ptp(z[fin]) + np.abs(z[fin]).max())
    count = np.zeros(z.shape, dtype=np.int32)
    out = np.zeros(f.shape[0])
    x0, y0 = mg.origin
    _walk(v, f, x0, y0, mg.step, zt, EDGE_EPS, 1, ztol, count, p, out)
    q = np.where(fin & np.isfinite(p), p, 0.0) * (mg.step * mg.step)
    _walk(v, f, x0, y0, mg.step, zt, EDGE_EPS, 2, ztol, count, q, out)
    return out
