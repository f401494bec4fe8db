"""Instrument formats (``.mi .sur .opd .datx .plu .nms`` ...) through SurfaceTopography
(the ``metrology`` extra), which knows the units and pixel sizes from the file.  Of a
multi-channel file (``.mi``) the first height channel is read, and
:attr:`HeightMap.source` names it.

SurfaceTopography detects the format from the content, and a few of its formats have no
header (``hgt``: any file of 2 n^2 bytes is a grid): a file is read only in a format that
recognises its first bytes or claims its suffix, else it is refused as not a surface.
Its warnings are silenced (a file's quirks are not the user's business), its errors
become one line naming the file.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ..topography import (
    HeightMap,
    check_stated_pixel,
    finish_heightmap,
    given_sizes,
    one_line,
    pixel_pair,
    unit_factor,
)
from ._files import (
    FORMATS_HELP,
    INSTRUMENT_EXAMPLES,
    METROLOGY_HINT,
    READ_BYTES_PER_POINT,
    check_grid,
)

_HEIGHT_CHANNEL = re.compile(r"topo|height|z ?sensor|^z$|^default$|surface", re.I)


def have_surfacetopography() -> bool:
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        return False
    return True


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
         height_scale: float, point_bytes: float = 0.0) -> HeightMap:
    """Any other format, through SurfaceTopography (which detects it from the content)."""
    if not have_surfacetopography():
        if suffix in INSTRUMENT_EXAMPLES:
            raise InputError(f"{name}: reading {suffix} files needs the metrology extra: "
                             f"{METROLOGY_HINT}")
        raise InputError(f"{name}: unknown surface file suffix {suffix or '(none)'!r}; "
                         f"supported: {FORMATS_HELP} (instrument formats need the metrology "
                         f"extra: {METROLOGY_HINT})")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # SurfaceTopography's notes on a file
        with np.errstate(all="ignore"):
            return read_with_surfacetopography(data, suffix, gz, name, unit, pixel_size,
                                               height_scale, point_bytes)


def _claims(suffix: str) -> list:
    """SurfaceTopography's readers that list ``suffix`` among their file extensions."""
    from SurfaceTopography.IO import readers
    out = []
    for r in readers:
        try:
            exts = r.file_extensions() or []
        except Exception:
            continue
        if suffix[1:] in [str(e).lower() for e in exts]:
            out.append(r)
    return out


def _check_format(reader, data: bytes, suffix: str, name: Path) -> None:
    """Refuse a file that SurfaceTopography reads only by guessing: a format that neither
    recognises the file's first bytes nor claims its suffix (random bytes of 2 n^2 bytes
    are a valid headerless .hgt grid, for instance)."""
    from SurfaceTopography.IO.Reader import MagicMatch
    cls = type(reader)
    try:
        magic = cls.can_read(data[:512])
    except Exception:
        magic = MagicMatch.MAYBE
    if magic == MagicMatch.YES or cls in _claims(suffix):
        return
    fmt = getattr(cls, "_format", None) or cls.__name__
    if _claims(suffix):
        raise TextureFileError(f"{name}: not a surface file: its content is not a {suffix} file "
                               f"(SurfaceTopography could read it only as {fmt!r}, a format "
                               f"without a header, which would make garbage heights)")
    raise InputError(f"{name}: unknown surface file format (suffix {suffix or '(none)'!r}; "
                     f"its content could be read only as {fmt!r}, a format without a header); "
                     f"supported: {FORMATS_HELP}")


def read_with_surfacetopography(data: bytes, suffix: str, gz: bool, name: Path, unit,
                                 pixel_size, height_scale: float,
                                 point_bytes: float = 0.0) -> HeightMap:
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
                if _claims(suffix):
                    raise TextureFileError(f"{name}: not a surface file: its content is not a "
                                           f"{suffix} file SurfaceTopography can read") from None
                raise InputError(f"{name}: unknown surface file format (suffix "
                                 f"{suffix or '(none)'!r}); supported: {FORMATS_HELP}") from None
            raise TextureFileError(f"{name}: cannot be read as a surface ({kind}: "
                                   f"{one_line(exc)})") from None
        try:
            _check_format(reader, data, suffix, name)
            return _read_channel(reader, channels, name, unit, pixel_size, height_scale,
                                 point_bytes, get_unit_conversion_factor)
        finally:
            close = getattr(reader, "close", None)
            if close is not None:
                try:
                    close()
                except Exception:
                    pass


def _read_channel(reader, channels, name, unit, pixel_size, height_scale, point_bytes,
                  get_unit_conversion_factor) -> HeightMap:
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
    try:
        nxy = tuple(int(k) for k in pick.nb_grid_pts)
    except Exception:
        nxy = None
    if nxy is not None and len(nxy) == 2:
        check_grid(nxy[0], nxy[1], name, READ_BYTES_PER_POINT + 8 + float(point_bytes))
    kwargs, given, pixel = {}, None, None
    if pick.physical_sizes is None or pick.unit is None:
        if unit is None or pixel_size is None:
            fmt = getattr(reader, "_format", None) or type(reader).__name__
            raise InputError(f"{name}: read as {fmt!r} by SurfaceTopography, which finds no "
                             f"pixel size or unit in it; pass unit and pixel_size")
        f = unit_factor(unit)
        ddx, ddy = pixel_pair(pixel_size, f)
        kwargs = dict(physical_sizes=(nxy[0] * ddx / f, nxy[1] * ddy / f), unit=_st_unit(unit))
    else:               # unit: the file's numbers read in it; pixel_size: replaces its
        given, pixel = given_sizes(name, unit, pixel_size)
    try:
        topo = reader.topography(channel_index=pick.index, **kwargs)
        h = topo.heights()
        sizes = topo.physical_sizes
        nb = topo.nb_grid_pts
        tunit = topo.unit
    except MemoryError:
        raise
    except Exception as exc:
        raise TextureFileError(f"{name}: cannot be read as a surface ({type(exc).__name__}: "
                               f"{one_line(exc)})") from None
    if np.ndim(h) != 2:
        raise InputError(f"{name}: holds a line scan; a height map (areal scan) is needed")
    if not getattr(topo, "is_uniform", True):
        raise InputError(f"{name}: holds a non-uniform grid; a regular height map is needed")
    try:
        f = given or float(get_unit_conversion_factor(tunit, "m"))
    except Exception:
        raise TextureFileError(f"{name}: unknown length unit {tunit!r} in the file") from None
    z = np.ma.filled(np.ma.asarray(h, dtype=np.float64), np.nan) * f
    try:
        dx = float(sizes[0]) * f / int(nb[0])
        dy = float(sizes[1]) * f / int(nb[1])
    except (TypeError, ValueError, ZeroDivisionError, IndexError, OverflowError):
        dx = dy = float("nan")
    if not (dx > 0 and dy > 0 and math.isfinite(dx * dy)):
        raise TextureFileError(f"{name}: the file states no valid pixel size")
    if pixel is not None:
        dx, dy = pixel
    elif not kwargs:
        check_stated_pixel(name, dx, dy, f"the {tunit} it states" if given is None else
                           "that unit")
    return finish_heightmap(z, dx, dy, source, height_scale, name, copy=False)


def _st_unit(unit: str) -> str:
    """SurfaceTopography's name for one of our units."""
    return {1.0: "m", 1e-3: "mm", 1e-6: "µm", 1e-9: "nm"}[unit_factor(unit)]
