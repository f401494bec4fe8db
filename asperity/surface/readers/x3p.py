"""ISO 25178-72 ``.x3p`` files, read by the built-in reader (a zip holding ``main.xml``
and the binary height member), about 30 times faster than SurfaceTopography and tolerant
of an empty z-offset element; SurfaceTopography is the fallback for variants it does not
know.  An x3p file states its unit (m) and pixel size.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ..topography import HeightMap, finish_heightmap, positive_length
from ._files import read_bytes, split_suffix

_X3P_DTYPES = {"I": "<i2", "L": "<i4", "F": "<f4", "D": "<f8"}


def _xml_child(elem, *names):
    """The element at the path of local tag names below ``elem`` (namespaces ignored)."""
    for n in names:
        if elem is None:
            return None
        elem = next((c for c in elem if c.tag.rsplit("}", 1)[-1] == n), None)
    return elem


def _xml_float(elem, default, what, name) -> float:
    if elem is None or elem.text is None or not elem.text.strip():
        return default                    # absent or empty element: the default
    try:
        return float(elem.text.strip())
    except ValueError:
        raise TextureFileError(f"{name}: main.xml {what} is not a number: "
                               f"{elem.text.strip()!r}") from None


def read_x3p(path, *, height_scale=1.0) -> HeightMap:
    """Read an ``.x3p`` (ISO 25178-72 / ISO 5436-2) areal surface with the built-in reader.

    Supports ``FeatureType`` SUR with incremental x and y axes and binary point data
    (``bindata/data.bin``; DataType I = int16, L = int32, F = float32, D = float64,
    little-endian, x running fastest), ``z = raw * Increment + Offset`` (an absent
    or empty Increment is 1, an absent or empty Offset 0).  Non-finite points (NaN,
    or +inf as some instruments write) and points cleared in the optional
    valid-points bit mask (``ValidPointsLink``, least significant bit first) are
    undefined pixels.  :func:`read_surface` uses it when SurfaceTopography is not
    installed or rejects a file.
    """
    p = Path(path)
    hs = positive_length("height_scale", height_scale)
    suffix, gz = split_suffix(p)
    return _read_x3p_bytes(read_bytes(p, gz), p, hs)


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
         height_scale: float) -> HeightMap:
    """The built-in reader; SurfaceTopography, when installed, for variants it rejects."""
    if unit is not None or pixel_size is not None:
        raise InputError(f"{name}: an x3p file states its unit (m) and pixel size; do not "
                         f"pass unit or pixel_size (height_scale scales the heights)")
    from .instrument import have_surfacetopography, read_with_surfacetopography
    try:
        return _read_x3p_bytes(data, name, height_scale)
    except InputError:
        if not have_surfacetopography():
            raise       # the built-in reader's message says what is wrong with the file
    # a variant the built-in reader does not know: SurfaceTopography decides
    return read_with_surfacetopography(data, suffix, gz, name, None, None, height_scale)


def _read_x3p_bytes(data: bytes, name: Path, height_scale: float) -> HeightMap:
    import io
    import zipfile
    from xml.etree import ElementTree

    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise TextureFileError(f"{name}: not an x3p file (an x3p file is a zip archive)") from None
    with zf:
        members = set(zf.namelist())
        if "main.xml" not in members:
            raise TextureFileError(f"{name}: not an x3p file (no main.xml in the archive)")
        try:
            root = ElementTree.fromstring(zf.read("main.xml"))
        except ElementTree.ParseError as exc:
            raise TextureFileError(f"{name}: main.xml is not valid XML ({exc})") from None
        r1, r3 = _xml_child(root, "Record1"), _xml_child(root, "Record3")
        if r1 is None or r3 is None:
            raise TextureFileError(f"{name}: main.xml lacks Record1 or Record3")
        ftype = (getattr(_xml_child(r1, "FeatureType"), "text", "") or "").strip()
        if ftype != "SUR":
            raise TextureFileError(f"{name}: x3p FeatureType {ftype!r} is not an areal surface "
                                   f"(SUR); profiles and point clouds are not supported")
        axes = _xml_child(r1, "Axes")
        cx, cy, cz = (_xml_child(axes, a) for a in ("CX", "CY", "CZ"))
        if cx is None or cy is None or cz is None:
            raise TextureFileError(f"{name}: main.xml lacks the CX, CY or CZ axis")
        for ax, label in ((cx, "CX"), (cy, "CY")):
            at = (getattr(_xml_child(ax, "AxisType"), "text", "") or "").strip()
            if at != "I":
                raise TextureFileError(f"{name}: x3p axis {label} has AxisType {at!r}; only "
                                       f"incremental (I) x and y axes are supported")
        dtype_code = (getattr(_xml_child(cz, "DataType"), "text", "") or "").strip()
        if dtype_code not in _X3P_DTYPES:
            raise TextureFileError(f"{name}: x3p CZ DataType {dtype_code!r}; allowed: "
                                   f"{', '.join(_X3P_DTYPES)}")
        dx = _xml_float(_xml_child(cx, "Increment"), None, "CX Increment", name)
        dy = _xml_float(_xml_child(cy, "Increment"), None, "CY Increment", name)
        if dx is None or dy is None or not (dx > 0 and dy > 0 and math.isfinite(dx * dy)):
            raise TextureFileError(f"{name}: x3p CX and CY need positive Increment values, "
                                   f"got {dx!r} and {dy!r}")
        zinc = _xml_float(_xml_child(cz, "Increment"), 1.0, "CZ Increment", name)
        zoff = _xml_float(_xml_child(cz, "Offset"), 0.0, "CZ Offset", name)
        dims = _xml_child(r3, "MatrixDimension")
        if dims is None:
            raise TextureFileError(f"{name}: x3p without MatrixDimension (a point list) is not "
                                   f"supported")
        try:
            nx, ny, nz = (int(_xml_child(dims, k).text.strip())
                          for k in ("SizeX", "SizeY", "SizeZ"))
        except (AttributeError, ValueError):
            raise TextureFileError(f"{name}: x3p MatrixDimension needs whole-number SizeX, "
                                   f"SizeY and SizeZ") from None
        if nz != 1 or nx < 1 or ny < 1:
            raise TextureFileError(f"{name}: x3p MatrixDimension {nx} x {ny} x {nz}; an areal "
                                   f"surface needs SizeZ = 1")
        link = _xml_child(r3, "DataLink", "PointDataLink")
        if link is None or not (link.text or "").strip():
            raise TextureFileError(f"{name}: x3p without binary point data (inline DataList) "
                                   f"is not supported")
        member = link.text.strip()
        if member not in members:
            raise TextureFileError(f"{name}: x3p point data {member!r} missing from the archive")
        raw = zf.read(member)
        dt = np.dtype(_X3P_DTYPES[dtype_code])
        n = nx * ny
        if len(raw) != n * dt.itemsize:
            raise TextureFileError(f"{name}: {member} holds {len(raw)} bytes, {nx} x {ny} "
                                   f"{dtype_code} values need {n * dt.itemsize}")
        z = np.frombuffer(raw, dtype=dt).astype(np.float64) * zinc + zoff
        z[~np.isfinite(z)] = np.nan       # NaN or (Alicona) +inf marks an invalid point
        vlink = _xml_child(r3, "DataLink", "ValidPointsLink")
        if vlink is not None and (vlink.text or "").strip():
            vmember = vlink.text.strip()
            if vmember not in members:
                raise TextureFileError(f"{name}: x3p valid-points file {vmember!r} missing from "
                                       f"the archive")
            bits = np.frombuffer(zf.read(vmember), dtype=np.uint8)
            if bits.size * 8 < n:
                raise TextureFileError(f"{name}: {vmember} holds {bits.size} bytes, {n} points "
                                       f"need {(n + 7) // 8}")
            valid = np.unpackbits(bits, bitorder="little")[:n].astype(bool)
            z[~valid] = np.nan
    heights = z.reshape(ny, nx).T              # x runs fastest in the file
    return finish_heightmap(heights, dx, dy, name.name, height_scale, name)
