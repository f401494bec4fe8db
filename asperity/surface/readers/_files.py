"""File-level helpers of the readers: the format suffix of a name, the bytes of a file
(gunzipped), and the texts the messages share."""
from __future__ import annotations

from pathlib import Path

from ...errors import InputError, TextureFileError
from ..topography import one_line

#: instrument suffixes named in messages (SurfaceTopography reads more)
INSTRUMENT_EXAMPLES = (".x3p", ".mi", ".sur", ".opd", ".datx", ".plu", ".nms")
FORMATS_HELP = (".stl .obj .ply (meshes), .npy .npz, .txt .asc .csv .dat (ASCII matrix), "
                ".x3p, and through SurfaceTopography .mi .sur .opd .datx .plu .nms and other "
                "instrument formats; any of them may be .gz-compressed")
METROLOGY_HINT = "pip install 'asperity[metrology]'"


def split_suffix(path: Path) -> tuple[str, bool]:
    """(format suffix, gzipped?) of a file name, e.g. ('.stl', True) for 'a.stl.gz'."""
    suffixes = [s.lower() for s in path.suffixes]
    if suffixes and suffixes[-1] == ".gz":
        return (suffixes[-2] if len(suffixes) >= 2 else ""), True
    return (suffixes[-1] if suffixes else ""), False


def read_bytes(path: Path, gz: bool) -> bytes:
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
            raise TextureFileError(f"{path}: not a valid gzip file ({one_line(exc)})") from None
    return data
