"""The mesh -> height grid of an elastic contact against the solve it serves: a mesh of a
self-affine height map's own triangles (N x N nodes, 2 (N-1)^2 triangles) rasterised on
its N x N grid (asperity.surface.mesh_grid.mesh_heightmap), solved on the free half-space
(p/E* = 0.005), and the solve's pressure mapped back to the triangles (face_forces).
Prints the three times and their ratios to the solve (taken in the same run; say the
machine's load with them).

    python benchmarks/mesh_grid_bench.py [N]      # default 512
"""
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from contact_peers import self_affine  # noqa: E402

from asperity.contact import solve_contact  # noqa: E402
from asperity.surface.mesh_grid import face_forces, mesh_heightmap  # noqa: E402
from asperity.surface.topography import TriangleMesh  # noqa: E402


def grid_mesh(z, dx):
    nx, ny = z.shape
    X, Y = np.meshgrid(np.arange(nx) * dx, np.arange(ny) * dx, indexing="ij")
    v = np.column_stack([X.ravel(), Y.ravel(), z.ravel()])
    idx = np.arange(nx * ny).reshape(nx, ny)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[:-1, 1:].ravel(), idx[1:, 1:].ravel()
    return v, np.concatenate([np.column_stack([a, b, c]), np.column_stack([d, c, b])])


def main(n=512, dx=1e-6):
    mesh_heightmap(TriangleMesh(*grid_mesh(np.zeros((4, 4)), dx)), dx)   # numba warm-up
    m = TriangleMesh(*grid_mesh(self_affine(n, n, dx=dx, seed=1), dx))
    t = time.perf_counter()
    mg = mesh_heightmap(m, dx)
    t_grid = time.perf_counter() - t
    t = time.perf_counter()
    res = solve_contact(mg.heightmap.heights, dx, 1e9, 5e6, boundary="free")
    t_solve = time.perf_counter() - t
    t = time.perf_counter()
    F = face_forces(m, mg, res.pressure)
    t_force = time.perf_counter() - t
    assert abs(F.sum() / (5e6 * n * n * dx * dx) - 1) < 1e-9
    print(f"{m.n_faces} triangles on {n} x {n} nodes: grid {t_grid:.3f} s, free solve "
          f"{t_solve:.3f} s, face forces {t_force:.3f} s; grid / solve {t_grid / t_solve:.3f}, "
          f"face forces / solve {t_force / t_solve:.3f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 512)
