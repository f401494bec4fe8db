"""ISO 25178-72 / ISO 5436-2 ``.x3p`` files, read by the built-in reader.

An x3p file is a zip archive holding ``main.xml`` (axes and layout) and, usually, a
binary member with the points.  What the standard allows for an areal surface is read:

* ``FeatureType`` SUR with a ``MatrixDimension`` of SizeX x SizeY x 1 points;
* incremental x and y axes (``AxisType`` I: ``x_i = i Increment``), or absolute ones
  (``AxisType`` A: a coordinate stored with every point) that form a regular grid;
* heights (the absolute z axis) of ``DataType`` I (int16), L (int32), F (float32) or
  D (float64), ``z = raw * Increment + Offset`` (an absent or empty Increment is 1, an
  absent or empty Offset 0);
* the points in a binary member (``DataLink``/``PointDataLink``, little-endian, x running
  fastest) or inline in ``main.xml`` (``DataList``: one ``Datum`` per point);
* missing points: NaN (or the +inf some instruments write) in float data, an empty
  ``<Datum/>``, a point cleared in the valid-points member (``ValidPointsLink``).

The rest of what the standard allows is refused in one line that says what the file is:
profiles (PRF), point clouds (PCL), point lists (``ListDimension``), several layers
(SizeZ > 1), absolute x/y coordinates that are no regular grid, a rotated data set.
Sizes are checked against the memory before anything is expanded; ``main.xml`` is parsed
as a stream and the points are read in pieces, so Ctrl-C is honoured.  The unit is the
metre and the file states the pixel size.
"""
from __future__ import annotations

import math
from pathlib import Path

from ...errors import InputError, TextureFileError
from ..topography import (
    HeightMap,
    check_height_scale,
    check_stated_pixel,
    finish_heightmap,
    given_sizes,
    one_line,
)
from ._files import READ_BYTES_PER_POINT, check_grid, read_bytes, split_suffix, surface_path
from ._x3p_points import (
    DTYPE_NAMES,
    X3P_DTYPES,
    Axis,
    InlinePoints,
    Layout,
    assemble,
    read_binary,
    read_valid,
)

_FEATURES = {"PRF": "a profile x3p (PRF, a line scan)", "PCL": "a point cloud x3p (PCL)"}
AREAL = "asperity reads areal grids (FeatureType SUR)"
#: bytes of main.xml allowed before its DataList (an x3p header takes a few kB)
MAX_HEADER_XML = 16 << 20
#: bytes of main.xml allowed per point of an inline DataList (a Datum "x;y;z" and its tags)
MAX_DATUM_BYTES = 200
#: elements of main.xml allowed outside its DataList
MAX_ELEMENTS = 100_000
_XML_PIECE = 1 << 20


def read_x3p(path, *, height_scale=1.0) -> HeightMap:
    """Read an ``.x3p`` areal surface (ISO 25178-72 / ISO 5436-2) with the built-in reader
    (see the module docstring for what is read and what is refused)."""
    p = surface_path(path)
    hs = check_height_scale(height_scale)
    suffix, gz = split_suffix(p)
    return read_x3p_bytes(read_bytes(p, gz), p, hs)


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
         height_scale: float, point_bytes: float = 0.0) -> HeightMap:
    """The built-in reader (the registry's entry for ``.x3p``).  The standard has every
    number in metres; ``unit`` reads them in that unit instead (a file written in another),
    ``pixel_size`` (in ``unit``) replaces the file's spacing."""
    factor, pixel = given_sizes(name, unit, pixel_size)
    return read_x3p_bytes(data, name, height_scale, point_bytes, factor=factor or 1.0,
                          pixel=pixel)


def read_x3p_bytes(data: bytes, name: Path, height_scale: float,
                   point_bytes: float = 0.0, *, factor: float = 1.0,
                   pixel: tuple | None = None) -> HeightMap:
    """The height map of the x3p archive ``data`` (``point_bytes``: memory per point the
    caller will need beyond reading, checked with the header); ``factor``: metres per
    number of the file (1: as the standard has them), ``pixel``: (dx, dy) in metres
    replacing the file's."""
    import io
    import zipfile

    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        raise TextureFileError(f"{name}: not an x3p file (an x3p file is a zip archive)") from None
    with zf:
        try:
            info = zf.getinfo("main.xml")
        except KeyError:
            raise TextureFileError(f"{name}: not an x3p file (no main.xml in the archive)") \
                from None
        layout, inline = _parse_main(zf, info, name, point_bytes)
        if inline is None:
            values = read_binary(zf, layout, name)
            valid = read_valid(zf, layout, name)
        else:
            values, valid = inline, None
    heights, dx, dy = assemble(values, valid, layout, name)
    del values
    if pixel is None:
        dx, dy = dx * factor, dy * factor
        check_stated_pixel(name, dx, dy, "metres" if factor == 1.0 else "that unit")
    else:
        dx, dy = pixel
    return finish_heightmap(heights, dx, dy, name.name, height_scale * factor, name)


