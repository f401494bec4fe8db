"""Height maps read a few lines at a time, for scans derived in tiles
(:mod:`asperity.surface.tiles`): the file is opened by whoever reads a tile (a Dask worker
reads its tiles from the path itself), and only the lines asked for are held.

A *line* is what the file stores contiguously: a row ``heights[i, :]`` of a C-ordered
``.npy`` (``axis`` 0), a column ``heights[:, j]`` of a Fortran-ordered one, a line of
points of an ``.x3p`` (x runs fastest: one y) or a line of a text matrix (one y) (``axis``
1).  Every value goes through the same conversions as the whole-file readers (data type,
unit, increments and offsets, invalid points, ``height_scale``), so a tile holds exactly
the numbers of the same pixels of the map read whole.

Streamed: ``.npy`` (memory-mapped, one tile's lines at a time), ``.x3p`` whose points are
a binary member on incremental x/y axes (the member read in pieces, forward; a tile
behind the current position reopens it), uncompressed text matrices (an index of line
offsets, then the lines of a tile parsed as they are read).  :func:`open_lines` returns
None for the other files (gzip, ``.npz``, instrument formats, inline or absolute-axis
x3p), which are read whole.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import TextureFileError
from ..topography import (
    check_height_scale,
    check_stated_pixel,
    given_sizes,
    one_line,
    pixel_pair,
    unit_factor,
)
from ._files import split_suffix, surface_path
from ._lines import LineSource

#: bytes read per piece from a zip member (Ctrl-C is honoured between pieces)
_PIECE = 1 << 24
#: lines of an x3p member kept after a read (the next tile's halo and spike window)
_TAIL_LINES = 16


class NpyLines(LineSource):
    """A ``.npy`` array, memory-mapped tile by tile (unit and scale applied as
    :mod:`.array` does: float64, x unit factor, x height_scale)."""

    def __init__(self, path, name, factor=1.0, height_scale=1.0, dx=None, dy=None):
        from .array import _check_shape, _header
        with open(path, "rb") as fh:
            shape, fortran, dtype, offset = _header(fh, name, "the array")
        _check_shape(shape, name, "the array", Path(path).stat().st_size - offset,
                     dtype.itemsize, None)
        if dtype.kind == "b":
            raise TextureFileError(f"{name}: the array holds booleans (a mask?), not heights")
        super().__init__(path, shape, dx, dy, Path(name).name)
        self.name = str(name)
        self.axis = 1 if fortran and min(shape) > 1 else 0
        self.dtype, self.offset = dtype, offset
        self.factor, self.height_scale = float(factor), float(height_scale)

    def lines(self, a, b):
        length = self.shape[1 - self.axis]
        mm = np.memmap(self.path, dtype=self.dtype, mode="r",
                       offset=self.offset + a * length * self.dtype.itemsize,
                       shape=(b - a, length))
        z = mm.astype(np.float64)
        del mm                               # unmapped: the tile's pages leave the RSS
        if self.dx is not None:
            check_finite_heights(z, self.name)
        if self.factor != 1.0:
            z *= self.factor
        if self.height_scale != 1.0:
            z *= self.height_scale
        return z if self.axis == 0 else z.T


class X3pLines(LineSource):
    """The binary point member of an ``.x3p`` on incremental x/y axes, read forward in
    pieces (values as :func:`._x3p_points.read_binary` and ``assemble`` make them)."""

    axis = 1

    def __init__(self, path, name, layout, height_scale, factor: float = 1.0, pixel=None):
        cx, cy, cz = layout.axes
        dx, dy = pixel or (cx.increment * factor, cy.increment * factor)
        if pixel is None:
            check_stated_pixel(name, dx, dy, "metres" if factor == 1.0 else "that unit")
        super().__init__(path, (layout.nx, layout.ny), dx, dy, Path(name).name)
        self.layout, self.name = layout, str(name)
        self.height_scale = float(height_scale) * factor

    def _member(self, which, start):
        """[open member, position, archive] (``which``: 'data' or 'valid') at or before
        byte ``start``: the open one when it has not passed ``start`` (or keeps the
        bytes since in its tail), else the member opened again."""
        import zipfile
        key = "_h" + which
        h = getattr(self, key, None)
        if h is None or h[3] > start:
            if h is not None:
                h[0].close()
                h[2].close()
            zf = zipfile.ZipFile(self.path)
            member = self.layout.member if which == "data" else self.layout.valid_member
            h = [zf.open(member), 0, zf, 0, b""]      # file, position, archive, tail start, tail
            setattr(self, key, h)
        return h

    def _read(self, which, start, count) -> bytes:
        """``count`` bytes of the member from byte ``start``: read forward; the last lines
        read are kept (the next tile starts with the halo line of this one)."""
        import zipfile
        import zlib
        member = self.layout.member if which == "data" else self.layout.valid_member
        try:
            h = self._member(which, start)
            fh = h[0]
            while h[1] < start:                        # forward: read and drop
                piece = fh.read(min(_PIECE, start - h[1]))
                if not piece:
                    raise EOFError("the member ends early")
                h[1] += len(piece)
                h[3], h[4] = h[1], b""
            parts = [h[4][start - h[3]:start - h[3] + count]] if start < h[1] else []
            got = len(parts[0]) if parts else 0
            while got < count:
                piece = fh.read(min(_PIECE, count - got))
                if not piece:
                    break
                parts.append(piece)
                got += len(piece)
                h[1] += len(piece)
        except (zipfile.BadZipFile, zlib.error, EOFError, OSError, NotImplementedError,
                ValueError, KeyError) as exc:
            raise TextureFileError(f"{self.name}: {member} cannot be read "
                                   f"({one_line(exc)})") from None
        if got != count:
            raise TextureFileError(f"{self.name}: {member} ends early")
        data = b"".join(parts)
        keep = min(len(data), _TAIL_LINES * self.layout.nx * self.layout.record.itemsize)
        h[3], h[4] = start + len(data) - keep, data[len(data) - keep:]
        return data

    def lines(self, a, b):
        from ._x3p_points import _real
        lay = self.layout
        rec = lay.record
        nx = lay.nx
        raw = np.frombuffer(self._read("data", a * nx * rec.itemsize, (b - a) * nx *
                                       rec.itemsize), dtype=rec)
        z = _real(raw["CZ"], lay.axes[2], self.name)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(z)
        if lay.valid_member is not None:
            p0, p1 = a * nx, b * nx
            bits = np.frombuffer(self._read("valid", p0 // 8, (p1 + 7) // 8 - p0 // 8),
                                 dtype=np.uint8)
            valid = np.unpackbits(bits, bitorder="little")[p0 % 8:p0 % 8 + (p1 - p0)]
            bad |= ~valid.view(bool)
        z[bad] = np.nan
        z = z.reshape(b - a, nx).T
        if self.height_scale != 1.0:
            z *= self.height_scale
        return z

    def close(self):
        for key in ("_hdata", "_hvalid"):
            h = getattr(self, key, None)
            if h is not None:
                h[0].close()
                h[2].close()
                setattr(self, key, None)


def _open_x3p(p: Path, height_scale: float, factor: float = 1.0, pixel=None):
    import zipfile
    from .x3p import _parse_main
    try:
        zf = zipfile.ZipFile(p)
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        return None                          # the whole-file reader says what is wrong
    with zf:
        try:
            info = zf.getinfo("main.xml")
        except KeyError:
            return None
        layout, inline = _parse_main(zf, info, p, None)
        if inline is not None or any(a.absolute for a in layout.axes[:2]):
            return None
        try:
            data = zf.getinfo(layout.member)
        except KeyError:
            raise TextureFileError(f"{p}: x3p point data {layout.member!r} missing from the "
                                   f"archive") from None
        need = layout.n * layout.record.itemsize
        if data.file_size != need:
            codes = "+".join(a.code for a in layout.stored)
            raise TextureFileError(f"{p}: {layout.member} holds {data.file_size} bytes, "
                                   f"{layout.nx} x {layout.ny} {codes} values need {need}")
        if layout.valid_member is not None:
            try:
                v = zf.getinfo(layout.valid_member)
            except KeyError:
                raise TextureFileError(f"{p}: x3p valid-points file {layout.valid_member!r} "
                                       f"missing from the archive") from None
            if v.file_size < (layout.n + 7) // 8:
                raise TextureFileError(f"{p}: {layout.valid_member} holds {v.file_size} "
                                       f"bytes, {layout.n} points need {(layout.n + 7) // 8}")
    return X3pLines(p, p, layout, height_scale, factor, pixel)


def open_lines(path, *, unit=None, pixel_size=None, height_scale=1.0):
    """A :class:`LineSource` of a height-map file that can be streamed, else None (read it
    whole).  Refuses what the whole-file readers refuse (missing unit, pixel size ...)."""
    from .text import open_text_lines
    p = surface_path(path)
    height_scale = check_height_scale(height_scale)
    suffix, gz = split_suffix(p)
    if gz or not p.is_file():
        return None
    if suffix == ".npy":
        if unit is None or pixel_size is None:
            return None                      # the whole-file reader's message
        f = unit_factor(unit)
        dx, dy = pixel_pair(pixel_size, f)
        return NpyLines(p, p, f, height_scale, dx, dy)
    if suffix == ".x3p":
        factor, pixel = given_sizes(p, unit, pixel_size)
        return _open_x3p(p, height_scale, factor or 1.0, pixel)
    if suffix in (".txt", ".asc", ".csv", ".dat"):
        return open_text_lines(p, unit, pixel_size, height_scale)
    return None


def check_finite_heights(z: np.ndarray, name) -> None:
    """Refuse infinite heights as the whole-file readers do."""
    with np.errstate(invalid="ignore"):
        if np.isinf(z).any():
            raise TextureFileError(f"{name}: the heights contain infinite values")
