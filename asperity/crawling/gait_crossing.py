"""Refusing a gait whose body crosses (or touches) itself during its period.

The body is sampled at ``samples`` instants of one period as a polyline: for curvature
gaits max(8 N, 512) equal segments, at most 16384 (rounded up to whole chunks; the
polyline departs from the curve by at most kappa h^2 / 8: 5e-8 L at kappa L = 100), for
a chain of links the links themselves (exact).  Two segments that are not neighbours and
come within ``tolerance`` (times L) of each other count as a crossing, as do two
neighbours folded back onto each other.

A body whose tangent angle spans less than a half-turn at every instant cannot touch
itself (:func:`_turns_less_than_half`: the curvature gaits' closed-form angle, no
positions needed); otherwise pairs are pruned in chunks of :data:`CHUNK` segments (more for long polylines: at most
:data:`MAX_CHUNKS` chunks).  A chunk lies within the arc length of its longer half from
its middle vertex, and two chunks farther apart than the sum of those radii cannot touch;
a run of one or two neighbouring chunks whose segment directions span less than pi (less
:data:`_MARGIN`) cannot cross itself (its projection on the mean direction grows by at
least h sin(margin / 2) a segment: more than the tolerance).  The remaining pairs of
segments, first those whose midpoints are within their half-lengths, are tested exactly,
in the order of time; the first instant with a contact is reported.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, check_int, check_range

CHUNK = 16                  #: segments per chunk (at least)
MAX_CHUNKS = 256
MAX_SEGMENTS = 16384
SAMPLES_RANGE = (4, 100_000)
_MARGIN = 0.01              #: rad below pi for the direction-span rule
_PAIRS = 2_000_000          #: segment pairs tested at once


def check_self_crossing(gait, n_points: int = 201, samples: int = 256,
                        tolerance: float = 1e-9) -> None:
    """Raise InputError with the first sampled time at which the body of ``gait`` crosses
    or touches itself (within ``tolerance`` L), and where along the body; else nothing.

    n_points : the points the solver will use (the polyline has at least 8 segments per
    point spacing, and 512); samples : instants over one period, t = i T / samples.
    """
    from .gait import POINTS_RANGE
    n = check_int("n_points", n_points, *POINTS_RANGE)
    nt = check_int("samples", samples, *SAMPLES_RANGE)
    tol = check_range("tolerance", tolerance, 0.0, 1e-3) * gait.length
    segments = -(-min(max(8 * n, 512), MAX_SEGMENTS) // CHUNK) * CHUNK
    t = np.arange(nt) * (gait.period / nt)
    if _turns_less_than_half(gait, t, segments):
        return
    k = -(-segments // max(CHUNK, -(-segments // MAX_CHUNKS)))
    step = max(1, min(2_000_000 // segments, 4_000_000 // (k * k)))   # memory
    for a in range(0, nt, step):
        verts, s = gait._polyline(t[a:a + step], segments)
        hit = first_contact(verts, tol)
        if hit is not None:
            i, p, q = hit
            sp, sq = 0.5 * (s[p] + s[p + 1]), 0.5 * (s[q] + s[q + 1])
            raise InputError(
                f"the gait crosses itself at t = {t[a + i]:.4g} s (s = {sp:.3g} m and "
                f"{sq:.3g} m of the body): lower the amplitude (or the joint angles), or "
                f"the number of waves")


def _turns_less_than_half(gait, t, segments: int) -> bool:
    """Whether the body never turns through pi (less :data:`_MARGIN`) at the instants t: its
    tangent angle then stays within a cone narrower than a half-turn, the body's projection
    on the cone's bisector grows by at least sin(margin / 2) per unit length, and no two of
    its points can meet (curvature gaits, whose tangent angle is in closed form, without
    their positions).  The span on the grid of ``segments`` intervals is padded by the
    largest step of the angle between grid points."""
    if not hasattr(gait, "tangent_angle"):
        return False
    phi, _ = gait.tangent_angle(t, np.linspace(0.0, gait.length, segments + 1))
    pad = float(np.abs(np.diff(phi, axis=1)).max(initial=0.0))
    span = float((phi.max(axis=1) - phi.min(axis=1)).max())
    return span + pad < math.pi - _MARGIN


def first_contact(verts: np.ndarray, tol: float):
    """The first instant at which a polyline touches itself: (instant, segment p, segment
    q) with p < q, or None.  verts : (nt, M + 1) complex, x + i y; tol : the distance that
    counts as touching."""
    nt, nv = verts.shape
    m = nv - 1
    d = np.diff(verts, axis=1)                               # (nt, M) segments
    length = np.abs(d)
    hits = np.full(nt, -1)
    found: dict = {}
    turn = d[:, 1:] * d[:, :-1].conj()                       # |d1| |d2| e^(i turning)
    # neighbours folded back: antiparallel, the far end of one within tol of the other
    fold = (turn.real < 0) & (np.abs(turn.imag) <= tol * np.maximum(length[:, 1:],
                                                                     length[:, :-1]))
    for i, j in zip(*np.nonzero(fold)):
        if hits[i] < 0:
            hits[i], found[i] = 1, (int(j), int(j) + 1)
    if m < 3:
        return _first(hits, found)
    size = min(max(CHUNK, -(-m // MAX_CHUNKS)), m)
    starts = np.arange(0, m, size)
    k = starts.size
    ends = np.minimum(starts + size, m)                      # the chunks' last vertices
    mid = (starts + ends) // 2
    centres = verts[:, mid]                                  # (nt, K)
    # every vertex of a chunk lies within the arc length of its half from the middle one
    halves = np.add.reduceat(length, np.ravel(np.column_stack([starts, mid])), axis=1)
    radius = np.maximum(halves[:, 0::2], halves[:, 1::2])
    # the direction of each segment, continuous along the body (relative to the first)
    angle = np.zeros((nt, m))
    np.cumsum(np.angle(turn), axis=1, out=angle[:, 1:])
    lo = np.minimum.reduceat(angle, starts, axis=1)
    hi = np.maximum.reduceat(angle, starts, axis=1)
    ia, ib = np.triu_indices(k)
    near = np.abs(centres[:, ia] - centres[:, ib]) <= radius[:, ia] + radius[:, ib] + tol
    same, nxt = ia == ib, ib == ia + 1
    near[:, same] = (hi - lo) >= math.pi - _MARGIN
    if k > 1:
        span = np.maximum(hi[:, 1:], hi[:, :-1]) - np.minimum(lo[:, 1:], lo[:, :-1])
        near[:, nxt] &= span >= math.pi - _MARGIN
    ti, c = np.nonzero(near)                                 # in the order of time
    ca, cb = ia[c], ib[c]
    b0, batch, most = 0, 16, max(1, _PAIRS // (size * size))
    while b0 < ti.size:                # small batches first: the first instant hit is early
        sl = slice(b0, b0 + batch)
        if hits[: ti[b0]].max(initial=-1) >= 0:              # an earlier instant has one
            break
        _pairs(verts, tol, ti[sl], starts[ca[sl]], ends[ca[sl]], starts[cb[sl]],
               ends[cb[sl]], size, hits, found)
        b0, batch = b0 + batch, min(2 * batch, most)
    return _first(hits, found)


def _first(hits, found):
    i = np.flatnonzero(hits >= 0)
    if i.size == 0:
        return None
    return int(i[0]), *found[int(i[0])]


def _pairs(verts, tol, ti, a0, a1, b0, b1, size, hits, found) -> None:
    """Test every pair of non-neighbouring segments between chunks [a0, a1) and [b0, b1)
    at instants ti (candidate arrays); record the first pair of each instant hit."""
    r = np.arange(size)
    p = a0[:, None, None] + r[None, :, None]                 # (c, size, 1)
    q = b0[:, None, None] + r[None, None, :]                 # (c, 1, size)
    ok = (p < a1[:, None, None]) & (q < b1[:, None, None]) & (q >= p + 2)
    c, i, j = np.nonzero(ok)
    if c.size == 0:
        return
    pp, qq, tt = p[c, i, 0], q[c, 0, j], ti[c]
    p1, p2, q1, q2 = verts[tt, pp], verts[tt, pp + 1], verts[tt, qq], verts[tt, qq + 1]
    # two segments touch only if their midpoints are within their half-lengths
    near = np.flatnonzero(np.abs(p1 + p2 - q1 - q2) <= np.abs(p2 - p1) + np.abs(q2 - q1)
                          + 2 * tol)
    pp, qq, tt = pp[near], qq[near], tt[near]
    d = segment_distance(p1[near], p2[near], q1[near], q2[near])
    for h in np.flatnonzero(d <= tol):
        if hits[tt[h]] < 0 or (pp[h], qq[h]) < found[tt[h]]:
            hits[tt[h]], found[tt[h]] = 1, (int(pp[h]), int(qq[h]))


def _cross(u, v):
    return (u.conj() * v).imag


def point_segment(x, a, b):
    """Distance from points x to segments [a, b] (complex arrays of one shape)."""
    ab = b - a
    den = np.abs(ab) ** 2
    u = np.clip(((x - a) * ab.conj()).real / np.where(den > 0, den, 1.0), 0.0, 1.0)
    return np.abs(a + u * ab - x)


def segment_distance(p1, p2, q1, q2):
    """Distance between segments [p1, p2] and [q1, q2] (complex arrays of one shape):
    zero where they cross, else the least of the four end-to-segment distances."""
    r, s = p2 - p1, q2 - q1
    o1, o2 = _cross(r, q1 - p1), _cross(r, q2 - p1)
    o3, o4 = _cross(s, p1 - q1), _cross(s, p2 - q1)
    crossing = (o1 * o2 < 0) & (o3 * o4 < 0)
    d = np.minimum.reduce([point_segment(q1, p1, p2), point_segment(q2, p1, p2),
                           point_segment(p1, q1, q2), point_segment(p2, q1, q2)])
    return np.where(crossing, 0.0, d)