# ----------------------------------------------------------------------------- main.xml

def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _child(elem, *names):
    """The element at the path of local tag names below ``elem`` (namespaces ignored)."""
    for n in names:
        if elem is None:
            return None
        elem = next((c for c in elem if _local(c.tag) == n), None)
    return elem


def _text(elem) -> str:
    return ((elem.text if elem is not None else None) or "").strip()


def _float(elem, default, what, name):
    t = _text(elem)
    if not t:
        return default                    # absent or empty element: the default
    try:
        x = float(t)
    except ValueError:
        raise TextureFileError(f"{name}: main.xml {what} is not a number: {t[:40]!r}") from None
    if not math.isfinite(x):
        raise TextureFileError(f"{name}: main.xml {what} must be finite, got {t[:40]!r}")
    return x


def _parse_main(zf, info, name, point_bytes):
    """(layout, inline values or None) from ``main.xml``, parsed as a stream: Datum entries
    are converted and dropped as they come, the size read is bounded."""
    import zipfile
    import zlib
    from xml.etree.ElementTree import ParseError, XMLPullParser

    parser = XMLPullParser(events=("start", "end"))
    state = {"root": None, "layout": None, "inline": None, "list": None, "elements": 0,
             "limit": MAX_HEADER_XML}

    def handle(event, elem):
        tag = _local(elem.tag)
        if event == "start":
            if state["root"] is None:
                state["root"] = elem
            if state["list"] is None:
                state["elements"] += 1
                if state["elements"] > MAX_ELEMENTS:
                    raise TextureFileError(f"{name}: main.xml holds more than {MAX_ELEMENTS} "
                                           f"elements besides its points; not an x3p header")
            if tag == "DataList" and state["list"] is None:
                layout = _layout(state["root"], name, point_bytes, inline=True)
                state.update(layout=layout, inline=InlinePoints(layout, name), list=elem,
                             limit=MAX_HEADER_XML + MAX_DATUM_BYTES * layout.n)
        elif state["list"] is not None and state["inline"] is not None:
            if tag == "Datum":
                state["inline"].add(elem.text)
                try:
                    state["list"].remove(elem)
                except ValueError:
                    pass
            elif tag == "DataList":
                state["inline"] = state["inline"].finish()

    fed = 0
    try:
        with zf.open(info) as fh:
            while True:
                piece = fh.read(_XML_PIECE)
                if not piece:
                    break
                if fed == 0 and b"<!DOCTYPE" in piece:
                    raise TextureFileError(f"{name}: main.xml declares a DOCTYPE (entities); "
                                           f"an x3p header has none")
                fed += len(piece)
                if fed > state["limit"]:
                    raise TextureFileError(f"{name}: main.xml is larger than its points can "
                                           f"need (over {state['limit'] >> 20} MB); not a "
                                           f"valid x3p header")
                parser.feed(piece)
                for event, elem in parser.read_events():
                    handle(event, elem)
        parser.close()
        for event, elem in parser.read_events():
            handle(event, elem)
    except ParseError as exc:
        raise TextureFileError(f"{name}: main.xml is not valid XML ({one_line(exc)})") from None
    except (zipfile.BadZipFile, zlib.error, OSError, EOFError, NotImplementedError) as exc:
        raise TextureFileError(f"{name}: main.xml cannot be read ({one_line(exc)})") from None
    if state["root"] is None:
        raise TextureFileError(f"{name}: main.xml is empty")
    if state["layout"] is None:
        return _layout(state["root"], name, point_bytes, inline=False), None
    if isinstance(state["inline"], InlinePoints):
        raise TextureFileError(f"{name}: main.xml ends inside its DataList")
    return state["layout"], state["inline"]


