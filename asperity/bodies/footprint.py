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
* :func:`mesh_patch` -- the contact patch of a triangle mesh (``.stl .obj .ply`` read as
  :func:`asperity.read_surface` reads meshes, or a TriangleMesh): the triangles whose three
  vertices lie within ``tolerance`` of the lowest point, projected on the x-y plane
  (their union: the outline of a flat bottom, a rim, several feet), sampled as a polygon;
* :func:`from_pressure` -- points with a pressure each (a contact solution, a measured
  pressure film): :func:`read_pressure` reads them from a CSV ``x_m,y_m,p_Pa`` or a
  ``.npy`` (n, 3) file.

Pressure profiles (``profile``): "uniform"; "hertz" (a disc: p ~ sqrt(1 - r^2/R^2)); and
"linear" (p = a + b x + c y: the pressure of a rigid flat body under an eccentric or tilted
load, fixed by its centre of pressure ``centre_of_pressure`` (x, y) in m; refused when
the pressure would be negative somewhere -- a centre of pressure outside the footprint's
core, |c| <= R/4 for a disc -- since such a profile does not carry the load).

:func:`coulomb_wrench` gives the friction force and torque of a footprint on isotropic
Coulomb friction for a slide and a spin: the check of a sampling against the closed forms
of :mod:`asperity.bodies.closed_forms` (SPEC.md 8), whose measured errors against N
chose :data:`DEFAULT_CONTACT_POINTS` (``python benchmarks/footprint_quadrature.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_array, check_choice, check_int, check_range

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
#: most vertices of a polygon (its self-crossing check takes k^2 / 2 edge pairs)
MAX_VERTICES = 10_000
#: size limits of a footprint's lengths, m
LENGTH_RANGE = (1e-9, 1e3)
NOT_CARRIED = "a pressure profile that does not carry the load"
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


# ----------------------------------------------------------------------------- polygons

def _signed_area(v: np.ndarray) -> float:
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _edges_moments(a: np.ndarray, b: np.ndarray):
    """Area, first and second moments (about the origin) of the region bounded by the
    directed edges a -> b (counter-clockwise outer boundaries), by Green's theorem."""
    cr = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
    A = 0.5 * cr.sum()
    Sx = np.sum(cr * (a[:, 0] + b[:, 0])) / 6.0
    Sy = np.sum(cr * (a[:, 1] + b[:, 1])) / 6.0
    Ixx = np.sum(cr * (a[:, 0] ** 2 + a[:, 0] * b[:, 0] + b[:, 0] ** 2)) / 12.0   # int x^2
    Iyy = np.sum(cr * (a[:, 1] ** 2 + a[:, 1] * b[:, 1] + b[:, 1] ** 2)) / 12.0   # int y^2
    Ixy = np.sum(cr * (2 * a[:, 0] * a[:, 1] + a[:, 0] * b[:, 1] + b[:, 0] * a[:, 1]
                       + 2 * b[:, 0] * b[:, 1])) / 24.0
    return A, np.array([Sx, Sy]), np.array([[Ixx, Ixy], [Ixy, Iyy]])


def _orient(p, q, r):
    """Twice the signed area of the triangles p, q, r (arrays of points, broadcast)."""
    return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - \
        (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])


def _on_segment(p, q, r, o, tol, slack):
    """r lies on the segment p-q, given _orient(p, q, r) = o."""
    return (np.abs(o) <= tol) & \
        (np.minimum(p[..., 0], q[..., 0]) - slack <= r[..., 0]) & \
        (r[..., 0] <= np.maximum(p[..., 0], q[..., 0]) + slack) & \
        (np.minimum(p[..., 1], q[..., 1]) - slack <= r[..., 1]) & \
        (r[..., 1] <= np.maximum(p[..., 1], q[..., 1]) + slack)


