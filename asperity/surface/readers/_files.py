"""File-level helpers of the readers: the format suffix of a name, the bytes of a file
(gunzipped, never more than memory allows), the memory a grid will need, and the texts
the messages share."""
from __future__ import annotations

import os
from pathlib import Path

from ...errors import InputError, ResourceError, TextureFileError
from ...resources import MEMORY_SHARE, available_memory, check_memory, format_bytes
from ..topography import one_line

#: instrument suffixes named in messages (SurfaceTopography reads more)
INSTRUMENT_EXAMPLES = (".x3p", ".mi", ".sur", ".opd", ".datx", ".plu", ".nms")
FORMATS_HELP = (".stl .obj .ply (meshes), .npy .npz, .txt .asc .csv .dat (ASCII matrix), "
                ".x3p, and through SurfaceTopography .mi .sur .opd .datx .plu .nms and other "
                "instrument formats; any of them may be .gz-compressed")
METROLOGY_HINT = "pip install 'asperity[metrology]'"
#: what lowers the memory a surface file needs (there is no flag: the scan itself)
SMALLER_SCAN = "crop or resample the scan to fewer points"
#: bytes per grid point of reading a height map (file data, float64 heights, their copy)
READ_BYTES_PER_POINT = 24
#: pieces in which gzip data is expanded (bounded, and Ctrl-C is honoured between them)
_GZ_PIECE = 1 << 24


def split_suffix(path: Path) -> tuple[str, bool]:
    """(format suffix, gzipped?) of a file name, e.g. ('.stl', True) for 'a.stl.gz'."""
    suffixes = [s.lower() for s in path.suffixes]
    if suffixes and suffixes[-1] == ".gz":
        return (suffixes[-2] if len(suffixes) >= 2 else ""), True
    return (suffixes[-1] if suffixes else ""), False


def surface_path(path) -> Path:
    """``path`` as a Path if it is a file name (str or path-like), else InputError."""
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not isinstance(path, (str, os.PathLike)):
        from ...errors import _kind, _show
        raise InputError(f"surface file must be a file name, got {_show(path)} ({_kind(path)})")
    p = Path(path)
    if not str(path).strip():
        raise InputError("surface file name is empty")
    return p


def read_bytes(path: Path, gz: bool) -> bytes:
    """The bytes of a surface file, gunzipped if ``gz``; InputError for a missing file, a
    folder, a special file, a file (or its expansion) that memory cannot hold."""
    if path.is_dir():
        raise InputError(f"surface file {str(path)!r} is a folder")
    if not path.is_file():
        if path.exists():
            raise InputError(f"surface file {str(path)!r} is not a regular file")
        raise InputError(f"surface file {str(path)!r} does not exist")
    try:
        size = path.stat().st_size
        check_memory(2 * size, f"{path}: this {format_bytes(size)} file", SMALLER_SCAN)
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror or type(exc).__name__})") \
            from None
    if gz:
        data = gunzip(data, path)
    return data


def gunzip(data: bytes, path) -> bytes:
    """Expand gzip ``data`` (one or more members) in bounded pieces: refused, before memory
    runs out, once the expansion exceeds what this machine can hold."""
    import zlib
    limit = int(MEMORY_SHARE * available_memory() / 4)     # the expansion, then its parsing
    out: list[bytes] = []
    total = 0
    view = memoryview(data)
    pos = 0
    d = zlib.decompressobj(wbits=31)
    try:
        if not data:
            raise zlib.error("the file is empty")
        while True:
            if d.eof:                                     # next member, if any
                rest = bytes(d.unused_data) + bytes(view[pos:])
                rest = rest.lstrip(b"\x00")
                if not rest:
                    break
                view, pos = memoryview(rest), 0
                d = zlib.decompressobj(wbits=31)
            if pos >= len(view):
                raise zlib.error("the compressed data ends early")
            piece = view[pos:pos + _GZ_PIECE]
            pos += len(piece)
            chunk = d.decompress(piece, _GZ_PIECE)
            while True:
                total += len(chunk)
                if total > limit:
                    raise ResourceError(f"{path}: expands to more than {format_bytes(limit)}, "
                                     f"more than this machine can read; {SMALLER_SCAN}")
                out.append(chunk)
                if d.eof or not d.unconsumed_tail:
                    break
                chunk = d.decompress(d.unconsumed_tail, _GZ_PIECE)
    except zlib.error as exc:
        raise TextureFileError(f"{path}: not a valid gzip file ({one_line(exc)})") from None
    return b"".join(out)


def check_grid(nx: int, ny: int, name, point_bytes: float) -> None:
    """Refuse, before anything is expanded, a grid of nx x ny points that needs more memory
    than this machine can give (``point_bytes`` per point: reading it, and what the caller
    does next)."""
    n = int(nx) * int(ny)
    check_memory(n * float(point_bytes), f"{name}: a {nx} x {ny} grid ({n:.3g} points)",
                 SMALLER_SCAN)
