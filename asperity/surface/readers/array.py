"""NumPy height maps (``.npy``, ``.npz``).

The array is ``heights[i, j]`` (first index along x), in ``unit``, on a grid of spacing
``pixel_size``; both are required.  NaN marks undefined pixels.  A ``.npz`` holds the array
as ``heights`` (or as its only array) and optionally a boolean ``mask`` (True = undefined).

The header of each array (shape, dtype) is read first: an array that is not 2-D real
numbers, whose data is shorter or longer than its shape, or that memory cannot hold is
refused before any of it is expanded.
"""
from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ..topography import UNIT_HELP, HeightMap, finish_heightmap, one_line, pixel_pair, unit_factor
from ._files import READ_BYTES_PER_POINT, check_grid

#: bytes of a .npy header read before the data (headers are at most a few kB)
_HEADER_PEEK = 1 << 16


def _header(fh, name, what):
    """(shape, fortran order, dtype, data offset) of the .npy stream ``fh``."""
    from numpy.lib import format as npf
    if fh.read(6) != b"\x93NUMPY":
        raise TextureFileError(f"{name}: not a surface file: {what} lacks the NumPy header "
                               f"of a .npy array")
    fh.seek(0)
    try:
        version = npf.read_magic(fh)
        if version == (1, 0):
            shape, fortran, dtype = npf.read_array_header_1_0(fh)
        else:                               # 2.0 and 3.0 differ only in the header's encoding
            shape, fortran, dtype = npf.read_array_header_2_0(fh)
    except Exception as exc:   # numpy raises ValueError, SyntaxError, EOFError ... on a bad header
        raise TextureFileError(f"{name}: {what} is not a readable .npy array "
                               f"({one_line(exc)})") from None
    if dtype.hasobject or dtype.names is not None or dtype.kind not in "biuf":
        raise TextureFileError(f"{name}: {what} must hold real numbers, got dtype {dtype}")
    return tuple(int(s) for s in shape), bool(fortran), dtype, fh.tell()


def _check_shape(shape, name, what, data_bytes, itemsize, point_bytes, two_d=True):
    """A height map's shape against its data size and (unless ``point_bytes`` is None: a
    map read in tiles) the memory its points need."""
    if two_d and len(shape) != 2:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got {what} of "
                               f"shape {shape}")
    n = int(np.prod(shape, dtype=object))
    if data_bytes != n * itemsize:
        raise TextureFileError(f"{name}: {what} holds {data_bytes} bytes of data, its shape "
                               f"{shape} needs {n * itemsize}")
    if point_bytes is None:
        return
    if len(shape) == 2:
        check_grid(shape[0], shape[1], name, point_bytes + itemsize)
    else:
        check_grid(n, 1, name, point_bytes + itemsize)


def _npy(data, name, what, point_bytes, two_d=True, as_float=True) -> np.ndarray:
    """The array of .npy bytes ``data``, as float64 (``as_float``, booleans kept) or as
    stored (a read-only view)."""
    shape, fortran, dtype, offset = _header(io.BytesIO(data), name, what)
    _check_shape(shape, name, what, len(data) - offset, dtype.itemsize, point_bytes, two_d)
    n = int(np.prod(shape, dtype=object))
    a = np.frombuffer(data, dtype=dtype, count=n, offset=offset)
    a = a.reshape(shape, order="F" if fortran else "C")
    return a if dtype.kind == "b" or not as_float else a.astype(np.float64)


def _npz(data, name, point_bytes, two_d):
    """(heights, mask or None) of .npz bytes, each member's header checked first."""
    import zipfile
    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        raise TextureFileError(f"{name}: not a .npz archive") from None
    with zf:
        members = {i.filename[:-4] if i.filename.endswith(".npy") else i.filename: i
                   for i in zf.infolist()}
        keys = list(members)
        arrays = [k for k in keys if k != "mask"]
        if "heights" in keys:
            key = "heights"
        elif len(arrays) == 1:
            key = arrays[0]
        else:
            raise TextureFileError(f"{name}: a .npz file needs an array named 'heights' "
                                   f"(found {', '.join(keys) or 'none'})")
        out = []
        for k in (key, "mask"):
            info = members.get(k)
            if info is None:
                out.append(None)
                continue
            what = f"array {k!r}"
            try:
                with zf.open(info) as fh:
                    head = fh.read(_HEADER_PEEK)
                shape, _, dtype, offset = _header(io.BytesIO(head), name, what)
                _check_shape(shape, name, what, info.file_size - offset, dtype.itemsize,
                             point_bytes, two_d)
                raw = zf.read(info)
            except (zipfile.BadZipFile, OSError, EOFError, ValueError) as exc:
                raise TextureFileError(f"{name}: {what} cannot be read from the archive "
                                       f"({one_line(exc)})") from None
            out.append(_npy(raw, name, what, 0, two_d, as_float=k != "mask"))
    return out[0], out[1]


def load_array(data: bytes, suffix: str, name, point_bytes: float = 0.0,
               two_d: bool = False) -> np.ndarray:
    """A float array from .npy/.npz bytes (``two_d``: a 2-D one), masked pixels (npz
    'mask') as NaN.

    point_bytes: memory per grid point the caller will need beyond reading (checked with
    the header, before the data is expanded)."""
    pb = READ_BYTES_PER_POINT + float(point_bytes)
    if data[:2] == b"PK" or suffix == ".npz":
        if data[:2] != b"PK":
            raise TextureFileError(f"{name}: not a .npz archive")
        arr, mask = _npz(data, name, pb, two_d)
    else:
        arr, mask = _npy(data, name, "the array", pb, two_d), None
    if arr.dtype.kind == "b":
        raise TextureFileError(f"{name}: the array holds booleans (a mask?), not heights")
    if mask is not None:
        if mask.shape != arr.shape or mask.dtype.kind not in "bi":
            raise TextureFileError(f"{name}: 'mask' must be a boolean array of the shape of "
                                   f"the heights {arr.shape}, got {mask.dtype} {mask.shape}")
        arr[mask.astype(bool)] = np.nan
    return arr


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
         height_scale: float, point_bytes: float = 0.0) -> HeightMap:
    if unit is None or pixel_size is None:
        missing = " and ".join(k for k, v in (("unit", unit), ("pixel_size", pixel_size))
                               if v is None)
        raise InputError(f"{name}: a {suffix} height map carries no length unit or pixel size; "
                         f"pass {missing} (unit one of {UNIT_HELP}; pixel_size in that unit, "
                         f"a number or (dx, dy))")
    factor = unit_factor(unit)
    dx, dy = pixel_pair(pixel_size, factor)
    z = load_array(data, suffix, name, point_bytes, two_d=True)
    if factor != 1.0:
        z *= factor                       # z is a fresh array (converted from the file's data)
    return finish_heightmap(z, dx, dy, name.name, height_scale, name, copy=False)
