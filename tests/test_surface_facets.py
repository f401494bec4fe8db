"""Any surface -> friction: facet homogenisation checked against the wedge closed form."""
import math

import numpy as np
import pytest

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.friction.faces import compute_reservoir
from asperity.friction.reservoir import directions
from asperity.surface.facets import heightmap_facets, mesh_facets
from asperity.surface.topography import TriangleMesh
from asperity.surface.wedge_surfaces import wedge_heightmap, wedge_mesh
from asperity.texture.wedges import GaussianWedgeTexture, WedgeTexture

PSI = directions(72)
TEXTURES = [WedgeTexture(30, 10, 0.1, 0.2), WedgeTexture(60, 15, 0.3, 0.1),
            GaussianWedgeTexture(30, 10, 0.1, 0.2, 5e-6, 1e-6, n_wedges=40)]


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
@pytest.mark.parametrize("tex", TEXTURES, ids=["wedge-30-10", "wedge-60-15", "gaussian"])
def test_wedge_mesh_reproduces_closed_form(tex, contact):
    mesh, mu = wedge_mesh(tex, periods=3)
    # the Gaussian texture's flat gaps carry no load: springs at rest on the base line z = 0
    rest = 0.0 if tex.kind == "gaussian-wedge" else None
    surf = mesh_facets(mesh, friction_map=mu, rest_level=rest)
    got, ref = compute_reservoir(surf, PSI, contact), compute_reservoir(tex, PSI, contact)
    np.testing.assert_array_equal(got.locked, ref.locked)
    np.testing.assert_array_equal(got.set_valued, ref.set_valued)
    ok = ~ref.locked
    np.testing.assert_allclose(got.p[ok], ref.p[ok], rtol=1e-13, atol=1e-14)   # 5e-15 reached


def test_wedge_mesh_axes_and_principal_direction():
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    mesh, mu = wedge_mesh(tex, periods=2)
    d = derive(mesh_facets(mesh, friction_map=mu), n_directions=72)
    ref = derive(tex, n_directions=72)
    assert d.principal_direction_deg == pytest.approx(0.0, abs=1e-12)     # 3e-14 reached
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
        assert d.axes[k] == pytest.approx(ref.axes[k], rel=1e-13)
    assert d.admissibility.admissible
    # dT/dpsi by steps of 1e-3 (surfaces) and 1e-6 (closed form): 6.6e-7 apart
    assert d.associativity.max_deviation == pytest.approx(ref.associativity.max_deviation, rel=2e-6)
    # anisotropy (max T - min T) / mean T, computed here from SPEC.md's T = p . s
    T = np.einsum("ij,ij->i", ref.reservoir.p, np.column_stack([np.cos(ref.reservoir.psi),
                                                                np.sin(ref.reservoir.psi)]))
    assert d.anisotropy == pytest.approx((T.max() - T.min()) / T.mean(), rel=1e-12)


@pytest.mark.parametrize("angle", [37.0, 123.0])
def test_rotated_texture_gives_rotated_reservoir(angle):
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    mesh, mu = wedge_mesh(tex, periods=2, angle_deg=angle)
    surf = mesh_facets(mesh, friction_map=mu)
    phi = math.radians(angle)
    got = compute_reservoir(surf, PSI + phi, "all-faces").p
    ref = compute_reservoir(tex, PSI, "all-faces").p
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    np.testing.assert_allclose(got, ref @ rot.T, rtol=1e-13, atol=1e-15)     # 1.4e-16 reached
    d = derive(surf, n_directions=72)
    assert d.principal_direction_deg == pytest.approx(angle % 180.0, abs=1e-12)   # 1e-13
    ref_axes = derive(tex, n_directions=72).axes
    # the principal direction is an axis: +t_a may come out reversed
    a = (d.axes["mu_a_plus"], d.axes["mu_a_minus"])
    assert sorted(a) == pytest.approx(sorted((ref_axes["mu_a_plus"], ref_axes["mu_a_minus"])), rel=1e-13)


def test_facets_given_as_views_keep_their_gradients():
    """A FacetSurface whose gx, gy are rows of one array in the other order, the same row
    twice or parts of rows: faces() gives (gx, gy) as given (turning or mirroring a surface
    by swapping its gradient rows must turn or mirror its friction)."""
    from asperity.surface.facets import FacetSurface
    g = np.array([[0.1, 0.2, 0.3], [-0.4, 0.5, -0.6]])
    for gx, gy in ((g[0], g[1]), (g[1], g[0]), (g[0], g[0]), (g[0, :2], g[1, :2])):
        s = FacetSurface(gx=gx, gy=gy, mu=0.2, weight=np.ones(gx.size), info={})
        np.testing.assert_array_equal(s.faces().gradient, np.column_stack([gx, gy]))


