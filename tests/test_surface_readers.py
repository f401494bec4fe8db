"""Surface readers: formats, units, errors, and the measured files."""
from __future__ import annotations

import io
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from surface_files import gz_copy, mesh_with_degenerates, write_matrix, write_x3p

from asperity.errors import InputError, TextureFileError
from asperity.surface.detrend import detrend
from asperity.surface.readers import read_surface
from asperity.surface.readers.x3p import read_x3p
from asperity.surface.topography import HeightMap, TriangleMesh

DATA = Path(__file__).parents[2] / "shared" / "data" / "surfaces"
needs_data = pytest.mark.skipif(
    not DATA.is_dir(), reason=f"measured surfaces not found in {DATA} (../shared/data/surfaces/)")

try:
    import SurfaceTopography  # noqa: F401
    HAVE_ST = True
except ImportError:
    HAVE_ST = False
needs_st = pytest.mark.skipif(not HAVE_ST, reason="SurfaceTopography (metrology extra) missing")


def _slopes(hm: HeightMap):
    """Forward-difference slopes over cells whose pixels are all defined."""
    z = hm.heights
    gx = (np.diff(z, axis=0)[:, :-1]) / hm.dx
    gy = (np.diff(z, axis=1)[:-1, :]) / hm.dy
    ok = np.isfinite(gx) & np.isfinite(gy)
    return gx[ok], gy[ok]


def _lay_angle(hm: HeightMap) -> float:
    """Direction (deg from +x, mod 180) of the smaller principal axis of sum(g g^T):
    the direction along which the heights vary least, the lay."""
    gx, gy = _slopes(hm)
    t = np.array([[gx @ gx, gx @ gy], [gx @ gy, gy @ gy]])
    w, v = np.linalg.eigh(t)
    return float(np.degrees(np.arctan2(v[1, 0], v[0, 0])) % 180.0)


def _skew(a):
    a = a - a.mean()
    return float(np.mean(a ** 3) / np.mean(a ** 2) ** 1.5)


def _hide_surfacetopography(monkeypatch):
    for name in list(sys.modules):
        if name == "SurfaceTopography" or name.startswith("SurfaceTopography."):
            monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)   # import now fails


# --- .npy / .npz -----------------------------------------------------------------------------

@pytest.mark.parametrize("unit,factor", [("m", 1.0), ("mm", 1e-3), ("um", 1e-6), ("µm", 1e-6),
                                         ("micrometre", 1e-6), ("nm", 1e-9)])
def test_npy_round_trip_and_units(tmp_path, unit, factor):
    z = np.random.default_rng(1).normal(size=(7, 5))
    p = tmp_path / "z.npy"
    np.save(p, z)
    hm = read_surface(p, unit=unit, pixel_size=0.5)
    assert isinstance(hm, HeightMap)
    assert hm.heights.shape == (7, 5) and (hm.nx, hm.ny) == (7, 5)
    np.testing.assert_allclose(hm.heights, z * factor, rtol=1e-15)
    assert hm.dx == pytest.approx(0.5 * factor) and hm.dy == pytest.approx(0.5 * factor)
    assert hm.physical_size == pytest.approx((3.5 * factor, 2.5 * factor))
    assert hm.n_undefined == 0 and hm.source == "z.npy"


def test_npy_pixel_pair_height_scale_and_gz(tmp_path):
    z = np.arange(12.0).reshape(3, 4)
    p = tmp_path / "z.npy"
    np.save(p, z)
    hm = read_surface(gz_copy(p), unit="um", pixel_size=(2, 3), height_scale=10)
    np.testing.assert_allclose(hm.heights, z * 1e-5)
    assert (hm.dx, hm.dy) == pytest.approx((2e-6, 3e-6))


