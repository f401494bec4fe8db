"""Tables of a friction law fine enough to hand to an FE code.

A :class:`LawTable` holds the law's force per unit normal load ``p(psi)`` at sliding
directions ``psi`` (rad, strictly increasing over one turn, periodic), to be interpolated
linearly between its nodes.  :func:`law_table` places the nodes adaptively until the
interpolated force is within ``BUILD_TOL`` of the law's own (``gl.force``) at three points
inside every interval and the nodes' polygon is within ``BUILD_TOL`` of the boundary of C
along every ray; then it checks the bound ``TOL`` (the issue's 1e-4) on 36 000 directions
and refuses, naming the directions, where a table cannot follow the law.

A flat edge of D (every force on an arc of C slides along one direction ``e``) becomes a run
of nodes within ``ARC_HALF`` of ``e`` that follows that arc of C, the node at ``e`` itself
holding the law's own force there (the point on the ray of the edge's middle), so the table
is single-valued and its polygon is the whole boundary of C.

A law family (:class:`~asperity.laws.family.GaugeFamily`) becomes a :class:`FamilyTable`:
tables at levels of pressure (its members and, where needed, pressures between them, taken
by ``GaugeFamily.at``) on one common set of directions, blended linearly in ln p as the
family itself is; levels are added until the blend is within ``TOL`` of ``fam.at(p)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..laws.geometry import TOL as GAUGE_TOL
from ..laws.geometry import TWO_PI, polar_angle

#: the largest force error (per unit normal load) a table may have: the issue's bound
TOL = 1e-4
#: the error the refinement aims at (a margin under TOL)
BUILD_TOL = 2.5e-5
#: most nodes of one table
MAX_NODES = 40_000
#: directions of the final check
CHECK_DIRECTIONS = 36_000
#: half-width (rad) of the run of nodes that stands for a flat edge of D
ARC_HALF = 4.0 * GAUGE_TOL.edge
#: intervals shorter than this (rad) are not split further
MIN_STEP = 1e-10
#: most pressure levels of a family table
MAX_LEVELS = 64


class TableError(InputError):
    """A law whose table cannot meet the bound (the message names the directions)."""


@dataclass(frozen=True)
class LawTable:
    """psi (n,) strictly increasing, psi[-1] < psi[0] + 2 pi; p (n, 2) the force per unit
    normal load at each; max_error: the largest force error found by the check;
    max_radial_error: the largest error of the nodes' polygon against C along a ray."""

    psi: np.ndarray
    p: np.ndarray
    max_error: float = 0.0
    max_radial_error: float = 0.0

    @property
    def n(self) -> int:
        return int(self.psi.size)

    def force(self, psi) -> np.ndarray:
        """(m, 2) the interpolated force for the sliding directions ``psi`` (rad)."""
        return _interp(self.psi, self.p, np.atleast_1d(np.asarray(psi, dtype=float)))

    def radial(self, phi) -> np.ndarray:
        """(m,) the distance to the nodes' polygon along the rays ``phi`` (rad)."""
        return _polygon_radial(self.p, np.atleast_1d(np.asarray(phi, dtype=float)))


def _interp(psi_n, p_n, psi):
    """Periodic linear interpolation of the node values p_n (n, k) at psi."""
    x = np.append(psi_n, psi_n[0] + TWO_PI)
    y = np.vstack([p_n, p_n[:1]])
    q = psi_n[0] + np.mod(psi - psi_n[0], TWO_PI)
    j = np.clip(np.searchsorted(x, q, side="right") - 1, 0, psi_n.size - 1)
    t = (q - x[j]) / (x[j + 1] - x[j])
    return y[j] + t[:, None] * (y[j + 1] - y[j])


