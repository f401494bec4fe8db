"""Form removal (detrending) and local friction maps of surfaces."""
from __future__ import annotations

import numpy as np
import pytest
from surface_files import mesh_with_degenerates, write_matrix

from asperity.errors import InputError
from asperity.surface.detrend import detrend
from asperity.surface.friction_map import read_friction_map
from asperity.surface.readers import read_surface
from asperity.surface.topography import HeightMap, TriangleMesh

# --- detrending -----------------------------------------------------------------------------

def _grid(nx=40, ny=30, dx=2e-6, dy=3e-6):
    x = np.arange(nx)[:, None] * dx
    y = np.arange(ny)[None, :] * dy
    return x, y


def test_detrend_removes_exact_plane_and_quadratic():
    x, y = _grid()
    plane = 1e-6 + 0.3 * x - 0.2 * y
    quad = plane + 4e3 * x ** 2 - 2e3 * x * y + 1e3 * y ** 2
    for z, deg in ((plane, 1), (quad, 2), (quad, 3), (np.full_like(plane, 5e-6), 0)):
        z = z.copy()
        z[3, 4] = np.nan
        hm = HeightMap(heights=z, dx=2e-6, dy=3e-6, source="t", n_undefined=1)
        out = detrend(hm, deg)
        assert isinstance(out, HeightMap) and out is not hm and out.n_undefined == 1
        assert np.isnan(out.heights[3, 4])
        assert np.nanmax(np.abs(out.heights)) < 1e-12 * np.nanmax(np.abs(z)), deg
        assert np.isnan(hm.heights[3, 4]) and np.nanmax(np.abs(hm.heights)) > 0  # untouched
    # a plane fit leaves the quadratic's curvature
    hm = HeightMap(heights=quad, dx=2e-6, dy=3e-6, source="t", n_undefined=0)
    assert np.max(np.abs(detrend(hm, 1).heights)) > 1e-9


def test_detrend_mesh_and_bad_degree():
    rng = np.random.default_rng(4)
    xy = rng.uniform(0, 1e-3, size=(50, 2))
    z = 2e-4 + 0.1 * xy[:, 0] + 0.05 * xy[:, 1]
    mesh = TriangleMesh(vertices=np.column_stack([xy, z]), faces=np.array([[0, 1, 2], [2, 3, 4]]),
                        source="t", n_degenerate=0)
    out = detrend(mesh, 1)
    assert isinstance(out, TriangleMesh)
    assert np.max(np.abs(out.vertices[:, 2])) < 1e-12 * np.max(z)
    np.testing.assert_array_equal(out.vertices[:, :2], xy)
    for bad in (-1, 1.5, "two"):
        with pytest.raises(InputError, match="degree"):
            detrend(mesh, bad)


# --- friction maps --------------------------------------------------------------------------

def test_friction_map_heightmap_orientation_and_errors(tmp_path):
    hm = HeightMap(heights=np.zeros((4, 3)), dx=1e-6, dy=1e-6, source="s", n_undefined=0)
    mu = np.random.default_rng(5).uniform(0.1, 0.3, size=(4, 3))
    np.save(tmp_path / "mu.npy", mu)
    np.testing.assert_array_equal(read_friction_map(tmp_path / "mu.npy", hm), mu)
    write_matrix(tmp_path / "mu.txt", mu.T, "# local friction\n")    # 3 lines of 4 values
    np.testing.assert_allclose(read_friction_map(tmp_path / "mu.txt", hm), mu)
    np.save(tmp_path / "wrong.npy", mu.T)
    with pytest.raises(InputError, match=r"wrong\.npy.*shape \(3, 4\), expected \(4, 3\)"):
        read_friction_map(tmp_path / "wrong.npy", hm)
    for bad in (-0.1, np.nan, np.inf):
        m = mu.copy()
        m[1, 1] = bad
        np.save(tmp_path / "bad.npy", m)
        with pytest.raises(InputError, match=r"bad\.npy.*finite and >= 0"):
            read_friction_map(tmp_path / "bad.npy", hm)
    with pytest.raises(InputError, match="friction map must be"):
        read_friction_map(tmp_path / "mu.stl", hm)


def test_friction_map_mesh_per_face(tmp_path):
    import trimesh
    v, f = mesh_with_degenerates()
    (tmp_path / "m.ply").write_bytes(trimesh.Trimesh(v, f, process=False).export(file_type="ply"))
    mesh = read_surface(tmp_path / "m.ply", unit="mm")
    (tmp_path / "kept.txt").write_text("0.1\n0.2\n0.3\n")
    np.testing.assert_allclose(read_friction_map(tmp_path / "kept.txt", mesh), [0.1, 0.2, 0.3])
    np.save(tmp_path / "all.npy", np.array([0.1, 0.2, 9.0, 9.0, 0.5]))   # one per file triangle
    np.testing.assert_allclose(read_friction_map(tmp_path / "all.npy", mesh), [0.1, 0.2, 0.5])
    np.save(tmp_path / "short.npy", np.array([0.1, 0.2]))
    with pytest.raises(InputError, match=r"short\.npy.*2 values, expected 3 \(or 5"):
        read_friction_map(tmp_path / "short.npy", mesh)
