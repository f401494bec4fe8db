"""Reading measured surfaces: height maps and triangle meshes, in metres.

Two kinds of surface come out of :func:`read_surface`:

* :class:`HeightMap` -- heights on a regular grid, ``heights[i, j] = z(x_i, y_j)`` with
  ``x_i = i dx`` and ``y_j = j dy`` (the first index runs along x), NaN where the
  instrument recorded nothing;
* :class:`TriangleMesh` -- vertices and triangles of an open (or closed) sheet.

Formats, chosen by the file's suffix; a trailing ``.gz`` is decompressed first, for
every format (``surface.stl.gz``, ``matrix.txt.gz``, ``scan.x3p.gz`` ...):

``.stl .obj .ply`` (meshes, read by trimesh)
    Mesh files carry no length unit, so ``unit`` is required.  Vertices with identical
    coordinates are merged, and degenerate triangles (a repeated vertex or zero area)
    are dropped and counted in :attr:`TriangleMesh.n_degenerate`.
``.npy`` / ``.npz`` (height maps)
    The array is ``heights[i, j]`` as in :class:`HeightMap` (first index along x), in
    ``unit``, on a grid of spacing ``pixel_size``; both are required.  NaN marks
    undefined pixels.  A ``.npz`` holds the array as ``heights`` (or as its only
    array) and optionally a boolean ``mask`` (True = undefined).
``.txt .asc .csv .dat`` (ASCII matrix)
    One line per y (the first line is y = 0), one column per x, so
    ``heights = matrix.T``; values separated by blanks, tabs, commas or semicolons;
    ``nan`` marks undefined pixels.  A header is read when present: Gwyddion-style
    ``# Width: 10.00 µm`` / ``# Height: 10.00 µm`` / ``# Value units: m`` lines, and
    ``key=value`` lines as in ``h=305 w=75`` / ``pixel size=3.69862e-007 m`` /
    ``data unit=rad`` / ``height conversion factor (-> m)=2.91818e-008``.  Width and
    Height are the physical size of the whole scan and the spacing is ``width / nx``
    (as in SurfaceTopography, whose ``physical_sizes`` are ``nx * dx``).  What the
    header does not state must be passed (``unit`` for the heights, ``pixel_size``);
    explicit arguments override the header (``unit`` then applies to the raw numbers
    in the file, ``pixel_size`` to the spacing).
``.x3p`` (ISO 25178-72) and the instrument formats (``.mi .sur .opd .datx .plu .nms``, ...)
    Read with SurfaceTopography (the ``metrology`` extra), which knows the units and
    pixel sizes from the file.  Of a multi-channel file (``.mi``) the first height
    channel is read, and :attr:`HeightMap.source` names it.  ``.x3p`` files are read by the built-in reader (:func:`read_x3p`, about 30 times
    faster and tolerant of an empty z-offset element), SurfaceTopography being the
    fallback for x3p variants it does not know.

Every error a user can cause (missing file, unknown suffix or unit, malformed header or
matrix, non-positive pixel size) is an :class:`~asperity.errors.InputError` (a
:class:`~asperity.errors.TextureFileError` for a file that does not follow its format)
with a one-line message naming the file.

The heavy libraries (trimesh, SurfaceTopography, zip and XML parsing) are imported only
when a file needs them.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .errors import InputError, TextureFileError, check_int, check_range

MESH_SUFFIXES = (".stl", ".obj", ".ply")
ARRAY_SUFFIXES = (".npy", ".npz")
TEXT_SUFFIXES = (".txt", ".asc", ".csv", ".dat")
INSTRUMENT_EXAMPLES = (".x3p", ".mi", ".sur", ".opd", ".datx", ".plu", ".nms")

#: length units accepted for ``unit`` (and in text headers): name -> metres
UNITS = {
    "m": 1.0, "metre": 1.0, "meter": 1.0, "metres": 1.0, "meters": 1.0,
    "mm": 1e-3, "millimetre": 1e-3, "millimeter": 1e-3, "millimetres": 1e-3,
    "millimeters": 1e-3,
    "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "micron": 1e-6, "microns": 1e-6,
    "micrometre": 1e-6, "micrometer": 1e-6, "micrometres": 1e-6, "micrometers": 1e-6,
    "nm": 1e-9, "nanometre": 1e-9, "nanometer": 1e-9, "nanometres": 1e-9,
    "nanometers": 1e-9,
}
_UNIT_HELP = "m, mm, um (µm), nm"
_FORMATS_HELP = (".stl .obj .ply (meshes), .npy .npz, .txt .asc .csv .dat (ASCII matrix), "
                 ".x3p, and through SurfaceTopography .mi .sur .opd .datx .plu .nms and other "
                 "instrument formats; any of them may be .gz-compressed")
_METROLOGY_HINT = "pip install 'asperity[metrology]'"


# --- the two surface types ----------------------------------------------------------------

@dataclass(frozen=True)
class HeightMap:
    """Heights on a regular grid, in metres.

    heights     : (nx, ny) float64, ``heights[i, j] = z(x_i = i dx, y_j = j dy)``; NaN marks
                  an undefined pixel
    dx, dy      : grid spacing along x and y, m (> 0)
    source      : file name (and channel) or a description
    n_undefined : number of undefined pixels
    """

    heights: np.ndarray
    dx: float
    dy: float
    source: str = ""
    n_undefined: int = 0

    def __post_init__(self):
        z = np.asarray(self.heights, dtype=np.float64)
        if z.ndim != 2 or z.shape[0] < 1 or z.shape[1] < 1:
            raise InputError(f"{self.source or 'height map'}: heights must be a 2-D array, "
                             f"got shape {z.shape}")
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "dx", _positive_length("dx", self.dx))
        object.__setattr__(self, "dy", _positive_length("dy", self.dy))
        object.__setattr__(self, "n_undefined", int(self.n_undefined))

    @property
    def nx(self) -> int:
        return int(self.heights.shape[0])

    @property
    def ny(self) -> int:
        return int(self.heights.shape[1])

    @property
    def physical_size(self) -> tuple[float, float]:
        """(lx, ly) = (nx dx, ny dy) in metres (the SurfaceTopography convention)."""
        return (self.nx * self.dx, self.ny * self.dy)


@dataclass(frozen=True)
class TriangleMesh:
    """A triangle mesh in metres.

    vertices     : (nv, 3) float64, m
    faces        : (nf, 3) int64 vertex indices; degenerate triangles already removed
    source       : file name or a description
    n_degenerate : number of degenerate triangles of the file that were dropped
    kept_faces   : (nf,) int64, index of each face among the file's triangles (None:
                   ``arange(nf)``); lets a friction map list one value per triangle
                   of the file
    """

    vertices: np.ndarray
    faces: np.ndarray
    source: str = ""
    n_degenerate: int = 0
    kept_faces: np.ndarray | None = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        v = np.asarray(self.vertices, dtype=np.float64)
        f = np.asarray(self.faces)
        name = self.source or "mesh"
        if v.ndim != 2 or v.shape[1] != 3:
            raise InputError(f"{name}: vertices must have shape (nv, 3), got {v.shape}")
        if f.ndim != 2 or f.shape[1] != 3:
            raise InputError(f"{name}: faces must have shape (nf, 3), got {f.shape}")
        f = f.astype(np.int64)
        if f.size and (f.min() < 0 or f.max() >= v.shape[0]):
            raise InputError(f"{name}: face vertex indices must be in [0, {v.shape[0] - 1}]")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)
        object.__setattr__(self, "n_degenerate", int(self.n_degenerate))
        if self.kept_faces is not None:
            k = np.asarray(self.kept_faces, dtype=np.int64)
            if k.shape != (f.shape[0],):
                raise InputError(f"{name}: kept_faces must have one index per face")
            object.__setattr__(self, "kept_faces", k)

    @property
    def n_faces(self) -> int:
        return int(self.faces.shape[0])


Surface = HeightMap | TriangleMesh


# --- small helpers ------------------------------------------------------------------------

def _positive_length(name: str, value) -> float:
    x = check_range(name, value, 0.0, None, low_open=True)
    if not math.isfinite(x):
        raise InputError(f"{name} must be finite, got {x:g}")
    return x


def unit_factor(unit, what: str = "unit") -> float:
    """Metres per ``unit`` (one of :data:`UNITS`), else InputError listing the allowed ones."""
    if isinstance(unit, str):
        key = unit.strip()
        f = UNITS.get(key, UNITS.get(key.lower()))
        if f is not None:
            return f
    raise InputError(f"{what} must be one of {_UNIT_HELP}, got {unit!r}")


def _pixel_pair(pixel_size, factor: float) -> tuple[float, float]:
    """(dx, dy) in metres from a number or a pair, given in a unit of ``factor`` metres."""
    if isinstance(pixel_size, (str, bytes)):
        raise InputError(f"pixel_size must be a number or a pair (dx, dy), got {pixel_size!r}")
    if np.ndim(pixel_size) == 0:
        d = _positive_length("pixel_size", pixel_size)
        return d * factor, d * factor
    vals = list(np.asarray(pixel_size, dtype=object).ravel())
    if len(vals) != 2:
        raise InputError(f"pixel_size must be a number or a pair (dx, dy), got {pixel_size!r}")
    return (_positive_length("pixel_size (dx)", vals[0]) * factor,
            _positive_length("pixel_size (dy)", vals[1]) * factor)


def _split_suffix(path: Path) -> tuple[str, bool]:
    """(format suffix, gzipped?) of a file name, e.g. ('.stl', True) for 'a.stl.gz'."""
    suffixes = [s.lower() for s in path.suffixes]
    if suffixes and suffixes[-1] == ".gz":
        return (suffixes[-2] if len(suffixes) >= 2 else ""), True
    return (suffixes[-1] if suffixes else ""), False


def _read_bytes(path: Path, gz: bool) -> bytes:
    if not path.is_file():
        raise InputError(f"surface file {str(path)!r} does not exist")
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror})") from None
    if gz:
        import gzip
        import zlib
        try:
            data = gzip.decompress(data)
        except (OSError, EOFError, zlib.error) as exc:
            raise TextureFileError(f"{path}: not a valid gzip file ({_one_line(exc)})") from None
    return data


def _one_line(exc: BaseException, limit: int = 160) -> str:
    text = str(exc).strip().splitlines()
    msg = text[0].strip() if text else type(exc).__name__
    return msg if len(msg) <= limit else msg[: limit - 3] + "..."


def _count_undefined(z: np.ndarray) -> int:
    return int(np.count_nonzero(np.isnan(z)))


def _finish_heightmap(z: np.ndarray, dx: float, dy: float, source: str, height_scale: float,
                      name) -> HeightMap:
    z = np.array(z, dtype=np.float64)  # a copy that owns its data
    if np.isinf(z).any():
        raise TextureFileError(f"{name}: the heights contain infinite values")
    if z.ndim != 2 or z.shape[0] < 1 or z.shape[1] < 1:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got shape {z.shape}")
    n_undef = _count_undefined(z)
    if n_undef == z.size:
        raise TextureFileError(f"{name}: every pixel is undefined")
    if height_scale != 1.0:
        z *= height_scale
    return HeightMap(heights=z, dx=dx, dy=dy, source=source, n_undefined=n_undef)


# --- the entry point ----------------------------------------------------------------------

def read_surface(path, *, unit=None, pixel_size=None, height_scale=1.0) -> HeightMap | TriangleMesh:
    """Read a mesh or height-map file (format by suffix, see the module docstring).

    unit         : length unit of the numbers in the file, one of m, mm, um/µm, nm (long
                   names such as 'micrometre' too).  Required for meshes, ``.npy``/``.npz``
                   and text matrices without a value unit in their header; for a text
                   matrix with a header it overrides the header's height unit.  Files
                   in instrument formats state their own unit and pixel size and reject
                   both arguments (unless the file lacks them, then both are required).
    pixel_size   : grid spacing of a height map in ``unit``, a number or (dx, dy).
                   Required for ``.npy``/``.npz`` and headerless text matrices; overrides
                   a text header's sizes (and then needs ``unit``).
    height_scale : factor (> 0) applied to the heights (z) after conversion to metres,
                   e.g. to make nanometre-high AFM relief steep enough for friction work.

    Returns a :class:`HeightMap` or a :class:`TriangleMesh`, in metres.
    """
    p = Path(path)
    hs = _positive_length("height_scale", height_scale)
    suffix, gz = _split_suffix(p)
    if unit is not None:
        unit_factor(unit)                 # fail early on an unknown unit
    if pixel_size is not None and suffix in MESH_SUFFIXES:
        raise InputError(f"{p}: pixel_size applies to height maps, not to a mesh file")
    data = _read_bytes(p, gz)
    if suffix in MESH_SUFFIXES:
        return _read_mesh(data, suffix, p, unit, hs)
    if suffix in ARRAY_SUFFIXES:
        return _read_array(data, suffix, p, unit, pixel_size, hs)
    if suffix in TEXT_SUFFIXES:
        return _read_text_heightmap(data, p, unit, pixel_size, hs)
    return _read_instrument(data, suffix, gz, p, unit, pixel_size, hs)


# --- meshes -------------------------------------------------------------------------------

def _read_mesh(data: bytes, suffix: str, name: Path, unit, height_scale: float) -> TriangleMesh:
    if unit is None:
        raise InputError(f"{name}: a {suffix} mesh file carries no length unit; pass unit "
                         f"(one of {_UNIT_HELP}; on the command line --unit)")
    factor = unit_factor(unit)
    import io
    import logging

    import trimesh
    logging.getLogger("trimesh").setLevel(logging.ERROR)
    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=suffix[1:], process=False,
                            force="mesh")
        vertices = np.asarray(mesh.vertices, dtype=np.float64)
        faces = np.asarray(mesh.faces, dtype=np.int64)
    except Exception as exc:  # trimesh raises many kinds on a malformed file
        raise TextureFileError(f"{name}: not a readable {suffix} mesh ({_one_line(exc)})") from None
    if faces.ndim != 2 or faces.shape[1] != 3 or faces.shape[0] == 0:
        raise TextureFileError(f"{name}: the {suffix} file holds no triangles")
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise TextureFileError(f"{name}: the {suffix} file holds no 3-D vertices")
    used = np.unique(faces)
    if used.size and (used[0] < 0 or used[-1] >= vertices.shape[0]):
        raise TextureFileError(f"{name}: a triangle refers to a vertex that does not exist")
    if not np.all(np.isfinite(vertices[used])):
        raise TextureFileError(f"{name}: vertex coordinates must be finite numbers")
    # merge vertices with identical coordinates (STL repeats them for every triangle),
    # numbered in order of first appearance
    uniq, first, inverse = np.unique(vertices, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    vertices = uniq[order]
    faces = rank[np.asarray(inverse).ravel()][faces]
    keep = ~_degenerate(vertices, faces)
    # drop vertices no kept triangle uses
    kept = faces[keep]
    used = np.unique(kept)
    remap = np.full(vertices.shape[0], -1, dtype=np.int64)
    remap[used] = np.arange(used.size)
    vertices = vertices[used] * factor
    if height_scale != 1.0:
        vertices[:, 2] *= height_scale
    if kept.shape[0] == 0:
        raise TextureFileError(f"{name}: every triangle of the mesh is degenerate")
    return TriangleMesh(vertices=vertices, faces=remap[kept], source=name.name,
                        n_degenerate=int(np.count_nonzero(~keep)),
                        kept_faces=np.flatnonzero(keep).astype(np.int64))


def _degenerate(vertices: np.ndarray, faces: np.ndarray, rel: float = 1e-12) -> np.ndarray:
    """Triangles with a repeated vertex or (relative to their longest edge) zero area."""
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    repeated = (a == b) | (b == c) | (a == c)
    p0, p1, p2 = vertices[a], vertices[b], vertices[c]
    cross = np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)
    longest2 = np.max(np.stack([np.sum((p1 - p0) ** 2, axis=1), np.sum((p2 - p1) ** 2, axis=1),
                                np.sum((p0 - p2) ** 2, axis=1)]), axis=0)
    return repeated | (cross <= rel * longest2)


# --- arrays -------------------------------------------------------------------------------

def _load_array(data: bytes, suffix: str, name) -> np.ndarray:
    """A float array from .npy/.npz bytes, masked pixels (npz 'mask') as NaN."""
    import io
    try:
        obj = np.load(io.BytesIO(data), allow_pickle=False)
    except Exception as exc:
        raise TextureFileError(f"{name}: not a readable {suffix} file ({_one_line(exc)})") from None
    if suffix == ".npz" or hasattr(obj, "files"):
        if not hasattr(obj, "files"):
            raise TextureFileError(f"{name}: not a .npz archive")
        keys = list(obj.files)
        arrays = [k for k in keys if k != "mask"]
        if "heights" in keys:
            key = "heights"
        elif len(arrays) == 1:
            key = arrays[0]
        else:
            raise TextureFileError(f"{name}: a .npz file needs an array named 'heights' "
                                   f"(found {', '.join(keys) or 'none'})")
        arr = obj[key]
        mask = obj["mask"] if "mask" in keys else None
    else:
        arr, mask = obj, None
    if arr.dtype.kind not in "biuf":
        raise TextureFileError(f"{name}: the array must hold real numbers, got dtype {arr.dtype}")
    arr = np.array(arr, dtype=np.float64)
    if mask is not None:
        mask = np.asarray(mask)
        if mask.shape != arr.shape or mask.dtype.kind not in "bi":
            raise TextureFileError(f"{name}: 'mask' must be a boolean array of the shape of "
                                   f"the heights {arr.shape}, got {mask.dtype} {mask.shape}")
        arr[mask.astype(bool)] = np.nan
    return arr


def _read_array(data: bytes, suffix: str, name: Path, unit, pixel_size,
                height_scale: float) -> HeightMap:
    if unit is None or pixel_size is None:
        missing = " and ".join(k for k, v in (("unit", unit), ("pixel_size", pixel_size))
                               if v is None)
        raise InputError(f"{name}: a {suffix} height map carries no length unit or pixel size; "
                         f"pass {missing} (unit one of {_UNIT_HELP}; pixel_size in that unit, "
                         f"a number or (dx, dy))")
    factor = unit_factor(unit)
    dx, dy = _pixel_pair(pixel_size, factor)
    z = _load_array(data, suffix, name)
    if z.ndim != 2:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got shape {z.shape}")
    return _finish_heightmap(z * factor, dx, dy, name.name, height_scale, name)


# --- plain-text matrices ------------------------------------------------------------------

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


def _parse_text_matrix(data: bytes, name) -> tuple[np.ndarray, dict[str, str], int]:
    """(matrix as in the file: rows = lines, header {lowercase key: value}, header lines).

    Leading lines that are not rows of numbers form the header: ``# key: value`` and
    ``key=value`` entries (several per line, as ``h=305 w=75``) are collected; other header
    lines are ignored.  After the first row of numbers every non-blank line must be a row
    of numbers with the same count; '#' comment lines are skipped anywhere.
    """
    if b"\x00" in data[:4096]:
        raise TextureFileError(f"{name}: a text matrix was expected, this is a binary file")
    text = _decode(data)
    header: dict[str, str] = {}
    rows: list[list[str]] = []
    linenos: list[int] = []
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
        rows.append(toks)
        linenos.append(lineno)
    if not rows:
        raise TextureFileError(f"{name}: no matrix of numbers found (rows of values separated by "
                               f"blanks, tabs, commas or semicolons)")
    try:
        m = np.array(rows, dtype=np.float64)
    except ValueError:
        k, bad = next(((k, t) for k, r in enumerate(rows) for t in r if not _is_number(t)),
                      (0, "?"))
        raise TextureFileError(f"{name}: line {linenos[k]}: {bad!r} in the matrix is not a "
                               f"number") from None
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
                                   f"{_UNIT_HELP}") from None
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


def _read_text_heightmap(data: bytes, name: Path, unit, pixel_size,
                         height_scale: float) -> HeightMap:
    m, header, _ = _parse_text_matrix(data, name)
    ny, nx = m.shape
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
                             f"({_UNIT_HELP}); pass unit to read them as lengths") from None
    else:
        raise InputError(f"{name}: the text matrix states no height unit; pass unit "
                         f"(one of {_UNIT_HELP}; on the command line --unit)")
    # spacing
    if pixel_size is not None:
        if unit is None:
            raise InputError(f"{name}: pixel_size is given in unit; pass unit too "
                             f"(one of {_UNIT_HELP})")
        dx, dy = _pixel_pair(pixel_size, unit_factor(unit))
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
    return _finish_heightmap(m.T * zfac, dx, dy, name.name, height_scale, name)


# --- x3p (built in) -----------------------------------------------------------------------

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
    hs = _positive_length("height_scale", height_scale)
    suffix, gz = _split_suffix(p)
    return _read_x3p_bytes(_read_bytes(p, gz), p, hs)


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
    return _finish_heightmap(heights, dx, dy, name.name, height_scale, name)


# --- instrument formats through SurfaceTopography ------------------------------------------

_HEIGHT_CHANNEL = re.compile(r"topo|height|z ?sensor|^z$|^default$|surface", re.I)


def _read_instrument(data: bytes, suffix: str, gz: bool, name: Path, unit, pixel_size,
                     height_scale: float) -> HeightMap:
    try:
        import SurfaceTopography  # noqa: F401
        have_st = True
    except ImportError:
        have_st = False
    if suffix == ".x3p":
        if unit is not None or pixel_size is not None:
            raise InputError(f"{name}: an x3p file states its unit (m) and pixel size; do not "
                             f"pass unit or pixel_size (height_scale scales the heights)")
        try:
            return _read_x3p_bytes(data, name, height_scale)
        except InputError:
            if not have_st:
                raise       # the built-in reader's message says what is wrong with the file
        # a variant the built-in reader does not know: SurfaceTopography decides
        return _read_with_surfacetopography(data, suffix, gz, name, None, None, height_scale)
    if not have_st:
        if suffix in INSTRUMENT_EXAMPLES:
            raise InputError(f"{name}: reading {suffix} files needs the metrology extra: "
                             f"{_METROLOGY_HINT}")
        raise InputError(f"{name}: unknown surface file suffix {suffix or '(none)'!r}; "
                         f"supported: {_FORMATS_HELP} (instrument formats need the metrology "
                         f"extra: {_METROLOGY_HINT})")
    return _read_with_surfacetopography(data, suffix, gz, name, unit, pixel_size, height_scale)


def _read_with_surfacetopography(data: bytes, suffix: str, gz: bool, name: Path, unit,
                                 pixel_size, height_scale: float) -> HeightMap:
    import os
    import tempfile

    from SurfaceTopography import open_topography
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor

    with tempfile.TemporaryDirectory(prefix="asperity-") as tmp:
        if gz:
            src = os.path.join(tmp, "surface" + suffix)
            with open(src, "wb") as fh:
                fh.write(data)
        else:
            src = str(name)
        try:
            reader = open_topography(src)
            channels = list(reader.channels)
        except Exception as exc:
            kind = type(exc).__name__
            if kind == "CannotDetectFileFormat":
                raise InputError(f"{name}: unknown surface file format (suffix "
                                 f"{suffix or '(none)'!r}); supported: {_FORMATS_HELP}") from None
            raise TextureFileError(f"{name}: cannot be read as a surface ({kind}: "
                                   f"{_one_line(exc)})") from None
        areal = [c for c in channels if getattr(c, "dim", 2) == 2]
        if not areal:
            raise InputError(f"{name}: holds line scans only; a height map (areal scan) is "
                             f"needed")
        pick = next((c for c in areal if _HEIGHT_CHANNEL.search(str(c.name or ""))), None)
        if pick is None:
            default = getattr(reader, "default_channel", None)
            pick = default if default in areal else areal[0]
        source = name.name
        if len(channels) > 1:
            source += (f" [channel {pick.name!r}, {channels.index(pick) + 1} of "
                       f"{len(channels)}]")
        kwargs = {}
        if pick.physical_sizes is None or pick.unit is None:
            if unit is None or pixel_size is None:
                fmt = getattr(reader, "_format", None) or type(reader).__name__
                raise InputError(f"{name}: read as {fmt!r} by SurfaceTopography, which finds no "
                                 f"pixel size or unit in it; pass unit and pixel_size")
            nxy = pick.nb_grid_pts
            ddx, ddy = _pixel_pair(pixel_size, 1.0)
            kwargs = dict(physical_sizes=(nxy[0] * ddx, nxy[1] * ddy), unit=_st_unit(unit))
        elif unit is not None or pixel_size is not None:
            raise InputError(f"{name}: the file states its unit and pixel size; do not pass "
                             f"unit or pixel_size (height_scale scales the heights)")
        try:
            topo = reader.topography(channel_index=pick.index, **kwargs)
            h = topo.heights()
            sizes = topo.physical_sizes
            nb = topo.nb_grid_pts
            tunit = topo.unit
        except Exception as exc:
            raise TextureFileError(f"{name}: cannot be read as a surface ({type(exc).__name__}: "
                                   f"{_one_line(exc)})") from None
        finally:
            close = getattr(reader, "close", None)
            if close is not None:
                try:
                    close()
                except Exception:
                    pass
    if np.ndim(h) != 2:
        raise InputError(f"{name}: holds a line scan; a height map (areal scan) is needed")
    if not getattr(topo, "is_uniform", True):
        raise InputError(f"{name}: holds a non-uniform grid; a regular height map is needed")
    try:
        f = float(get_unit_conversion_factor(tunit, "m"))
    except Exception:
        raise TextureFileError(f"{name}: unknown length unit {tunit!r} in the file") from None
    z = np.ma.filled(np.ma.asarray(h, dtype=np.float64), np.nan) * f
    dx = float(sizes[0]) * f / int(nb[0])
    dy = float(sizes[1]) * f / int(nb[1])
    if not (dx > 0 and dy > 0 and math.isfinite(dx * dy)):
        raise TextureFileError(f"{name}: the file states a non-positive pixel size")
    return _finish_heightmap(z, dx, dy, source, height_scale, name)


def _st_unit(unit: str) -> str:
    """SurfaceTopography's name for one of our units."""
    return {1.0: "m", 1e-3: "mm", 1e-6: "µm", 1e-9: "nm"}[unit_factor(unit)]


