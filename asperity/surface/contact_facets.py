"""A height map's facets weighted by the normal force of an elastic contact (SPEC.md 7).

Under a nominal pressure p the counter-face touches only the summits, and the elasticity
of the bodies sets how the load shares out between them.  Here the map is pressed onto an
elastic half-space of effective modulus E* (frictionless normal contact, Polonsky-Keer:
:func:`asperity.contact.solve_contact`) and each facet weighs the normal force it carries,
the node pressures averaged onto it (:func:`.grid_facets.pressure_weight`).  The facet
law is unchanged.  The weighting assumes that the normal contact sets the load shares: it
stops being right where the pressure reaches the hardness (plastic flow: the optional cap
H only clips the pressure) and where sliding redistributes the load (tangential
tractions, ploughing, the sliding-induced tilt of the contact are left out).

* :class:`ElasticContact` -- the options: E*, one pressure or several (a load curve: each
  solution starts the next), the boundary (``periodic``: the map is one period and its
  cells across the edges are facets too; ``free``: a non-periodic scan), the hardness;
* :func:`elastic_facets` -- the facets of a HeightMap at each pressure; or of a
  TriangleMesh, pressed as its upper envelope on a height grid, each triangle weighing the
  force of the grid nodes it holds (:mod:`.mesh_grid`);
* :func:`load_elastic` -- the same from a surface file with :func:`load_surface`'s options.

Slope removal (``detrend="slope"``): on a ``free`` map the mean facet gradient is removed
from the facets and the same plane from the heights the half-space meets; a ``periodic``
map's mean slope is zero by construction (its facets' gradients telescope over the
period), so nothing is removed.  Memory: the solve's (``asperity.contact``), then the
facets' (:func:`.facets.facet_bytes` with a pressure field) and the pressure kept, 8
bytes a pixel; a family keeps every pressure's facets in contact.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError, check_array, check_choice, check_int, check_range, \
    is_array
from . import grid_facets as grid
from .facets import FacetSurface, facet_bytes, heightmap_facets
from .prepare import check_surface_options, prepare_surface
from .topography import HeightMap

BOUNDARIES = ("periodic", "free")
#: most pressures of one family
MAX_PRESSURES = 100
#: what the weighting assumes and where it stops being right (the text output's lines)
ASSUMPTIONS = ("load shares: the normal force each facet carries in a frictionless "
               "elastic contact (Polonsky-Keer half-space); the facet law is unchanged",
               "not right where the pressure reaches the hardness (plastic flow) nor where "
               "sliding redistributes the load (tangential tractions, ploughing)")


@dataclass(frozen=True)
class ElasticContact:
    """Contact-force weighting of a surface's facets: the options of the elastic contact.

    Under a nominal pressure the counter-face touches only the summits, and the elasticity
    sets how the load shares out between them.  With an ElasticContact the surface is
    pressed onto an elastic half-space (frictionless normal contact, Polonsky-Keer:
    :func:`asperity.solve_contact`) and each facet weighs the normal force it carries
    (SPEC.md section 7); the facet law is unchanged.  The fields are checked when it is made.

    Parameters
    ----------
    E_star : float
        Effective modulus of the elastic half-space, Pa, > 0
        (:func:`asperity.effective_modulus`).
    pressure : float or sequence of float
        Nominal mean pressure over the map's projected area, Pa, > 0; or a sequence of 1 to
        100 of them (a family: one law per pressure, each solve started from the previous).
    boundary : {"periodic", "free"} or None, default None
        ``periodic``: the map is one period (its cells across the edges are facets too);
        ``free``: a non-periodic scan; None: free for files and height maps, periodic for
        wedge textures.
    hardness : float or None, default None
        A perfectly plastic cap H, Pa, above every pressure.
    tol : float, default 1e-8
        Relative tolerance of the contact solve, in [1e-15, 0.1].
    max_iterations : int or None, default None
        Iteration limit of the contact solve, in [1, 1e7]; None: the solver's.

    Raises
    ------
    asperity.InputError
        A field that is not a real number or lies outside its range (one line naming it).

    See Also
    --------
    asperity.derive, asperity.derive_family, asperity.load_elastic, asperity.solve_contact

    Notes
    -----
    The weighting assumes that the normal contact sets the load shares: it stops being right
    where the pressure reaches the hardness (plastic flow: the cap only clips the pressure)
    and where sliding redistributes the load (tangential tractions, ploughing, the
    sliding-induced tilt of the contact are left out).  The load shares are only as good as
    the contact spots are resolved: give each spot tens of pixels.

    Examples
    --------
    The sawtooth of flank slopes 0.1 and 0.5 (mu = 0.15) at p/E* = 1e-2 (area weighting:
    mu_a+ = 0.15724):

    >>> e = asperity.ElasticContact(E_star=1e9, pressure=1e7)
    >>> print(e.pressures, e.family)
    (10000000.0,) False
    >>> saw = asperity.WedgeTexture(5.71059, 26.5651, 0.15, 0.15)
    >>> d = asperity.derive(saw, elastic=e)
    >>> print(f"contact {d.texture.elastic['area_fraction']:.4f}, "
    ...       f"mu_a+ = {d.axes['mu_a_plus']:.5f}")
    contact 0.1318, mu_a+ = 0.15737
    """

    E_star: float
    pressure: object
    boundary: str | None = None
    hardness: float | None = None
    tol: float = 1e-8
    max_iterations: int | None = None

    def __post_init__(self):
        E = check_range("E_star", self.E_star, 0.0, None, low_open=True, unit="Pa")
        raw = self.pressure
        seq = is_array(raw)
        values = [raw]
        if seq:
            values = list(check_array("pressure", raw, ndim=1, finite=False))
            check_int("pressure (number of values)", len(values), 1, MAX_PRESSURES)
        ps = tuple(check_range("pressure", v, 0.0, None, low_open=True, unit="Pa")
                   for v in values)
        if self.boundary is not None:
            check_choice("boundary", self.boundary, BOUNDARIES)
        H = self.hardness
        if H is not None:
            H = check_range("hardness", H, max(ps), None, low_open=True,
                            unit="Pa (above the mean pressure)")
        object.__setattr__(self, "E_star", E)
        object.__setattr__(self, "pressure", ps if seq else ps[0])
        object.__setattr__(self, "hardness", H)
        object.__setattr__(self, "tol", check_range("tol", self.tol, 1e-15, 0.1))
        if self.max_iterations is not None:
            object.__setattr__(self, "max_iterations",
                               check_int("max_iterations", self.max_iterations, 1, 10 ** 7))

    @property
    def pressures(self) -> tuple[float, ...]:
        """The pressures, as a tuple (one for a single pressure)."""
        return self.pressure if isinstance(self.pressure, tuple) else (self.pressure,)

    @property
    def family(self) -> bool:
        """Several pressures were given (a sequence, even of one)."""
        return isinstance(self.pressure, tuple)

    def boundary_or(self, default: str) -> str:
        return self.boundary or default


def check_elastic(elastic) -> ElasticContact:
    if not isinstance(elastic, ElasticContact):
        raise InputError(f"elastic must be an ElasticContact, got {type(elastic).__name__}")
    return elastic


def mean_facet_gradient(z: np.ndarray, dx: float, dy: float) -> tuple[float, float]:
    """The mean gradient of the map's defined facets (all of equal area): the plane the
    facets' slope removal takes off."""
    g = np.empty((2, 2 * (z.shape[0] - 1) * (z.shape[1] - 1)))
    grid.cell_gradients(z, dx, dy, g)
    ok = np.isfinite(g[0]) & np.isfinite(g[1])
    if not ok.any():
        raise InputError("the height map has no defined facet (no 2 x 2 block of defined "
                         "pixels): nothing can carry the load")
    return float(g[0][ok].mean()), float(g[1][ok].mean())


