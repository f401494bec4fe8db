"""Body files: a planar rigid body in TOML (issue 20).

::

    name = "L-bracket"                       # optional
    description = "a bent sheet part"        # optional

    [body]
    shape = "polygon"                        # disc | ring | rectangle | polygon | mesh
    vertices = [[0, 0], [0.05, 0], [0.05, 0.01], [0.01, 0.01], [0.01, 0.04], [0, 0.04]]
    mass = 0.012                             # kg
    inertia = 3.0e-6                         # kg m^2, optional: default the uniform lamina's
    contact_points = 512                     # optional: default per shape
    pressure_profile = "linear"              # uniform (default) | hertz (disc) | linear
    centre_of_pressure = [0.002, 0.0]        # m, for "linear", in the centred body frame
    # pressure_file = "pressure.csv"         # per point (x_m,y_m,p_Pa or .npy), instead

The shape's size: ``radius`` (disc, ring), ``size = [a, b]`` (rectangle, a along the
body's x), ``vertices`` (polygon, m, either orientation; the body frame's origin is moved
to the polygon's centroid), or ``mesh = "part.stl"`` with ``unit`` (and optionally
``tolerance``, m) for the contact patch of a triangle mesh.  File names (``mesh``,
``pressure_file``) are relative to the body file's folder (:func:`asperity.paths.named_path`,
as every reader of names in files).  A pressure file's points are in the frame of the
shape as written (a polygon's vertices' frame; disc, ring and rectangle centred on 0).

Shipped examples: ``surfaces/body-bracket.toml`` (a polygon part with an eccentric load)
and ``surfaces/body-plate.toml`` (a rectangular plate); read them with :func:`read_body`.
"""
from __future__ import annotations

from dataclasses import dataclass
from os import PathLike
from pathlib import Path

from ..errors import InputError, check_choice, check_instance, check_range, check_table, check_text
from . import footprint as fpm
from . import pressure as fpp

SHAPES = ("disc", "ring", "rectangle", "polygon", "mesh")
_TOP = {"name", "description", "body"}
_BODY = {"shape", "radius", "size", "vertices", "mesh", "unit", "tolerance", "mass",
         "inertia", "contact_points", "pressure_profile", "centre_of_pressure",
         "pressure_file"}
#: size of each shape: the keys it needs (the others are refused)
_SIZE_KEYS = {"disc": ("radius",), "ring": ("radius",), "rectangle": ("size",),
              "polygon": ("vertices",), "mesh": ("mesh",)}
MASS_RANGE = (1e-9, 1e9)
INERTIA_RANGE = (1e-30, 1e12)


@dataclass(frozen=True)
class Body:
    """A planar rigid body: its footprint, mass (kg) and inertia about the centroid
    (kg m^2), a name and where it was read from."""

    footprint: fpm.Footprint
    mass: float
    inertia: float
    name: str = ""
    description: str = ""
    source: str = ""


def read_body(path) -> Body:
    """Read a TOML body file: a planar rigid body's footprint, mass and inertia.

    Parameters
    ----------
    path : str or os.PathLike
        The body file (format: the module's docstring, ``asperity.bodies.body_file``).
        The files it names (``mesh``, ``pressure_file``) are relative to its folder.

    Returns
    -------
    Body
        A frozen record: ``footprint`` (:class:`asperity.Footprint`), ``mass`` (kg),
        ``inertia`` about the centroid (kg m^2; default the footprint's uniform lamina,
        mass x ``inertia_per_mass``), ``name`` (default the file's stem), ``description``
        and ``source`` (the path read).

    Raises
    ------
    InputError
        Every bad field, in one line naming the file and the field (``body.mass``, ...).

    See Also
    --------
    asperity.slide_body, asperity.disc_footprint, asperity.polygon_footprint,
    asperity.mesh_patch, asperity.read_pressure

    Examples
    --------
    The shipped 80 x 30 mm plate (512 points, uniform pressure; inertia m (a^2 + b^2)/12)
    and bracket (a polygon, the load's centre 2 mm towards +x):

    >>> plate = asperity.read_body("surfaces/body-plate.toml")
    >>> plate.name, plate.footprint.kind, plate.footprint.n, plate.mass
    ('plate', 'rectangle', 512, 0.0194)
    >>> print(f"{plate.inertia:.4e}")                  # kg m^2
    1.1802e-05
    >>> bracket = asperity.read_body("surfaces/body-bracket.toml")
    >>> bracket.footprint.profile, round(float(bracket.footprint.centre_of_pressure[0]), 4)
    ('linear', 0.002)
    """
    from ..io import read_toml
    p = Path(check_instance("path", path, (str, PathLike), "file name (text or a Path)"))
    data = read_toml(p, "body file", _TOP, InputError)
    try:
        return _body(data, p)
    except InputError as exc:
        msg = str(exc)
        raise type(exc)(msg if msg.startswith(str(p)) else f"{p}: {msg}") from None