def test_npy_undefined_pixels_counted(tmp_path):
    z = np.ones((4, 4))
    z[1, 2] = z[3, 0] = np.nan
    np.save(tmp_path / "z.npy", z)
    hm = read_surface(tmp_path / "z.npy", unit="m", pixel_size=1)
    assert hm.n_undefined == 2 and np.isnan(hm.heights[1, 2])
    mask = np.zeros((4, 4), bool)
    mask[0, 0] = True
    np.savez(tmp_path / "m.npz", heights=np.ones((4, 4)), mask=mask)
    hm = read_surface(tmp_path / "m.npz", unit="m", pixel_size=1)
    assert hm.n_undefined == 1 and np.isnan(hm.heights[0, 0])


def test_npy_requires_unit_and_pixel_size(tmp_path):
    np.save(tmp_path / "z.npy", np.zeros((3, 3)))
    with pytest.raises(InputError, match=r"z\.npy.*pass unit"):
        read_surface(tmp_path / "z.npy", pixel_size=1)
    with pytest.raises(InputError, match=r"z\.npy.*pass pixel_size"):
        read_surface(tmp_path / "z.npy", unit="um")


@pytest.mark.parametrize("kw,msg", [
    (dict(unit="furlong", pixel_size=1), r"unit must be one of m, mm, um"),
    (dict(unit="um", pixel_size=0), r"pixel_size must be in \(0, inf\)"),
    (dict(unit="um", pixel_size=-2), r"pixel_size must be in"),
    (dict(unit="um", pixel_size=(1, 0)), r"pixel_size \(dy\)"),
    (dict(unit="um", pixel_size=(1, 2, 3)), r"number or a pair"),
    (dict(unit="um", pixel_size="big"), r"number or a pair"),
    (dict(unit="um", pixel_size=1, height_scale=0), r"height_scale"),
])
def test_bad_arguments_are_one_line_input_errors(tmp_path, kw, msg):
    np.save(tmp_path / "z.npy", np.zeros((3, 3)))
    with pytest.raises(InputError, match=msg) as ei:
        read_surface(tmp_path / "z.npy", **kw)
    assert "\n" not in str(ei.value)


def test_missing_file_unknown_suffix_and_bad_content(tmp_path):
    with pytest.raises(InputError, match="nothere.npy.*does not exist"):
        read_surface(tmp_path / "nothere.npy", unit="m", pixel_size=1)
    (tmp_path / "g.abc").write_bytes(b"\x01\x02\x03" * 7)
    with pytest.raises(InputError, match=r"g\.abc.*supported: \.stl"):
        read_surface(tmp_path / "g.abc")
    (tmp_path / "bad.npy").write_bytes(b"not numpy")
    with pytest.raises(TextureFileError, match=r"bad\.npy"):
        read_surface(tmp_path / "bad.npy", unit="m", pixel_size=1)
    (tmp_path / "bad.txt.gz").write_bytes(b"not gzip")
    with pytest.raises(TextureFileError, match=r"bad\.txt\.gz.*gzip"):
        read_surface(tmp_path / "bad.txt.gz", unit="m", pixel_size=1)
    np.save(tmp_path / "inf.npy", np.array([[1.0, np.inf], [0, 0]]))
    with pytest.raises(TextureFileError, match="infinite"):
        read_surface(tmp_path / "inf.npy", unit="m", pixel_size=1)


# --- text matrices --------------------------------------------------------------------------


def test_text_without_header_needs_unit_and_pixel_size(tmp_path):
    m = np.random.default_rng(2).normal(size=(3, 5))       # 3 lines (y) of 5 values (x)
    write_matrix(tmp_path / "a.txt", m)
    hm = read_surface(tmp_path / "a.txt", unit="nm", pixel_size=(4, 2))
    assert hm.heights.shape == (5, 3)                      # (nx, ny)
    np.testing.assert_allclose(hm.heights, m.T * 1e-9)
    assert (hm.dx, hm.dy) == pytest.approx((4e-9, 2e-9))
    with pytest.raises(InputError, match=r"a\.txt.*no height unit.*--unit"):
        read_surface(tmp_path / "a.txt", pixel_size=1)
    with pytest.raises(InputError, match=r"a\.txt.*no pixel size"):
        read_surface(tmp_path / "a.txt", unit="nm")
    # csv with commas, nan, and gzip give the same
    m2 = m.copy()
    m2[1, 1] = np.nan
    write_matrix(tmp_path / "b.csv", m2, sep=",")
    hm2 = read_surface(gz_copy(tmp_path / "b.csv"), unit="nm", pixel_size=(4, 2))
    assert hm2.n_undefined == 1 and np.isnan(hm2.heights[1, 1])
    np.testing.assert_allclose(hm2.heights[~np.isnan(hm2.heights)], (m2.T * 1e-9)[~np.isnan(m2.T)])


