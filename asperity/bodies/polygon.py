"""Simple polygons for footprints: the self-crossing check, Green's-theorem moments and the
exact clipping of a polygon by the cells of a grid (the sampling of polygons, rectangles and
mesh patches in :mod:`asperity.bodies.footprint`)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_array

#: most vertices of a polygon (its self-crossing check takes k^2 / 2 edge pairs)
MAX_VERTICES = 10_000
#: size limits of a footprint's lengths, m
LENGTH_RANGE = (1e-9, 1e3)


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