# --- form removal -------------------------------------------------------------------------

def _monomials(degree: int) -> list[tuple[int, int]]:
    return [(a, t - a) for t in range(degree + 1) for a in range(t, -1, -1)]


def detrend(surface: Surface, degree: int) -> Surface:
    """Subtract the least-squares polynomial in (x, y) of total degree ``degree`` from z.

    degree 0 removes the mean height, 1 a tilted plane, 2 a quadratic form, 3 ...
    The fit runs over the defined pixels of a height map (undefined stay NaN) or over
    the vertices of a mesh.  Returns a new object of the same type.
    """
    deg = check_int("degree", degree, 0, 10)
    terms = _monomials(deg)
    if isinstance(surface, HeightMap):
        x = np.arange(surface.nx) * surface.dx
        y = np.arange(surface.ny) * surface.dy
        z = surface.heights
        ok = np.isfinite(z)
        ii, jj = np.nonzero(ok)
        xs, ys, zs = x[ii], y[jj], z[ok]
    elif isinstance(surface, TriangleMesh):
        xs, ys, zs = surface.vertices[:, 0], surface.vertices[:, 1], surface.vertices[:, 2]
    else:
        raise InputError(f"detrend needs a HeightMap or TriangleMesh, got {type(surface).__name__}")
    if zs.size < len(terms):
        raise InputError(f"{surface.source}: a degree-{deg} form needs at least {len(terms)} "
                         f"defined points, the surface has {zs.size}")
    # centred and scaled coordinates keep the least-squares problem well conditioned
    cx, cy = 0.5 * (xs.max() + xs.min()), 0.5 * (ys.max() + ys.min())
    sx = 0.5 * (xs.max() - xs.min()) or 1.0
    sy = 0.5 * (ys.max() - ys.min()) or 1.0
    u, v = (xs - cx) / sx, (ys - cy) / sy
    A = np.stack([u ** a * v ** b for a, b in terms], axis=1)
    coef, *_ = np.linalg.lstsq(A, zs, rcond=None)
    if isinstance(surface, HeightMap):
        U, V = ((x - cx) / sx)[:, None], ((y - cy) / sy)[None, :]
        form = sum(c * U ** a * V ** b for c, (a, b) in zip(coef, terms))
        return replace(surface, heights=surface.heights - form)
    verts = surface.vertices.copy()
    verts[:, 2] = zs - A @ coef
    return replace(surface, vertices=verts, kept_faces=surface.kept_faces)