def test_text_gwyddion_header(tmp_path):
    m = np.arange(20.0).reshape(4, 5)                       # ny = 4, nx = 5
    hdr = "# Channel: Height\n# Width: 10.00 µm\n# Height: 2.00 µm\n# Value units: nm\n"
    write_matrix(tmp_path / "g.txt", m, hdr, sep="\t")
    hm = read_surface(tmp_path / "g.txt")
    np.testing.assert_allclose(hm.heights, m.T * 1e-9)
    assert hm.dx == pytest.approx(10e-6 / 5) and hm.dy == pytest.approx(2e-6 / 4)
    assert hm.physical_size == pytest.approx((10e-6, 2e-6))
    # explicit arguments override the header
    hm = read_surface(tmp_path / "g.txt", unit="um", pixel_size=1)
    np.testing.assert_allclose(hm.heights, m.T * 1e-6)
    assert (hm.dx, hm.dy) == pytest.approx((1e-6, 1e-6))
    # a value unit that is not a length
    write_matrix(tmp_path / "v.txt", m, "# Width: 1 um\n# Height: 1 um\n# Value units: V\n")
    with pytest.raises(InputError, match=r"v\.txt.*'V', not a length"):
        read_surface(tmp_path / "v.txt")
    assert read_surface(tmp_path / "v.txt", unit="nm").dx == pytest.approx(0.2e-6)
    # an unknown length unit in the header
    write_matrix(tmp_path / "u.txt", m, "# Width: 1 furlong\n# Height: 1 um\n# Value units: m\n")
    with pytest.raises(TextureFileError, match=r"u\.txt.*'width' has unit 'furlong'"):
        read_surface(tmp_path / "u.txt")


def test_text_key_value_header(tmp_path):
    m = np.random.default_rng(3).normal(size=(6, 3))       # h = 6 lines, w = 3 columns
    hdr = ("h=6 w=3\npixel size=3.69862e-007 m\ndata unit=rad\n"
           "height conversion factor (-> m)=2.91818e-008\n")
    write_matrix(tmp_path / "k.txt", m, hdr)
    hm = read_surface(tmp_path / "k.txt")
    assert hm.heights.shape == (3, 6)
    np.testing.assert_allclose(hm.heights, m.T * 2.91818e-8)
    assert hm.dx == hm.dy == pytest.approx(3.69862e-7)
    write_matrix(tmp_path / "bad.txt", m, hdr.replace("w=3", "w=4"))
    with pytest.raises(TextureFileError, match=r"bad\.txt.*w=4 but the matrix has 3 columns"):
        read_surface(tmp_path / "bad.txt")


@pytest.mark.parametrize("body,msg", [
    ("1 2 3\n4 5\n", r"line 2 has 2 values, the matrix rows above have 3"),
    ("1 2 3\n4 x 6\n", r"line 2: 'x' in the matrix is not a number"),
    ("1 2\n3 inf\n", r"infinite"),
    ("# Width: 1 um\n", r"no matrix of numbers"),
    ("", r"no matrix of numbers"),
])
def test_malformed_text_matrix(tmp_path, body, msg):
    (tmp_path / "m.txt").write_text(body)
    with pytest.raises(TextureFileError, match=r"m\.txt.*" + msg) as ei:
        read_surface(tmp_path / "m.txt", unit="m", pixel_size=1)
    assert "\n" not in str(ei.value)


