"""ASCII matrices (``.txt .asc .csv .dat``), with or without a header.

One line per y (the first line is y = 0), one column per x, so ``heights = matrix.T``;
values separated by blanks, tabs, commas or semicolons; ``nan`` marks undefined pixels.  A
header is read when present: Gwyddion-style ``# Width: 10.00 µm`` / ``# Height: 10.00 µm`` /
``# Value units: m`` lines, and ``key=value`` lines as in ``h=305 w=75`` /
``pixel size=3.69862e-007 m`` / ``data unit=rad`` / ``height conversion factor
(-> m)=2.91818e-008``.  Width and Height are the physical size of the whole scan and the
spacing is ``width / nx`` (as in SurfaceTopography, whose ``physical_sizes`` are
``nx * dx``).  What the header does not state must be passed (``unit`` for the heights,
``pixel_size``); explicit arguments override the header.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ...resources import check_memory
from ..topography import UNIT_HELP, HeightMap, finish_heightmap, pixel_pair, unit_factor
from ._files import SMALLER_SCAN
from ._lines import LineSource

_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_SEPARATORS = re.compile(r"[\s,;]+")


def _decode(data: bytes) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _is_number(tok: str) -> bool:
    try:
        float(tok)
    except ValueError:
        return False
    return True


def parse_text_matrix(data: bytes, name) -> tuple[np.ndarray, dict[str, str], int]:
    """(matrix as in the file: rows = lines, header {lowercase key: value}, header lines).

    Leading lines that are not rows of numbers form the header: ``# key: value`` and
    ``key=value`` entries (several per line, as ``h=305 w=75``) are collected; other header
    lines are ignored.  After the first row of numbers every non-blank line must be a row
    of numbers with the same count; '#' comment lines are skipped anywhere.
    """
    if b"\x00" in data[:4096]:
        raise TextureFileError(f"{name}: a text matrix was expected, this is a binary file")
    check_memory(4.0 * len(data), f"{name}: parsing this text matrix", SMALLER_SCAN)
    text = _decode(data)
    header: dict[str, str] = {}
    rows: list[np.ndarray] = []               # converted line by line: 8 bytes per value
    n_header = 0
    width = None
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#") or line.startswith("%"):
            if not rows:
                n_header += 1
                _header_entry(line.lstrip("#%").strip(), header)
            continue
        toks = [t for t in _SEPARATORS.split(line) if t]
        if not rows and not all(_is_number(t) for t in toks):
            n_header += 1
            _header_entry(line, header)
            continue
        if width is None:
            width = len(toks)
        elif len(toks) != width:
            raise TextureFileError(f"{name}: line {lineno} has {len(toks)} values, the matrix "
                                   f"rows above have {width}")
        try:
            rows.append(np.array(toks, dtype=np.float64))
        except ValueError:
            bad = next((t for t in toks if not _is_number(t)), "?")
            raise TextureFileError(f"{name}: line {lineno}: {bad[:40]!r} in the matrix is not "
                                   f"a number") from None
    if not rows:
        raise TextureFileError(f"{name}: no matrix of numbers found (rows of values separated by "
                               f"blanks, tabs, commas or semicolons)")
    m = np.array(rows, dtype=np.float64)
    del rows
    if np.isinf(m).any():
        raise TextureFileError(f"{name}: the matrix contains infinite values")
    return m, header, n_header


def _header_entry(line: str, header: dict[str, str]) -> None:
    if "=" in line:
        # key=value pairs; several may share a line ("h=305 w=75")
        parts = re.findall(r"([^=]+?)\s*=\s*([^=]*?)(?=\s+[^\s=]+\s*=|$)", line)
        for k, v in parts:
            header[k.strip().lower()] = v.strip()
    elif ":" in line:
        k, v = line.split(":", 1)
        header[k.strip().lower()] = v.strip()


def _header_length(header: dict[str, str], key: str, unit, name) -> float:
    """A 'number unit' header value in metres (the unit from the value, else ``unit``)."""
    raw = header[key]
    m = _NUMBER_UNIT.match(raw)
    if not m:
        raise TextureFileError(f"{name}: header entry {key!r} should be a number and a length "
                               f"unit, got {raw!r}")
    value, u = float(m.group(1)), m.group(2)
    if u:
        try:
            f = unit_factor(u)
        except InputError:
            raise TextureFileError(f"{name}: header entry {key!r} has unit {u!r}; allowed: "
                                   f"{UNIT_HELP}") from None
    elif unit is not None:
        f = unit_factor(unit)
    else:
        raise TextureFileError(f"{name}: header entry {key!r} = {raw!r} gives no unit; pass unit")
    if not (value > 0 and math.isfinite(value)):
        raise TextureFileError(f"{name}: header entry {key!r} must be positive, got {raw!r}")
    return value * f


_WIDTH_KEYS = ("width", "x-length", "x length", "xlength")
_HEIGHT_KEYS = ("height", "y-length", "y length", "ylength")
_VALUE_UNIT_KEYS = ("value units", "value unit", "data unit", "z unit", "zunit", "units")
_FACTOR_KEYS = ("height conversion factor (-> m)", "height conversion factor")
_PIXEL_KEYS = ("pixel size", "pixel_size", "pixelsize")


def _first_key(header: dict[str, str], keys) -> str | None:
    return next((k for k in keys if k in header), None)


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
                         height_scale: float, point_bytes: float = 0.0) -> HeightMap:
    m, header, _ = parse_text_matrix(data, name)
    ny, nx = m.shape
    zfac, dx, dy = text_scales(header, nx, ny, unit, pixel_size, name)
    return finish_heightmap(m.T * zfac, dx, dy, name.name, height_scale, name)


def text_scales(header: dict, nx: int, ny: int, unit, pixel_size, name):
    """(metres per number in the file, dx, dy) of a text matrix of ``ny`` lines of ``nx``
    values from its header and the caller's unit and pixel size."""
    # grid counts stated in the header must match the matrix
    for key, n, what in (("w", nx, "columns"), ("h", ny, "rows")):
        if key in header:
            try:
                stated = int(float(header[key]))
            except ValueError:
                raise TextureFileError(f"{name}: header entry {key}={header[key]!r} is not a "
                                       f"whole number") from None
            if stated != n:
                raise TextureFileError(f"{name}: header says {key}={stated} but the matrix has "
                                       f"{n} {what}")
    # heights: metres per number in the file
    if unit is not None:
        zfac = unit_factor(unit)
    elif (k := _first_key(header, _FACTOR_KEYS)) is not None:
        try:
            zfac = float(header[k])
        except ValueError:
            raise TextureFileError(f"{name}: header entry {k!r} is not a number: "
                                   f"{header[k]!r}") from None
        if not (math.isfinite(zfac) and zfac != 0):
            raise TextureFileError(f"{name}: header entry {k!r} must be a non-zero number")
    elif (k := _first_key(header, _VALUE_UNIT_KEYS)) is not None:
        try:
            zfac = unit_factor(header[k])
        except InputError:
            raise InputError(f"{name}: the values are in {header[k]!r}, not a length unit "
                             f"({UNIT_HELP}); pass unit to read them as lengths") from None
    else:
        raise InputError(f"{name}: the text matrix states no height unit; pass unit "
                         f"(one of {UNIT_HELP}; on the command line --unit)")
    # spacing
    if pixel_size is not None:
        if unit is None:
            raise InputError(f"{name}: pixel_size is given in unit; pass unit too "
                             f"(one of {UNIT_HELP})")
        dx, dy = pixel_pair(pixel_size, unit_factor(unit))
    elif (k := _first_key(header, _PIXEL_KEYS)) is not None:
        dx = dy = _header_length(header, k, unit, name)
    else:
        kw, kh = _first_key(header, _WIDTH_KEYS), _first_key(header, _HEIGHT_KEYS)
        if kw is not None and kh is not None:
            dx = _header_length(header, kw, unit, name) / nx
            dy = _header_length(header, kh, unit, name) / ny
        else:
            part = (f" (the header gives {'Width' if kw else 'Height'} only)"
                    if (kw or kh) else "")
            raise InputError(f"{name}: the text matrix states no pixel size{part}; pass "
                             f"pixel_size (in unit, a number or (dx, dy))")
    return zfac, dx, dy