def test_heightmap_slopes_with_rectangular_pixels():
    """A plane z = 0.3 x - 0.2 y sampled on pixels 1 um x 3 um: every facet has the plane's
    gradient, and its friction is that of one tilted plane, SPEC.md 2 for one face."""
    from asperity.surface.topography import HeightMap
    dx, dy = 1e-6, 3e-6
    x, y = np.arange(40) * dx, np.arange(25) * dy
    z = 0.3 * x[:, None] - 0.2 * y[None, :]
    s = heightmap_facets(HeightMap(heights=z, dx=dx, dy=dy, source="plane", n_undefined=0),
                         mu=0.25)
    np.testing.assert_allclose(s.gx, 0.3, rtol=1e-9)
    np.testing.assert_allclose(s.gy, -0.2, rtol=1e-9)
    one = compute_reservoir(s, PSI, "all-faces").p
    from asperity.friction.faces import compute_face_reservoir
    np.testing.assert_allclose(one, compute_face_reservoir([[0.3, -0.2]], [0.25], [1.0], PSI).p,
                               rtol=1e-9)


def test_transposed_heightmap_mirrors_the_reservoir():
    """Swapping x and y (heights transposed, pixel sizes swapped) mirrors the surface about
    the diagonal: p(psi) -> (p_b, p_a) at 90 deg - psi, the principal direction goes to
    90 deg - theta, mu_a+- stay, mu_b+ and mu_b- swap.  Random heights, pixels 1 x 2.5 um."""
    from asperity.surface.topography import HeightMap
    rng = np.random.default_rng(5)
    z = rng.normal(0, 0.4e-6, (30, 22))
    z += np.linspace(0, 3e-6, 30)[:, None] * np.sin(np.arange(22) / 3.0)[None, :]
    a = heightmap_facets(HeightMap(heights=z, dx=1e-6, dy=2.5e-6, source="a", n_undefined=0),
                         mu=0.2)
    b = heightmap_facets(HeightMap(heights=z.T.copy(), dx=2.5e-6, dy=1e-6, source="b",
                                   n_undefined=0), mu=0.2)
    for contact in ("all-faces", "windward"):
        pa = compute_reservoir(a, PSI, contact).p
        pb = compute_reservoir(b, 0.5 * np.pi - PSI, contact).p
        np.testing.assert_allclose(pb[:, ::-1], pa, rtol=1e-12, atol=1e-15)
        da, db = derive(a, contact, n_directions=360), derive(b, contact, n_directions=360)
        d = (da.principal_direction_deg + db.principal_direction_deg - 90.0) % 180.0
        assert min(d, 180.0 - d) < 1e-9, (da.principal_direction_deg, db.principal_direction_deg)
        assert db.anisotropy == pytest.approx(da.anisotropy, rel=1e-12)


def _heightmap_error(tex, n, contact, offsets=8):
    """RMS over directions of |p_map - p_closed| / |p_closed|, averaged over ``offsets``
    positions of the pixel grid relative to the ridges."""
    ref = compute_reservoir(tex, PSI, contact).p
    errs = []
    for off in (np.arange(offsets) + 0.5) / offsets:
        hm, mu = wedge_heightmap(tex, n, periods=1, ny=2, offset=off)
        got = compute_reservoir(heightmap_facets(hm, friction_map=mu), PSI, contact).p
        errs.append(np.sqrt(np.mean(np.sum((got - ref) ** 2, axis=1) / np.sum(ref ** 2, axis=1))))
    return float(np.mean(errs))


NS = [32, 64, 128, 256, 512]


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_sampled_heightmap_converges_first_order(contact):
    """Cells straddling a ridge or valley get a blended gradient: their share is O(h), so
    the error is first order in the pixel size h."""
    tex = WedgeTexture(30, 10, 0.1, 0.1)
    err = [_heightmap_error(tex, n, contact) for n in NS]
    order = -np.polyfit(np.log(NS), np.log(err), 1)[0]
    assert 0.9 < order < 1.1, (err, order)
    assert err[-1] < {"all-faces": 1e-3, "windward": 1e-2}[contact], err


def test_sampled_heightmap_with_friction_map_converges():
    """Faces of different friction: facets straddling a face boundary also average the
    friction of their corners, a second O(h) error whose constant changes sign with the
    grid, so the convergence is first order on average, not term by term."""
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    err = [_heightmap_error(tex, n, "all-faces") for n in NS]
    order = -np.polyfit(np.log(NS), np.log(err), 1)[0]
    assert 0.6 < order < 1.4, (err, order)
    assert err[-1] < 0.1 * err[0]


def _plates(mu_top=0.3, mu_bottom=0.1):
    """Two horizontal unit squares: one at z = 1 (mu_top), one at z = 0 (mu_bottom)."""
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    v = np.vstack([np.column_stack([sq, np.ones(4)]), np.column_stack([sq + [2, 0], np.zeros(4)])])
    f = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    return TriangleMesh(vertices=v, faces=f, source="plates", n_degenerate=0), \
        np.array([mu_top, mu_top, mu_bottom, mu_bottom])


