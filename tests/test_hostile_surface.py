"""Hostile input to the surface room (issue 11, classes 2 to 7): surface files and flags
from every corner, refused in one line (exit 1, nothing on stdout, an existing output file
untouched) or read correctly; x3p files as ISO 5436-2 allows them; sizes in headers
checked against the memory before anything is expanded; Ctrl-C during a long facet
computation; the public API of the surface room raising one-line InputErrors."""
from __future__ import annotations

import gzip
import io
import json
import os
from pathlib import Path

import numpy as np
import pytest
from cli_run import run
from hostile import assert_finite_output, assert_refused, cli, interrupt, limit_memory
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from x3p_files import main_xml, x3p_bytes, zeros_member

import asperity as A
from asperity.errors import InputError, ResourceError
from asperity.surface import facets as F
from asperity.surface.readers import read_surface
from asperity.surface.readers import _files
from asperity.surface.topography import HeightMap, TriangleMesh

DATA = Path(__file__).parents[2] / "shared" / "data" / "surfaces"
try:
    import SurfaceTopography  # noqa: F401
    HAVE_ST = True
except ImportError:
    HAVE_ST = False
needs_st = pytest.mark.skipif(not HAVE_ST, reason="SurfaceTopography (metrology extra) missing")

Z = np.random.default_rng(11).normal(size=(24, 20))
BASE = ["--unit", "um", "--pixel-size", "1"]


@pytest.fixture()
def zmap(tmp_path):
    p = tmp_path / "z.npy"
    np.save(p, Z)
    return p


def _one_line(exc) -> str:
    msg = str(exc)
    assert msg and "\n" not in msg, msg
    return msg


# ----------------------------------------------------------------------------- class 2: numbers

#: flags with numbers no surface has (appended to z.npy --unit um --pixel-size 1)
EXTREME_FLAGS = [
    (["--pixel-size", "1e-300"], "--pixel-size must be in [1e-12, 1] m, got 1e-306 m"),
    (["--pixel-size", "1e300"], "--pixel-size must be in [1e-12, 1] m"),
    (["--pixel-size", "0"], "--pixel-size must be in (0, inf)"),
    (["--pixel-size=-1"], "--pixel-size must be in (0, inf)"),
    (["--pixel-size", "nan"], "--pixel-size must be in"),
    (["--pixel-size", "inf"], "--pixel-size must be a finite number"),
    (["--pixel-size", "1", "5e-324"], "--pixel-size (dy) must be in"),
    (["--pixel-size", "1", "2", "3"], "--pixel-size takes one value or two"),
    (["--pixel-size", "1e-7", "--unit", "nm"], "--pixel-size must be in [1e-12, 1] m"),
    (["--height-scale", "1e308"], "--height-scale must be in [1e-06, 1e+06], got 1e+308"),
    (["--height-scale", "0"], "--height-scale must be in"),
    (["--height-scale", "5e-324"], "--height-scale must be in"),
    (["--height-scale=-1"], "--height-scale must be in"),
    (["--height-scale", "nan"], "--height-scale must be in"),
    (["--height-scale", "inf"], "--height-scale must be a finite number"),
    (["--height-scale", "1e6", "--unit", "mm"], "heights must lie within +-1000 m"),
    (["--unit", "km"], "--unit must be one of m, mm, um (µm), nm, got 'km'"),
    (["--unit", ""], "--unit must be one of"),
    (["--unit", "1e-6"], "--unit must be one of"),
    (["--unit", "um\x00"], "--unit must be one of"),
    (["--mu", "nan"], "--mu must be in [0, 100]"),
    (["--mu", "1e300"], "--mu must be in [0, 100]"),
    (["--mu=-0.1"], "--mu must be in [0, 100]"),
    (["--rest-level", "nan"], "--rest-level must be in [-1000, 1000] m"),
    (["--rest-level", "1e300"], "--rest-level must be in [-1000, 1000] m"),
    (["--rest-level", "1"], "lies above the highest facet"),
    (["--bearing-fraction", "0"], "--bearing-fraction must be in (0, 1]"),
    (["--bearing-fraction", "inf"], "--bearing-fraction must be a finite number"),
    (["--directions", "7"], "directions must be a whole number in [8, 100000]"),
    (["--directions", "1000000"], "directions must be a whole number in [8, 100000]"),
]
#: the edges of the ranges: accepted, with a finite result
EXTREME_ACCEPTED = [
    ["--height-scale", "1e6"], ["--height-scale", "1e-6"], ["--pixel-size", "1e-6"],
    ["--pixel-size", "1e6"], ["--mu", "0"], ["--mu", "100"], ["--bearing-fraction", "1e-9"],
    ["--rest-level", "-1000"], ["--contact", "windward", "--height-scale", "1e6"],
]


