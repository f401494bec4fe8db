"""Running the spring-on-wedge kernels: the cost of a request, checked before any work, and
the kernels run in pieces that Ctrl-C can stop, with progress (physics in
:mod:`asperity.texture.springs`).

Units.  The kernels work in units of the texture's highest point z_max (lengths) and of
k_n z_max (forces).  The model's friction depends only on k_f/k_n and preload/(k_n z_max),
so a texture 1e-10 m or 100 m high computes alike: the squared forces of the return
mapping neither underflow nor overflow (a 1e-300 m wedge once gave mu = 444200).

Cost.  :func:`plan` gives, for every sliding direction, the springs N and the steps of the
kernel (the averaging window, and with finite k_f the run-in over RUN_IN_SLIP_LENGTHS
elastic slip lengths) before anything runs; :func:`check_cost` refuses a request beyond
MAX_UPDATES spring-tip updates with the reason and what lowers it.

Pieces.  Springs go in blocks of at most SPRINGS_PER_PIECE, each block's steps in pieces of
about UPDATES_PER_PIECE spring-tip updates (~0.05 s); Python raises KeyboardInterrupt
between two pieces and reports progress.  The tips carry their state from piece to piece
and the per-spring sums are added spring after spring, so a run gives the same result bit
for bit however it is split.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import progress
from ..errors import InputError, ResourceError
from .spring_model import (
    DIRECTION_UPDATES,
    LOCK_FORCE_RATIO,
    MAX_UPDATES,
    RUN_IN_SLIP_LENGTHS,
    SpringModel,
    _face_points,
    _Setup,
)

#: most springs of one kernel call
SPRINGS_PER_PIECE = 4096
#: spring-tip updates of one kernel call (about 0.05 s on one core)
UPDATES_PER_PIECE = {"rigid": 2_000_000, "elastic": 100_000}
LABEL = "spring simulation"
#: largest share of the friction a single sample (spring and step) may carry
MAX_SAMPLE_SHARE = 0.01


@dataclass(frozen=True)
class Plan:
    """Springs, averaging window, step (units of z_max) and kernel steps per direction."""

    springs: np.ndarray     # (n,) int, N
    window: np.ndarray      # (n,) int, m
    ds: np.ndarray          # (n,) float, step along s
    steps: np.ndarray       # (n,) float (may be astronomical before check_cost)
    face_p: np.ndarray      # (n, faces) |p_f| of each face (_faces), 0 where it locks

    def take(self, k: int) -> tuple[int, int, float, int]:
        return (int(self.springs[k]), int(self.window[k]), float(self.ds[k]),
                int(self.steps[k]))

    @property
    def updates(self) -> np.ndarray:
        return self.springs * self.steps


def _faces(st: _Setup):
    """(g, mu, where): slope and friction of each face of the profile (alpha, beta, flat
    gap; a Gaussian texture's wedges share them up to rounding, so a face's first segment
    stands for it) and the face of every segment, for the work done per face."""
    if st.seg_face.size <= 64:                  # a few segments: each its own face
        return st.seg_g, st.seg_mu, np.arange(st.seg_face.size)
    _, first, where = np.unique(st.seg_face, return_index=True, return_inverse=True)
    return st.seg_g[first], st.seg_mu[first], where.ravel()


def plan(st: _Setup, psi, model: SpringModel) -> Plan:
    """The plan of every direction psi (n,) for the texture of ``st`` (any direction's set-up).

    Stratified springs X_i = (i + 1/2) L/N, N = n_springs per pitch; the window is
    m = ceil(steps_per_period / n_springs) steps of W/(m |cos psi|), W = L/N, capped at one
    pitch; (nearly) along the ridges the body does not travel across the texture, so
    steps_per_period springs per pitch sample it in one step.  Finite k_f: a run-in of
    RUN_IN_SLIP_LENGTHS slip lengths plus one window first.
    """
    psi = np.asarray(psi, dtype=float)
    period = float(st.xs[-1]) / st.zref
    pitch = period / st.n_pitch
    n0 = model.n_springs * st.n_pitch
    m0 = -(-model.steps_per_period // model.n_springs)
    c, sn = np.cos(psi), np.sin(psi)
    ac = np.abs(c)
    ridge = ac * pitch * m0 <= period / n0
    N = np.where(ridge, max(n0, model.steps_per_period * st.n_pitch), n0)
    W = period / N
    m = np.where(ridge, 1, m0)
    across = ac * pitch * m > W
    with np.errstate(divide="ignore"):
        ds = np.where(across, W / (m * np.where(across, ac, 1.0)), pitch)
    g, mu, _ = _faces(st)
    px, py, lock = _face_points(g[None, :], mu[None, :], c[:, None], sn[:, None])
    face_p = np.where(lock, 0.0, np.hypot(px, py))
    if model.rigid:
        return Plan(N, m, ds, m.astype(float), face_p)
    pmax = np.where(lock.all(axis=1), 1.0, face_p.max(axis=1))
    z_rest = st.z_rest / st.zref
    slip = (1.0 + pmax + float(st.seg_mu.max())) * (1.0 - z_rest) / (model.k_f / model.k_n)
    run_in = RUN_IN_SLIP_LENGTHS * slip + m * ds
    return Plan(N, m, ds, np.ceil(run_in / ds) + m + 1, face_p)


def check_resolution(st: _Setup, psi, pl: Plan, model: SpringModel) -> None:
    """Refuse a sampling too coarse for the texture: a single sample (spring and step) may
    carry at most MAX_SAMPLE_SHARE of the friction.  A sample on segment j weighs
    k_n (z - z_r) |p_j|, at most (z_max - z_r) max_j |p_j|; the friction is
    S sum_j A_j |p_j| over the S samples of a pitch, A_j = the integral of (z - z_r)+ over
    segment j per pitch.  Catches faces too narrow for their force (a frictionless wall of
    89.99 deg is 3e-5 of the pitch and carries 90 % of mu_a+) and rest levels too close
    to the highest point."""
    dx = np.diff(st.xs)
    a, b = st.zs[:-1] - st.z_rest, st.zs[1:] - st.z_rest
    hi, lo = np.maximum(a, b), np.minimum(a, b)
    cut = lo < 0.0                              # the rest level crosses the segment
    area = 0.5 * dx * np.where(cut, np.maximum(hi, 0.0) ** 2 / np.where(hi > lo, hi - lo, 1.0),
                               a + b)
    where = _faces(st)[2]
    area = np.bincount(where, area, pl.face_p.shape[1]) * st.n_pitch / float(st.xs[-1])
    p = np.where(area > 0.0, pl.face_p, 0.0)
    total = p @ area
    samples = pl.springs * pl.window / st.n_pitch
    some = total > 0.0                          # else every face locks: nothing to sample
    share = np.where(some, (st.zs.max() - st.z_rest) * p.max(axis=1)
                     / (samples * np.where(some, total, 1.0)), 0.0)
    k = int(np.argmax(share))
    if share[k] <= MAX_SAMPLE_SHARE:            # (never NaN: that would be refused)
        return
    need = math.ceil(model.steps_per_period * share[k] / MAX_SAMPLE_SHARE)
    fix = (f"raise steps_per_period (--steps-per-period) to {need} or more" if need <= 1e8
           else "use the closed form (--method closed-form)")
    raise InputError(f"{model.steps_per_period} samples per pitch are too few for this texture "
                     f"(a face too narrow for its force, or a rest level close to the highest "
                     f"point): at psi = {math.degrees(psi[k]):g} deg a single sample may carry "
                     f"{share[k]:.2g} of the friction, at most {MAX_SAMPLE_SHARE:g}; {fix}")


def check_cost(pl: Plan, st: _Setup, model: SpringModel, lower: str | None = None) -> float:
    """Refuse a request beyond MAX_UPDATES spring-tip updates (ResourceError naming what
    lowers the cost, ``lower`` if given); else return its updates (progress total)."""
    kind = "rigid" if model.rigid else "elastic"
    n = pl.springs.size
    updates = float(np.sum(pl.updates)) + n * DIRECTION_UPDATES[kind]
    limit = MAX_UPDATES[kind]
    if updates <= limit:
        return updates
    k = int(np.argmax(pl.updates))
    what = (f"the spring simulation ({kind} springs, {n} direction{'s' if n > 1 else ''}) "
            f"needs {updates:.3g} spring-tip updates, at most {limit:.3g}")
    if lower is not None:
        raise ResourceError(f"{what}; {lower}")
    run_in = (pl.steps[k] - 2 * pl.window[k] - 1) * pl.ds[k]   # 20 slip lengths, units of z_max
    pitches = run_in * st.n_pitch * st.zref / float(st.xs[-1])
    if kind == "elastic" and pitches > 1.0:
        raise ResourceError(f"{what}: the run-in of {RUN_IN_SLIP_LENGTHS:g} elastic slip "
                            f"lengths (1 + max|p| + max mu) k_n (z_max - z_r)/k_f is "
                            f"{pitches:.3g} wedge pitches; raise k_f/k_n (--k-f, --k-n) or "
                            "lower the preload (--preload)")
    more = " or the number of directions (--directions)" if n > 1 else ""
    raise ResourceError(f"{what}; lower n_springs or steps_per_period (--n-springs, "
                        f"--steps-per-period){more}")


def check_cost_early(texture, n_directions: int, model: SpringModel,
                     steps: int | None = None) -> None:
    """Before a Gaussian texture's profile is built: refuse a request whose cheapest
    directions (n_springs x n_wedges springs over one window, or ``steps``) already exceed
    MAX_UPDATES."""
    if not hasattr(texture, "n_wedges"):
        return                  # a periodic wedge: the full plan is cheap
    wedges = int(texture.n_wedges)
    m0 = -(-model.steps_per_period // model.n_springs) if steps is None else steps
    least = float(n_directions) * model.n_springs * wedges * m0
    kind = "rigid" if model.rigid else "elastic"
    if least > MAX_UPDATES[kind]:
        lower = ("lower n_springs or steps_per_period (--n-springs, --steps-per-period), the "
                 "number of directions (--directions) or of wedges (n_wedges)" if steps is None
                 else "lower n_steps, n_springs or n_wedges")
        raise ResourceError(f"the spring simulation ({kind} springs, {n_directions} "
                            f"direction{'s' if n_directions > 1 else ''}, {wedges} wedges) "
                            f"needs more than {least:.3g} spring-tip updates, at most "
                            f"{MAX_UPDATES[kind]:.3g}; {lower}")


class Tracker:
    """Progress over the updates of one request (reported to :func:`progress.report`)."""

    def __init__(self, total: float):
        self.total = max(float(total), 1.0)
        self.done = 0.0

    def add(self, updates: float) -> None:
        self.done += updates
        progress.report(min(self.done / self.total, 1.0), LABEL)


@dataclass(frozen=True)
class _Scaled:
    xs: np.ndarray
    zs: np.ndarray
    z_rest: float
    kf: float
    lock_force: float


def _scaled(st: _Setup, model: SpringModel) -> _Scaled:
    z_rest = st.z_rest / st.zref
    xs = np.ascontiguousarray(st.xs / st.zref)
    if not np.all(xs[1:] > xs[:-1]):
        raise InputError("texture profile nodes closer together than the rounding of their "
                         "positions (a wedge far smaller than the tallest one?)")
    return _Scaled(xs, np.ascontiguousarray(st.zs / st.zref), z_rest, model.k_f / model.k_n,
                   LOCK_FORCE_RATIO * (1.0 - z_rest))


def _blocks(N: int, n_steps: int, kind: str):
    """(i0, i1, pieces): spring blocks, each with its (s0, s1) step pieces (a generator)."""
    b = min(N, SPRINGS_PER_PIECE)
    q = max(1, UPDATES_PER_PIECE[kind] // b)
    for i0 in range(0, N, b):
        yield i0, min(N, i0 + b), ((s0, min(n_steps, s0 + q)) for s0 in range(0, n_steps, q))


class _Outcome:
    """Sums over all springs and the first failure or lock, in spring order."""

    def __init__(self, width: int):
        self.total = np.zeros(width)
        self.code = 0           # first status other than 0 and 1
        self.locked = False
        self.lock_seg = -1      # segment of the first locked spring

    def collect(self, status: np.ndarray, lock_seg: np.ndarray) -> None:
        if not status.any():
            return
        bad = status[(status != 0) & (status != 1)]
        if bad.size and not self.code:
            self.code = int(bad[0])
        if np.any(status == 1):
            self.locked = True
            seg = lock_seg[(status == 1) & (lock_seg >= 0)]
            if seg.size and self.lock_seg < 0:
                self.lock_seg = int(seg[0])


def run_sliding(st: _Setup, model: SpringModel, N: int, m: int, ds: float, n_steps: int,
                tracker: Tracker) -> _Outcome:
    """Steady sliding of one direction (plan values N, m, ds, n_steps): sums (5,) =
    [R_x, R_y, R_z, in contact, sliding] in units of k_n z_max over the window."""
    from . import _spring_kernels as K
    sc = _scaled(st, model)
    W = sc.xs[-1] / N
    kind = "rigid" if model.rigid else "elastic"
    res = _Outcome(5)
    for i0, i1, pieces in _blocks(N, n_steps, kind):
        nb = i1 - i0
        X0 = (np.arange(i0, i1) + 0.5) * W
        out = np.zeros((nb, 5))
        status = np.zeros(nb, np.int64)
        lock_seg = np.full(nb, -1, np.int64)
        tip, tip_at, rec = np.zeros((nb, 3)), np.zeros((nb, 2), np.int64), np.zeros((1, 1, 5))
        for s0, s1 in pieces:
            if model.rigid:
                K.rigid_piece(sc.xs, sc.zs, st.seg_px, st.seg_py, st.seg_lock, st.seg_loaded,
                              X0, np.arange(s0 + 1, s1 + 1) * ds * st.c, 1.0, sc.z_rest, out,
                              status, lock_seg)
            else:
                d = np.arange(s0, s1) * ds
                K.elastic_piece(sc.xs, sc.zs, st.seg_mu, st.seg_loaded, X0, d * st.c, d * st.sn,
                                1.0, sc.kf, sc.z_rest, st.c, s0, n_steps - m, False,
                                sc.lock_force, tip, tip_at, out, rec, status, lock_seg)
            tracker.add(nb * (s1 - s0))
        K.add_rows(res.total, out)
        res.collect(status, lock_seg)
    return res


def run_loading(st: _Setup, model: SpringModel, N: int, d: np.ndarray,
                tracker: Tracker) -> _Outcome:
    """Loading from rest along the displacements d (m): per-step sums (d.size, 5) in units
    of k_n z_max."""
    from . import _spring_kernels as K
    sc = _scaled(st, model)
    W = sc.xs[-1] / N
    dz = d / st.zref
    ux, uy = dz * st.c, dz * st.sn
    n_steps = d.size
    res = _Outcome(5)
    res.total = np.zeros((n_steps, 5))
    for i0, i1, pieces in _blocks(N, n_steps, "elastic"):
        nb = i1 - i0
        X0 = (np.arange(i0, i1) + 0.5) * W
        out = np.zeros((nb, 5))
        status = np.zeros(nb, np.int64)
        lock_seg = np.full(nb, -1, np.int64)
        tip, tip_at = np.zeros((nb, 3)), np.zeros((nb, 2), np.int64)
        for s0, s1 in pieces:
            rec = np.zeros((nb, s1 - s0, 5))
            K.elastic_piece(sc.xs, sc.zs, st.seg_mu, st.seg_loaded, X0, ux[s0:s1], uy[s0:s1],
                            1.0, sc.kf, sc.z_rest, st.c, s0, n_steps - 1, True, sc.lock_force,
                            tip, tip_at, out, rec, status, lock_seg)
            K.add_records(res.total, rec, s0)
            tracker.add(nb * (s1 - s0))
        res.collect(status, lock_seg)
    return res


def scale_of_forces(st: _Setup, model: SpringModel) -> float:
    """N per kernel force unit (k_n z_max)."""
    return model.k_n * st.zref