def test_rest_level_makes_friction_depend_on_load():
    mesh, mu = _plates()
    psi = np.radians([0.0, 90.0, 211.0])
    uniform = compute_reservoir(mesh_facets(mesh, friction_map=mu), psi).tangential
    np.testing.assert_allclose(uniform, 0.2, rtol=1e-12)
    light = compute_reservoir(mesh_facets(mesh, friction_map=mu, rest_level=0.5), psi).tangential
    np.testing.assert_allclose(light, 0.3, rtol=1e-12)           # only the upper plate touches
    heavy = compute_reservoir(mesh_facets(mesh, friction_map=mu, rest_level=-1.0), psi).tangential
    np.testing.assert_allclose(heavy, (2 * 0.3 + 1 * 0.1) / 3, rtol=1e-12)  # loads 2 : 1
    half = mesh_facets(mesh, friction_map=mu, bearing_fraction=0.5)
    assert half.info["rest_level_m"] == pytest.approx(0.5)
    np.testing.assert_allclose(compute_reservoir(half, psi).tangential, 0.3, rtol=1e-12)
    with pytest.raises(InputError, match="rest_level"):
        mesh_facets(mesh, friction_map=mu, rest_level=2.0)


def test_mesh_skips_vertical_and_overhanging_triangles():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0],       # floor, faces up
                  [0, 0, 1], [1, 0, 1]], float)
    f = np.array([[0, 1, 2], [1, 3, 2],                                # up
                  [0, 1, 5],                                           # vertical wall
                  [0, 2, 1]])                                          # floor seen from below
    s = mesh_facets(TriangleMesh(vertices=v, faces=f, source="t", n_degenerate=0), mu=0.2)
    assert s.n_facets == 2
    assert s.info["n_skipped_vertical"] == 1 and s.info["n_skipped_overhanging"] == 1
    np.testing.assert_allclose(compute_reservoir(s, PSI).tangential, 0.2, rtol=1e-12)


def test_heightmap_undefined_pixels_skip_their_triangles():
    tex = WedgeTexture(30, 30, 0.2, 0.2)
    hm, _ = wedge_heightmap(tex, 32, periods=2, ny=8)
    z = hm.heights.copy()
    z[5, 3] = np.nan
    from asperity.surface.topography import HeightMap
    s = heightmap_facets(HeightMap(heights=z, dx=hm.dx, dy=hm.dy, source="t", n_undefined=1),
                         mu=0.2)
    assert s.n_undefined == 1
    assert s.info["n_skipped_undefined"] == 6          # a pixel touches six triangles
    assert s.n_facets == 2 * (z.shape[0] - 1) * (z.shape[1] - 1) - 6
    assert np.all(np.isfinite(compute_reservoir(s, PSI).p))


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_tilt_removed_by_mean_slope_levelling(contact):
    """A wedge mesh sheared by a tilt z += 0.1 x - 0.05 y: levelling the mean facet slope
    gives back the closed form (a least-squares plane would not: a sawtooth over a few
    periods has a non-zero regression slope)."""
    import dataclasses
    tex = WedgeTexture(30, 10, 0.1, 0.2)
    mesh, mu = wedge_mesh(tex, periods=3)
    v = mesh.vertices.copy()
    v[:, 2] += 0.1 * v[:, 0] - 0.05 * v[:, 1]
    tilted = dataclasses.replace(mesh, vertices=v)
    ref = compute_reservoir(tex, PSI, contact).p
    raw = compute_reservoir(mesh_facets(tilted, friction_map=mu), PSI, "all-faces").p
    assert np.max(np.abs(raw - compute_reservoir(tex, PSI, "all-faces").p)) > 0.05  # tilt matters
    s = mesh_facets(tilted, friction_map=mu, level_slope=True)
    np.testing.assert_allclose(s.info["removed_slope"], [0.1, -0.05], rtol=1e-13)  # 2e-16
    np.testing.assert_allclose(compute_reservoir(s, PSI, contact).p, ref, rtol=1e-13, atol=1e-14)


def test_self_locking_load_share_is_the_locking_faces_area_share():
    """A steep alpha face (80 deg, mu 0.3 > cot 80) locks across the ridges: its share of
    the projected area is cot(alpha) / (cot(alpha) + cot(beta))."""
    tex = WedgeTexture(80, 10, 0.3, 0.2)
    ca, cb = 1 / math.tan(math.radians(80)), 1 / math.tan(math.radians(10))
    mesh, mu = wedge_mesh(tex, periods=2)
    for surf in (tex, mesh_facets(mesh, friction_map=mu)):
        d = derive(surf, n_directions=72)
        assert d.reservoir.locked.any()
        assert d.locking_share == pytest.approx(ca / (ca + cb), rel=1e-13)   # 1.3e-15 reached
    assert derive(WedgeTexture(30, 10, 0.1, 0.2), n_directions=36).locking_share == 0.0