def open_text_lines(p: Path, unit, pixel_size, height_scale):
    """A :class:`~._streams.TextLines` of an uncompressed text matrix: the header read and
    the offset of every matrix line indexed (values are parsed tile by tile); None for a
    file whose lines do not end in newlines."""
    header: dict[str, str] = {}
    offsets, linenos = [], []
    width = None
    with open(p, "rb") as fh:
        head = fh.read(4096)
        if b"\x00" in head:
            raise TextureFileError(f"{p}: a text matrix was expected, this is a binary file")
        if b"\r" in head.replace(b"\r\n", b""):
            return None                      # old Mac line ends: read whole
        fh.seek(0)
        pos = 0
        for lineno, raw in enumerate(fh, start=1):
            off, pos = pos, pos + len(raw)
            if lineno == 1 and raw.startswith(b"\xef\xbb\xbf"):
                raw = raw[3:]
                off += 3
            line = raw.strip()
            if not line:
                continue
            if line[:1] in (b"#", b"%"):
                if width is None:
                    _header_entry(_decode(line).lstrip("#%").strip(), header)
                continue
            if width is None:
                text = _decode(line)
                toks = [t for t in _SEPARATORS.split(text) if t]
                if not all(_is_number(t) for t in toks):
                    _header_entry(text, header)
                    continue
                width = len(toks)
            offsets.append(off)
            linenos.append(lineno)
    if width is None:
        raise TextureFileError(f"{p}: no matrix of numbers found (rows of values separated by "
                               f"blanks, tabs, commas or semicolons)")
    zfac, dx, dy = text_scales(header, width, len(offsets), unit, pixel_size, p)
    return TextLines(p, width, np.array(offsets, dtype=np.int64),
                     np.array(linenos, dtype=np.int64), zfac, dx, dy, height_scale)