def _body(data: dict, p: Path) -> Body:
    from ..paths import named_path
    if "body" not in data:
        raise InputError("missing table [body]")
    b = check_table("body", data["body"], _BODY, ("shape", "mass"))
    shape = check_choice("body.shape", b["shape"], SHAPES)
    for k in set(_BODY) & {"radius", "size", "vertices", "mesh"}:
        if k in b and k not in _SIZE_KEYS[shape]:
            raise InputError(f"body.{k} does not apply to shape {shape!r} (it takes "
                             f"{', '.join(_SIZE_KEYS[shape])})")
    for k in _SIZE_KEYS[shape]:
        if k not in b:
            raise InputError(f"missing key body.{k} (shape {shape!r} needs it)")
    if shape != "mesh" and ("unit" in b or "tolerance" in b):
        raise InputError("body.unit and body.tolerance apply to shape 'mesh' only")
    mass = check_range("body.mass", b["mass"], *MASS_RANGE, unit="kg")
    n = b.get("contact_points")
    profile = b.get("pressure_profile", "uniform")
    cop = b.get("centre_of_pressure", (0.0, 0.0))
    if "centre_of_pressure" in b and profile != "linear":
        raise InputError("body.centre_of_pressure applies to pressure_profile = \"linear\" "
                         f"only, got {profile!r}")
    if "pressure_file" in b and ("pressure_profile" in b or "contact_points" in b):
        raise InputError("body.pressure_file gives the points and their pressure: leave out "
                         "pressure_profile and contact_points")
    kw = {"contact_points": n, "profile": profile, "centre_of_pressure": cop}
    try:
        if shape == "disc":
            fp = fpm.disc(b["radius"], **kw)
        elif shape == "ring":
            if "pressure_profile" in b and profile != "uniform":
                raise InputError(f"pressure_profile of a ring must be uniform, got {profile!r}")
            fp = fpm.ring(b["radius"], contact_points=n)
        elif shape == "rectangle":
            size = b["size"]
            if not isinstance(size, list) or len(size) != 2:
                raise InputError("size must be [a, b] (m), two numbers")
            for i, v in enumerate(size):    # named as the file names them (not 'a', 'b')
                check_range(f"size[{i}]", v, *fpm.LENGTH_RANGE, unit="m")
            fp = fpm.rectangle(size[0], size[1], **kw)
        elif shape == "polygon":
            fp = fpm.polygon(b["vertices"], **kw)
        else:
            mesh = named_path(check_text("body.mesh", b["mesh"]), p.parent)
            fp = fpp.mesh_patch(mesh, unit=b.get("unit"), tolerance=b.get("tolerance"), **kw)
    except InputError as exc:
        raise InputError(f"body.{exc}") from None
    if "pressure_file" in b:
        pf = named_path(check_text("body.pressure_file", b["pressure_file"]), p.parent)
        pts, pr = fpp.read_pressure(pf)
        try:
            fp = fpp.from_pressure(pts, pr, shape=fp)
        except InputError as exc:
            raise InputError(f"body.pressure_file {pf.name}: {exc}") from None
    if "inertia" in b:
        inertia = check_range("body.inertia", b["inertia"], *INERTIA_RANGE, unit="kg m^2")
    else:
        inertia = mass * fp.inertia_per_mass
        if inertia <= 0:
            raise InputError("body.inertia is needed: the footprint has no area to give the "
                             "lamina's")
    name = check_text("name", data.get("name", p.stem), 200)
    description = check_text("description", data.get("description", ""))
    return Body(fp, mass, inertia, name, description, str(p))