@pytest.mark.parametrize("flags,msg", EXTREME_FLAGS)
def test_extreme_numbers_refused_in_one_line(capsys, zmap, flags, msg):
    code, out, err = run(capsys, "derive", zmap, *BASE, *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


@pytest.mark.parametrize("flags", EXTREME_ACCEPTED)
def test_range_edges_give_finite_results(capsys, zmap, flags):
    code, out, err = run(capsys, "derive", zmap, *BASE, *flags, "--directions", "16", "--json")
    assert code == 0 and err == "", err
    assert_finite_output(out.replace(zmap.name, ""))
    d = json.loads(out)
    assert all(x["self_locking"] or np.isfinite(x["tangential"]) for x in d["directions"])


def test_no_runtime_warning_reaches_the_terminal(tmp_path):
    p = tmp_path / "nan.npy"
    z = np.full((6, 5), np.nan)
    np.save(p, z)
    assert_refused(cli("derive", p, *BASE), contains="every pixel is undefined")
    z[1:3, 1:3] = 0.0
    np.save(p, z)
    status, out, err = cli("derive", p, *BASE, "--contact", "windward", "--json")
    assert status == 0 and err == "", err


# ----------------------------------------------------------------------------- class 3: content

def _bad_files(tmp_path: Path) -> dict:
    """name -> (file, extra flags, words of the message)."""
    rng = np.random.default_rng(3)
    out = {}

    def put(name, data, flags=(), msg=""):
        p = tmp_path / name
        if isinstance(data, bytes):
            p.write_bytes(data)
        else:
            data(p)
        out[name] = (p, list(flags), msg)
    noise = rng.bytes(2 * 50 * 50)          # a valid headerless .hgt grid, by its size
    put("noise.mi", noise, BASE, "not a surface file")
    put("noise.sur", noise, BASE, "not a surface file")
    put("noise.opd", noise, (), "")
    put("noise.npy", noise, BASE, "not a surface file")
    put("noise.npz", noise, BASE, "not a .npz archive")
    put("noise.x3p", noise, (), "not an x3p file")
    put("noise.txt", noise, BASE, "binary file")
    put("noise.stl", noise, ["--unit", "mm"], "")
    put("noise.npy.gz", noise, BASE, "not a valid gzip file")
    put("noise.xyz1", noise, BASE, "unknown surface file")
    put("empty.npy", b"", BASE, "not a surface file")
    put("empty.x3p", b"", (), "not an x3p file")
    put("empty.txt", b"", BASE, "no matrix of numbers")
    put("prose.txt", b"This is a letter,\nnot a matrix of heights.\n", BASE, "no matrix")
    put("column.txt", b"1\n2\n3\n4\n", BASE, "at least 2 x 2 pixels")
    put("inf.txt", b"1 2\ninf 3\n", BASE, "infinite")
    put("ragged.txt", b"1 2 3\n4 5\n", BASE, "line 2 has 2 values")
    put("bool.npy", lambda p: np.save(p, np.ones((4, 4), bool)), BASE, "booleans")
    put("complex.npy", lambda p: np.save(p, np.ones((4, 4), complex)), BASE, "real numbers")
    put("object.npy", lambda p: np.save(p, np.array([[1, "a"]], dtype=object)), BASE,
        "real numbers")
    put("vector.npy", lambda p: np.save(p, np.ones(9)), BASE, "must be a 2-D array")
    put("cube.npy", lambda p: np.save(p, np.ones((3, 3, 3))), BASE, "must be a 2-D array")
    put("inf.npy", lambda p: np.save(p, np.array([[1.0, np.inf], [0, 0]])), BASE, "infinite")
    put("huge.npy", lambda p: np.save(p, np.full((3, 3), 1e300)), BASE, "within +-1000 m")
    put("two.npz", lambda p: np.savez(p, a=Z, b=Z), BASE, "needs an array named 'heights'")
    put("mask.npz", lambda p: np.savez(p, heights=Z, mask=np.ones(3, bool)), BASE, "'mask'")
    put("short.npy", lambda p: p.write_bytes(_npy(Z)[:-8]), BASE, "its shape (24, 20) needs")
    (tmp_path / "folder.npy").mkdir()
    out["folder.npy"] = (tmp_path / "folder.npy", BASE, "is a folder")
    os.mkfifo(tmp_path / "fifo.npy")
    out["fifo.npy"] = (tmp_path / "fifo.npy", BASE, "not a regular file")
    out["missing.npy"] = (tmp_path / "missing.npy", BASE, "does not exist")
    return out


def _npy(a) -> bytes:
    b = io.BytesIO()
    np.save(b, a)
    return b.getvalue()


BAD_CONTENT = ["noise.mi", "noise.sur", "noise.opd", "noise.npy", "noise.npz", "noise.x3p",
               "noise.txt", "noise.stl", "noise.npy.gz", "noise.xyz1", "empty.npy", "empty.x3p",
               "empty.txt", "prose.txt", "column.txt", "inf.txt", "ragged.txt", "bool.npy",
               "complex.npy", "object.npy", "vector.npy", "cube.npy", "inf.npy", "huge.npy",
               "two.npz", "mask.npz", "short.npy", "folder.npy", "fifo.npy", "missing.npy"]


@pytest.mark.parametrize("name", BAD_CONTENT)
def test_content_that_is_not_a_surface_is_refused(capsys, tmp_path, name):
    if name.startswith("noise.") and name[6:] in ("mi", "sur", "opd", "xyz1") and not HAVE_ST:
        pytest.skip("instrument formats need SurfaceTopography")
    path, flags, msg = _bad_files(tmp_path)[name]
    plot = tmp_path / "old.png"
    plot.write_bytes(b"an older figure")
    code, out, err = run(capsys, "derive", path, *flags, "--plot", plot)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err
    assert "Traceback" not in err and str(path.name) in err
    assert plot.read_bytes() == b"an older figure"


def test_fit_keeps_an_existing_gauge_when_the_surface_is_refused(capsys, tmp_path):
    gauge = tmp_path / "old.json"
    gauge.write_text('{"an": "older gauge"}')
    bad = tmp_path / "bad.npy"
    np.save(bad, np.ones((4, 4), bool))
    for flags in (["--height-scale", "1e308"], []):
        code, out, err = run(capsys, "fit", bad, *BASE, *flags, "-o", gauge)
        assert code == 1 and out == "" and err.count("\n") == 1, err
    assert gauge.read_text() == '{"an": "older gauge"}'


def test_random_instrument_file_through_the_real_command(tmp_path):
    if not HAVE_ST:
        pytest.skip("instrument formats need SurfaceTopography")
    p = tmp_path / "scan.mi"
    p.write_bytes(np.random.default_rng(5).bytes(2 * 64 * 64))
    assert_refused(cli("derive", p, *BASE), contains=["scan.mi", "not a surface file"])


#: every suffix a reader claims (and a gzipped one of each kind)
SUFFIXES = [".npy", ".npz", ".txt", ".csv", ".dat", ".asc", ".x3p", ".stl", ".obj", ".ply",
            ".mi", ".sur", ".opd", ".datx", ".plu", ".nms", ".npy.gz", ".x3p.gz", ".txt.gz"]
_INSTRUMENT = {".mi", ".sur", ".opd", ".datx", ".plu", ".nms"}


@settings(max_examples=120, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(suffix=st.sampled_from(SUFFIXES), data=st.binary(min_size=0, max_size=3000),
       hgt=st.booleans())
def test_random_bytes_with_every_suffix(tmp_path, suffix, data, hgt):
    """Random bytes (or a square number of int16s, which a headerless format would take
    for a grid) are refused in one line, never read as heights from an instrument file."""
    if hgt:
        data = (data * 8)[:2 * 32 * 32].ljust(2 * 32 * 32, b"\x01")
    if suffix.endswith(".gz") and data[:1] != b"\x1f":
        data = gzip.compress(data)
    base = suffix.split(".")[1]
    if base in {s[1:] for s in _INSTRUMENT} and not HAVE_ST:
        return
    p = tmp_path / f"r{suffix}"
    p.write_bytes(data)
    kw = {}
    if base in ("npy", "npz", "txt", "csv", "dat", "asc") or f".{base}" in _INSTRUMENT:
        kw = dict(unit="um", pixel_size=1.0)
    elif base in ("stl", "obj", "ply"):
        kw = dict(unit="mm")
    try:
        s = read_surface(p, **kw)
    except InputError as exc:
        _one_line(exc)
        return
    # only text-like formats can hold what random bytes happen to spell as numbers
    assert base in ("txt", "csv", "dat", "asc", "obj", "ply", "stl"), (suffix, s)
    assert isinstance(s, (HeightMap, TriangleMesh))


# ----------------------------------------------------------------------------- class 7: x3p

_I, _J = np.meshgrid(np.arange(6), np.arange(5), indexing="ij")
ZX = np.random.default_rng(7).normal(size=(6, 5)) * 1e-6
RAW = np.random.default_rng(8).integers(-3000, 3000, size=(6, 5))
XA = 1e-3 + _I * 1.5e-6                 # absolute, regular
YA = -2e-3 + _J * 2.5e-6
MISSING = ZX.copy()
MISSING[2, 3] = np.nan
VALID = np.ones(ZX.shape, bool)
VALID[0, 4] = VALID[5, 0] = False

#: name -> (x3p_bytes arguments, expected heights [i, j] in m, (dx, dy) in m)
X3P_CONFORMING = {
    "binary D": (dict(z=ZX), ZX, (1e-6, 2e-6)),
    "binary F": (dict(z=ZX, code="F"), ZX.astype(np.float32), (1e-6, 2e-6)),
    "binary I with increment and offset": (dict(z=RAW, code="I", zinc=2e-9, zoff=1e-6),
                                           RAW * 2e-9 + 1e-6, (1e-6, 2e-6)),
    "binary L with increment": (dict(z=RAW * 1000, code="L", zinc=1e-12), RAW * 1e-9,
                                (1e-6, 2e-6)),
    "binary I, empty Increment element (1)": (dict(z=RAW // 10, code="I", zinc=""),
                                              RAW // 10 * 1.0, (1e-6, 2e-6)),
    "binary D with NaN": (dict(z=MISSING), MISSING, (1e-6, 2e-6)),
    "binary I with valid-points mask": (dict(z=RAW, code="I", zinc=1e-9, valid=VALID),
                                        np.where(VALID, RAW * 1e-9, np.nan), (1e-6, 2e-6)),
    "inline D": (dict(z=ZX, inline=True), ZX, (1e-6, 2e-6)),
    "inline D, empty Datum = missing": (dict(z=MISSING, inline=True), MISSING, (1e-6, 2e-6)),
    "inline I with increment and offset": (dict(z=RAW, code="I", inline=True, zinc=2e-9,
                                                zoff=-1e-6), RAW * 2e-9 - 1e-6, (1e-6, 2e-6)),
    "inline L": (dict(z=RAW, code="L", inline=True, zinc=1e-9), RAW * 1e-9, (1e-6, 2e-6)),
    "inline F": (dict(z=ZX, code="F", inline=True), ZX, (1e-6, 2e-6)),
    "absolute x and y, binary": (dict(z=ZX, x=XA, y=YA), ZX, (1.5e-6, 2.5e-6)),
    "absolute x and y, inline": (dict(z=ZX, x=XA, y=YA, inline=True), ZX, (1.5e-6, 2.5e-6)),
    "absolute x, decreasing": (dict(z=ZX, x=XA[::-1]), ZX[::-1], (1.5e-6, 2e-6)),
    "absolute y as int32 with increment": (dict(z=ZX, y=_J * 25 + 7, ycode="L", y_inc=1e-7),
                                           ZX, (1e-6, 2.5e-6)),
    "absolute x as float32": (dict(z=ZX, x=XA, xcode="F"), ZX, (1.5e-6, 2e-6)),
    "identity rotation": (dict(z=ZX, rotation=np.eye(3).tolist()), ZX, (1e-6, 2e-6)),
}
#: name -> (x3p_bytes arguments, words of the refusal)
X3P_REFUSED = {
    "profile PRF": (dict(feature="PRF"), "a profile x3p (PRF"),
    "point cloud PCL": (dict(feature="PCL"), "a point cloud x3p (PCL); asperity reads areal"),
    "unknown feature": (dict(feature="VOL"), "FeatureType 'VOL' is none of SUR"),
    "point list": (dict(list_dim=30), "an x3p point list (ListDimension"),
    "several layers": (dict(size_z=3), "a multi-layer x3p (3 layers"),
    "one line": (dict(z=ZX[:1]), "single line of points (1 x 5)"),
    "unknown DataType": (dict(members={"main.xml": main_xml(nx=6, ny=5, code="Q")}),
                         "CZ DataType 'Q' is unknown"),
    "incremental z": (dict(z_kind="I"), "CZ axis is incremental"),
    "absolute axis without DataType": (
        dict(members={"main.xml": main_xml(nx=6, ny=5, x_abs=(None, None, None))}),
        "CX is absolute and needs a DataType"),
    "irregular absolute x": (dict(x=XA + np.where(_J == 2, 4e-7, 0.0)),
                             "absolute x coordinates do not form a regular grid"),
    "absolute x along j": (dict(x=_J * 1e-6), "do not form a regular grid"),
    "rotated": (dict(rotation=[[0, 1, 0], [-1, 0, 0], [0, 0, 1]]), "a rotated x3p"),
    "no main.xml": (dict(members={"main.xml": None}), "no main.xml in the archive"),
    "main.xml not XML": (dict(members={"main.xml": b"<p:ISO5436_2"}), "not valid XML"),
    "main.xml other root": (dict(members={"main.xml": b"<html/>"}), "root element 'html'"),
    "main.xml with entities": (dict(members={"main.xml": b'<?xml version="1.0"?><!DOCTYPE a '
                                             b'[<!ENTITY x "xx">]><a>&x;</a>'}), "DOCTYPE"),
    "point data missing": (dict(members={"bindata/data.bin": None}), "missing from the archive"),
    "point data short": (dict(members={"bindata/data.bin": b"\0" * 200}),
                         "holds 200 bytes, 6 x 5 D values need 240"),
    "valid mask short": (dict(z=RAW, code="I", zinc=1e-9, valid=VALID,
                              members={"bindata/valid.bin": b"\xff"}), "holds 1 bytes"),
    "too few Datum": (dict(members={"main.xml": main_xml(nx=6, ny=5,
                                                         data="<Datum>1</Datum>" * 29)}),
                      "holds 29 Datum entries"),
    "too many Datum": (dict(members={"main.xml": main_xml(nx=6, ny=5,
                                                          data="<Datum>1</Datum>" * 31)}),
                       "more Datum entries"),
    "Datum not a number": (dict(members={"main.xml": main_xml(nx=6, ny=5,
                                                              data="<Datum>x</Datum>" * 30)}),
                           "Datum 1: 'x' is not a number"),
    "Datum with extra values": (dict(members={"main.xml": main_xml(
        nx=6, ny=5, data="<Datum>1;2</Datum>" * 30)}), "expected 1 value(s)"),
    "every point missing": (dict(members={"main.xml": main_xml(nx=6, ny=5,
                                                               data="<Datum/>" * 30)}),
                            "every pixel is undefined"),
    "increment not a number": (dict(zinc="abc"), "CZ Increment is not a number"),
    "metres of raw integers": (dict(z=RAW, code="I"), "heights must lie within +-1000 m"),
}


def _x3p(**kw) -> bytes:
    kw.setdefault("z", ZX)
    return x3p_bytes(kw.pop("z"), **kw)


@pytest.mark.parametrize("name", list(X3P_CONFORMING))
def test_x3p_areal_grids_the_standard_allows(tmp_path, name):
    kw, expect, (dx, dy) = X3P_CONFORMING[name]
    p = tmp_path / "s.x3p"
    p.write_bytes(_x3p(**kw))
    for path in (p, _gz(p)):
        hm = read_surface(path)
        assert hm.dx == pytest.approx(dx, rel=1e-4) and hm.dy == pytest.approx(dy, rel=1e-4)
        np.testing.assert_array_equal(np.isnan(hm.heights), np.isnan(expect))
        np.testing.assert_allclose(hm.heights, expect, rtol=1e-12, atol=1e-21)
        assert hm.n_undefined == int(np.isnan(expect).sum())


def _gz(p: Path) -> Path:
    out = p.with_name(p.name + ".gz")
    out.write_bytes(gzip.compress(p.read_bytes()))
    return out


@pytest.mark.parametrize("name", list(X3P_REFUSED))
def test_x3p_refusals_say_what_the_file_is(tmp_path, name):
    kw, msg = X3P_REFUSED[name]
    if name == "metres of raw integers":
        kw = dict(kw, z=RAW * 1000)
    p = tmp_path / "s.x3p"
    p.write_bytes(_x3p(**kw))
    with pytest.raises(InputError) as exc:
        read_surface(p)
    assert msg in _one_line(exc.value) and "s.x3p" in str(exc.value)


def test_x3p_refusal_through_the_real_command(tmp_path):
    p = tmp_path / "cloud.x3p"
    p.write_bytes(_x3p(feature="PCL"))
    out = tmp_path / "r.png"
    out.write_bytes(b"keep")
    assert_refused(cli("derive", p, "--plot", out), contains="a point cloud x3p (PCL)")
    assert out.read_bytes() == b"keep"


@needs_st
def test_x3p_agrees_with_surfacetopography_on_what_both_read(tmp_path):
    from SurfaceTopography import read_topography
    for name in ("binary F", "binary I with increment and offset", "binary D with NaN",
                 "binary I with valid-points mask"):
        p = tmp_path / "s.x3p"
        p.write_bytes(_x3p(**X3P_CONFORMING[name][0]))
        theirs = np.ma.filled(read_topography(str(p)).heights().astype(float), np.nan)
        np.testing.assert_allclose(read_surface(p).heights, theirs, rtol=1e-12, atol=1e-21,
                                   err_msg=name)


# ----------------------------------------------------------------------------- class 4: memory

_HUGE = 65536                               # 4.3e9 points: more than any machine holds


def _claims(tmp_path, **kw) -> Path:
    """An x3p whose header claims a _HUGE x _HUGE grid (its data is not there)."""
    p = tmp_path / "claim.x3p"
    p.write_bytes(x3p_bytes(ZX, members={"main.xml": main_xml(nx=_HUGE, ny=_HUGE, **kw)}))
    return p


def _resource_cases(tmp_path) -> dict:
    """name -> (argv of asperity, words of the refusal)."""
    # held in memory (--tile-rows 0): refused from the header; in tiles the missing data is
    # what gets it refused (tests/test_scan_tiles.py)
    cases = {"x3p binary claim": (["derive", _claims(tmp_path), "--tile-rows", "0"],
                                  "65536 x 65536 grid")}
    q = tmp_path / "inline.x3p"
    q.write_bytes(x3p_bytes(ZX, members={"main.xml": main_xml(
        nx=_HUGE, ny=_HUGE, data="<Datum>1</Datum>" * 10)}))
    cases["x3p inline claim"] = (["derive", q], "65536 x 65536 grid")
    npy = tmp_path / "claim.npy"
    npy.write_bytes(_npy(np.zeros((2, 2))).replace(b"(2, 2)", b"(65536, 65536)"))
    cases["npy header claim"] = (["derive", npy, *BASE], "its shape (65536, 65536) needs")
    xml = tmp_path / "xmlbomb.x3p"
    xml.write_bytes(x3p_bytes(ZX, members={"main.xml": b"<!--" + b"a" * (17 << 20) + b"-->"}))
    cases["x3p main.xml of 17 MB"] = (["derive", xml], "main.xml is larger than")
    many = tmp_path / "elements.x3p"
    many.write_bytes(x3p_bytes(ZX, members={"main.xml": main_xml(nx=6, ny=5).replace(
        "<Record2>", "<Record2>" + "<a/>" * 100_001)}))
    cases["x3p 1e5 elements"] = (["derive", many], "more than 100000 elements")
    cases["bench --facets 16384"] = (["bench", "--only", "facets", "--facets", "16384"],
                                     "--facets must be a whole number in [2, 8192]")
    cases["bench work"] = (["bench", "--only", "facets", "--facets", "8192", "--directions",
                            "100000"], "lower --directions or --facets")
    cases["bench NumPy work"] = (["bench", "--only", "facets", "--facets", "8192",
                                  "--numpy-directions", "360"],
                                 "lower --numpy-directions or --facets")
    return cases


RESOURCE_CASES = ["x3p binary claim", "x3p inline claim", "npy header claim",
                  "x3p main.xml of 17 MB", "x3p 1e5 elements", "bench --facets 16384",
                  "bench work", "bench NumPy work"]


@pytest.mark.parametrize("name", RESOURCE_CASES)
def test_requests_that_cannot_fit_are_refused_before_expanding(capsys, tmp_path, name):
    argv, msg = _resource_cases(tmp_path)[name]
    code, out, err = run(capsys, *argv)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


def test_gzip_expansion_is_bounded(tmp_path, monkeypatch):
    p = tmp_path / "zeros.npy.gz"
    with gzip.open(p, "wb", compresslevel=1) as fh:
        fh.write(_npy(np.zeros((2048, 2048))))            # 32 MB of zeros, 32 kB on disk
    monkeypatch.setattr(_files, "available_memory", lambda: 64 << 20)
    with pytest.raises(ResourceError, match="expands to more than 12.8 MB"):
        read_surface(p, unit="um", pixel_size=1.0)


def test_memory_bound_of_a_claimed_grid_under_a_2_gb_limit(tmp_path):
    """The claimed grid is refused by the estimate, not by running out of memory."""
    p = tmp_path / "claim.x3p"
    p.write_bytes(x3p_bytes(ZX, members={"main.xml": main_xml(nx=8192, ny=8192)}))
    assert_refused(cli("derive", p, "--tile-rows", "0", preexec_fn=limit_memory(2 << 30)),
                   contains=["8192 x 8192 grid", "GB of memory", "crop or resample"])
    assert_refused(cli("bench", "--only", "facets", "--facets", "8192",
                       preexec_fn=limit_memory(2 << 30)),
                   contains=["the facet benchmark on a 8192 x 8192 grid", "lower --facets"])


@pytest.mark.slow
def test_zipped_zeros_claiming_16384_squared_float64(tmp_path):
    """The issue's case: a 2 MB x3p whose member expands to 2 GiB of float64 zeros.  Read
    for derive in memory (--tile-rows 0): refused at once from the header (in tiles it is
    a flat scan like any other, read in bounded memory); read alone under a 2 GB address-space
    limit: refused by the estimate, well before the limit."""
    p = tmp_path / "bomb.x3p"
    zeros_member(p, "bindata/data.bin", 16384 * 16384 * 8, main_xml(nx=16384, ny=16384))
    assert p.stat().st_size < 4 << 20
    assert_refused(cli("derive", p, "--tile-rows", "0", timeout=60),
                   contains="16384 x 16384 grid")
    code = ("import sys\nfrom asperity.surface.readers import read_surface\n"
            "try:\n    read_surface(sys.argv[1])\nexcept Exception as e:\n"
            "    print(type(e).__name__, e)\n")
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-c", code, str(p)], capture_output=True, text=True,
                       timeout=60, preexec_fn=limit_memory(2 << 30))
    assert r.stdout.startswith("ResourceError") and "16384 x 16384" in r.stdout, r


# ----------------------------------------------------------------------------- class 5: Ctrl-C

def test_facet_kernel_pieces_give_the_same_result_bit_for_bit(monkeypatch):
    from asperity.bench import rough_surface_facets
    from asperity.friction import facet_reservoir as R
    gx, gy, w = rough_surface_facets(160, 0.9)
    mu = np.random.default_rng(2).uniform(0.05, 0.5, gx.size)
    psi = np.linspace(0.0, 2 * np.pi, 29, endpoint=False)
    whole = {c: R.compute_facet_reservoir(gx, gy, mu, w, psi, c)
             for c in ("all-faces", "windward")}
    monkeypatch.setattr(R, "PIECE_WORK", 3000)
    for c, ref in whole.items():
        seen = []
        r = R.compute_facet_reservoir(gx, gy, mu, w, psi, c, progress=seen.append)
        for k in ("p", "locked", "locked_face", "set_valued"):
            np.testing.assert_array_equal(getattr(r, k), getattr(ref, k), err_msg=f"{c} {k}")
        assert len(seen) >= 20 and seen[-1] == 1.0 and np.all(np.diff(seen) > 0), seen
    assert whole["all-faces"].locked.any()          # the first-locked facet is compared too


@pytest.mark.slow
def test_ctrl_c_stops_a_long_derive(tmp_path):
    big = tmp_path / "big.npy"
    np.save(big, np.random.default_rng(0).normal(size=(2000, 2000)))
    plot = tmp_path / "old.png"
    plot.write_bytes(b"an older figure")
    status, err = interrupt("derive", big, "--unit", "nm", "--pixel-size", "10",
                            "--directions", "100000", "--plot", plot)
    assert status == 130 and "interrupted" in err and "Traceback" not in err, err
    assert err.count("\n") == 1, err
    assert plot.read_bytes() == b"an older figure"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["big.npy", "old.png"]


# ----------------------------------------------------------------------------- class 6: API

_HM = HeightMap(np.zeros((3, 3)), 1e-6, 1e-6, "hm")
_NAN = float("nan")

#: public entry points of the surface room fed what they cannot use
API = {
    "load_surface(None)": lambda p: A.load_surface(None),
    "load_surface(5)": lambda p: A.load_surface(5),
    "load_surface('')": lambda p: A.load_surface(""),
    "load_surface(folder)": lambda p: A.load_surface(p.parent),
    "load_surface(detrend=[1])": lambda p: A.load_surface(p, unit="um", pixel_size=1,
                                                          detrend=[1]),
    "load_surface(unit=5)": lambda p: A.load_surface(p, unit=5, pixel_size=1),
    "load_surface(pixel_size='1')": lambda p: A.load_surface(p, unit="um", pixel_size="1"),
    "load_surface(pixel_size=[[1, 2]])": lambda p: A.load_surface(p, unit="um",
                                                                  pixel_size=[[1, 2]]),
    "load_surface(pixel_size=nan)": lambda p: A.load_surface(p, unit="um", pixel_size=_NAN),
    "load_surface(height_scale='2')": lambda p: A.load_surface(p, unit="um", pixel_size=1,
                                                               height_scale="2"),
    "load_surface(mu='0.1')": lambda p: A.load_surface(p, unit="um", pixel_size=1, mu="0.1"),
    "load_surface(rest_level='0')": lambda p: A.load_surface(p, unit="um", pixel_size=1,
                                                             rest_level="0"),
    "load_surface(friction_map ragged)": lambda p: A.load_surface(
        p, unit="um", pixel_size=1, friction_map=[[0.1, 0.2], [0.3]]),
    "load_surface(friction_map nan)": lambda p: A.load_surface(
        p, unit="um", pixel_size=1, friction_map=np.full(Z.shape, _NAN)),
    "load_surface(friction_map 1e9)": lambda p: A.load_surface(
        p, unit="um", pixel_size=1, friction_map=np.full(Z.shape, 1e9)),
    "read_surface(None)": lambda p: A.read_surface(None),
    "read_surface(b'')": lambda p: A.read_surface(b""),
    "HeightMap(None)": lambda p: HeightMap(None, 1e-6, 1e-6),
    "HeightMap(text)": lambda p: HeightMap("abc", 1e-6, 1e-6),
    "HeightMap(ragged)": lambda p: HeightMap([[1.0, 2.0], [3.0]], 1e-6, 1e-6),
    "HeightMap(inf)": lambda p: HeightMap(np.full((3, 3), np.inf), 1e-6, 1e-6),
    "HeightMap(1-D)": lambda p: HeightMap(np.zeros(4), 1e-6, 1e-6),
    "HeightMap(dx None)": lambda p: HeightMap(np.zeros((3, 3)), None, 1e-6),
    "HeightMap(dx 1e-300)": lambda p: HeightMap(np.zeros((3, 3)), 1e-300, 1e-6),
    "HeightMap(source 5)": lambda p: HeightMap(np.zeros((3, 3)), 1e-6, 1e-6, source=5),
    "TriangleMesh(None)": lambda p: TriangleMesh(None, None),
    "TriangleMesh(NaN vertex)": lambda p: TriangleMesh(np.full((3, 3), _NAN), [[0, 1, 2]]),
    "TriangleMesh(faces 0.5)": lambda p: TriangleMesh(np.eye(3), [[0.5, 1, 2]]),
    "TriangleMesh(face index 3)": lambda p: TriangleMesh(np.eye(3), [[0, 1, 3]]),
    "TriangleMesh(km vertices)": lambda p: TriangleMesh(np.eye(3) * 1e4, [[0, 1, 2]]),
    "heightmap_facets(None)": lambda p: F.heightmap_facets(None),
    "mesh_facets(text)": lambda p: F.mesh_facets("mesh.stl"),
    "surface_facets(None)": lambda p: F.surface_facets(None),
    "surface_facets(mu=-1)": lambda p: F.surface_facets(_HM, mu=-1),
    "surface_facets(level_slope='yes')": lambda p: F.surface_facets(_HM, level_slope="yes"),
    "derive(None)": lambda p: A.derive(None),
    "derive(text)": lambda p: A.derive("z.npy"),
    "derive(progress=5)": lambda p: A.derive(_HM, progress=5),
    "compute_reservoir(None)": lambda p: A.compute_reservoir(None, [0.0]),
    "compute_facet_reservoir(None)": lambda p: A.compute_facet_reservoir(None, None, 0.1, None,
                                                                         [0.0]),
    "compute_facet_reservoir(mu text)": lambda p: A.compute_facet_reservoir([0.1], [0.1], "0.1",
                                                                            [1.0], [0.0]),
    "compute_facet_reservoir(psi nan)": lambda p: A.compute_facet_reservoir([0.1], [0.1], 0.1,
                                                                            [1.0], [_NAN]),
    "compute_facet_reservoir(2-D gx)": lambda p: A.compute_facet_reservoir([[0.1]], [[0.1]], 0.1,
                                                                           [[1.0]], [0.0]),
}


@pytest.mark.parametrize("name", list(API))
def test_public_api_raises_one_line_input_errors(zmap, name):
    with pytest.raises(InputError) as exc:
        API[name](zmap)
    _one_line(exc.value)


def test_derive_takes_a_height_map_as_its_facets():
    z = np.add.outer(np.arange(8.0), np.zeros(6)) * 1e-7
    d = A.derive(HeightMap(z, 1e-6, 1e-6, "ramp"), n_directions=8)
    assert d.texture.n_facets == 2 * 7 * 5
    assert d.axes["mu_a_plus"] == pytest.approx(0.1, rel=1e-9)   # mean slope removed