def parse_lines(fh, count: int, width: int, linenos, name) -> np.ndarray:
    """(count, width) values of the next ``count`` matrix lines of ``fh`` (blank and '#'
    lines skipped), with the whole-file reader's messages."""
    rows = np.empty((count, width))
    k = 0
    while k < count:
        raw = fh.readline()
        if not raw:
            raise TextureFileError(f"{name}: the file ended early (changed while read?)")
        line = raw.decode("latin-1").strip()
        if not line or line[0] in "#%":
            continue
        toks = [t for t in _SEPARATORS.split(line) if t]
        if len(toks) != width:
            raise TextureFileError(f"{name}: line {linenos[k]} has {len(toks)} values, the "
                                   f"matrix rows above have {width}")
        try:
            rows[k] = np.array(toks, dtype=np.float64)
        except ValueError:
            bad = next((t for t in toks if not _is_number(t)), "?")
            raise TextureFileError(f"{name}: line {linenos[k]}: {bad[:40]!r} in the matrix is "
                                   f"not a number") from None
        k += 1
    if np.isinf(rows).any():
        raise TextureFileError(f"{name}: the matrix contains infinite values")
    return rows


class TextLines(LineSource):
    """A text matrix (one line per y), its lines parsed tile by tile."""

    axis = 1

    def __init__(self, path, width, offsets, linenos, zfac, dx, dy, height_scale):
        super().__init__(path, (width, offsets.size), dx, dy, Path(path).name)
        self.name = str(path)
        self.offsets, self.linenos = offsets, linenos
        self.zfac, self.height_scale = float(zfac), float(height_scale)

    def lines(self, a, b):
        with open(self.path, "rb") as fh:
            fh.seek(int(self.offsets[a]))
            rows = parse_lines(fh, b - a, self.shape[0], self.linenos[a:b], self.name)
        z = rows.T * self.zfac
        if self.height_scale != 1.0:
            z *= self.height_scale
        return z
