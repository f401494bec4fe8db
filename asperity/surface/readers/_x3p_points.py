"""The points of an x3p file (:mod:`.x3p` reads its header): the binary member or the
inline ``DataList``, the valid-points member, and the grid they form.

Per point, the file stores the values of its *absolute* axes in x, y, z order (an
incremental axis has no stored values: its coordinate is ``index * Increment``), x running
fastest; a value is ``raw * Increment + Offset``.  Binary data is little-endian, packed.
"""
from __future__ import annotations

import math
import zipfile
import zlib
from dataclasses import dataclass

import numpy as np

from ...errors import InputError, TextureFileError
from ...progress import report
from ..topography import one_line

X3P_DTYPES = {"I": "<i2", "L": "<i4", "F": "<f4", "D": "<f8"}
DTYPE_NAMES = "I (int16), L (int32), F (float32), D (float64)"
#: bytes of the binary member read per piece (Ctrl-C is honoured between pieces)
PIECE = 1 << 24
#: Datum entries converted at once
_BATCH = 1 << 16
#: values scaled at once
_SCALE_PIECE = 1 << 20
#: a regular grid's coordinates may deviate from it by this share of the spacing
GRID_TOLERANCE = 1e-3


@dataclass(frozen=True)
class Axis:
    """One axis of Record1: absolute (values stored per point) or incremental."""

    label: str              # CX, CY or CZ
    absolute: bool
    code: str               # DataType: I, L, F or D
    increment: float
    offset: float


@dataclass(frozen=True)
class Layout:
    """What Record1 and Record3 say about the points."""

    nx: int
    ny: int
    axes: tuple             # (CX, CY, CZ)
    member: str | None      # binary point data member; None: inline DataList
    valid_member: str | None

    @property
    def n(self) -> int:
        return self.nx * self.ny

    @property
    def stored(self) -> list:
        """The absolute axes, whose values every point stores (x, y, z order)."""
        return [a for a in self.axes if a.absolute]

    @property
    def record(self) -> np.dtype:
        return np.dtype([(a.label, X3P_DTYPES[a.code]) for a in self.stored])


def _real(raw: np.ndarray, axis: Axis, name) -> np.ndarray:
    """float64 ``raw * Increment + Offset`` in a fresh array."""
    return _scale(raw.astype(np.float64), axis, name)


def _scale(v: np.ndarray, axis: Axis, name) -> np.ndarray:
    """``v * Increment + Offset`` in place (in pieces: no temporary of the whole grid);
    TextureFileError, and no RuntimeWarning, when a finite value leaves the float range
    (an Increment or Offset that cannot be right)."""
    if axis.increment == 1.0 and axis.offset == 0.0:
        return v
    for lo in range(0, v.size, _SCALE_PIECE):
        piece = v[lo:lo + _SCALE_PIECE]
        finite = np.isfinite(piece)
        with np.errstate(over="ignore", invalid="ignore"):
            if axis.increment != 1.0:
                piece *= axis.increment
            if axis.offset != 0.0:
                piece += axis.offset
        lost = finite & ~np.isfinite(piece)
        if lost.any():
            raise TextureFileError(f"{name}: x3p {axis.label} Increment {axis.increment:g} "
                                   f"and Offset {axis.offset:g} take values beyond the float "
                                   f"range; check the axis's Increment and Offset")
    return v


def read_binary(zf: zipfile.ZipFile, layout: Layout, name) -> dict:
    """{axis label: (n,) float64 real values} of the binary point member, read in pieces."""
    member = layout.member
    try:
        info = zf.getinfo(member)
    except KeyError:
        raise TextureFileError(f"{name}: x3p point data {member!r} missing from the "
                               f"archive") from None
    rec = layout.record
    need = layout.n * rec.itemsize
    if info.file_size != need:
        codes = "+".join(a.code for a in layout.stored)
        raise TextureFileError(f"{name}: {member} holds {info.file_size} bytes, "
                               f"{layout.nx} x {layout.ny} {codes} values need {need}")
    buf = np.empty(layout.n, dtype=rec)
    view = memoryview(buf.view(np.uint8))
    pos = 0
    try:
        with zf.open(info) as fh:
            while pos < need:
                piece = fh.read(min(PIECE, need - pos))
                if not piece:
                    break
                view[pos:pos + len(piece)] = piece
                pos += len(piece)
                report(pos / need, "reading x3p")
            if pos == need and fh.read(1):
                pos += 1
    except (zipfile.BadZipFile, zlib.error, EOFError, OSError, NotImplementedError,
            ValueError) as exc:
        raise TextureFileError(f"{name}: {member} cannot be read ({one_line(exc)})") from None
    if pos != need:
        raise TextureFileError(f"{name}: {member} holds {'more' if pos > need else 'fewer'} "
                               f"bytes than its {need} declared")
    del view
    out = {a.label: _real(buf[a.label], a, name) for a in layout.stored}
    del buf
    return out


def read_valid(zf: zipfile.ZipFile, layout: Layout, name) -> np.ndarray | None:
    """(n,) bool, True for valid points, from the valid-points member (None: none)."""
    member = layout.valid_member
    if member is None:
        return None
    try:
        info = zf.getinfo(member)
    except KeyError:
        raise TextureFileError(f"{name}: x3p valid-points file {member!r} missing from the "
                               f"archive") from None
    need = (layout.n + 7) // 8
    if info.file_size < need:
        raise TextureFileError(f"{name}: {member} holds {info.file_size} bytes, {layout.n} "
                               f"points need {need}")
    try:
        with zf.open(info) as fh:
            raw = fh.read(need)
    except (zipfile.BadZipFile, zlib.error, EOFError, OSError, NotImplementedError) as exc:
        raise TextureFileError(f"{name}: {member} cannot be read ({one_line(exc)})") from None
    if len(raw) < need:
        raise TextureFileError(f"{name}: {member} ends early")
    bits = np.frombuffer(raw, dtype=np.uint8)
    return np.unpackbits(bits, count=layout.n, bitorder="little").view(bool)