def contact_heights(hm: HeightMap, periodic: bool, level_slope: bool) -> np.ndarray:
    """The heights the half-space meets: the map's, less the facets' mean slope plane on a
    free map when the slope is removed."""
    z = np.ascontiguousarray(hm.heights)      # the solver's flat views need C order
    if periodic or not level_slope:
        return z
    a, b = mean_facet_gradient(z, float(hm.dx), float(hm.dy))
    x = np.arange(z.shape[0]) * float(hm.dx)
    y = np.arange(z.shape[1]) * float(hm.dy)
    return z - a * x[:, None] - b * y[None, :]


def contact_solutions(hm: HeightMap, elastic: ElasticContact, boundary: str,
                      level_slope: bool, observe=None):
    """Yield the ContactResult at each pressure of ``elastic``, in its order (the load
    curve of :func:`asperity.contact.iter_load_curve`: solved in increasing order, each
    from the previous pressure field); ``observe(result)``, when given, sees each first
    (the web page keeps a preview of the pressure field)."""
    from ..contact.curve import iter_load_curve
    z = contact_heights(hm, boundary == "periodic", level_slope)
    for res in iter_load_curve(
            z, (float(hm.dx), float(hm.dy)), elastic.E_star, elastic.pressures,
            boundary=boundary, hardness=elastic.hardness, tol=elastic.tol,
            max_iterations=elastic.max_iterations):
        if observe is not None:
            observe(res)
        yield res


