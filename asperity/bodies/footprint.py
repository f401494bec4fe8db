"""Footprints of planar rigid bodies: where a body touches its support and what share of the
normal load each contact point carries (issue 20).

A :class:`Footprint` is a set of contact points in the body frame (m; the origin is the
centroid of the footprint, which is the centre of mass of a uniform lamina of its shape)
with weights: the share of the normal load each point carries (> 0, summing to 1; pressure
times the area of the point's cell over the load).  The body solver applies the friction
law at every point with the normal load ``weight * N``.

Constructors, each sampling its shape at about ``contact_points`` points
(:data:`DEFAULT_CONTACT_POINTS` per kind when None):

* :func:`disc` -- a polar product rule: n_r ~ 0.7 sqrt(N) rings at the nodes of Gauss's
  rule in the radius (Gauss-Legendre for uniform pressure, exact for int r^k r dr,
  k = -1 .. 2 n_r - 2, so that the slow-slide force and the pure-spin torque are exact;
  Gauss-Jacobi with the weight sqrt(1 - r/R) for Hertz's pressure), each with equally
  spaced points, their number ~ r^(1/4) (more points, hence smaller cells, near the centre
  than cells of equal size would give: a point's error near the instantaneous centre is
  about its weight, and the force there is ~ eps), turned by the golden angle from ring to
  ring; weight = ring weight / points on the ring (times the profile);
* :func:`ring` -- a thin ring: N equally spaced points on the circle, equal weights;
* :func:`rectangle` -- a x b (a along the body's x axis), the midpoints of an n_a x n_b
  grid of equal cells about square, equal weights;
* :func:`polygon` -- a simple polygon (vertices in either orientation; zero area or a
  boundary that crosses itself refused): the cells of a square grid that the polygon
  covers, each point at the centroid of the covered part of its cell, weight its area
  (about N points: the grid is sized so);
* :func:`~asperity.bodies.pressure.mesh_patch` -- the contact patch of a triangle mesh (``.stl .obj .ply`` read as
  :func:`asperity.read_surface` reads meshes, or a TriangleMesh): the triangles whose three
  vertices lie within ``tolerance`` of the lowest point, projected on the x-y plane
  (their union: the outline of a flat bottom, a rim, several feet), sampled as a polygon;
* :func:`~asperity.bodies.pressure.from_pressure` -- points with a pressure each (a contact solution, a measured
  pressure film): :func:`~asperity.bodies.pressure.read_pressure` reads them from a CSV ``x_m,y_m,p_Pa`` or a
  ``.npy`` (n, 3) file.

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

    kind             : "point", "disc", "ring", "rectangle", "polygon", "mesh" or "pressure"
    points           : (n, 2) float, m, body frame (origin: the footprint's centroid)
    weights          : (n,) float > 0, sum 1: share of the normal load of each point
    outline          : (k, 2) float, m: the footprint's boundary for drawing (a disc or
                       ring: its circle; a mesh patch: its boundary edges end to end, NaN
                       rows between separate loops)
    area             : m^2 (0 for a point and the thin ring)
    radius           : m for a disc or ring, else None
    profile          : the pressure profile: "uniform", "hertz", "linear" or "file"
    inertia_per_mass : m^2, I / m of the uniform lamina (the thin ring: R^2) about the
                       centroid -- the body's inertia when none is given
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
    """A disc of radius R (m) sampled at ``contact_points`` points (see the module
    docstring for the rule); ``profile`` "uniform", "hertz" or "linear" (with
    ``centre_of_pressure`` inside the core |c| <= R/4)."""
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
    """A thin ring of radius R (m): N equally spaced points on the circle, equal weights
    (uniform pressure along the ring); I/m = R^2."""
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
    """A rectangle a x b (m; a along the body's x axis) centred on the origin: the
    midpoints of an n_a x n_b grid of equal cells (n_a n_b <= N, cells about square).
    ``profile`` "uniform" or "linear" (``centre_of_pressure`` inside the core, the rhombus
    |x|/(a/6) + |y|/(b/6) <= 1)."""
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
    """A simple polygon (vertices (k, 2) in m, either orientation, in any frame: the
    footprint is moved so that its centroid is the origin; ``info['centroid_shift']`` says
    by how much).  About N points, the covered cells of a square grid."""
    v = check_polygon(vertices)
    n = _count("polygon", contact_points)
    profile = _profile(profile, ("uniform", "linear"))
    cop = _cop(centre_of_pressure, profile)
    return _lamina("polygon", v, np.roll(v, -1, axis=0), n, profile, cop,
                   np.vstack([v, v[:1]]))
