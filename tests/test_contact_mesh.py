"""Elastic contact of a triangle mesh (asperity.surface.mesh_grid): the mesh's upper
envelope on a regular grid is pressed, and each triangle weighs the force of the grid
nodes it holds.

Checks: a faceted sphere cap (an icosphere, cut) against Hertz; a mesh made from a height
map (its nodes, the facets' own diagonals) gives the height map's pressure and, on
``derive --elastic``, friction close to the height map's (the triangles' forces converge
to the height map's facet forces as the grid is refined); the forces sum to the load;
``asperity contact`` and ``derive --elastic`` on mesh files; bad input in one line."""
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json

from asperity.contact import solve_contact
from asperity.errors import InputError
from asperity.surface.contact_facets import ElasticContact, elastic_facets
from asperity.surface.mesh_grid import face_forces, mesh_heightmap
from asperity.surface.topography import TriangleMesh

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from contact_peers import self_affine  # noqa: E402

E = 1e9


def grid_mesh(z, dx):
    """The triangles of a height map as heightmap_facets makes them: each cell split
    along its (i+1, j)-(i, j+1) diagonal; vertices at the nodes (i dx, j dx)."""
    nx, ny = z.shape
    X, Y = np.meshgrid(np.arange(nx) * dx, np.arange(ny) * dx, indexing="ij")
    v = np.column_stack([X.ravel(), Y.ravel(), z.ravel()])
    idx = np.arange(nx * ny).reshape(nx, ny)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[:-1, 1:].ravel(), idx[1:, 1:].ravel()
    f = np.concatenate([np.column_stack([a, b, c]), np.column_stack([d, c, b])])
    return v, f


def write_obj(path, v, f):
    with open(path, "w") as fh:
        fh.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in v)
        fh.writelines(f"f {i + 1} {j + 1} {k + 1}\n" for i, j, k in f)


# ---- Hertz: a faceted sphere cap ------------------------------------------------------

def test_icosphere_cap_against_hertz():
    """Radius R, contact radius a = R / 10 (loaded for it), 64 grid steps across the
    contact.  The cap is flat triangles (edges ~ R / 116): their kinks raise the pressure
    locally (a logarithmic peak at each edge), so the peak is checked loosely and the
    pressure as averaged over rings; the contact radius within 1 %, the ring means of
    r < 0.8 a within 1 % of p0 of Hertz's, the force balance to rounding."""
    trimesh = pytest.importorskip("trimesh")
    R = 0.01
    a = 0.1 * R
    m = trimesh.creation.icosphere(subdivisions=7, radius=R)
    v, f = np.asarray(m.vertices), np.asarray(m.faces)
    c = v[f].mean(axis=1)
    keep = (np.hypot(c[:, 0], c[:, 1]) < 1.6 * a) & (c[:, 2] > 0)
    h = 2 * a / 64
    mg = mesh_heightmap(TriangleMesh(v, f[keep], source="cap"), h)
    z = mg.heightmap.heights
    nx, ny = z.shape
    assert mg.heightmap.n_undefined > 0 and np.isnan(z[0, 0])      # round: corners empty
    P = 4 * E * a ** 3 / (3 * R)
    res = solve_contact(z, h, E, P / (nx * ny * h * h), boundary="free", tol=1e-10)
    assert np.nansum(res.pressure) * h * h == pytest.approx(P, rel=1e-10)
    a_num = math.sqrt(np.count_nonzero(res.contact) * h * h / math.pi)
    assert a_num == pytest.approx(a, rel=0.01)
    p0 = 3 * P / (2 * math.pi * a * a)
    x = mg.origin[0] + np.arange(nx) * h
    y = mg.origin[1] + np.arange(ny) * h
    r = np.hypot(x[:, None], y[None, :])
    edges = np.linspace(0, 0.8 * a, 9)
    for r0, r1 in zip(edges[:-1], edges[1:]):
        ring = (r >= r0) & (r < r1)
        ref = p0 * np.sqrt(1 - (r[ring] / a) ** 2).mean()
        assert abs(res.pressure[ring].mean() - ref) < 0.01 * p0, (r0, r1)
    assert p0 < res.max_pressure < 1.1 * p0


# ---- a mesh made from a height map -----------------------------------------------------

@pytest.fixture(scope="module")
def scan():
    z = self_affine(48, 40, dx=1e-6, seed=5)
    return z, 1e-6


def test_height_map_mesh_gives_the_height_maps_grid_and_pressure(scan):
    z, dx = scan
    v, f = grid_mesh(z, dx)
    mg = mesh_heightmap(TriangleMesh(v, f, source="grid"), dx)
    assert mg.heightmap.heights.shape == z.shape and mg.heightmap.n_undefined == 0
    assert np.abs(mg.heightmap.heights - z).max() < 1e-12 * np.ptp(z)
    a = solve_contact(z, dx, E, 5e6, boundary="free")
    b = solve_contact(mg.heightmap.heights, dx, E, 5e6, boundary="free")
    assert np.abs(a.pressure - b.pressure).max() < 1e-7 * a.pressure.max()
    assert np.array_equal(a.contact, b.contact)
    # each node's force goes to one triangle that holds it: the forces sum to the load
    F = face_forces(TriangleMesh(v, f), mg, b.pressure)
    assert F.sum() == pytest.approx(5e6 * z.size * dx * dx, rel=1e-12)
    assert (F >= 0).all()