def elastic_facets(hm, elastic: ElasticContact, *, mu=None, friction_map=None,
                   level_slope=True, info=None, max_slope=None, default_boundary="free",
                   observe=None, grid_step=None, node_bytes=0.0):
    """Yield the facets of ``hm`` weighted by the contact force at each pressure of
    ``elastic`` (FacetSurfaces whose ``elastic`` holds the contact's figures: the keys of
    ``asperity contact --json``).  Options as :func:`.facets.heightmap_facets`;
    ``default_boundary`` when ``elastic.boundary`` is None; ``observe`` as
    :func:`contact_solutions`'s.

    ``hm`` a TriangleMesh: its upper envelope on a grid of ``grid_step`` (m; None: the
    default of :func:`.mesh_grid.mesh_heightmap`; ``node_bytes`` for its memory check) is
    pressed, and each of the mesh's own triangles weighs the force of the grid nodes it
    holds (:func:`.mesh_grid.face_forces`); its facets are :func:`.facets.mesh_facets`'s
    (``elastic`` gains the grid's figures, :meth:`.mesh_grid.MeshGrid.to_dict`)."""
    from .topography import TriangleMesh
    if isinstance(hm, TriangleMesh):
        yield from _mesh_elastic_facets(hm, check_elastic(elastic), mu, friction_map,
                                        level_slope, info, max_slope, default_boundary,
                                        observe, grid_step, node_bytes)
        return
    if not isinstance(hm, HeightMap):
        raise InputError(f"elastic contact needs a height map or a triangle mesh, got "
                         f"{type(hm).__name__}")
    if grid_step is not None:
        raise InputError("grid_step applies to meshes (a height map has its own grid)")
    elastic = check_elastic(elastic)
    boundary = elastic.boundary_or(default_boundary)
    periodic = boundary == "periodic"
    for res in contact_solutions(hm, elastic, boundary, level_slope, observe):
        fs = heightmap_facets(hm, mu=mu, friction_map=friction_map, info=info,
                              level_slope=level_slope and not periodic, max_slope=max_slope,
                              pressure=res.pressure, periodic=periodic)
        summary = res.to_dict()
        del res
        yield replace(fs, elastic=summary)


def _mesh_elastic_facets(mesh, elastic, mu, friction_map, level_slope, info, max_slope,
                         default_boundary, observe, grid_step, node_bytes):
    from .facets import mesh_facets
    from .mesh_grid import face_forces, mesh_heightmap
    boundary = elastic.boundary_or(default_boundary)
    if boundary == "periodic":
        raise InputError("boundary of a mesh must be free (its height grid is no period of "
                         "a texture), got periodic")
    mg = mesh_heightmap(mesh, grid_step, node_bytes)
    for res in contact_solutions(mg.heightmap, elastic, boundary, level_slope, observe):
        force = face_forces(mesh, mg, res.pressure)
        summary = {**res.to_dict(), **mg.to_dict()}
        del res
        fs = mesh_facets(mesh, mu=mu, friction_map=friction_map, info=info,
                         level_slope=level_slope, max_slope=max_slope, force=force)
        yield replace(fs, elastic=summary)