def test_binary_data_in_a_text_suffix(tmp_path):
    (tmp_path / "b.dat").write_bytes(b"\x00\x01\x02" * 100)
    with pytest.raises(TextureFileError, match=r"b\.dat.*binary"):
        read_surface(tmp_path / "b.dat", unit="m", pixel_size=1)


# --- meshes ---------------------------------------------------------------------------------


@pytest.mark.parametrize("file_type,suffix", [("stl", ".stl"), ("stl_ascii", ".stl"),
                                              ("obj", ".obj"), ("ply", ".ply")])
def test_mesh_round_trip_drops_degenerate_triangles(tmp_path, file_type, suffix):
    import trimesh
    v, f = mesh_with_degenerates()
    data = trimesh.Trimesh(v, f, process=False).export(file_type=file_type)
    p = tmp_path / ("m" + suffix)
    p.write_bytes(data.encode() if isinstance(data, str) else data)
    for path in (p, gz_copy(p)):
        mesh = read_surface(path, unit="mm")
        assert isinstance(mesh, TriangleMesh)
        assert mesh.n_degenerate == 2 and mesh.faces.shape == (3, 3)
        assert mesh.faces.dtype == np.int64 and mesh.vertices.dtype == np.float64
        np.testing.assert_array_equal(mesh.kept_faces, [0, 1, 4])
        assert mesh.vertices.shape == (5, 3)                # merged, unused vertex 5 dropped
        tri = mesh.vertices[mesh.faces]
        np.testing.assert_allclose(tri, v[f[[0, 1, 4]]] * 1e-3)
    scaled = read_surface(p, unit="um", height_scale=3)
    np.testing.assert_allclose(scaled.vertices[:, 2].max(), 3e-6)


def test_mesh_requires_unit(tmp_path):
    import trimesh
    v, f = mesh_with_degenerates()
    (tmp_path / "m.stl").write_bytes(trimesh.Trimesh(v, f, process=False).export(file_type="stl"))
    with pytest.raises(InputError, match=r"m\.stl.*no length unit; pass unit.*--unit"):
        read_surface(tmp_path / "m.stl")
    with pytest.raises(InputError, match="pixel_size applies to height maps"):
        read_surface(tmp_path / "m.stl", unit="mm", pixel_size=1)
    (tmp_path / "bad.ply").write_bytes(b"ply\nformat nonsense\n")
    with pytest.raises(TextureFileError, match=r"bad\.ply"):
        read_surface(tmp_path / "bad.ply", unit="mm")


# --- x3p ------------------------------------------------------------------------------------


def test_builtin_x3p_int16_with_empty_offset_and_valid_mask(tmp_path):
    raw = np.arange(-6, 6, dtype=np.int16).reshape(4, 3)
    valid = np.ones((4, 3), bool)
    valid[2, 1] = False
    p = tmp_path / "i.x3p"
    write_x3p(p, raw, "I", inc="2e-9", off="<Offset/>", valid=valid)
    for hm in (read_x3p(p), read_surface(p), read_surface(gz_copy(p))):
        assert hm.heights.shape == (4, 3) and (hm.dx, hm.dy) == pytest.approx((1e-6, 2e-6))
        assert hm.n_undefined == 1 and np.isnan(hm.heights[2, 1])
        expect = raw * 2e-9
        np.testing.assert_allclose(hm.heights[valid], expect[valid])


def test_builtin_x3p_float_offset_nan_and_inf(tmp_path):
    raw = np.random.default_rng(6).normal(size=(5, 4)) * 1e-6
    raw[0, 3], raw[4, 0] = np.nan, np.inf
    write_x3p(tmp_path / "f.x3p", raw, "D", inc=None, off="<Offset>1e-6</Offset>")
    hm = read_x3p(tmp_path / "f.x3p")
    assert hm.n_undefined == 2
    ok = np.isfinite(raw)
    np.testing.assert_allclose(hm.heights[ok], raw[ok] + 1e-6)
    um = read_surface(tmp_path / "f.x3p", unit="um")     # a file written in micrometres
    np.testing.assert_allclose(um.heights[ok], (raw[ok] + 1e-6) * 1e-6)
    assert (um.dx, um.dy) == pytest.approx((hm.dx * 1e-6, hm.dy * 1e-6))
    with pytest.raises(InputError, match="needs its unit: pass unit too"):
        read_surface(tmp_path / "f.x3p", pixel_size=0.5)