def test_mesh_facet_forces_converge_to_the_height_maps(scan):
    """The height map's facets weigh the node pressures' mean over each triangle (second
    order); the mesh's triangles weigh the grid nodes they hold (a node on an edge or a
    vertex shared).  On grids of step dx and dx / 4 over the same triangles (the finer
    grid's own triangles lie inside the mesh's, with their gradients), the mesh's friction
    is that grid's height map's within 0.3 % on every axis, closer on the finer grid; the
    facets' forces sum to the load."""
    from asperity.friction.derive import derive
    z, dx = scan
    ec = ElasticContact(E, 5e6)
    v, f = grid_mesh(z, dx)
    mesh = TriangleMesh(v, f, source="mesh")
    errs = []
    for step in (dx, dx / 4):
        hm = mesh_heightmap(mesh, step).heightmap
        ref = derive(next(elastic_facets(hm, ec, mu=0.15)), n_directions=24).axes
        fs = next(elastic_facets(mesh, ec, mu=0.15, grid_step=step))
        assert fs.elastic["grid_step_m"] == step and fs.info["kind"] == "mesh"
        assert fs.weight.sum() == pytest.approx(5e6 * hm.heights.size * step * step,
                                                rel=1e-9)
        got = derive(fs, n_directions=24).axes
        errs.append(max(abs(got[k] / ref[k] - 1) for k in ref))
    assert errs[0] < 0.003 and errs[1] < 0.6 * errs[0], errs


# ---- the command line ------------------------------------------------------------------