def _crossing(v: np.ndarray):
    """The first pair (i, j) of non-adjacent edges of the closed polygon v that meet, else
    None (segments touching at a point count: a boundary that touches itself)."""
    k = v.shape[0]
    a, b = v, np.roll(v, -1, axis=0)
    scale = float(np.max(np.abs(v))) or 1.0
    tol, slack = 1e-12 * scale * scale, 1e-12 * scale
    for i in range(k - 2):
        j = np.arange(i + 2, k if i > 0 else k - 1)          # not i's neighbours
        if j.size == 0:
            continue
        o1, o2 = _orient(a[i], b[i], a[j]), _orient(a[i], b[i], b[j])
        o3, o4 = _orient(a[j], b[j], a[i]), _orient(a[j], b[j], b[i])
        proper = (o1 * o2 < 0) & (o3 * o4 < 0)
        touch = _on_segment(a[i], b[i], a[j], o1, tol, slack) | \
            _on_segment(a[i], b[i], b[j], o2, tol, slack) | \
            _on_segment(a[j], b[j], a[i], o3, tol, slack) | \
            _on_segment(a[j], b[j], b[i], o4, tol, slack)
        hit = np.flatnonzero(proper | touch)
        if hit.size:
            return i, int(j[hit[0]])
    return None


def check_polygon(vertices) -> np.ndarray:
    """``vertices`` (k, 2) of a simple polygon, counter-clockwise (turned if given
    clockwise); InputError for fewer than 3 vertices, zero area, or a boundary that crosses
    or touches itself."""
    v = check_array("vertices", vertices, shape=(None, 2))
    if v.shape[0] < 3:
        raise InputError(f"vertices must hold at least 3 points (x, y), got {v.shape[0]}")
    if v.shape[0] > MAX_VERTICES:
        raise InputError(f"vertices must hold at most {MAX_VERTICES} points, got {v.shape[0]}")
    if np.any(np.abs(v) > LENGTH_RANGE[1]):
        raise InputError(f"vertices must lie within {LENGTH_RANGE[1]:g} m of the origin")
    if v.shape[0] > 3 and np.all(v[0] == v[-1]):
        v = v[:-1]                                     # a closed list: last = first
    span = float(np.ptp(v, axis=0).max())
    A = _signed_area(v)
    if not span or abs(A) <= 1e-12 * span * span:
        raise InputError(f"vertices: the polygon has zero area (area must be > 0, got "
                         f"{abs(A):g} m^2)")
    hit = _crossing(v)
    if hit is not None:
        i, j = hit
        raise InputError(f"vertices: the polygon's boundary crosses itself (edge {i} "
                         f"{tuple(np.round(v[i], 6))}-{tuple(np.round(v[(i + 1) % len(v)], 6))}"
                         f" meets edge {j}); a footprint must be a simple polygon")
    return v if A > 0 else v[::-1].copy()