def test_builtin_x3p_errors(tmp_path):
    (tmp_path / "z.x3p").write_bytes(b"not a zip")
    with pytest.raises(TextureFileError, match=r"z\.x3p.*zip"):
        read_x3p(tmp_path / "z.x3p")
    p = tmp_path / "short.x3p"
    write_x3p(p, np.zeros((3, 3)), "F")
    buf = io.BytesIO()
    with zipfile.ZipFile(p) as src, zipfile.ZipFile(buf, "w") as dst:
        for n in src.namelist():
            dst.writestr(n, src.read(n)[:-4] if n == "bindata/data.bin" else src.read(n))
    p.write_bytes(buf.getvalue())
    with pytest.raises(TextureFileError, match=r"short\.x3p.*holds 32 bytes.*need 36"):
        read_x3p(p)


@needs_st
def test_builtin_x3p_agrees_with_surfacetopography_writer(tmp_path):
    from SurfaceTopography import Topography, read_topography
    z = np.random.default_rng(7).normal(size=(9, 6)) * 1e-7
    mask = np.zeros_like(z, bool)
    mask[1, 4] = mask[7, 0] = True
    t = Topography(np.ma.masked_array(z, mask), physical_sizes=(9e-6, 12e-6), unit="m")
    for dtype in ("I", "L", "F", "D"):
        p = tmp_path / f"st_{dtype}.x3p"
        t.to_x3p(str(p), dtype=dtype)
        ours = read_x3p(p)
        theirs = np.ma.filled(read_topography(str(p)).heights().astype(float), np.nan)
        assert ours.n_undefined == 2
        np.testing.assert_array_equal(np.isnan(ours.heights), np.isnan(theirs))
        np.testing.assert_allclose(ours.heights, theirs, rtol=1e-12, atol=1e-20)
        assert (ours.dx, ours.dy) == pytest.approx((1e-6, 2e-6))


def test_without_surfacetopography(tmp_path, monkeypatch):
    _hide_surfacetopography(monkeypatch)
    (tmp_path / "scan.mi").write_bytes(b"fileType Image\n")
    with pytest.raises(InputError, match=r"scan\.mi: reading \.mi files needs the metrology "
                                         r"extra: pip install 'asperity\[metrology\]'"):
        read_surface(tmp_path / "scan.mi")
    (tmp_path / "scan.xyz1").write_bytes(b"?")
    with pytest.raises(InputError, match=r"unknown surface file suffix '\.xyz1'.*metrology"):
        read_surface(tmp_path / "scan.xyz1")
    write_x3p(tmp_path / "a.x3p", np.ones((3, 2)), "F")
    hm = read_surface(tmp_path / "a.x3p")                      # the built-in reader
    np.testing.assert_allclose(hm.heights, np.full((3, 2), 1e-6))


