"""Footprints from pressure per point (a contact solution, a measured pressure film, a CSV or
.npy file) and from the contact patch of a triangle mesh (see :mod:`asperity.bodies.footprint`
for the footprint and its conventions)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_array, check_int, check_range
from .footprint import (
    DEFAULT_CONTACT_POINTS,
    MAX_CONTACT_POINTS,
    NOT_CARRIED,
    Footprint,
    _cop,
    _count,
    _lamina,
    _profile,
)
from .polygon import LENGTH_RANGE, _inside_polygon

# ----------------------------------------------------------------------------- pressure per point

def _bin_points(p: np.ndarray, w: np.ndarray, n: int):
    """Points p (m, 2) with loads w merged into the cells of a square grid, about n of them
    occupied: each cell's point at the load centroid of its points, its load their sum
    (the total load and the centre of pressure are kept exactly)."""
    lo, hi = p.min(axis=0), p.max(axis=0)
    span = float(np.max(hi - lo))
    h = span / math.sqrt(n) if span > 0 else 1.0
    best = None
    for _ in range(8):
        idx = np.floor((p - lo) / h).astype(np.int64)
        key = idx[:, 0] * (int(idx[:, 1].max()) + 1) + idx[:, 1]
        uniq, inv = np.unique(key, return_inverse=True)
        if best is None or abs(uniq.size - n) < abs(best[0].size - n) or \
                (best[0].size > n >= uniq.size):
            best = (uniq, inv.ravel())
        if uniq.size == n or (n < uniq.size <= 1.05 * n):
            break
        h *= math.sqrt(uniq.size / n)
    uniq, inv = best
    W = np.bincount(inv, weights=w, minlength=uniq.size)
    X = np.bincount(inv, weights=w * p[:, 0], minlength=uniq.size) / W
    Y = np.bincount(inv, weights=w * p[:, 1], minlength=uniq.size) / W
    return np.column_stack([X, Y]), W


def from_pressure(points, pressures, *, shape: Footprint | None = None,
                  cell_areas=None, contact_points: int | None = None) -> Footprint:
    """A footprint of given points and their pressures: a contact solution or a measured
    pressure film (public as ``pressure_footprint``).

    Each point carries pressure x area of its cell; only the shape of the pressure
    matters, the weights are normalised (the body's weight is the load).  Points of zero
    pressure are dropped.

    Parameters
    ----------
    points : (n, 2) array_like of float
        The points, m, within 1e3 m of the origin; n <= 1e6.
    pressures : (n,) array_like of float
        Pa, each >= 0 and some > 0.
    shape : Footprint or None, optional
        The footprint the pressure acts on: its outline, area and inertia are kept, the
        points are in its frame before it was centred (its ``info['centroid_shift']`` is
        subtracted) and points outside it are refused.  None (default): the points' own
        (their convex hull as outline and area, the uniform lamina of the points for the
        inertia, centred on their area-weighted mean).
    cell_areas : (n,) array_like of float or None, optional
        Area of each point's cell, m^2, > 0; None (default): equal cells, the points of a
        regular grid.
    contact_points : int or None, optional
        None (default) keeps every point of positive pressure; a number in [1, 1e6] merges
        them into about that many (the cells of a square grid, each at the load centroid of
        its points: the load and the centre of pressure are kept) -- for a fine contact map.

    Returns
    -------
    Footprint
        profile "file"; kind "pressure", or the kind of ``shape``.

    Raises
    ------
    InputError
        A negative pressure or all zero (a pressure that does not carry the load), a point
        outside ``shape``, a value outside its range.

    See Also
    --------
    asperity.read_pressure, asperity.contact_footprint, asperity.Footprint

    Examples
    --------
    A 5 x 5 grid, 20 x 20 mm, whose pressure rises along x: the centre of pressure sits
    1 mm towards +x (20 times the mean x^2 of the grid):

    >>> x = np.linspace(-0.01, 0.01, 5)
    >>> pts = np.column_stack([np.repeat(x, 5), np.tile(x, 5)])          # m
    >>> fp = asperity.pressure_footprint(pts, 1e5 * (1 + 20 * pts[:, 0]))   # Pa
    >>> fp.n, round(fp.area, 6), round(float(fp.centre_of_pressure[0]), 6)     # m^2, m
    (25, 0.0004, 0.001)
    """
    p = check_array("points", points, shape=(None, 2), min_size=2)
    q = check_array("pressures", pressures, shape=(p.shape[0],))
    if p.shape[0] > MAX_CONTACT_POINTS:
        raise InputError(f"contact_points (the pressure's points) must be a whole number in "
                         f"[1, {MAX_CONTACT_POINTS}], got {p.shape[0]}")
    if np.any(np.abs(p) > LENGTH_RANGE[1]):
        raise InputError(f"points must lie within {LENGTH_RANGE[1]:g} m of the origin")
    if np.any(q < 0):
        k = int(np.flatnonzero(q < 0)[0])
        raise InputError(f"pressures must be >= 0 Pa, got {q[k]:g} at point {k}: {NOT_CARRIED}")
    if not np.any(q > 0):
        raise InputError(f"pressures are all zero: {NOT_CARRIED}")
    if cell_areas is None:
        cells = np.ones(p.shape[0])
    else:
        cells = check_array("cell_areas", cell_areas, shape=(p.shape[0],))
        if np.any(cells <= 0):
            raise InputError("cell_areas must be > 0 m^2")
    if shape is not None:
        from ..errors import check_instance
        check_instance("shape", shape, Footprint)
        shift = np.asarray(shape.info.get("centroid_shift", (0.0, 0.0)), dtype=float)
        p = p - shift
        if shape.kind in ("disc", "ring"):
            tol = 1e-9 * shape.radius
            r = np.hypot(p[:, 0], p[:, 1])
            out = (r > shape.radius + tol) if shape.kind == "disc" else \
                (np.abs(r - shape.radius) > 1e-6 * shape.radius)
        elif shape.kind in ("rectangle", "polygon"):
            o = shape.outline[:-1]
            out = ~_inside_polygon(p, o, 1e-9 * float(np.ptp(o, axis=0).max()))
        else:
            out = np.zeros(p.shape[0], dtype=bool)
        if np.any(out):
            k = int(np.flatnonzero(out)[0])
            raise InputError(f"points: point {k} ({points[k][0]:g}, {points[k][1]:g}) m lies "
                             f"outside the body's {shape.kind}")
    nbin = None if contact_points is None else check_int("contact_points", contact_points, 1,
                                                         MAX_CONTACT_POINTS)
    keep = q > 0
    w = q[keep] * cells[keep]
    w = w / w.sum()
    pk = p[keep]
    if nbin is not None and pk.shape[0] > nbin:
        pk, w = _bin_points(pk, w, nbin)
        w = w / w.sum()
    if shape is not None:
        return Footprint(shape.kind, pk, w, shape.outline, shape.area, shape.radius,
                         "file", shape.inertia_per_mass, dict(shape.info))
    c = cells @ p / cells.sum()
    p = p - c
    area, outline = float(cells.sum()) if cell_areas is not None else 0.0, p[:1]
    if p.shape[0] >= 3:
        from scipy.spatial import ConvexHull, QhullError
        try:
            hull = ConvexHull(p)
            outline = np.vstack([p[hull.vertices], p[hull.vertices[:1]]])
            if cell_areas is None:
                area = float(hull.volume)
        except (QhullError, ValueError):        # all points on a line
            pass
    J = float(cells @ (p**2).sum(axis=1) / cells.sum())
    return Footprint("pressure", pk - c, w, outline, area, None, "file", J,
                     {"centroid_shift": c.tolist()})


def from_contact(result, *, contact_points: int | None = None) -> Footprint:
    """The footprint of an elastic contact solution: the pixels in contact with their
    pressure (public as ``contact_footprint``).

    Parameters
    ----------
    result : ContactResult
        A solution of :func:`asperity.solve_contact` (a part's bottom, heights in m,
        pressed on a flat); pixel (i, j) is at (i dx, j dy).
    contact_points : int or None, optional
        The pixels are merged into about this many points, in [1, 1e6] (see
        :func:`asperity.pressure_footprint`); None (default): 1024.

    Returns
    -------
    Footprint
        kind "pressure", profile "file", centred on the contact pixels' centroid;
        ``info['contact_area_m2']`` the area of the pixels in contact.

    Raises
    ------
    InputError
        A result whose pressure is negative, infinite or nowhere > 0.

    See Also
    --------
    asperity.solve_contact, asperity.pressure_footprint, asperity.slide_body

    Examples
    --------
    A sphere's cap of radius 10 mm on E* = 1 GPa under the load that gives Hertz's contact
    radius a = 0.1 mm (SPEC.md 7): the contact area is pi a^2 to 1 %:

    >>> R, E, a, n, dx = 0.01, 1e9, 1e-4, 32, 1e-5
    >>> x = (np.arange(n) - (n - 1) / 2) * dx
    >>> h = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)             # m, cap up
    >>> P = 4 * E * a**3 / (3 * R)                                     # N
    >>> res = asperity.solve_contact(h, (dx, dx), E, P / (n * dx) ** 2, boundary="free")
    >>> fp = asperity.contact_footprint(res)
    >>> print(f"{fp.info['contact_area_m2']:.3e} {np.pi * a**2:.3e}")   # m^2
    3.160e-08 3.142e-08
    """
    from ..contact.solver import ContactResult
    from ..errors import check_array, check_instance
    check_instance("result", result, ContactResult)
    pr = check_array("result.pressure", result.pressure, ndim=2, finite=False)
    if np.isinf(pr).any() or (pr < 0).any():     # a result made by hand, not solved
        raise InputError("result.pressure must be finite and >= 0 Pa (NaN: undefined)")
    dx, dy = check_array("result.pixel_size", result.pixel_size, shape=(2,)).tolist()
    if not (dx > 0 and dy > 0):
        raise InputError(f"result.pixel_size must be two lengths > 0 m, got {[dx, dy]}")
    i, j = np.nonzero(np.nan_to_num(pr) > 0)
    if i.size == 0:
        raise InputError(f"result: no pixel carries pressure: {NOT_CARRIED}")
    pts = np.column_stack([i * dx, j * dy])
    n = DEFAULT_CONTACT_POINTS["polygon"] if contact_points is None else contact_points
    fp = from_pressure(pts, pr[i, j], cell_areas=np.full(i.size, dx * dy),
                       contact_points=n)
    fp.info["contact_area_m2"] = float(i.size * dx * dy)
    return fp


def read_pressure(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a pressure file: points and their pressure.

    Parameters
    ----------
    path : str or os.PathLike
        A CSV file with the header ``x_m,y_m,p_Pa`` (commas, one point a line, ``#``
        comments) or a ``.npy`` array (n, 3) of the same columns.

    Returns
    -------
    points : (n, 2) numpy.ndarray
        m.
    pressures : (n,) numpy.ndarray
        Pa (checked by :func:`asperity.pressure_footprint`, not here).

    Raises
    ------
    InputError
        A missing or unreadable file, a wrong header, a line that is not three numbers.

    See Also
    --------
    asperity.pressure_footprint, asperity.read_body

    Examples
    --------
    >>> np.savetxt("pressure.csv", [[-0.01, 0, 1e5], [0.01, 0, 3e5]], delimiter=",",
    ...            header="x_m,y_m,p_Pa", comments="")
    >>> points, pressures = asperity.read_pressure("pressure.csv")
    >>> points.shape, pressures.tolist()
    ((2, 2), [100000.0, 300000.0])
    >>> fp = asperity.pressure_footprint(points, pressures)
    >>> fp.weights.tolist(), round(float(fp.centre_of_pressure[0]), 4)      # m
    ([0.25, 0.75], 0.005)
    """
    from os import PathLike
    from pathlib import Path

    from ..errors import check_instance
    from ..io import read_text_file
    pth = Path(check_instance("path", path, (str, PathLike), "file name (text or a Path)"))
    if not str(path):
        raise InputError("path: the pressure file's name is empty")
    if pth.suffix.lower() == ".npy":
        if not pth.is_file():
            raise InputError(f"pressure file {str(pth)!r} does not exist or is not a file")
        try:
            a = np.load(pth, allow_pickle=False)
        except (OSError, ValueError, EOFError) as exc:
            from ..errors import one_line
            raise InputError(f"{pth}: not a readable .npy pressure file ({one_line(exc)})") \
                from None
        a = check_array(f"{pth}: pressure array", a, shape=(None, 3), min_size=3)
    else:
        text = read_text_file(pth, "pressure file")
        lines = [ln.strip() for ln in text.splitlines() if ln.strip() and
                 not ln.lstrip().startswith("#")]
        if not lines or [h.strip() for h in lines[0].split(",")] != ["x_m", "y_m", "p_Pa"]:
            raise InputError(f"{pth}: a pressure file's first line must be the header "
                             "x_m,y_m,p_Pa")
        rows = []
        for i, ln in enumerate(lines[1:], start=2):
            parts = ln.split(",")
            try:
                if len(parts) != 3:
                    raise ValueError
                rows.append([float(x) for x in parts])
            except ValueError:
                raise InputError(f"{pth}: line {i} must hold three numbers x_m,y_m,p_Pa, "
                                 f"got {ln[:60]!r}") from None
        if not rows:
            raise InputError(f"{pth}: the pressure file holds no points")
        a = check_array(f"{pth}: pressure values", rows, shape=(None, 3))
    return a[:, :2].copy(), a[:, 2].copy()