class InlinePoints:
    """The ``Datum`` entries of an inline ``DataList``, converted in batches: each holds
    the values of the absolute axes separated by ';'; an empty one is a missing point."""

    def __init__(self, layout: Layout, name):
        self.layout = layout
        self.name = name
        self.k = 0
        self.pending: list = []
        self.values = np.full((len(layout.stored), layout.n), np.nan)

    def add(self, text) -> None:
        self.pending.append(text)
        if len(self.pending) >= _BATCH:
            self.flush()

    def flush(self) -> None:
        texts, self.pending = self.pending, []
        n, m = self.layout.n, len(self.layout.stored)
        if self.k + len(texts) > n:
            raise TextureFileError(f"{self.name}: main.xml holds more Datum entries than the "
                                   f"{self.layout.nx} x {self.layout.ny} points of its "
                                   f"MatrixDimension")
        out = self.values
        labels = ", ".join(a.label for a in self.layout.stored)
        for t in texts:
            if t is not None and t.strip():
                parts = t.split(";")
                if len(parts) != m:
                    raise TextureFileError(f"{self.name}: main.xml Datum {self.k + 1} holds "
                                           f"{_short(t)}; expected {m} value(s) separated by "
                                           f"';' ({labels})")
                for c, p in enumerate(parts):
                    if p.strip():
                        try:
                            out[c, self.k] = float(p)
                        except ValueError:
                            raise TextureFileError(f"{self.name}: main.xml Datum {self.k + 1}: "
                                                   f"{_short(p)} is not a number") from None
            self.k += 1
        report(self.k / n, "reading x3p")

    def finish(self) -> dict:
        self.flush()
        if self.k != self.layout.n:
            raise TextureFileError(f"{self.name}: main.xml holds {self.k} Datum entries, its "
                                   f"MatrixDimension {self.layout.nx} x {self.layout.ny} "
                                   f"needs {self.layout.n}")
        out = {}
        for c, a in enumerate(self.layout.stored):
            out[a.label] = _scale(self.values[c], a, self.name)
        self.values = None
        return out


def _short(text: str) -> str:
    t = text.strip()
    return repr(t if len(t) <= 40 else t[:37] + "...")


def assemble(values: dict, valid, layout: Layout, name):
    """(heights (nx, ny) view, dx, dy): missing points NaN, absolute x/y turned into the
    spacing of the regular grid they must form (a decreasing axis is flipped)."""
    cx, cy, _ = layout.axes
    z = values["CZ"]
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(z)            # NaN, or the +inf some instruments write
    if valid is not None:
        bad |= ~valid
    for a in (cx, cy):
        if a.absolute:
            bad |= ~np.isfinite(values[a.label])
    z[bad] = np.nan
    shape = (layout.ny, layout.nx)      # x runs fastest in the file
    heights = z.reshape(shape).T
    ok = ~bad.reshape(shape).T
    if not ok.any():
        raise TextureFileError(f"{name}: every pixel is undefined")
    dx = cx.increment if not cx.absolute else \
        _spacing(values[cx.label].reshape(shape).T, ok, 0, cx, name)
    dy = cy.increment if not cy.absolute else \
        _spacing(values[cy.label].reshape(shape).T, ok, 1, cy, name)
    if dx < 0:
        heights, dx = heights[::-1, :], -dx
    if dy < 0:
        heights, dy = heights[:, ::-1], -dy
    return heights, dx, dy


def _spacing(c: np.ndarray, ok: np.ndarray, along: int, axis: Axis, name) -> float:
    """Spacing of absolute coordinates ``c[i, j]`` that must depend on the index ``along``
    (0: i, 1: j) only, evenly spaced; else InputError naming what the file is."""
    other = 1 - along
    counts = ok.sum(axis=other)
    sums = np.where(ok, c, 0.0).sum(axis=other)
    k = np.flatnonzero(counts)
    what = "x" if axis.label == "CX" else "y"
    if k.size < 2:
        raise InputError(f"{name}: an x3p with absolute {what} coordinates whose defined points "
                         f"lie on one grid line: no spacing; asperity reads areal grids")
    w = counts[k].astype(np.float64)
    mean = sums[k] / w
    km = np.average(k, weights=w)
    d = float(np.sum(w * (k - km) * (mean - np.average(mean, weights=w))) /
              np.sum(w * (k - km) ** 2))
    c0 = float(np.average(mean, weights=w)) - d * km
    line = c0 + d * np.arange(c.shape[along])
    dev = np.abs(c - np.expand_dims(line, other))
    dev[~ok] = 0.0
    worst = float(dev.max())
    scale = float(np.max(np.abs(mean))) + abs(d) * c.shape[along]
    eps = 0.0 if axis.code in "IL" else float(np.finfo(X3P_DTYPES[axis.code]).eps)
    tol = GRID_TOLERANCE * abs(d) + 8 * eps * scale
    if not (d != 0 and math.isfinite(d) and worst <= tol):
        raise InputError(f"{name}: an x3p whose absolute {what} coordinates do not form a "
                         f"regular grid (they deviate up to {worst:.3g} m from a spacing of "
                         f"{abs(d):.3g} m); asperity reads regular grids")
    return d