def test_import_stays_light():
    code = ("import sys, asperity, asperity.surface.readers; "
            "print(sorted(m for m in ('trimesh', 'SurfaceTopography', 'xml.etree.ElementTree')"
            " if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


# --- the measured files ---------------------------------------------------------------------

@needs_data
def test_ski_x3p_size_undefined_slopes_and_lay():
    hm = read_surface(DATA / "SkiInfiniteFocus.x3p")
    assert (hm.nx, hm.ny) == (1197, 940)
    assert hm.physical_size == pytest.approx((4.40e-3, 3.46e-3), rel=2e-3)
    assert hm.n_undefined == 4272                  # stored as +inf by the instrument: 0.38 %
    hm = detrend(hm, 1)
    gx, gy = _slopes(hm)
    assert np.sqrt(np.mean(gx ** 2)) == pytest.approx(0.214, abs=0.005)
    assert np.sqrt(np.mean(gy ** 2)) == pytest.approx(0.287, abs=0.005)
    # The grind grooves run at 30.5 deg from +x in the file's own frame (x the fastest
    # axis of data.bin, y the second): the README's "~120 deg" is the across-groove
    # direction, 90 deg off; its rms slopes (0.21 x < 0.29 y) agree with a lay at 30 deg.
    assert _lay_angle(hm) == pytest.approx(30.5, abs=2.0)


@needs_data
def test_ski_builtin_reader_agrees_with_surfacetopography(monkeypatch):
    builtin = read_x3p(DATA / "SkiInfiniteFocus.x3p")
    if HAVE_ST:
        st = read_surface(DATA / "SkiInfiniteFocus.x3p")
        np.testing.assert_array_equal(np.isnan(builtin.heights), np.isnan(st.heights))
        np.testing.assert_array_equal(np.nan_to_num(builtin.heights), np.nan_to_num(st.heights))
        assert (builtin.dx, builtin.dy) == (st.dx, st.dy) and builtin.n_undefined == st.n_undefined
    _hide_surfacetopography(monkeypatch)
    fallback = read_surface(DATA / "SkiInfiniteFocus.x3p")
    np.testing.assert_array_equal(np.nan_to_num(fallback.heights), np.nan_to_num(builtin.heights))


@needs_data
@needs_st
def test_mi_first_height_channel_and_sawtooth_asymmetry():
    hm = read_surface(DATA / "mi-1.mi")
    assert "channel 'Topography', 1 of 4" in hm.source
    assert (hm.nx, hm.ny) == (256, 256)
    assert hm.physical_size == pytest.approx((20e-6, 20e-6))
    assert hm.n_undefined == 0
    hm = detrend(hm, 1)
    gx, gy = _slopes(hm)
    assert np.sqrt(np.mean(gx ** 2)) == pytest.approx(0.0095, abs=0.001)   # nm relief
    # steep rises, gentle falls along +x: strongly positive skewness of dz/dx
    assert _skew(gx) == pytest.approx(2.71, abs=0.1)
    assert 1e-9 < np.std(hm.heights) < 1e-7


@needs_data
def test_matrix3_gwyddion_header():
    hm = read_surface(DATA / "matrix-3.txt")
    assert (hm.nx, hm.ny) == (256, 256)
    assert hm.physical_size == pytest.approx((10e-6, 10e-6))
    assert hm.dx == pytest.approx(10e-6 / 256)
    gx, gy = _slopes(hm)
    rx, ry = np.sqrt(np.mean(gx ** 2)), np.sqrt(np.mean(gy ** 2))
    assert rx == pytest.approx(0.133, abs=0.003) and ry == pytest.approx(0.139, abs=0.003)
    if HAVE_ST:
        from SurfaceTopography import read_topography
        t = read_topography(str(DATA / "matrix-3.txt"))
        np.testing.assert_allclose(hm.heights, t.heights(), rtol=1e-12)
        np.testing.assert_allclose((hm.dx, hm.dy), t.pixel_size, rtol=1e-12)


@needs_data
def test_matrix4_gz_key_value_header_grooves_along_y():
    hm = read_surface(DATA / "matrix-4.txt.gz")
    assert (hm.nx, hm.ny) == (75, 305)
    assert hm.physical_size == pytest.approx((27.74e-6, 112.81e-6), rel=1e-3)
    hm = detrend(hm, 1)
    gx, gy = _slopes(hm)
    rx, ry = np.sqrt(np.mean(gx ** 2)), np.sqrt(np.mean(gy ** 2))
    assert rx == pytest.approx(0.059, abs=0.002) and ry == pytest.approx(0.033, abs=0.002)
    assert rx > 1.5 * ry                              # grooves along y: slopes mostly along x
    assert _lay_angle(hm) == pytest.approx(90.0, abs=3.0)


@needs_data
def test_example_stl_gz_mesh():
    mesh = read_surface(DATA / "example_surface.stl.gz", unit="mm")
    assert mesh.n_degenerate == 0
    assert mesh.faces.shape == (16672 - mesh.n_degenerate, 3)
    assert mesh.vertices.shape == (8599, 3)
    span = mesh.vertices.max(axis=0) - mesh.vertices.min(axis=0)
    assert span[:2] == pytest.approx((21.7e-3, 27.6e-3), rel=2e-3)
    with pytest.raises(InputError, match="--unit"):
        read_surface(DATA / "example_surface.stl.gz")


# --- the registry ----------------------------------------------------------------------------

def _registry_samples(tmp_path) -> dict:
    """One sample file per reader of the registry, with the options it needs."""
    import trimesh
    v, f = mesh_with_degenerates()
    mesh = tmp_path / "m.stl"
    mesh.write_bytes(trimesh.Trimesh(v, f, process=False).export(file_type="stl"))
    z = np.random.default_rng(3).normal(size=(6, 4))
    np.save(tmp_path / "h.npy", z)
    write_matrix(tmp_path / "h.txt", z.T)
    write_x3p(tmp_path / "h.x3p", z, "D")
    return {"mesh": (mesh, dict(unit="mm"), TriangleMesh),
            "array": (tmp_path / "h.npy", dict(unit="um", pixel_size=1.0), HeightMap),
            "text": (tmp_path / "h.txt", dict(unit="um", pixel_size=1.0), HeightMap),
            "x3p": (tmp_path / "h.x3p", {}, HeightMap),
            "instrument": (DATA / "mi-1.mi", {}, HeightMap)}


@needs_data
@needs_st
def test_every_reader_of_the_registry_reads_its_sample(tmp_path):
    """The contract of the ordered registry: each reader claims its sample's suffix (also
    gzipped), and read_surface returns the kind of surface the reader promises."""
    from asperity.surface.readers import READERS, reader_for
    samples = _registry_samples(tmp_path)
    assert set(samples) == {r.name for r in READERS}, "a reader without a sample"
    assert not READERS[-1].suffixes, "the last reader is the catch-all"
    for name, (path, opts, kind) in samples.items():
        reader, suffix, gz = reader_for(path)
        assert reader.name == name and not gz, path
        assert reader_for(str(path) + ".gz")[0].name == name
        assert all(not r.can_read(suffix) for r in READERS[:READERS.index(reader)])
        assert isinstance(read_surface(path, **opts), kind), name


def test_x3p_written_in_micrometres_is_read_with_the_unit_given(tmp_path):
    """An x3p whose numbers are micrometres (the standard has metres: a pixel of 2 "m") is
    refused with the way forward, and read with unit (and pixel_size) given, whole and
    streamed in tiles alike."""
    from asperity.friction.derive import derive
    from asperity.friction.tiled import derive_scan
    from asperity.surface.facets import load_surface
    x = np.arange(40.0)
    raw = np.add.outer(0.4 * (x % 8) - 0.05 * (x % 8) ** 2, 0.01 * np.arange(30.0))  # um
    p = tmp_path / "um.x3p"
    write_x3p(p, raw, "D", inc=None, dx=2.0, dy=2.0)
    with pytest.raises(TextureFileError, match=r"states a pixel size dx of 2 m, outside "
                       r"\[1e-12, 1\] m: if its numbers are not in metres, pass unit"):
        read_surface(p)
    hm = read_surface(p, unit="um")
    assert (hm.dx, hm.dy) == pytest.approx((2e-6, 2e-6), rel=1e-15)
    np.testing.assert_allclose(hm.heights, raw * 1e-6, rtol=1e-15)
    hm = read_surface(p, unit="um", pixel_size=(0.5, 0.25))
    assert (hm.dx, hm.dy) == pytest.approx((0.5e-6, 0.25e-6), rel=1e-15)
    for kw in ({"unit": "um"}, {"unit": "um", "pixel_size": 0.5}):
        whole = derive(load_surface(p, **kw), n_directions=8)
        tiled = derive_scan(p, **kw, n_directions=8, tile_lines=7)
        np.testing.assert_allclose(tiled.reservoir.p, whole.reservoir.p, rtol=1e-12,
                                   atol=1e-15)
