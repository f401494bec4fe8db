"""A mesh pressed on its height grid keeps the load: the triangles' normal forces add up to
the nodes' p h^2 over the nodes with a surface (a node without a defined pressure carries
none), wherever the mesh lies (origin away from zero); a grid step must be a positive
length."""
from __future__ import annotations

import numpy as np
import pytest

from asperity.errors import InputError
from asperity.surface.mesh_grid import face_forces, mesh_heightmap
from asperity.surface.topography import TriangleMesh


def bumpy_mesh(n=9, dx=1e-4, origin=(0.3, -0.7)):
    """A wavy sheet of n x n vertices, its lowest corner far from the origin."""
    x = origin[0] + np.arange(n) * dx
    y = origin[1] + np.arange(n) * dx
    X, Y = np.meshgrid(x, y, indexing="ij")
    Z = 2e-6 * np.sin(X / (2.1 * dx)) * np.cos(Y / (1.7 * dx))
    v = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[:-1, 1:].ravel(), \
        idx[1:, 1:].ravel()
    f = np.concatenate([np.column_stack([a, b, c]), np.column_stack([d, c, b])])
    return TriangleMesh(v, f, "bumpy sheet")


@pytest.mark.parametrize("origin", [(0.0, 0.0), (0.3, -0.7)])
def test_face_forces_add_up_to_the_nodes_load(origin):
    mesh = bumpy_mesh(origin=origin)
    mg = mesh_heightmap(mesh, 3.3e-5)
    z = mg.heightmap.heights
    fin = np.isfinite(z)
    assert fin.sum() > 100
    rng = np.random.default_rng(1)
    p = np.where(fin, rng.uniform(0.0, 1e6, z.shape), np.nan)
    k = np.flatnonzero(fin.ravel())[[3, 40]]
    p.ravel()[k] = [np.nan, np.inf]                 # defined nodes without a pressure
    out = face_forces(mesh, mg, p)
    assert out.shape == (mesh.faces.shape[0],) and out.min() >= 0.0
    good = fin & np.isfinite(p)
    assert out.sum() == pytest.approx(p[good].sum() * mg.step ** 2, rel=1e-12)


@pytest.mark.parametrize("step", [0.0, -1e-4, -1.0])
def test_grid_step_must_be_a_positive_length(step):
    with pytest.raises(InputError, match=r"grid_step must be in \(0, inf\) m") as e:
        mesh_heightmap(bumpy_mesh(), step)
    assert "\n" not in str(e.value)