def load_elastic(path, elastic: ElasticContact, *, unit=None, pixel_size=None,
                 height_scale=1.0, detrend="slope", mu=None, friction_map=None,
                 despike=None, despike_window=None, max_slope=None,
                 observe=None, grid_step=None) -> list[FacetSurface]:
    """Read a surface file and weight its facets by the force of an elastic contact.

    :func:`asperity.load_surface` with each facet weighing the normal force it carries when
    the surface is pressed onto an elastic half-space (:class:`asperity.ElasticContact`):
    one FacetSurface per pressure.  A height map or a mesh, read whole (no tiles); a mesh is
    pressed as its upper envelope on a height grid, and each of its triangles weighs the
    force of the grid nodes it holds.

    Parameters
    ----------
    path : str or os.PathLike
        The height-map or mesh file.
    elastic : ElasticContact
        The contact: its pressures, E* and boundary (None: ``free``).
    unit, pixel_size, height_scale, detrend, mu, friction_map : optional
        As for :func:`asperity.load_surface`.
    despike, despike_window, max_slope : optional
        As for :func:`asperity.load_surface`.
    observe : callable or None, default None
        ``observe(result)`` sees each pressure's contact solution first.
    grid_step : float or None, default None
        Spacing of a mesh's height grid, m, finite and > 0; None: its default (refused for
        a height map, which has its own grid).

    Returns
    -------
    list of FacetSurface
        One a pressure, in the order given: the facets in contact, weighted by their normal
        force (N); ``elastic`` holds the contact's figures (the keys of ``asperity contact
        --json``: ``area_fraction``, ``max_pressure_Pa``, ``iterations``, ...).

    Raises
    ------
    asperity.InputError
        As for :func:`asperity.load_surface`; a ``grid_step`` for a height map, ``observe``
        not callable, a periodic boundary for a mesh.
    asperity.AsperityError
        ``ContactNotConverged`` when a solve reaches its iteration limit.

    See Also
    --------
    asperity.load_surface, asperity.ElasticContact, asperity.derive_family

    Examples
    --------
    The ridged 64 x 64 scan at two pressures: the contact grows with the load, and the facets
    in contact with it:

    >>> surfaces = asperity.load_elastic("surfaces/scan-ridges.txt",
    ...                                  asperity.ElasticContact(1e9, [1e6, 1e7]), mu=0.15)
    >>> for s in surfaces:
    ...     print(f"{s.elastic['pressure_Pa']:g} Pa: {s.n_facets} facets, "
    ...           f"contact {s.elastic['area_fraction']:.4f}")
    1e+06 Pa: 237 facets, contact 0.0171
    1e+07 Pa: 1521 facets, contact 0.1343
    """
    from ..contact.elastic import BYTES_PER_PIXEL
    elastic = check_elastic(elastic)
    if grid_step is not None:
        g = check_range("grid_step", grid_step, 0.0, None, low_open=True, unit="m")
        if not np.isfinite(g):
            raise InputError(f"grid_step must be a finite length in m, got {g}")
    if observe is not None and not callable(observe):
        raise InputError(f"observe must be a callable or None, got "
                         f"{type(observe).__name__}")
    despike, max_slope = check_surface_options(detrend=detrend, mu=mu, despike=despike,
                                               despike_window=despike_window,
                                               max_slope=max_slope)
    boundary = elastic.boundary_or("free")
    per_point = max(BYTES_PER_PIXEL[boundary], facet_bytes(False, True)) + 16
    prep = prepare_surface(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale,
                           detrend=detrend, friction_map=friction_map, despike=despike,
                           point_bytes=per_point)
    out = []
    if grid_step is not None and isinstance(prep.surface, HeightMap):
        raise InputError(f"grid_step applies to meshes; {path} is a height map (its own "
                         "grid)")
    for fs in elastic_facets(prep.surface, replace(elastic, boundary=boundary), mu=mu,
                             friction_map=prep.friction_map, level_slope=prep.level_slope,
                             info=prep.info, max_slope=max_slope, observe=observe,
                             grid_step=grid_step, node_bytes=per_point):
        fs.quality.update(prep.quality)
        out.append(fs)
    return out


def contact_lines(c: dict) -> list[str]:
    """Text lines of a contact's figures (``c``: the keys of ``asperity contact --json``)
    and of what the weighting assumes."""
    H = c.get("hardness_Pa")
    lines = [f"elastic contact: p = {c['pressure_Pa']:.4g} Pa (p/E* = "
             f"{c['pressure_Pa'] / c['E_star_Pa']:.3g}), E* = {c['E_star_Pa']:.4g} Pa, "
             f"boundary {c['boundary']}, hardness "
             + ("none" if H is None else f"{H:.4g} Pa"),
             f"  contact area fraction {c['area_fraction']:.4g}, max pressure "
             f"{c['max_pressure_Pa']:.4g} Pa, mean gap {c['mean_gap_m']:.4g} m; "
             f"{c['iterations']} iterations, residual {c['residual']:.2g}"]
    if c["area_fraction"] >= 1.0:
        lines.append("  full contact: the whole surface carries load (the load shares "
                     "still follow the pressure, not the area)")
    if c.get("plastic_fraction"):
        lines.append(f"  {100 * c['plastic_fraction']:.3g} % of the surface at the hardness "
                     "(plastic)")
    return lines + ["  " + a for a in ASSUMPTIONS]