def _polygon_radial(pts, phi):
    """Ray-polygon distance for a polygon of nodes in (weakly) increasing polar angle."""
    ang = np.unwrap(polar_angle(pts))
    a = np.append(ang, ang[0] + TWO_PI)
    v = np.vstack([pts, pts[:1]])
    q = ang[0] + np.mod(phi - ang[0], TWO_PI)
    j = np.clip(np.searchsorted(a, q, side="right") - 1, 0, pts.shape[0] - 1)
    v0, d = v[j], v[j + 1] - v[j]
    u = np.column_stack([np.cos(q), np.sin(q)])
    den = u[:, 0] * d[:, 1] - u[:, 1] * d[:, 0]
    num = v0[:, 0] * d[:, 1] - v0[:, 1] * d[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(np.abs(den) > 0, num / den, np.hypot(v0[:, 0], v0[:, 1]))
    return r


def _edge_distance(psi, edges) -> np.ndarray:
    """(m,) the angle (rad) from each direction psi to the nearest edge (inf without one)."""
    if not edges.size:
        return np.full(np.shape(psi), np.inf)
    d = np.abs(np.remainder(np.asarray(psi)[:, None] - edges[None, :] + math.pi, TWO_PI) - math.pi)
    return d.min(axis=1)


def _edges(gl) -> np.ndarray:
    return np.mod(np.asarray(getattr(gl.law.D, "edges", np.empty(0)), dtype=float), TWO_PI)


def _arc_nodes(gl, e: float):
    """Nodes (psi, p) standing for the flat edge of D at e: C's boundary from the force's
    left limit to its right limit, the law's own force at e."""
    f = gl.force(np.array([e]))
    C = gl.law.C
    phi = [polar_angle(v[None, :])[0] for v in (f.p_minus[0], f.p[0], f.p_plus[0])]
    halves = []
    for a, b, side in ((phi[0], phi[1], -1.0), (phi[1], phi[2], 1.0)):
        span = math.remainder(b - a, TWO_PI)
        m = max(2, math.ceil(abs(span) / 0.004) + 1)
        s = np.linspace(0.0, 1.0, m)
        ph = a + span * s
        verts = np.asarray(getattr(C, "angles", np.empty(0)), dtype=float)
        if verts.size:                                  # keep C's own vertices on the arc
            sv = np.mod(verts - a, TWO_PI) / span if span > 0 else np.empty(0)
            s = np.unique(np.concatenate([s, sv[(sv > 0) & (sv < 1)]]))
            ph = a + span * s
        r = C.radial(ph)
        pts = r[:, None] * np.column_stack([np.cos(ph), np.sin(ph)])
        pts[0] = f.p_minus[0] if side < 0 else f.p[0]
        pts[-1] = f.p[0] if side < 0 else f.p_plus[0]
        ps = e + ARC_HALF * (s - 1.0) if side < 0 else e + ARC_HALF * s
        halves.append((ps, pts) if side < 0 else (ps[1:], pts[1:]))
    ps, pts = np.concatenate([h[0] for h in halves]), np.vstack([h[1] for h in halves])
    keep = np.append(True, np.diff(ps) > 0)               # s that round to one float
    return ps[keep], pts[keep]


def law_table(gl, tol: float = TOL, start: int = 360) -> LawTable:
    """The table of the GaugeLaw ``gl`` (see the module's text); :class:`TableError` when the
    bound ``tol`` cannot be met, naming the directions."""
    from ..errors import check_range
    tol = check_range("tol", tol, 1e-9, 0.1)
    build = min(BUILD_TOL, 0.25 * tol)
    edges = _edges(gl)
    psi = TWO_PI * np.arange(start) / start
    psi = psi[_edge_distance(psi, edges) > 3.0 * ARC_HALF]
    p = gl.force(psi).p
    arc = np.full(psi.size, -1)
    for k, e in enumerate(edges):
        a_psi, a_p = _arc_nodes(gl, float(e))
        psi, p = np.concatenate([psi, a_psi]), np.vstack([p, a_p])
        arc = np.concatenate([arc, np.full(a_psi.size, k)])
    psi = np.mod(psi, TWO_PI)
    order = np.argsort(psi, kind="stable")
    psi, p, arc = psi[order], p[order], arc[order]
    C = gl.law.C
    for _ in range(60):
        x1 = np.append(psi[1:], psi[0] + TWO_PI)
        p1 = np.vstack([p[1:], p[:1]])
        a1 = np.append(arc[1:], arc[0])
        free = ~((arc >= 0) & (arc == a1)) & (x1 - psi > MIN_STEP)
        bad = np.zeros(psi.size, bool)
        for t in (0.25, 0.5, 0.75):
            q = psi + t * (x1 - psi)
            lin = p + t * (p1 - p)
            bad |= free & (np.hypot(*(gl.force(q).p - lin).T) > build)
        mid = 0.5 * (p + p1)                              # the chord against C on its ray
        rm = np.hypot(mid[:, 0], mid[:, 1])
        ok = rm > 0
        chord = np.zeros(psi.size)
        chord[ok] = np.abs(C.radial(polar_angle(mid[ok])) - rm[ok])
        bad |= free & (chord > build)
        if not bad.any():
            break
        if psi.size + int(bad.sum()) > MAX_NODES:
            break
        new = 0.5 * (psi[bad] + x1[bad])
        psi = np.concatenate([psi, np.mod(new, TWO_PI)])
        p = np.vstack([p, gl.force(new).p])
        arc = np.concatenate([arc, np.full(new.size, -1)])
        order = np.argsort(psi, kind="stable")
        psi, p, arc = psi[order], p[order], arc[order]
    return _checked(gl, psi, p, tol, edges)


def _checked(gl, psi, p, tol, edges) -> LawTable:
    """The final check on CHECK_DIRECTIONS directions (and the polygon against C)."""
    if np.any(np.diff(psi) <= 0):
        raise TableError("law table: two nodes at one sliding direction (the law's D is not "
                         "convex enough to be tabulated)")
    ang = np.unwrap(polar_angle(p))
    if np.any(np.diff(np.append(ang, ang[0] + TWO_PI)) < -1e-12):
        k = int(np.argmin(np.diff(np.append(ang, ang[0] + TWO_PI))))
        raise TableError(f"law table: the force turns back at psi = {math.degrees(psi[k]):.4f} "
                         "deg (C is not star-shaped about the origin along the sliding rule)")
    chk = TWO_PI * (np.arange(CHECK_DIRECTIONS) + 0.5) / CHECK_DIRECTIONS
    if edges.size:
        chk = np.concatenate([chk[_edge_distance(chk, edges) > 2.0 * ARC_HALF], edges])
    err = np.hypot(*(_interp(psi, p, chk) - gl.force(chk).p).T)
    phi = TWO_PI * np.arange(CHECK_DIRECTIONS) / CHECK_DIRECTIONS
    rerr = np.abs(_polygon_radial(p, phi) - gl.law.C.radial(phi))
    if err.max() > tol or rerr.max() > tol:
        bad = np.degrees(chk[err > tol]) if err.max() > tol else np.degrees(phi[rerr > tol])
        what = "force" if err.max() > tol else "boundary of C (polar angles)"
        raise TableError(
            f"law table: {psi.size} nodes cannot hold the {what} within {tol:g} at "
            f"{bad.size} directions, from {bad.min():.4f} to {bad.max():.4f} deg (largest "
            f"error {max(err.max(), rerr.max()):.3g}: the force changes faster there than "
            f"{MAX_NODES} nodes can follow, or jumps)")
    psi.setflags(write=False)
    p.setflags(write=False)
    return LawTable(psi, p, float(err.max()), float(rerr.max()))


@dataclass(frozen=True)
class FamilyTable:
    """Tables of a law family on common directions: psi (n,), p (L, n, 2) at the pressure
    levels pressures (L,) (Pa, increasing), blended linearly in ln p between two levels;
    clamped (no extrapolation) outside [pressures[0], pressures[-1]]."""

    psi: np.ndarray
    p: np.ndarray
    pressures: np.ndarray
    max_error: float = 0.0

    @property
    def n(self) -> int:
        return int(self.psi.size)

    def weights(self, pressure: float) -> tuple[int, float, bool]:
        """(k, w, clamped): the blend (1 - w) level k + w level k+1 at ``pressure``."""
        ps = self.pressures
        if ps.size == 1:
            return 0, 0.0, pressure != ps[0]
        if pressure <= ps[0]:
            return 0, 0.0, pressure < ps[0]
        if pressure >= ps[-1]:
            return ps.size - 2, 1.0, pressure > ps[-1]
        k = int(np.searchsorted(ps, pressure, side="right") - 1)
        w = math.log(pressure / ps[k]) / math.log(ps[k + 1] / ps[k])
        return k, w, False

    def level(self, pressure: float) -> LawTable:
        """The blended table at ``pressure`` (clamped to the levels' range)."""
        k, w, _ = self.weights(pressure)
        if self.pressures.size == 1:
            return LawTable(self.psi, self.p[0])
        return LawTable(self.psi, (1.0 - w) * self.p[k] + w * self.p[k + 1])


def family_table(fam, tol: float = TOL) -> FamilyTable:
    """The FamilyTable of a GaugeFamily: a level at each member, more levels between two
    members wherever the blend is not within ``tol`` of ``fam.at(p)``."""
    levels = {float(pk): law_table(m, tol) for pk, m in zip(fam.pressures, fam.members)}
    check = TWO_PI * (np.arange(3600) + 0.5) / 3600
    worst = 0.0
    todo = list(zip(fam.pressures[:-1], fam.pressures[1:]))
    while todo:
        a, b = todo.pop()
        ta, tb = levels[a], levels[b]
        errs, refs = [], {}
        for w in (0.25, 0.5, 0.75):
            refs[w] = ref = fam.at(a * (b / a) ** w)
            f = (1.0 - w) * ta.force(check) + w * tb.force(check)
            e = np.hypot(*(f - ref.force(check).p).T)
            e[_near_edges(check, ref)] = 0.0
            errs.append(float(e.max()))
        if max(errs) <= 0.8 * tol:
            worst = max(worst, max(errs))
            continue
        if len(levels) >= MAX_LEVELS or b / a < 1.0 + 1e-6:
            raise TableError(f"law family table: the laws between {a:g} and {b:g} Pa change "
                             f"too fast to blend within {tol:g} (error {max(errs):.3g} with "
                             f"{len(levels)} pressure levels)")
        pm = a * (b / a) ** 0.5                   # the middle level: the w = 0.5 law
        levels[pm] = law_table(refs[0.5], tol)
        todo += [(a, pm), (pm, b)]
    ps = np.array(sorted(levels))
    grid = np.unique(np.concatenate([levels[k].psi for k in ps]))
    grid = grid[np.append(True, np.diff(grid) > 1e-13)]
    p = np.stack([levels[k].force(grid) for k in ps])
    return FamilyTable(grid, p, ps, max(worst, max(t.max_error for t in levels.values())))


def _near_edges(psi, gl) -> np.ndarray:
    """Directions within 1e-3 rad of a flat edge of the law's D (where a family's members'
    edges move with the pressure, so a blend carries two half-jumps)."""
    return _edge_distance(psi, _edges(gl)) <= 2.0 * ARC_HALF + 1e-3