def _layout(root, name, point_bytes, inline: bool) -> Layout:
    """Record1 and Record3 checked: an areal grid, or InputError saying what the file is."""
    if _local(root.tag) != "ISO5436_2":
        raise TextureFileError(f"{name}: main.xml is not an ISO 5436-2 document (root "
                               f"element {_local(root.tag)!r})")
    r1, r3 = _child(root, "Record1"), _child(root, "Record3")
    if r1 is None or r3 is None:
        raise TextureFileError(f"{name}: main.xml lacks Record1 or Record3")
    ftype = _text(_child(r1, "FeatureType"))
    if ftype != "SUR":
        if ftype in _FEATURES:
            raise InputError(f"{name}: {_FEATURES[ftype]}; {AREAL}")
        raise TextureFileError(f"{name}: x3p FeatureType {ftype[:20]!r} is none of SUR "
                               f"(areal), PRF (profile), PCL (point cloud)")
    if _child(r3, "ListDimension") is not None:
        raise InputError(f"{name}: an x3p point list (ListDimension: points without a grid); "
                         f"{AREAL} with a MatrixDimension")
    dims = _child(r3, "MatrixDimension")
    if dims is None:
        raise TextureFileError(f"{name}: main.xml Record3 has no MatrixDimension")
    try:
        nx, ny, nz = (int(_text(_child(dims, k))) for k in ("SizeX", "SizeY", "SizeZ"))
    except ValueError:
        raise TextureFileError(f"{name}: x3p MatrixDimension needs whole-number SizeX, SizeY "
                               f"and SizeZ") from None
    if nz != 1 and nz > 0:
        raise InputError(f"{name}: a multi-layer x3p ({nz} layers, SizeZ = {nz}); {AREAL} "
                         f"with one layer")
    if min(nx, ny, nz) < 1:
        raise TextureFileError(f"{name}: x3p MatrixDimension {nx} x {ny} x {nz} holds no points")
    if min(nx, ny) < 2:
        raise InputError(f"{name}: an x3p of a single line of points ({nx} x {ny}): a "
                         f"profile; {AREAL} of at least 2 x 2 points")
    axes_elem = _child(r1, "Axes")
    axes = tuple(_axis(axes_elem, label, name, inline) for label in ("CX", "CY", "CZ"))
    _check_rotation(_child(axes_elem, "Rotation"), name)
    member = valid = None
    if not inline:
        link = _child(r3, "DataLink")
        member = _text(_child(link, "PointDataLink"))
        if link is None or not member:
            raise TextureFileError(f"{name}: x3p Record3 has neither a DataLink to binary "
                                   f"point data nor a DataList")
        valid = _text(_child(link, "ValidPointsLink")) or None
    layout = Layout(nx, ny, axes, member, valid)
    xy = sum(8 for a in axes[:2] if a.absolute)
    if point_bytes is not None or inline:      # None: streamed in tiles, never held whole
        check_grid(nx, ny, name, READ_BYTES_PER_POINT + layout.record.itemsize + 3 * xy + 2 +
                   float(point_bytes or 0.0))
    return layout


def _axis(axes, label, name, inline) -> Axis:
    ax = _child(axes, label)
    if ax is None:
        raise TextureFileError(f"{name}: main.xml lacks the {label} axis")
    kind = _text(_child(ax, "AxisType"))
    if kind not in ("I", "A"):
        raise TextureFileError(f"{name}: x3p {label} AxisType {kind[:20]!r} is neither I "
                               f"(incremental) nor A (absolute)")
    code = _text(_child(ax, "DataType")) or None
    if code is not None and code not in X3P_DTYPES:
        raise TextureFileError(f"{name}: x3p {label} DataType {code[:20]!r} is unknown; the "
                               f"standard's types are {DTYPE_NAMES}")
    inc = _float(_child(ax, "Increment"), None, f"{label} Increment", name)
    off = _float(_child(ax, "Offset"), 0.0, f"{label} Offset", name)
    if kind == "I":
        if label == "CZ":
            raise TextureFileError(f"{name}: x3p CZ axis is incremental (AxisType I); the "
                                   f"standard's heights are an absolute axis (A)")
        if inc is None or not inc > 0:
            raise TextureFileError(f"{name}: x3p {label} is incremental and needs a positive "
                                   f"Increment, got {inc!r}")
        return Axis(label, False, code or "D", inc, off)
    if code is None and not inline:
        raise TextureFileError(f"{name}: x3p {label} is absolute and needs a DataType "
                               f"({DTYPE_NAMES})")
    inc = 1.0 if inc is None else inc
    if inc == 0:
        raise TextureFileError(f"{name}: x3p {label} Increment must not be 0")
    return Axis(label, True, code or "D", inc, off)


def _check_rotation(rot, name) -> None:
    if rot is None:
        return
    for i in range(3):
        for j in range(3):
            r = _float(_child(rot, f"r{i + 1}{j + 1}"), None, f"Rotation r{i + 1}{j + 1}", name)
            if r is None or abs(r - (1.0 if i == j else 0.0)) > 1e-12:
                raise InputError(f"{name}: a rotated x3p (its Rotation is not the identity); "
                                 f"asperity reads unrotated grids")