@pytest.fixture(scope="module")
def files(tmp_path_factory, scan):
    z, dx = scan
    d = tmp_path_factory.mktemp("mesh")
    np.save(d / "z.npy", z)
    v, f = grid_mesh(z, dx)
    write_obj(d / "z.obj", v, f)
    (d / "empty.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    return d


def test_contact_of_a_mesh_file_is_the_height_maps(files, capsys, tmp_path):
    base = ["--elastic", "1e9", "--pressure", "5e6"]
    hm = run_json(capsys, "contact", files / "z.npy", "--unit", "m", "--pixel-size", "1e-6",
                  *base)
    out = tmp_path / "p.npy"
    me = run_json(capsys, "contact", files / "z.obj", "--unit", "m", "--grid-step", "1e-6",
                  *base, "--save-pressure", out)
    t = me["texture"]
    assert t["kind"] == "mesh" and t["grid"] == [48, 40] and t["grid_step_m"] == 1e-6
    assert not t["grid_step_default"] and t["n_triangles"] == 2 * 47 * 39
    assert me["boundary"] == "free"                       # the meshes' default
    for k in ("area_fraction", "max_pressure_Pa", "mean_gap_m"):
        assert me[k] == pytest.approx(hm[k], rel=1e-6), k
    assert np.load(out).shape == (48, 40)
    code, text, err = run(capsys, "contact", files / "z.obj", "--unit", "m", *base)
    assert code == 0, err
    assert "upper envelope" in text and "(the default step)" in text


def test_derive_fit_risk_of_a_mesh_with_elastic(files, capsys):
    d = run_json(capsys, "derive", files / "z.obj", "--unit", "m", "--mu", "0.15",
                 "--elastic", "1e9", "--pressure", "5e6", "--grid-step", "1e-6",
                 "--directions", "24")
    c = d["elastic_contact"]
    assert c["grid_step_m"] == 1e-6 and c["boundary"] == "free"
    ref = run_json(capsys, "derive", files / "z.npy", "--unit", "m", "--pixel-size", "1e-6",
                   "--mu", "0.15", "--elastic", "1e9", "--pressure", "5e6",
                   "--directions", "24")
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
        assert d[k] == pytest.approx(ref[k], rel=0.003), k
    gauge = files / "g.json"
    run_json(capsys, "fit", files / "z.obj", "--unit", "m", "--elastic", "1e9", "--pressure",
             "5e6", "--grid-step", "1e-6", "-o", gauge)
    src = json.loads(gauge.read_text())["source"]
    assert src["elastic_contact"]["grid_step_m"] == 1e-6
    r = run_json(capsys, "risk", files / "z.obj", ROOT / "surfaces" / "two-node-spec.toml",
                 "--unit", "m", "--elastic", "1e9", "--pressure", "5e6")
    assert r["friction"]["elastic_contact"]["grid_step_default"] is True
    for cmd in ("derive", "contact"):
        code, _, err = run(capsys, cmd, files / "z.obj", "--unit", "m", "--elastic", "1e9",
                           "--pressure", "5e6", "--window", "16")
        assert code == 1 and "--window takes windows of a height map" in err, err
    fam = run_json(capsys, "derive", files / "z.obj", "--unit", "m", "--elastic", "1e9",
                   "--pressure", "1e6", "1e7", "--directions", "24")
    assert [m["elastic_contact"]["pressure_Pa"] for m in fam["members"]] == pytest.approx([1e6, 1e7], rel=1e-12)


@pytest.mark.parametrize("more, words", [
    (["--grid-step", "0"], "--grid-step must be in (0, inf) m"),
    (["--grid-step=-1e-6"], "--grid-step must be in (0, inf) m"),
    (["--grid-step", "nan"], "--grid-step"),
    (["--grid-step", "1e-3"], "--grid-step 0.001 m gives a grid of 1 x 1 nodes"),
    (["--grid-step", "1e-11"], "give a coarser grid_step (--grid-step)"),
    (["--boundary", "periodic"], "--boundary of a mesh must be free"),
])
def test_bad_mesh_input_one_line(files, capsys, tmp_path, more, words):
    out = tmp_path / "p.npy"
    code, _, err = run(capsys, "contact", files / "z.obj", "--unit", "m", "--elastic", "1e9",
                       "--pressure", "5e6", "--save-pressure", out, *more)
    assert code != 0 and words in err and len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err and not out.exists()


def test_mesh_without_triangles_and_grid_step_of_a_height_map(files, capsys):
    code, _, err = run(capsys, "contact", files / "empty.obj", "--unit", "m", "--elastic",
                       "1e9", "--pressure", "5e6")
    assert code != 0 and "holds no triangles" in err and len(err.strip().splitlines()) == 1
    code, _, err = run(capsys, "contact", files / "z.npy", "--unit", "m", "--pixel-size",
                       "1e-6", "--elastic", "1e9", "--pressure", "5e6", "--grid-step", "1e-6")
    assert code != 0 and "--grid-step applies to meshes" in err
    code, _, err = run(capsys, "derive", files / "z.npy", "--unit", "m", "--pixel-size",
                       "1e-6", "--elastic", "1e9", "--pressure", "5e6", "--grid-step", "1e-6")
    assert code != 0 and "--grid-step applies to meshes" in err
    code, _, err = run(capsys, "derive", files / "z.obj", "--unit", "m", "--grid-step", "1e-6")
    assert code != 0 and "--grid-step needs --elastic" in err
    with pytest.raises(InputError, match="no triangle"):
        mesh_heightmap(TriangleMesh(np.zeros((3, 3)), np.zeros((0, 3), dtype=int)))


def test_closed_mesh_is_pressed_on_its_upper_envelope():
    """A closed sphere (both hemispheres over each node): the grid takes the upper one,
    z = +sqrt(R^2 - r^2) less the triangles' sag; nodes outside the disc are undefined."""
    trimesh = pytest.importorskip("trimesh")
    R = 1e-3
    m = trimesh.creation.icosphere(subdivisions=4, radius=R)
    mg = mesh_heightmap(TriangleMesh(np.asarray(m.vertices), np.asarray(m.faces)), R / 20)
    z = mg.heightmap.heights
    x = mg.origin[0] + np.arange(z.shape[0]) * mg.step
    y = mg.origin[1] + np.arange(z.shape[1]) * mg.step
    r2 = x[:, None] ** 2 + y[None, :] ** 2
    inner = r2 < (0.9 * R) ** 2
    assert np.isfinite(z[inner]).all() and np.isnan(z[r2 > (1.01 * R) ** 2]).all()
    # the flat triangles lie inside the sphere by their sag (edges ~ 1.1 R / 16: < 0.3 % R);
    # the lower hemisphere would be 2 sqrt(R^2 - r^2) > 0.87 R away
    d = np.sqrt(R * R - r2[inner]) - z[inner]
    assert d.min() > -1e-12 * R and d.max() < 0.003 * R


def test_default_grid_step():
    """Median projected edge / 4, refined to at least 65536 nodes, coarsened to at most
    4194304."""
    from asperity.surface.mesh_grid import default_step
    for n, want in ((48, lambda L: math.sqrt(L * L / 65536)), (300, lambda L: 1e-6 / 4),
                    (600, lambda L: math.sqrt(L * L / 4194304))):
        z = np.zeros((n, n))
        v, f = grid_mesh(z, 1e-6)
        L = (n - 1) * 1e-6
        assert default_step(TriangleMesh(v, f)) == pytest.approx(want(L), rel=1e-12)
    v, f = grid_mesh(np.zeros((2, 2)), 1.0)        # two triangles of a metre
    v[:, :2] *= 1e-3                               # 1 mm: 65536 nodes, not 16
    assert default_step(TriangleMesh(v, f)) == pytest.approx(1e-3 / 256, rel=1e-12)
    v[:, 0] *= 1e4                                 # 10 m x 1 mm: still >= 65536 nodes
    s = default_step(TriangleMesh(v, f))
    assert s == pytest.approx(math.sqrt(10 * 1e-3 / 65536), rel=1e-12)