def _green_cells(XL, XH, YL, YH, a, b):
    """Area and first moments of the region bounded by the directed edges a -> b (e,)
    within each cell [XL, XH] x [YL, YH] ((c, 1) arrays): Green's theorem with clamped
    integrands (area = closed integral of (clamp(x) - XL) 1[y in cell] dy), each edge split
    where it crosses the cell's lines and integrated exactly (Simpson on each piece, the
    integrands being at most quadratic there)."""
    ax, ay = a[None, :, 0], a[None, :, 1]
    dx, dy = b[None, :, 0] - ax, b[None, :, 1] - ay
    # parameters where the edge crosses the cell's lines, clamped to [0, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        tx0 = np.where(dx != 0, (XL - ax) / dx, 0.0)
        tx1 = np.where(dx != 0, (XH - ax) / dx, 0.0)
        ty0 = np.where(dy != 0, (YL - ay) / dy, 0.0)
        ty1 = np.where(dy != 0, (YH - ay) / dy, 0.0)
    shape = np.broadcast_shapes(tx0.shape, ax.shape)
    ts = np.stack([np.zeros(shape), np.clip(tx0, 0, 1), np.clip(tx1, 0, 1),
                   np.clip(ty0, 0, 1), np.clip(ty1, 0, 1), np.ones(shape)], axis=-1)
    ts.sort(axis=-1)
    t0, t1 = ts[..., :-1], ts[..., 1:]
    tm = 0.5 * (t0 + t1)
    # the piece's midpoint decides whether the piece is inside the strip (its end points
    # lie on the strip's lines)
    ym = ay[..., None] + dy[..., None] * tm
    inside = (ym >= YL[..., None]) & (ym <= YH[..., None])
    a_ = mx_ = my_ = 0.0
    for t, wgt in ((t0, 1.0), (tm, 4.0), (t1, 1.0)):
        x = ax[..., None] + dx[..., None] * t
        y = ay[..., None] + dy[..., None] * t
        xc = np.clip(x, XL[..., None], XH[..., None])
        F = np.where(inside, xc - XL[..., None], 0.0)
        a_ = a_ + wgt * F
        mx_ = mx_ + wgt * np.where(inside, 0.5 * (xc * xc - XL[..., None] ** 2), 0.0)
        my_ = my_ + wgt * y * F
    w = (t1 - t0) * dy[..., None] / 6.0
    return (np.sum(a_ * w, axis=(-1, -2)), np.sum(mx_ * w, axis=(-1, -2)),
            np.sum(my_ * w, axis=(-1, -2)))


