"""Footprints of planar rigid bodies: where a body touches its support and what share of the
normal load each contact point carries (issue 20).

A :class:`~asperity.Footprint` is a set of contact points in the body frame (m; the origin
is the centroid of the footprint, the centre of mass of a uniform lamina of its shape) with
weights: the share of the normal load each point carries (> 0, summing to 1; pressure times
the area of the point's cell over the load).  The body solver applies the friction law at
every point with the normal load ``weight * N``.

Constructors, each sampling its shape at about ``contact_points`` points
(:data:`DEFAULT_CONTACT_POINTS` per kind when None; their docstrings give the rules):
:func:`disc` (a polar product rule, Gauss in the radius), :func:`ring` (a thin ring),
:func:`rectangle` and :func:`polygon` (the covered cells of a grid);
:func:`~asperity.bodies.pressure.mesh_patch` (the contact patch of a triangle mesh) and
:func:`~asperity.bodies.pressure.from_pressure` (points with a pressure each: a contact
solution, a pressure film, a file read by :func:`~asperity.bodies.pressure.read_pressure`)
sit in :mod:`asperity.bodies.pressure`.

Pressure profiles (``profile``): "uniform"; "hertz" (a disc: p ~ sqrt(1 - r^2/R^2)); and
"linear" (p = a + b x + c y: the pressure of a rigid flat body under an eccentric or tilted
load, fixed by its centre of pressure ``centre_of_pressure`` (x, y) in m; refused when
the pressure would be negative somewhere -- a centre of pressure outside the footprint's
core, |c| <= R/4 for a disc -- since such a profile does not carry the load).

:func:`~asperity.bodies.accuracy.coulomb_wrench` gives the friction force and torque of a footprint on isotropic
Coulomb friction for a slide and a spin: the check of a sampling against the closed forms
of :mod:`asperity.bodies.closed_forms` (SPEC.md 8), whose measured errors against N
chose :data:`DEFAULT_CONTACT_POINTS` (``python benchmarks/footprint_quadrature.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_array, check_choice, check_int, check_range
from .polygon import LENGTH_RANGE, _edges_moments, _sample_region, check_polygon

KINDS = ("point", "disc", "ring", "rectangle", "polygon", "mesh", "pressure")
PROFILES = ("uniform", "hertz", "linear")
#: contact points of each kind when none are asked for: the disc's force and torque are
#: then within 0.5 % of the closed forms for every eps (measured, see the module docstring)
DEFAULT_CONTACT_POINTS = {"disc": 1024, "ring": 512, "rectangle": 1024, "polygon": 1024,
                          "mesh": 1024}
#: the disc rule: n_r = round(RINGS_PER_SQRT_N sqrt(N)) rings, points per ring ~ r^RING_POWER
RINGS_PER_SQRT_N = 0.7
RING_POWER = 0.25
#: most contact points of a footprint (a solver step visits each)
MAX_CONTACT_POINTS = 1_000_000
#: memory a contact point costs in a footprint and a solver (points, weights, work arrays)
BYTES_PER_POINT = 512
NOT_CARRIED = "a pressure distribution that does not carry the load"
GOLDEN_ANGLE = math.pi * (3.0 - math.sqrt(5.0))


@dataclass(frozen=True)
class Footprint:
    """Contact points of a planar rigid body and the share of the load each carries.

    The body solver (:func:`asperity.slide_body`) applies the friction law at every point
    with the normal load ``weight * N``.  Build one with a constructor
    (:func:`asperity.disc_footprint` and the others below) rather than by hand; the fields
    are checked and the arrays made read-only.

    Parameters
    ----------
    kind : str
        "point", "disc", "ring", "rectangle", "polygon", "mesh" or "pressure".
    points : (n, 2) array_like of float
        Contact points, m, in the body frame (origin: the footprint's centroid).
    weights : (n,) array_like of float
        Share of the normal load each point carries: each > 0, their sum 1 (to 1e-9).
    outline : (k, 2) array_like of float
        The footprint's boundary for drawing, m (a disc or ring: its circle; a mesh patch:
        its boundary edges end to end, NaN rows between separate loops).
    area : float
        Area, m^2, >= 0 (0 for a point and the thin ring).
    radius : float or None, optional
        Radius of a disc or ring, m, in [1e-9, 1e3]; None for other shapes.
    profile : str, optional
        The pressure profile: "uniform" (default), "hertz", "linear" or "file".
    inertia_per_mass : float, optional
        I / m of the uniform lamina about the centroid, m^2, >= 0 (the thin ring: R^2): the
        body's inertia when none is given.
    info : dict, optional
        How the footprint was made (e.g. ``centroid_shift``: by how much, m, the given
        shape was moved to put its centroid at the origin); not compared.

    Raises
    ------
    InputError
        A field outside its range, or weights that are not positive shares summing to 1.

    See Also
    --------
    asperity.disc_footprint, asperity.ring_footprint, asperity.rectangle_footprint,
    asperity.polygon_footprint, asperity.mesh_patch, asperity.pressure_footprint,
    asperity.contact_footprint, asperity.slide_body

    Notes
    -----
    ``fp.n`` is the number of points and ``fp.centre_of_pressure`` (m) the load-weighted
    mean of the points (0 for a uniform pressure).

    Examples
    --------
    Two points carrying a quarter and three quarters of the load:

    >>> fp = asperity.Footprint("pressure", [[-0.01, 0.0], [0.01, 0.0]], [0.25, 0.75],
    ...                         [[-0.01, 0.0], [0.01, 0.0]], 0.0)
    >>> fp.n, [round(float(c), 4) for c in fp.centre_of_pressure]      # m
    (2, [0.005, 0.0])
    """

    kind: str
    points: np.ndarray
    weights: np.ndarray
    outline: np.ndarray
    area: float
    radius: float | None = None
    profile: str = "uniform"
    inertia_per_mass: float = 0.0
    info: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        check_choice("kind", self.kind, KINDS)
        check_choice("profile", self.profile, PROFILES + ("file",))
        from ..errors import check_instance
        check_instance("info", self.info, dict)
        p = check_array("points", self.points, shape=(None, 2), min_size=2)
        w = check_array("weights", self.weights, shape=(p.shape[0],))
        if np.any(w <= 0) or abs(w.sum() - 1.0) > 1e-9:
            raise InputError("weights must be > 0 and sum to 1 (shares of the load), got "
                             f"min {w.min():g}, sum {w.sum():.12g}")
        o = check_array("outline", self.outline, shape=(None, 2), finite=False)
        for name, a in (("points", p), ("weights", w), ("outline", o)):
            a = np.array(a, dtype=float)
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        check_range("area", self.area, 0.0, None)
        check_range("inertia_per_mass", self.inertia_per_mass, 0.0, None, unit="m^2")
        if self.radius is not None:
            check_range("radius", self.radius, *LENGTH_RANGE, unit="m")

    @property
    def n(self) -> int:
        """Number of contact points."""
        return int(self.points.shape[0])

    @property
    def centre_of_pressure(self) -> np.ndarray:
        """(2,) m: the load-weighted mean of the points (0 for a uniform pressure)."""
        return self.weights @ self.points


# ----------------------------------------------------------------------------- checks

def _length(name: str, value) -> float:
    return check_range(name, value, *LENGTH_RANGE, unit="m")


def _count(kind: str, contact_points) -> int:
    if contact_points is None:
        return DEFAULT_CONTACT_POINTS[kind]
    n = check_int("contact_points", contact_points, 1, MAX_CONTACT_POINTS)
    from ..resources import check_memory
    check_memory(n * BYTES_PER_POINT, f"{n} contact points", "lower contact_points")
    return n


def _profile(profile, allowed=PROFILES) -> str:
    return check_choice("pressure_profile", profile, allowed)


def _cop(value, profile: str) -> np.ndarray:
    c = check_array("centre_of_pressure", value, shape=(2,))
    for v in c:
        check_range("centre_of_pressure", v, -LENGTH_RANGE[1], LENGTH_RANGE[1], unit="m")
    if profile != "linear" and np.any(c != 0):
        raise InputError("centre_of_pressure applies to pressure_profile linear only, got "
                         f"{profile!r}")
    return c


def _linear_beta(cop: np.ndarray, area: float, J: np.ndarray) -> np.ndarray:
    """beta of p = a (1 + beta . r) with centre of pressure ``cop``: J beta = A cop, J the
    second moments [[Ixx, Ixy], [Ixy, Iyy]] about the centroid."""
    return np.linalg.solve(J, area * cop)


def _refuse_negative(cop, beta, boundary, core_note: str):
    """InputError if 1 + beta . r < 0 at some boundary point r (the linear pressure is then
    negative there: the profile cannot carry the load)."""
    if boundary.size == 0 or not np.any(beta):
        return
    q = 1.0 + boundary @ beta
    k = int(np.argmin(q))
    if q[k] < -1e-12:
        x, y = boundary[k]
        raise InputError(f"centre_of_pressure ({cop[0]:g}, {cop[1]:g}) m: {NOT_CARRIED} (the "
                         f"linear pressure is negative at ({x:.4g}, {y:.4g}) m); it must lie "
                         f"in the footprint's core{core_note}")


# ----------------------------------------------------------------------------- disc and ring

def _ring_counts(radii: np.ndarray, n: int) -> np.ndarray:
    """Points per ring: n in all, proportional to the radii (largest remainders), >= 1 each."""
    share = radii / radii.sum() * n
    k = np.maximum(np.floor(share).astype(int), 1)
    while k.sum() > n:                                   # only when n < number of rings
        k[np.argmax(k)] -= 1
    rest = n - k.sum()
    if rest > 0:
        order = np.argsort(-(share - np.floor(share)), kind="stable")
        k[order[:rest]] += 1
    return k


def _disc_rule(n: int, profile: str):
    """(radii in units of R, ring weights summing to 1, points per ring) of the disc rule."""
    from scipy.special import roots_jacobi, roots_legendre
    n_r = min(n, max(1, int(round(RINGS_PER_SQRT_N * math.sqrt(n)))))
    if profile == "hertz":
        # int_0^1 2 r (3/2) sqrt(1 - r^2) g dr, x = 2 r - 1: (1 - x)^(1/2) times smooth
        x, w = roots_jacobi(n_r, 0.5, 0.0)
        r = 0.5 * (1.0 + x)
        W = w * r * np.sqrt(1.0 + r)
    else:
        x, w = roots_legendre(n_r)
        r = 0.5 * (1.0 + x)
        W = w * r                                        # int 2 r g dr = sum w r g (x 1)
    W = W / W.sum()
    return r, W, _ring_counts(r ** RING_POWER, n)


def disc(radius: float, *, contact_points: int | None = None, profile: str = "uniform",
         centre_of_pressure=(0.0, 0.0)) -> Footprint:
    """A disc of radius R sampled by a polar product rule (public as ``disc_footprint``).

    Parameters
    ----------
    radius : float
        R, m, in [1e-9, 1e3].
    contact_points : int or None, optional
        About how many points, in [1, 1e6]; None: 1024.
    profile : str, optional
        The pressure: "uniform" (default), "hertz" (p ~ sqrt(1 - r^2/R^2)) or "linear"
        (p = a + b x + c y, fixed by ``centre_of_pressure``).
    centre_of_pressure : (2,) array_like of float, optional
        (x, y), m, of a "linear" profile, inside the core ``|c| <= R/4`` (default (0, 0));
        other profiles take (0, 0) only.

    Returns
    -------
    Footprint
        kind "disc", the points centred on the disc's centre, ``inertia_per_mass`` R^2/2,
        ``info['rings']`` the number of rings.

    Raises
    ------
    InputError
        A value outside its range; a centre of pressure outside the core (the linear
        pressure would be negative at the rim: it does not carry the load).

    See Also
    --------
    asperity.ring_footprint, asperity.disc_f_m, asperity.slide_body

    Notes
    -----
    n_r ~ 0.7 sqrt(N) rings at the nodes of Gauss's rule in the radius: Gauss-Legendre for
    uniform pressure, exact for the integrals of r^k r dr, k = -1 .. 2 n_r - 2, so that the
    slow-slide force and the pure-spin torque are exact; Gauss-Jacobi with the weight
    sqrt(1 - r/R) for Hertz's pressure.  Each ring holds equally spaced points, their
    number ~ r^(1/4) (more points, hence smaller cells, near the centre than cells of equal
    size would give: a point's error near the instantaneous centre is about its weight, and
    the force there is ~ eps), turned by the golden angle from ring to ring; a point's
    weight is its ring's weight over the points on the ring (times the profile).

    Examples
    --------
    The pure-spin torque arm, the load-weighted mean of ``|r|``, is 2R/3 (m(0) = 2/3 of
    SPEC.md 8), exactly:

    >>> fp = asperity.disc_footprint(0.05)
    >>> fp.n, fp.info["rings"]
    (1024, 22)
    >>> print(f"{fp.weights @ np.hypot(*fp.points.T) / 0.05:.12f}")
    0.666666666667
    """
    R = _length("radius", radius)
    n = _count("disc", contact_points)
    profile = _profile(profile)
    cop = _cop(centre_of_pressure, profile)
    r, W, k = _disc_rule(n, profile)
    pts, wts = [], []
    for j, (rj, Wj, kj) in enumerate(zip(r, W, k)):
        phi = GOLDEN_ANGLE * j + 2.0 * math.pi * np.arange(kj) / kj
        pts.append(R * rj * np.column_stack([np.cos(phi), np.sin(phi)]))
        wts.append(np.full(kj, Wj / kj))
    pts, wts = np.concatenate(pts), np.concatenate(wts)
    if profile == "linear":
        J = np.eye(2) * math.pi * R**4 / 4.0
        beta = _linear_beta(cop, math.pi * R * R, J)
        th = np.linspace(0.0, 2 * math.pi, 721)
        _refuse_negative(cop, beta, R * np.column_stack([np.cos(th), np.sin(th)]),
                         f" |c| <= R/4 = {R / 4:g} m")
        wts = wts * (1.0 + pts @ beta)
        wts = wts / wts.sum()
    th = np.linspace(0.0, 2.0 * math.pi, 181)
    return Footprint("disc", pts, wts, R * np.column_stack([np.cos(th), np.sin(th)]),
                     math.pi * R * R, R, profile, 0.5 * R * R,
                     {"rings": int(r.size)})


def ring(radius: float, *, contact_points: int | None = None) -> Footprint:
    """A thin ring of radius R: equally spaced points on the circle, equal weights
    (public as ``ring_footprint``).

    Parameters
    ----------
    radius : float
        R, m, in [1e-9, 1e3].
    contact_points : int or None, optional
        Number of points, in [3, 1e6]; None: 512.

    Returns
    -------
    Footprint
        kind "ring", uniform pressure along the ring, area 0, ``inertia_per_mass`` R^2.

    Raises
    ------
    InputError
        A value outside its range.

    See Also
    --------
    asperity.disc_footprint, asperity.ring_f_m

    Examples
    --------
    >>> fp = asperity.ring_footprint(0.02, contact_points=8)
    >>> fp.n, [round(float(c), 5) for c in fp.points[1]], round(fp.inertia_per_mass, 6)
    (8, [0.01414, 0.01414], 0.0004)
    """
    R = _length("radius", radius)
    n = _count("ring", contact_points)
    if n < 3:
        raise InputError(f"contact_points of a ring must be a whole number in [3, "
                         f"{MAX_CONTACT_POINTS}], got {n}")
    phi = 2.0 * math.pi * np.arange(n) / n
    pts = R * np.column_stack([np.cos(phi), np.sin(phi)])
    th = np.linspace(0.0, 2.0 * math.pi, 181)
    return Footprint("ring", pts, np.full(n, 1.0 / n),
                     R * np.column_stack([np.cos(th), np.sin(th)]), 0.0, R, "uniform", R * R)


def point() -> Footprint:
    """A point contact (the point mass of ``asperity slide``): one point, weight 1."""
    z = np.zeros((1, 2))
    return Footprint("point", z, np.ones(1), z, 0.0, None, "uniform", 0.0)


def _lamina(kind, a, b, n, profile, cop, outline, grid=None, core=""):
    """The footprint of the region bounded by the directed edges a -> b."""
    area, S, _ = _edges_moments(a, b)
    c = S / area
    a, b = a - c, b - c
    outline = outline - c
    area, _, J = _edges_moments(a, b)
    g = None if grid is None else (grid[0] - c[0], grid[1] - c[1], *grid[2:])
    pts, cell, hxy = _sample_region(a, b, n, area, g)
    w = cell / cell.sum()
    if profile == "linear":
        beta = _linear_beta(cop, area, J)
        _refuse_negative(cop, beta, np.concatenate([a, b]), core)
        w = cell * (1.0 + pts @ beta)          # exact integral of a linear p over the cell
        if np.any(w <= 0):
            keep = w > 0
            pts, w = pts[keep], w[keep]
        w = w / w.sum()
    elif profile == "hertz":
        raise InputError(f"pressure_profile hertz is for a disc, got a {kind}; use uniform "
                         "or linear")
    return Footprint(kind, pts, w, outline, float(area), None, profile,
                     float((J[0, 0] + J[1, 1]) / area),
                     {"centroid_shift": c.tolist(), "cell": [float(hxy[0]), float(hxy[1])]})


def _grid_counts(n: int, a: float, b: float) -> tuple[int, int]:
    """(n_a, n_b): n_a n_b <= n as large as possible with cells within 1.5 of square
    (closest to square among those)."""
    ideal = math.sqrt(n * a / b)
    best = None
    lo = min(n, max(1, int(ideal / 1.6)))
    for na in range(lo, max(lo, min(n, int(ideal * 1.6) + 2)) + 1):
        nb = max(1, n // na)
        aspect = (a / na) / (b / nb)
        key = (1 / 1.5 <= aspect <= 1.5, na * nb, -abs(math.log(aspect)))
        if best is None or key > best[0]:
            best = (key, na, nb)
    return best[1], best[2]


def rectangle(a: float, b: float, *, contact_points: int | None = None,
              profile: str = "uniform", centre_of_pressure=(0.0, 0.0)) -> Footprint:
    """A rectangle a x b centred on the origin, sampled at the midpoints of a grid of
    equal cells (public as ``rectangle_footprint``).

    Parameters
    ----------
    a : float
        Side along the body's x axis, m, in [1e-9, 1e3].
    b : float
        Side along the body's y axis, m, in [1e-9, 1e3].
    contact_points : int or None, optional
        At most this many points, in [1, 1e6]: an n_a x n_b grid, n_a n_b <= N, cells
        about square; None: 1024.
    profile : str, optional
        "uniform" (default) or "linear" (p = a + b x + c y, fixed by
        ``centre_of_pressure``).
    centre_of_pressure : (2,) array_like of float, optional
        (x, y), m, of a "linear" profile, inside the core, the rhombus
        ``|x|/(a/6) + |y|/(b/6) <= 1`` (default (0, 0)).

    Returns
    -------
    Footprint
        kind "rectangle", ``inertia_per_mass`` (a^2 + b^2)/12, ``info['cell']`` the cell's
        sides (m).

    Raises
    ------
    InputError
        A value outside its range; a centre of pressure outside the core; profile "hertz"
        (a disc's).

    See Also
    --------
    asperity.polygon_footprint, asperity.read_body

    Examples
    --------
    An 80 x 30 mm plate on 12 points, a 6 x 2 grid of 13.3 x 15 mm cells:

    >>> fp = asperity.rectangle_footprint(0.08, 0.03, contact_points=12)
    >>> fp.n, [round(c, 4) for c in fp.info["cell"]], round(fp.area, 6)
    (12, [0.0133, 0.015], 0.0024)
    >>> print(f"{fp.inertia_per_mass:.4e}")           # m^2, (a^2 + b^2) / 12
    6.0833e-04
    """
    a = _length("a", a)
    b = _length("b", b)
    n = _count("rectangle", contact_points)
    profile = _profile(profile, ("uniform", "linear"))
    cop = _cop(centre_of_pressure, profile)
    na, nb = _grid_counts(n, a, b)
    v = np.array([[-a / 2, -b / 2], [a / 2, -b / 2], [a / 2, b / 2], [-a / 2, b / 2]])
    fp = _lamina("rectangle", v, np.roll(v, -1, axis=0), n, profile, cop,
                 np.vstack([v, v[:1]]), grid=(-a / 2, -b / 2, a / na, b / nb, na, nb),
                 core=f" |x|/{a / 6:g} + |y|/{b / 6:g} <= 1")
    return fp


def polygon(vertices, *, contact_points: int | None = None, profile: str = "uniform",
            centre_of_pressure=(0.0, 0.0)) -> Footprint:
    """A simple polygon sampled at the covered cells of a square grid (public as
    ``polygon_footprint``).

    Parameters
    ----------
    vertices : (k, 2) array_like of float
        The polygon's corners, m, in either orientation and any frame; zero area or a
        boundary that crosses itself is refused.  The footprint is moved so that its
        centroid is the origin (``info['centroid_shift']`` says by how much).
    contact_points : int or None, optional
        About how many points, in [1, 1e6] (the grid is sized so); None: 1024.
    profile : str, optional
        "uniform" (default) or "linear" (p = a + b x + c y, fixed by
        ``centre_of_pressure``).
    centre_of_pressure : (2,) array_like of float, optional
        (x, y), m, of a "linear" profile in the centred frame, inside the polygon's core
        (the pressure >= 0 at every vertex); default (0, 0).

    Returns
    -------
    Footprint
        kind "polygon": each point at the centroid of the covered part of its cell, its
        weight that part's area (times the profile).

    Raises
    ------
    InputError
        A bad polygon, a value outside its range, a centre of pressure outside the core,
        profile "hertz".

    See Also
    --------
    asperity.rectangle_footprint, asperity.mesh_patch, asperity.read_body

    Examples
    --------
    A right triangle 60 x 30 mm: centroid at (20, 10) mm, I/m = (a^2 + b^2)/18:

    >>> fp = asperity.polygon_footprint([[0, 0], [0.06, 0], [0, 0.03]], contact_points=200)
    >>> [round(c, 4) for c in fp.info["centroid_shift"]], round(fp.area, 6)
    ([0.02, 0.01], 0.0009)
    >>> print(f"{fp.inertia_per_mass:.6f}")           # m^2
    0.000250
    """
    v = check_polygon(vertices)
    n = _count("polygon", contact_points)
    profile = _profile(profile, ("uniform", "linear"))
    cop = _cop(centre_of_pressure, profile)
    return _lamina("polygon", v, np.roll(v, -1, axis=0), n, profile, cop,
                   np.vstack([v, v[:1]]))
