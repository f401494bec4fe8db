"""Metamorphic tests of the contact rooms (issue 25, item 5): the same physical problem
posed another way must give the same answer, mapped.

* a map transposed with its pixel sides (dx, dy) exchanged, or turned half a turn, gives
  the contact-weighted law mirrored (or turned) with it: every direction's reservoir
  point, t_a, mu_a+- and mu_b+- (non-square pixels, both boundaries, with and without a
  hardness cap; t_a near 90 deg, so that the transposed t_a wraps through 180 deg);
* an undefined border moves a free map's origin away from zero: nothing changes but the
  nominal pressure over the larger map;
* full contact (area fraction exactly 1) weighs the facets by the closed-form pressure;
* units: lengths x 1e-6 (m <-> um) leave the pressures and the law unchanged and scale the
  gap; E*, p and H x k scale the pressures only;
* a triangle mesh moved far from the origin carries the same force on each triangle, and
  the forces sum to the load; a mesh of a grid of 2h x h cells pressed on a grid of step h
  is the map with its x-pixels interpolated exactly;
* windows of a scan of non-square pixels are the solves (and derive --window's laws the
  laws) of its crops, placed at their origins in metres.
The fixtures have no mirror symmetry (tests/lays.py)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from cli_run import run, run_json
from lays import assert_mapped, isometry, lay

from asperity.contact import solve_contact
from asperity.friction.derive import derive
from asperity.surface.contact_facets import ElasticContact, elastic_facets
from asperity.surface.facets import heightmap_facets
from asperity.surface.mesh_grid import face_forces, mesh_heightmap
from asperity.surface.topography import HeightMap, TriangleMesh

E = 1e9
P = 2e7
DX, DY = 1.0e-6, 0.6e-6
N_DIR = 72                         # a multiple of 4: quarter turns map the grid to itself


@pytest.fixture(scope="module")
def scan():
    """40 x 28 pixels of 1 x 0.6 um, ridges across 95 deg (t_a near 90 deg)."""
    return lay(40, 28, DX, DY, angle_deg=95.0, seed=1)


def weighted(z, dx, dy, boundary, hardness=None, pressure=P, E_star=E):
    ec = ElasticContact(E_star, pressure, boundary=boundary, hardness=hardness, tol=1e-11)
    return derive(HeightMap(z, dx, dy, n_undefined=int(np.isnan(z).sum())), "all-faces",
                  "closed-form", N_DIR, elastic=ec)


# ---- isometries of a non-square-pixel map -----------------------------------------------

@pytest.mark.parametrize("iso, boundary, hardness", [
    ("transpose", "periodic", None), ("transpose", "free", 2e8),
    ("half-turn", "free", None), ("half-turn", "periodic", 2e8)])
def test_a_transposed_or_half_turned_map_mirrors_or_turns_the_weighted_law(scan, iso, boundary,
                                                                          hardness):
    """The contact solve and the facets' corner-averaged weights are both invariant under
    these two isometries (they keep each cell's diagonal), so the law maps to rounding."""
    a = weighted(scan, DX, DY, boundary, hardness)
    z, dx, dy, Q = isometry(iso, scan, DX, DY)
    b = weighted(z, dx, dy, boundary, hardness)
    ca, cb = a.texture.elastic, b.texture.elastic
    assert abs(ca["area_fraction"] - cb["area_fraction"]) * scan.size <= 1.0
    for k in ("max_pressure_Pa", "mean_gap_m", "pressure_Pa"):
        assert cb[k] == pytest.approx(ca[k], rel=1e-9), k
    if hardness is not None:
        assert ca["max_pressure_Pa"] <= hardness and ca["plastic_fraction"] > 0
    assert_mapped(a, b, Q, iso)
    # the fixture is asymmetric both ways, and the transposed t_a wraps through 180 deg
    assert abs(a.axes["mu_a_plus"] - a.axes["mu_a_minus"]) > 5e-3
    assert abs(a.axes["mu_b_plus"] - a.axes["mu_b_minus"]) > 1e-3
    if iso == "transpose":
        assert 90.0 < a.principal_direction_deg < 180.0


# ---- origin, units --------------------------------------------------------------------

@pytest.mark.parametrize("hardness", [None, 2.5e8])
def test_an_undefined_border_moves_the_origin_and_changes_nothing(scan, hardness):
    """A free map padded with undefined pixels before its first row and column: the same
    pixels carry the same load (the nominal pressure is over the larger map), so the
    contact and the weighted law are the same."""
    nx, ny = scan.shape
    big = np.full((nx + 7, ny + 5), np.nan)
    big[7:, 5:] = scan
    a = weighted(scan, DX, DY, "free", hardness)
    b = weighted(big, DX, DY, "free", hardness, pressure=P * scan.size / big.size)
    ca, cb = a.texture.elastic, b.texture.elastic
    assert abs(cb["area_fraction"] - ca["area_fraction"]) * scan.size <= 1.0   # defined px
    for k in ("max_pressure_Pa", "mean_gap_m", "plastic_fraction"):
        assert cb[k] == pytest.approx(ca[k], rel=1e-8, abs=1e-15), k
    np.testing.assert_allclose(b.reservoir.p, a.reservoir.p, rtol=0,
                               atol=1e-8 * np.abs(a.reservoir.p).max())
    assert b.principal_direction_deg == pytest.approx(a.principal_direction_deg, abs=1e-6)


def test_units_scale_the_gap_and_the_pressures_as_the_physics_says(scan):
    """Lengths (heights and pixel sides) x 1e-6: the same pressures, the same law, the gap x
    1e-6.  E*, p and H x 1e3: the same contact and law, pressures x 1e3."""
    a = weighted(scan, DX, DY, "periodic", 3e8)
    um = weighted(scan * 1e6, DX * 1e6, DY * 1e6, "periodic", 3e8)
    stiff = weighted(scan, DX, DY, "periodic", 3e11, pressure=P * 1e3, E_star=E * 1e3)
    ca, cu, cs = a.texture.elastic, um.texture.elastic, stiff.texture.elastic
    assert cu["area_fraction"] == ca["area_fraction"] == cs["area_fraction"]
    assert cu["max_pressure_Pa"] == pytest.approx(ca["max_pressure_Pa"], rel=1e-8)
    assert cu["mean_gap_m"] == pytest.approx(ca["mean_gap_m"] * 1e6, rel=1e-8)
    assert cs["max_pressure_Pa"] == pytest.approx(ca["max_pressure_Pa"] * 1e3, rel=1e-8)
    assert cs["mean_gap_m"] == pytest.approx(ca["mean_gap_m"], rel=1e-8)
    for d in (um, stiff):
        np.testing.assert_allclose(d.reservoir.p, a.reservoir.p, rtol=0,
                                   atol=1e-9 * np.abs(a.reservoir.p).max())


def test_the_command_line_reads_micrometres_as_metres_divided(scan, tmp_path, capsys):
    """The same map written in um (--unit um, pixel sides in um) and in m: one contact."""
    np.save(tmp_path / "m.npy", scan)
    np.save(tmp_path / "um.npy", scan * 1e6)
    common = ("--elastic", E, "--pressure", P, "--boundary", "free", "--detrend", "none")
    a = run_json(capsys, "contact", tmp_path / "m.npy", "--unit", "m", "--pixel-size", DX, DY,
                 *common)
    b = run_json(capsys, "contact", tmp_path / "um.npy", "--unit", "um", "--pixel-size",
                 DX * 1e6, DY * 1e6, *common)
    assert b["texture"]["pixel_size_m"] == pytest.approx([DX, DY], rel=1e-12)
    assert b["area_fraction"] == a["area_fraction"]
    for k in ("max_pressure_Pa", "mean_gap_m", "pressure_Pa"):
        assert b[k] == pytest.approx(a[k], rel=1e-8), k


def test_full_contact_weighs_the_facets_by_the_closed_form_pressure():
    """Area fraction exactly 1 (an edge value): a periodic map of oblong pixels pressed
    beyond full contact carries p = p_mean + E* |q| h_q / 2 (u = h - d everywhere), and the
    law is the facets weighted by that pressure -- not the area-weighted law."""
    nx, ny = 40, 28
    z = lay(nx, ny, DX, DY, angle_deg=95.0, seed=1, height=0.3e-6)
    qx = 2 * np.pi * np.fft.fftfreq(nx, DX)[:, None]
    qy = 2 * np.pi * np.fft.fftfreq(ny, DY)[None, :]
    dp = np.fft.ifft2(np.fft.fft2(z) * E * np.hypot(qx, qy) / 2).real
    p_mean = -1.5 * dp.min()
    a = weighted(z, DX, DY, "periodic", pressure=p_mean)
    c = a.texture.elastic
    assert c["area_fraction"] == 1.0 and c["mean_gap_m"] == 0.0
    assert c["max_pressure_Pa"] == pytest.approx((p_mean + dp).max(), rel=1e-8)
    hm = HeightMap(z, DX, DY)
    ref = derive(heightmap_facets(hm, pressure=p_mean + dp, periodic=True), n_directions=N_DIR)
    np.testing.assert_allclose(a.reservoir.p, ref.reservoir.p, rtol=0, atol=1e-12)
    area = derive(heightmap_facets(hm, periodic=True), n_directions=N_DIR)
    assert np.abs(area.reservoir.p - a.reservoir.p).max() > 1e-6          # it matters


# ---- meshes ---------------------------------------------------------------------------

def jittered_mesh(seed=4):
    """A sheet of 24 x 20 nodes (1.5 x 1.2 um apart, the inner ones jittered by 0.2 of
    that), heights of an asymmetric lay at 40 deg, every seventh triangle cut out."""
    rng = np.random.default_rng(seed)
    mx, my, h = 24, 20, 1.5e-6
    X, Y = np.meshgrid(np.arange(mx) * h, np.arange(my) * 0.8 * h, indexing="ij")
    inner = (np.arange(mx)[:, None] % (mx - 1) > 0) & (np.arange(my)[None, :] % (my - 1) > 0)
    X = X + rng.uniform(-0.2, 0.2, X.shape) * h * inner
    Y = Y + rng.uniform(-0.2, 0.2, Y.shape) * h * inner
    Z = lay(mx, my, h, 0.8 * h, angle_deg=40.0, seed=2)
    v = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    return v, grid_faces(mx, my)[np.arange(2 * (mx - 1) * (my - 1)) % 7 != 0]


def grid_faces(mx, my):
    """Triangles of an mx x my grid of nodes, each cell split along its (i+1, j)-(i, j+1)
    diagonal (as a height map's facets)."""
    idx = np.arange(mx * my).reshape(mx, my)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[:-1, 1:].ravel(), idx[1:, 1:].ravel()
    return np.concatenate([np.column_stack([a, b, c]), np.column_stack([d, c, b])])


def test_a_mesh_away_from_the_origin_carries_the_same_load_on_the_same_triangles():
    v, f = jittered_mesh()
    step = 0.4e-6
    ec = ElasticContact(E, 1e7, boundary="free", tol=1e-11)
    base = None
    for shift in ((0.0, 0.0, 0.0), (-3.7e-3, 5.2e-3, 1e-4), (2.5e-2, -1.1e-2, -3e-5)):
        mesh = TriangleMesh(v + np.array(shift), f, source="sheet")
        mg = mesh_heightmap(mesh, step)
        z = mg.heightmap.heights
        assert mg.origin == pytest.approx(tuple(v[:, :2].min(axis=0) + shift[:2]), abs=1e-15)
        assert 0 < mg.heightmap.n_undefined < z.size // 4          # the holes
        res = solve_contact(z, step, E, 1e7, boundary="free", tol=1e-11)
        F = face_forces(mesh, mg, res.pressure)
        load = 1e7 * z.size * step * step                       # p x the grid's area
        assert F.sum() == pytest.approx(load, rel=1e-12), f"load lost at origin {shift}"
        assert (F >= 0).all() and np.count_nonzero(F) > 20
        fs = next(elastic_facets(mesh, ec, mu=0.2, grid_step=step))
        assert fs.weight.sum() == pytest.approx(load, rel=1e-12)
        d = derive(fs, n_directions=N_DIR)
        if base is None:
            base = (z - shift[2], F, d)
            continue
        np.testing.assert_allclose(z - shift[2], base[0], rtol=0, atol=1e-9 * np.nanmax(
            np.abs(base[0])), equal_nan=True)     # the height offset's rounding
        np.testing.assert_allclose(F, base[1], rtol=0, atol=1e-8 * F.max())
        np.testing.assert_allclose(d.reservoir.p, base[2].reservoir.p, rtol=0, atol=1e-8)


def test_a_mesh_of_oblong_cells_on_a_square_grid_is_the_map_interpolated_along_x(scan):
    """A height map of 2h x h pixels as a mesh of its facets, on a grid of step h: every
    grid node lies on a vertex or on an x-edge of the mesh, so the envelope is the map with
    its x-pixels linearly interpolated, exactly; the load is carried whole."""
    z = scan[:20, :16]
    h = 0.6e-6
    nx, ny = z.shape
    X, Y = np.meshgrid(np.arange(nx) * 2 * h + 1.3e-3, np.arange(ny) * h - 0.7e-3,
                       indexing="ij")
    mesh = TriangleMesh(np.column_stack([X.ravel(), Y.ravel(), z.ravel()]),
                        grid_faces(nx, ny), source="oblong")
    mg = mesh_heightmap(mesh, h)
    fine = np.empty((2 * nx - 1, ny))
    fine[0::2] = z
    fine[1::2] = 0.5 * (z[:-1] + z[1:])
    assert mg.heightmap.heights.shape == fine.shape and mg.heightmap.n_undefined == 0
    np.testing.assert_allclose(mg.heightmap.heights, fine, rtol=0, atol=1e-12 * np.ptp(z))
    res = solve_contact(mg.heightmap.heights, h, E, P, boundary="free", tol=1e-10)
    F = face_forces(mesh, mg, res.pressure)
    assert F.sum() == pytest.approx(P * fine.size * h * h, rel=1e-12)


# ---- windows ----------------------------------------------------------------------------

@pytest.mark.parametrize("placement", ["grid", "random"])
def test_windows_of_a_non_square_scan_are_the_solves_of_its_crops(scan, tmp_path, capsys,
                                                                   placement):
    """Each window's contact is the solve of the scan's crop at its origin with the scan's
    own (dx, dy), its origin in metres the pixel origin times (dx, dy); the window may be as
    large as the scan's short side and not one pixel more."""
    path = tmp_path / "scan.npy"
    np.save(path, scan)
    nx, ny = scan.shape
    more = () if placement == "grid" else ("--window-seed", 5)
    d = run_json(capsys, "contact", path, "--unit", "m", "--pixel-size", DX, DY, "--detrend",
                 "none", "--elastic", E, "--pressure", P, "--window", ny, "--windows", 3,
                 "--window-placement", placement, *more)
    assert d["windows"]["used"] == 3 and d["windows"]["window_m"] == pytest.approx(
        [ny * DX, ny * DY], rel=1e-12)
    origins = set()
    for w in d["per_window"]:
        i0, j0 = w["origin_px"]
        assert 0 <= i0 <= nx - ny and j0 == 0, "a window runs past the scan"
        assert w["origin_m"] == pytest.approx([i0 * DX, j0 * DY], rel=1e-12, abs=0)
        ref = solve_contact(scan[i0:i0 + ny, j0:j0 + ny], (DX, DY), E, P, boundary="free")
        c = w["elastic_contact"]
        assert c["area_fraction"] == pytest.approx(ref.area_fraction, abs=1.5 / ny ** 2)
        assert c["max_pressure_Pa"] == pytest.approx(ref.max_pressure, rel=1e-5)
        assert c["mean_gap_m"] == pytest.approx(ref.mean_gap, rel=1e-5)
        origins.add(i0)
    assert len(origins) > 1                                  # not all the same window
    code, out, err = run(capsys, "contact", path, "--unit", "m", "--pixel-size", DX, DY,
                         "--elastic", E, "--pressure", P, "--window", ny + 1)
    assert code == 1 and out == "" and "--window" in err and len(err.strip().splitlines()) == 1
    json.dumps(d)                                            # finite numbers only


def test_derive_windows_of_a_non_square_scan_are_the_laws_of_its_crops(scan, tmp_path, capsys):
    """derive --window: each window's weighted law is that of the scan's crop at its
    origin with the scan's (dx, dy), its + and - exchanged where it is listed turned to
    the windows' common t_a (``reversed``)."""
    path = tmp_path / "scan.npy"
    np.save(path, scan)
    d = run_json(capsys, "derive", path, "--unit", "m", "--pixel-size", DX, DY, "--detrend",
                 "none", "--elastic", E, "--pressure", P, "--window", 20, "--windows", 3,
                 "--directions", 24)
    ec = ElasticContact(E, P, boundary="free")
    seen = set()
    for w in d["per_window"]:
        i0, j0 = w["origin_px"]
        seen.add((i0, j0))
        crop = HeightMap(np.ascontiguousarray(scan[i0:i0 + 20, j0:j0 + 20]), DX, DY)
        ref = derive(next(elastic_facets(crop, ec, level_slope=False)), n_directions=24)
        assert abs(math.remainder(w["principal_direction_deg"]
                                  - ref.principal_direction_deg, 180.0)) < 1e-9
        want = dict(ref.axes)
        if w["reversed"]:
            want = {"mu_a_plus": want["mu_a_minus"], "mu_a_minus": want["mu_a_plus"],
                    "mu_b_plus": want["mu_b_minus"], "mu_b_minus": want["mu_b_plus"]}
        for k, v in want.items():
            assert w[k] == pytest.approx(v, rel=1e-9), (i0, j0, k)
        assert w["elastic_contact"]["area_fraction"] == ref.texture.elastic["area_fraction"]
    assert len(seen) == 3 and any(i0 > 0 and j0 > 0 for i0, j0 in seen)