# ----------------------------------------------------------------------------- a mesh's patch

def mesh_patch(mesh, *, unit: str | None = None, tolerance: float | None = None,
               contact_points: int | None = None, profile: str = "uniform",
               centre_of_pressure=(0.0, 0.0)) -> Footprint:
    """The contact patch of a triangle mesh resting on a plane, sampled as a polygon.

    The patch is made of the triangles whose three vertices lie within ``tolerance`` of
    the mesh's lowest point, projected on the x-y plane -- a flat bottom, a rim, several
    feet.  Their union is sampled as :func:`asperity.polygon_footprint` samples a polygon
    (the boundary edges of the projected triangles, so that edges shared by two triangles
    cancel).

    Parameters
    ----------
    mesh : str, os.PathLike or TriangleMesh
        A file read as :func:`asperity.read_surface` reads meshes (``.stl .obj .ply``), or
        a ``TriangleMesh`` (m).
    unit : str or None, optional
        Length unit of a mesh file (required for a file: the files carry none).
    tolerance : float or None, optional
        m, in [0, 1e3]; None (default): 1e-3 of the mesh's largest extent.
    contact_points : int or None, optional
        About how many points, in [1, 1e6]; None: 1024.
    profile : str, optional
        "uniform" (default) or "linear" (fixed by ``centre_of_pressure``).
    centre_of_pressure : (2,) array_like of float, optional
        (x, y), m, of a "linear" profile in the centred frame, inside the patch's core;
        default (0, 0).

    Returns
    -------
    Footprint
        kind "mesh", its outline the patch's boundary edges (NaN rows between loops);
        ``info`` holds ``faces`` (triangles in the patch), ``tolerance_m``, ``lowest_z_m``
        and ``source``.

    Raises
    ------
    InputError
        A file that is not a triangle mesh, no triangle with an area seen from below within
        ``tolerance`` of the lowest point (raise ``tolerance``), a value outside its range.

    See Also
    --------
    asperity.polygon_footprint, asperity.read_surface, asperity.read_body

    Notes
    -----
    Triangles standing on edge (no projected area) add nothing, and where the selected
    triangles face both ways (a closed mesh, normals outward) only those facing down are
    kept.  Triangles that overlap seen from below (a mesh that is not a single surface)
    would count twice.

    What it is not: a contact solution.  It assumes the part rests on the plane with the
    patch flat on it (rigid part, rigid support), pressure by ``profile``.

    Examples
    --------
    A pyramid on its 20 x 20 mm base: the patch is the base (two triangles), centred on
    its centroid, I/m = (a^2 + b^2)/12:

    >>> from asperity.surface.topography import TriangleMesh
    >>> v = [[0, 0, 0], [0.02, 0, 0], [0.02, 0.02, 0], [0, 0.02, 0], [0.01, 0.01, 0.01]]
    >>> f = [[0, 2, 1], [0, 3, 2], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    >>> fp = asperity.mesh_patch(TriangleMesh(v, f, "pyramid"), contact_points=100)
    >>> fp.n, fp.info["faces"], round(fp.area, 6), f"{fp.inertia_per_mass:.4e}"
    (100, 2, 0.0004, '6.6667e-05')
    """
    from os import PathLike

    from ..errors import check_instance
    from ..surface.topography import TriangleMesh
    check_instance("mesh", mesh, (str, PathLike, TriangleMesh),
                   "mesh file name or TriangleMesh")
    if not isinstance(mesh, TriangleMesh):
        from ..surface.readers import read_surface
        if not str(mesh):
            raise InputError("mesh: the file name is empty")
        try:
            mesh = read_surface(mesh, unit=unit)
        except InputError as exc:
            raise type(exc)(f"mesh: {exc}") from None
        if not isinstance(mesh, TriangleMesh):
            raise InputError("mesh must be a triangle mesh (.stl .obj .ply), got a height map")
    n = _count("mesh", contact_points)
    profile = _profile(profile, ("uniform", "linear"))
    cop = _cop(centre_of_pressure, profile)
    v, f = np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64)
    extent = float(np.ptp(v, axis=0).max())
    if tolerance is None:
        tol = 1e-3 * extent
    else:
        tol = check_range("tolerance", tolerance, 0.0, LENGTH_RANGE[1], unit="m")
    z0 = float(v[f].reshape(-1, 3)[:, 2].min())
    sel = f[np.all(v[f][:, :, 2] <= z0 + tol, axis=1)]
    tri = v[sel][:, :, :2]
    s = 0.5 * ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
               - (tri[:, 2, 0] - tri[:, 0, 0]) * (tri[:, 1, 1] - tri[:, 0, 1]))
    flat = np.abs(s) > 1e-12 * max(extent, 1e-300) ** 2
    sel, s = sel[flat], s[flat]
    if np.any(s < 0) and np.any(s > 0):
        # both windings: a closed mesh with outward normals; its underside faces down
        # (clockwise seen from above), the tops of inner steps up -- keep the underside
        sel, s = sel[s < 0], s[s < 0]
    if sel.shape[0] == 0:
        raise InputError(f"tolerance: no triangle of the mesh lies within {tol:g} m of its "
                         "lowest point with an area seen from below: no contact patch "
                         "(raise tolerance)")
    sel = np.where((s < 0)[:, None], sel[:, ::-1], sel)          # counter-clockwise
    e = np.concatenate([sel[:, [0, 1]], sel[:, [1, 2]], sel[:, [2, 0]]])
    key = np.sort(e, axis=1)
    sign = np.where(e[:, 0] < e[:, 1], 1, -1)
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    net = np.zeros(uniq.shape[0], dtype=np.int64)
    np.add.at(net, inv.ravel(), sign)
    keep = net != 0
    edges = []
    for (i, j), k in zip(uniq[keep], net[keep]):
        for _ in range(abs(int(k))):
            edges.append((i, j) if k > 0 else (j, i))
    ed = np.asarray(edges, dtype=np.int64)
    a, b = v[ed[:, 0], :2], v[ed[:, 1], :2]
    outline = np.full((3 * a.shape[0], 2), np.nan)
    outline[0::3], outline[1::3] = a, b
    fp = _lamina("mesh", a, b, n, profile, cop, outline)
    fp.info.update({"faces": int(sel.shape[0]), "tolerance_m": tol, "lowest_z_m": z0,
                    "source": mesh.source})
    return fp