# --- friction maps ------------------------------------------------------------------------

def read_friction_map(path, surface: Surface) -> np.ndarray:
    """Local friction coefficients matching ``surface``.

    For a :class:`HeightMap`: one value per pixel, shape (nx, ny), in the orientation
    rules of the heights (a ``.npy`` holds ``mu[i, j]`` with i along x; a text matrix has
    one line per y and one column per x; '#' header lines are skipped).  For a
    :class:`TriangleMesh`: one value per kept triangle (``.npy`` or text, any layout,
    read in order), or one per triangle of the mesh file (the values of the dropped
    degenerate ones are then discarded).  Values must be finite and >= 0.
    """
    p = Path(path)
    suffix, gz = _split_suffix(p)
    if suffix not in ARRAY_SUFFIXES + TEXT_SUFFIXES:
        raise InputError(f"{p}: a friction map must be .npy, .npz or a text matrix "
                         f"({' '.join(TEXT_SUFFIXES)}), optionally .gz; got suffix "
                         f"{suffix or '(none)'!r}")
    data = _read_bytes(p, gz)
    is_map = isinstance(surface, HeightMap)
    if suffix in ARRAY_SUFFIXES:
        m = _load_array(data, suffix, p)
    else:
        m, _, _ = _parse_text_matrix(data, p)
        if is_map:
            m = m.T
    if is_map:
        expected = (surface.nx, surface.ny)
        if m.shape != expected:
            raise InputError(f"{p}: friction map has shape {m.shape}, expected {expected} "
                             f"(nx, ny) like the heights of {surface.source or 'the surface'}"
                             f" (a text matrix: {surface.ny} lines of {surface.nx} values)")
    else:
        m = m.ravel()
        nf = surface.n_faces
        n_file = nf + surface.n_degenerate
        if m.size == n_file and surface.n_degenerate and surface.kept_faces is not None:
            m = m[surface.kept_faces]
        elif m.size != nf:
            also = (f" (or {n_file}, one per triangle of the file)"
                    if surface.n_degenerate and surface.kept_faces is not None else "")
            raise InputError(f"{p}: friction map has {m.size} values, expected {nf}{also}, one "
                             f"per triangle of {surface.source or 'the mesh'}")
    bad = ~np.isfinite(m) | (m < 0)
    if bad.any():
        k = int(np.flatnonzero(bad.ravel())[0])
        raise InputError(f"{p}: friction map values must be finite and >= 0; found "
                         f"{m.ravel()[k]:g} ({int(bad.sum())} bad values)")
    return np.array(m, dtype=np.float64)