def _clip_cells(a: np.ndarray, b: np.ndarray, x0: float, y0: float, hx: float, hy: float,
                nx: int, ny: int):
    """Area and centroid of the region bounded by the directed edges a -> b within each
    cell [x0 + i hx, +hx] x [y0 + j hy, +hy] (:func:`_green_cells`), row by row with the
    edges that reach into the row (the others add nothing).  Returns (area, cx, cy),
    flat arrays of the nx x ny cells, index i ny + j."""
    A = np.zeros((nx, ny))
    Mx = np.zeros((nx, ny))
    My = np.zeros((nx, ny))
    ylo, yhi = np.minimum(a[:, 1], b[:, 1]), np.maximum(a[:, 1], b[:, 1])
    slanted = yhi > ylo                               # horizontal edges add nothing
    xl = x0 + np.arange(nx) * hx
    for j in range(ny):
        yl_ = y0 + j * hy
        sel = slanted & (ylo < yl_ + hy) & (yhi > yl_)
        if not np.any(sel):
            continue
        ea, eb = a[sel], b[sel]
        chunk = max(1, 100_000 // ea.shape[0])
        for c0 in range(0, nx, chunk):
            XL = xl[c0:c0 + chunk, None]
            YL = np.full_like(XL, yl_)
            A[c0:c0 + chunk, j], Mx[c0:c0 + chunk, j], My[c0:c0 + chunk, j] = \
                _green_cells(XL, XL + hx, YL, YL + hy, ea, eb)
    A, Mx, My = A.ravel(), Mx.ravel(), My.ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        cx = Mx / A
        cy = My / A
    return A, cx, cy


def _sample_region(a, b, n: int, area: float, grid=None):
    """Points (cell centroids) and areas of the region bounded by edges a -> b on a grid of
    about ``n`` covered cells (``grid`` (x0, y0, hx, hy, nx, ny) fixes the grid)."""
    lo = np.minimum(a.min(axis=0), b.min(axis=0))
    hi = np.maximum(a.max(axis=0), b.max(axis=0))
    if grid is not None:
        A, cx, cy = _clip_cells(a, b, *grid)
        keep = A > 1e-9 * grid[2] * grid[3]
        return np.column_stack([cx[keep], cy[keep]]), A[keep], (grid[2], grid[3])
    h = math.sqrt(area / n)
    best = None
    for _ in range(6):
        nx = max(1, int(math.ceil((hi[0] - lo[0]) / h - 1e-9)))
        ny = max(1, int(math.ceil((hi[1] - lo[1]) / h - 1e-9)))
        # the grid centred on the bounding box
        x0 = 0.5 * (lo[0] + hi[0]) - 0.5 * nx * h
        y0 = 0.5 * (lo[1] + hi[1]) - 0.5 * ny * h
        A, cx, cy = _clip_cells(a, b, x0, y0, h, h, nx, ny)
        keep = A > 1e-9 * h * h
        cnt = int(keep.sum())
        if best is None or abs(cnt - n) < abs(best[0] - n):
            best = (cnt, np.column_stack([cx[keep], cy[keep]]), A[keep], h)
        if cnt == n:
            break
        h *= math.sqrt(cnt / n)
    return best[1], best[2], (best[3], best[3])


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


# ----------------------------------------------------------------------------- checks of a sampling

def coulomb_wrench(fp: Footprint, eps: float, R: float | None = None,
                   direction: float = 0.0) -> tuple[np.ndarray, float]:
    """Friction force (2,) and torque of footprint ``fp`` on isotropic Coulomb friction
    (mu = 1, unit load) sliding at v = eps R along ``direction`` (rad) while spinning at
    omega = 1 rad/s (eps = inf: a pure slide at unit speed), torque in units of R.  A point
    at rest carries no force.  The closed forms give, for a disc, force -f(eps) along the
    velocity and torque -m(eps)."""
    R = fp.radius if R is None else R
    r = fp.points
    if math.isinf(eps):
        u = np.tile([math.cos(direction), math.sin(direction)], (r.shape[0], 1))
    else:
        u = eps * R * np.array([math.cos(direction), math.sin(direction)]) + \
            np.column_stack([-r[:, 1], r[:, 0]])
    s = np.hypot(u[:, 0], u[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.where(s[:, None] > 0, u / s[:, None], 0.0)
    F = -(fp.weights[:, None] * d).sum(axis=0)
    T = -float(np.sum(fp.weights * (r[:, 0] * d[:, 1] - r[:, 1] * d[:, 0]))) / R
    return F, T


# ----------------------------------------------------------------------------- pressure per point

def _inside_polygon(pts: np.ndarray, v: np.ndarray, tol: float) -> np.ndarray:
    """Whether each point lies in the closed polygon v (even-odd rule), or within ``tol``
    of its boundary."""
    x, y = pts[:, 0:1], pts[:, 1:2]
    a, b = v[None, :, :], np.roll(v, -1, axis=0)[None, :, :]
    ya, yb = a[..., 1], b[..., 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[..., 0] + (y - ya) * (b[..., 0] - a[..., 0]) / (yb - ya)
    cross = ((ya > y) != (yb > y)) & (x < xc)
    inside = np.count_nonzero(cross, axis=1) % 2 == 1
    # distance to the edges
    d = b - a
    L2 = np.maximum((d**2).sum(-1), 1e-300)
    t = np.clip(((pts[:, None, :] - a) * d).sum(-1) / L2, 0, 1)
    near = np.hypot(*(a + t[..., None] * d - pts[:, None, :]).transpose(2, 0, 1)).min(axis=1)
    return inside | (near <= tol)


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
    """A footprint of given points (n, 2) m and their pressures (n,) Pa (>= 0, some > 0):
    a contact solution or a measured pressure film.  Each point carries pressure x area of
    its cell (``cell_areas`` (n,) m^2; None: equal cells, the points of a regular grid);
    only the shape of the pressure matters, the weights are normalised (the body's weight
    is the load).  Points of zero pressure are dropped.

    ``shape``: the footprint the pressure acts on (its outline, area and inertia; the
    points are in its frame before it was centred, i.e. its ``info['centroid_shift']`` is
    subtracted; points outside it are refused).  None: the points' own (their convex hull
    as outline and area, the uniform lamina of the points for the inertia, centred on
    their area-weighted mean).

    ``contact_points``: None keeps every point of positive pressure; a number merges them
    into about that many (the cells of a square grid, each at the load centroid of its
    points: the load and the centre of pressure are kept) -- for a fine contact map."""
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
    """The footprint of an elastic contact solution (:func:`asperity.solve_contact`: a
    part's bottom, heights in m, pressed on a flat): the pixels in contact with their
    pressure, merged into about ``contact_points`` points (default: the polygon's default;
    see :func:`from_pressure`).  Pixel (i, j) is at (i dx, j dy)."""
    from ..contact.solver import ContactResult
    from ..errors import check_instance
    check_instance("result", result, ContactResult)
    pr = np.asarray(result.pressure, dtype=float)
    dx, dy = result.pixel_size
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
    """(points (n, 2) m, pressures (n,) Pa) of a pressure file: CSV with the header
    ``x_m,y_m,p_Pa`` (commas, one point a line) or a ``.npy`` array (n, 3) of the same
    columns."""
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
    """The contact patch of a triangle mesh resting on a plane: the triangles whose three
    vertices lie within ``tolerance`` (m; None: 1e-3 of the mesh's largest extent) of its
    lowest point, projected on the x-y plane -- a flat bottom, a rim, several feet.  Their
    union is sampled as a polygon (the boundary edges of the projected triangles, so that
    edges shared by two triangles cancel); triangles standing on edge (no projected area)
    add nothing, and where the selected triangles face both ways (a closed mesh, normals
    outward) only those facing down are kept.  Triangles that overlap seen from below
    (a mesh that is not a single surface) would count twice.  ``mesh``: a file read as :func:`asperity.read_surface` reads meshes
    (``.stl .obj .ply``; ``unit`` required, the files carry none) or a TriangleMesh.

    What it is not: a contact solution.  It assumes the part rests on the plane with the
    patch flat on it (rigid part, rigid support), pressure by ``profile``."""
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


#: the eps of the error table (issue 20): pure spin, slow slide, the disc's terminal ratio,
#: the instantaneous centre on the rim, fast slides
TABLE_EPS = (0.0, 0.1, 0.653, 1.0, 3.0, 100.0)


def sampling_errors(fp: Footprint, eps_values, directions: int = 48) -> list[dict]:
    """Worst relative errors of a disc's or ring's sampled Coulomb force (as a vector:
    |F + f e_v| / f) and torque (|T + m| / m) against the closed forms, over ``directions``
    velocity directions, for each eps (at eps = 0 the force's magnitude itself, the exact
    force being zero)."""
    from .closed_forms import footprint_f_m
    if fp.kind not in ("disc", "ring"):
        raise InputError(f"sampling_errors: a disc or ring footprint, got a {fp.kind}")
    R = fp.radius
    r = fp.points / R
    d = 2.0 * math.pi * np.arange(directions) / directions
    ev = np.column_stack([np.cos(d), np.sin(d)])                   # (k, 2)
    out = []
    for eps in eps_values:
        f, m = footprint_f_m(fp.kind, float(eps))
        if math.isinf(eps):
            u = np.broadcast_to(ev[:, None, :], (directions, r.shape[0], 2))
        else:
            u = eps * ev[:, None, :] + np.column_stack([-r[:, 1], r[:, 0]])[None]
        s = np.hypot(u[..., 0], u[..., 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            un = np.where(s[..., None] > 0, u / s[..., None], 0.0)
        F = np.einsum("j,kjc->kc", fp.weights, un)
        T = np.einsum("j,kj->k", fp.weights, r[:, 0] * un[..., 1] - r[:, 1] * un[..., 0])
        ef = np.hypot(*(F - f * ev).T).max() / (f if f > 0 else 1.0)
        em = np.abs(T - m).max() / (m if m > 0 else 1.0)
        out.append({"eps": float(eps), "force": float(ef), "torque": float(em)})
    return out
