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
``.x3p`` (ISO 25178-72 / ISO 5436-2)
    Read by the built-in reader (:mod:`.x3p`): every areal grid the standard allows
    (binary or inline points, the four data types, valid-point masks, incremental or
    regular absolute x/y axes); profiles, point clouds and the like are refused with a
    message that says what the file is.
The instrument formats (``.mi .sur .opd .datx .plu .nms``, ...)
    Read with SurfaceTopography (the ``metrology`` extra), which knows the units and
    pixel sizes from the file.  Of a multi-channel file (``.mi``) the first height
    channel is read, and :attr:`HeightMap.source` names it.  A file whose content is not
    a surface in the format of its suffix is refused.
    A file written in another unit than it states (an x3p in micrometres: a pixel of
    2 "m") is read with ``unit``: its numbers are taken in that unit; ``pixel_size`` (in
    ``unit``) replaces its spacing.

Every error a user can cause (missing file, unknown suffix or unit, malformed header or
matrix, a pixel size or height outside the physical ranges of
:mod:`~asperity.surface.topography`, a file too large for the memory) is an
:class:`~asperity.errors.InputError` (a :class:`~asperity.errors.TextureFileError` for a
file that does not follow its format) with a one-line message naming the file.  Sizes
stated in a file's header are checked against the memory before the data is expanded.

The heavy libraries (trimesh, SurfaceTopography, zip and XML parsing) are imported only
when a file needs them.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass

from ...errors import InputError, check_range
from ..topography import HeightMap, TriangleMesh, check_height_scale, unit_factor
from ._files import read_bytes, split_suffix, surface_path


@dataclass(frozen=True)
class Reader:
    """One format family: the suffixes it claims and the module whose ``read`` reads it.

    ``read(data, *, suffix, gz, name, unit, pixel_size, height_scale, point_bytes)`` gets
    the file's bytes (gunzipped) and returns a :class:`HeightMap` or a
    :class:`TriangleMesh` in metres; ``point_bytes`` is the memory per grid point the caller
    needs beyond reading (a reader that knows the grid size from a header checks it first).
    """

    name: str
    format: str
    suffixes: tuple[str, ...]     # () claims every suffix (the last reader, a catch-all)
    module: str                   # module of this package holding ``read``
    sizes: str                    # where the lengths come from (the file-format reference's table)
    takes_pixel_size: bool = True

    def can_read(self, suffix: str) -> bool:
        return not self.suffixes or suffix in self.suffixes

    def read(self, data: bytes, **kwargs):
        return importlib.import_module(f"{__name__}.{self.module}").read(data, **kwargs)


#: the readers in the order they are asked; the first whose ``can_read`` says yes reads
READERS = (
    Reader("mesh", "triangle mesh (trimesh)", (".stl", ".obj", ".ply"), "mesh",
           "none in the file: unit required", takes_pixel_size=False),
    Reader("array", "NumPy height map", (".npy", ".npz"), "array",
           "none in the file: unit and pixel size required"),
    Reader("text", "ASCII matrix, one line per y", (".txt", ".asc", ".csv", ".dat"), "text",
           "from a header, else unit and pixel size"),
    Reader("x3p", "ISO 25178-72 x3p (built in)", (".x3p",), "x3p", "from the file"),
    Reader("instrument", "instrument formats through SurfaceTopography", (), "instrument",
           "from the file"),
)


def reader_for(path) -> tuple[Reader, str, bool]:
    """(reader, format suffix, gzipped?) of a file name."""
    suffix, gz = split_suffix(surface_path(path))
    return next(r for r in READERS if r.can_read(suffix)), suffix, gz


def read_surface(path, *, unit=None, pixel_size=None, height_scale=1.0,
                 point_bytes: float = 0.0) -> HeightMap | TriangleMesh:
    """Read a mesh or height-map file, in metres (the format chosen by the file's suffix).

    Formats (a trailing ``.gz`` is decompressed first, for every format): meshes ``.stl
    .obj .ply`` (read by trimesh; vertices merged, degenerate triangles dropped and
    counted); NumPy height maps ``.npy .npz``; ASCII matrices ``.txt .asc .csv .dat`` (one
    line per y, one column per x, ``nan`` undefined, a Gwyddion-style or ``key=value``
    header read when present); ISO 25178-72 ``.x3p`` (built-in reader); instrument formats
    (``.mi .sur .opd .datx .plu .nms`` ...) through SurfaceTopography (the ``metrology``
    extra).  The file-format reference (surface files) gives the details.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    unit : str or None, default None
        Length unit of the numbers in the file: m, mm, um/µm, nm (long names such as
        "micrometre" too).  Required for meshes, ``.npy``/``.npz`` and text matrices without
        a value unit in their header; for a text matrix with a header it overrides the
        header's height unit.  Files in instrument formats (x3p too) state their own unit
        and pixel size; ``unit`` then reads their numbers in that unit instead (a file
        written in another unit than it states), and is required with ``pixel_size``.
    pixel_size : float or (float, float) or None, default None
        Grid spacing of a height map in ``unit``, one number or (dx, dy).  Required for
        ``.npy``/``.npz`` and headerless text matrices; overrides a header's or an
        instrument file's sizes (and then needs ``unit``); refused for a mesh.
    height_scale : float, default 1.0
        Factor in [1e-6, 1e6] applied to the heights (z) after conversion to metres, e.g. to
        make nanometre-high AFM relief steep enough for friction work.
    point_bytes : float, default 0.0
        Memory per grid point the caller needs beyond reading (``load_surface``: the
        facets), bytes, in [0, 1e6]; a file whose grid cannot fit is refused before its data
        is expanded.

    Returns
    -------
    HeightMap or TriangleMesh
        A height map ``heights[i, j] = z(x_i, y_j)`` (m, first index along x, NaN where
        undefined) with its spacings ``dx``, ``dy`` (m); or a mesh's ``vertices`` (m) and
        ``faces`` (vertex indices of each triangle).

    Raises
    ------
    asperity.InputError
        A missing file, an unknown suffix or unit, a malformed header or matrix, a pixel
        size or height outside the physical ranges, or a file too large for the memory (one
        line naming the file).

    See Also
    --------
    asperity.load_surface : The file's facets, ready for the friction.
    asperity.solve_contact : The elastic contact of a height map.

    Examples
    --------
    A 64 x 64 text matrix whose Gwyddion header gives the sizes, and a mesh in micrometres:

    >>> hm = asperity.read_surface("surfaces/scan-ridges.txt")
    >>> print(hm.heights.shape, f"pixel {hm.dx * 1e6:g} x {hm.dy * 1e6:g} um")
    (64, 64) pixel 1 x 1 um
    >>> mesh = asperity.read_surface("surfaces/wedge-30-10.stl", unit="um")
    >>> print(len(mesh.vertices), "vertices,", len(mesh.faces), "triangles")
    18 vertices, 16 triangles
    """
    p = surface_path(path)
    hs = check_height_scale(height_scale)
    point_bytes = check_range("point_bytes", point_bytes, 0.0, 1e6, unit="bytes")
    reader, suffix, gz = reader_for(p)
    if unit is not None:
        unit_factor(unit)                 # fail early on an unknown unit
    if pixel_size is not None and not reader.takes_pixel_size:
        raise InputError(f"{p}: pixel_size applies to height maps, not to a mesh file")
    return reader.read(read_bytes(p, gz), suffix=suffix, gz=gz, name=p, unit=unit,
                       pixel_size=pixel_size, height_scale=hs, point_bytes=point_bytes)
