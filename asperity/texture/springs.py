"""Spring-on-wedge simulation: the micro-model behind the closed form (SPEC.md section 2).

Model
-----
A rigid body slides quasi-statically at fixed height over a texture profile z(x)
(periodic, piecewise linear along ``t_a``, uniform along ``t_b``; texture.profile()).
It carries springs (``density`` per m^2).  Spring i has its base at the horizontal
position ``b_i = (X_i, Y_i) + u``, ``u = d s(psi)``; its tip touches the surface at the
horizontal position ``x_t`` with offset ``d_i = x_t - b_i``.  The reaction of the
support on the tip (and, through the spring, on the body) is

    R = (k_f d_i, k_n (z(x_t) - z_r)),      z_r = -preload / k_n          (1)

when ``z(x_t) > z_r``; otherwise the tip hangs free under its base (``x_t = b_i``, R = 0).
The reservoir point is taken from time-averaged sums over a steady-sliding window,

    p = -(sum_i,steps R_h) / (sum_i,steps R_z)       (in the (t_a, t_b) frame)  (2)

Coulomb law per tip, on the face under it (unit upward normal m, local friction mu):
R_n = R.m, R_t = R - R_n m.  Stick if |R_t| <= mu R_n; slide otherwise with

    R_t = -mu R_n w/|w|                                                      (3)

where w is the tip's slip over the step (backward Euler, implicit in R_n).  In the face
coordinates xi (xi1 up the slope, xi2 = t_b) the tangential reaction is the gradient of
the spring energy, G(xi) = G_trial + K (xi - xi_old), K = diag((k_f + k_n g^2)/(1+g^2), k_f)
(anisotropic when k_f != k_n), and R_n is affine in xi1: R_n = R_n,trial + a1 D1,
a1 = g (k_n - k_f)/(1 + g^2).  Equation (3) becomes the 2x2 problem

    G_trial + K D = -mu (R_n,trial + a1 D1) D/|D|,

solved exactly (to round-off) by a bracketed secant on R_n in [0, |G_trial|/mu] around a
monotone Newton solve for |D| at fixed R_n (_spring_kernels._face_return).  A tip whose
slip leaves the face stops at the node (sub-step: the y-offset is interpolated along the
slip) and is re-solved on the next face from there with the same base position, any
number of times per step.

Corners (nodes).  At a node the tip tries the face ahead first, then the other one; if
each face's return mapping pushes it back towards the node (a valley, or rarely a ridge),
the tip is held on the node line: its in-plane reaction (R_x, R_z) is split on the two
face normals, N_l m_l + N_r m_r, and it may slide along the node line (t_b) when
|R_y| > mu_l N_l+ + mu_r N_r+ (1D return mapping).  This approximates the union of the
two cones; it only matters while a tip is held, for a base travel of order
k_n h / k_f, so its effect on p vanishes like k_n/k_f (tested).
If the frictionless equilibrium on the face ahead already has R_n <= 0 (a tip flung
over a ridge onto a steep lee face), the tip leaves the surface and lands under its base
(a snap of size O(k_n h/k_f)).

k_f = inf: the tip stays under its base and slides with the lifted velocity
v = (s, g.s), so its force ratio on face f is the closed form's per-face point
p_f = -F_h/F_z, F = m - mu v/|v|, weighted by R_z = k_n (z - z_r): eq. (2) is then a
quadrature of the closed form, exact up to the step resolution.

Contact regimes: ``all-faces`` every face can carry load; ``windward`` only faces with
g.s > 0 (the body climbs them), and when none is climbed (sliding exactly along the
ridges) the level faces, as in :mod:`asperity.friction.faces` (the direction is flagged set-valued).
Tips over unloaded faces hang free.

Self-locking: with k_f = inf a tip on a loaded face with F_z <= 0 (friction.reservoir.LOCK_TOL);
with finite k_f a tip stuck on a face the base climbs with the limiting force direction
(-s, 0) inside the cone, ((1 + g^2) <= (1 + mu^2) g^2 cos^2 psi), or any tip whose
horizontal force exceeds LOCK_FORCE_RATIO x k_n (z_max - z_r).  Then ``locked=True``,
``p = (inf, inf)``, never NaN.

Sampling (resolution)
---------------------
``n_springs`` springs per wedge pitch (for a Gaussian texture of n_wedges wedges the
profile period holds n_springs x n_wedges springs) at stratified positions
X_i = (i + 1/2) L / N.  In steady sliding every spring is the same spring shifted in x,
so averaging all springs over an x-travel of one spring spacing L/N samples the period
uniformly, as averaging one spring over whole periods would.  The window is
``m = ceil(steps_per_period / n_springs)`` steps, so the period is sampled at
N m ~ steps_per_period x n_wedges points (steps_per_period is "samples per wedge
pitch").  The s-step is W/(m |cos psi|) (W = L/N), capped at one wedge pitch: within
~1/steps_per_period rad of psi = 90 deg (along the ridges) the body does not travel
across the wedges and the period is sampled by the N springs only, so use more springs
there.  With finite k_f a run-in of 20 x (1 + max|p_f| + max mu) k_n (z_max - z_r)/k_f
plus one window precedes the window, so every tip has left its rest state.  A sampling
too coarse for the texture's narrowest loaded face (a single sample would carry more than
1 % of the friction) and a request of more spring-tip updates than spring_model.MAX_UPDATES
are refused before any work; the kernels run in pieces that Ctrl-C can stop
(:mod:`asperity.texture.spring_runs`, which also holds the units of the kernels: h and k_n h).
"""
from __future__ import annotations

import math
import numbers

import numpy as np

from ..errors import InputError, check_array, check_int, check_range
from ..friction.reservoir import Reservoir
from ..resources import check_memory
from .spring_model import (
    _STATUS_TEXT,
    LoadingCurve,
    SlidingResult,
    SpringModel,
    _check_model,
    _check_psi,
    _check_texture,
    _face_of_segment,
    _setup,
    _slip_length,
)
from .spring_runs import (
    Tracker,
    check_cost,
    check_cost_early,
    check_resolution,
    plan,
    run_loading,
    run_sliding,
    scale_of_forces,
)

#: most sliding directions of one request
MAX_DIRECTIONS = 1_000_000
#: bytes per step of a loading curve (per-step sums, displacements, stresses)
LOADING_BYTES_PER_STEP = 200


def simulate_sliding(texture, psi: float, model: SpringModel = SpringModel(),
                     contact: str = "all-faces") -> SlidingResult:
    """Steady quasi-static sliding in direction psi (radians from t_a towards t_b).

    Returns the averaged reservoir point p = -lambda_T/lambda_N (eq. 2 of the module
    docstring) and its tangential/lateral parts; ``locked`` (p = inf) if a tip
    self-locks.  Raises InputError for bad input or a kernel failure other than locking,
    ResourceError (before any work) for a request beyond spring_model.MAX_UPDATES.
    """
    psi = _check_psi(psi)
    model = _check_model(model)
    check_cost_early(_check_texture(texture), 1, model)
    st = _setup(texture, psi, model, contact)
    pl = plan(st, [psi], model)
    check_resolution(st, [psi], pl, model)
    tracker = Tracker(check_cost(pl, st, model))
    return _slide(st, psi, model, *pl.take(0), tracker)


def _slide(st, psi, model, N, m, ds, n_steps, tracker) -> SlidingResult:
    out = run_sliding(st, model, N, m, ds, n_steps, tracker)
    if out.code:
        raise InputError(f"spring simulation failed at psi = {math.degrees(psi):g} deg: "
                         f"{_STATUS_TEXT.get(out.code, 'status %d' % out.code)}")
    if out.locked:
        return SlidingResult(psi, np.array([np.inf, np.inf]), math.inf, 0.0, math.inf, True,
                             _face_of_segment(st, np.array([out.lock_seg])), N, n_steps, 0.0,
                             st.set_valued, _STATUS_TEXT[1])
    tot = out.total
    if not tot[2] > 0.0:
        raise InputError(f"no spring tip touched the texture at psi = {math.degrees(psi):g} "
                         "deg: the rest level -preload/k_n is too close to the highest point "
                         "for the springs' spacing (lower it, or use more springs)")
    p = -tot[:2] / tot[2]
    s = np.array([st.c, st.sn])
    sp = np.array([-st.sn, st.c])
    normal_stress = model.density * scale_of_forces(st, model) * tot[2] / (N * m)
    frac = float(tot[4] / tot[3]) if tot[3] > 0 else 0.0
    return SlidingResult(psi, p, float(p @ s), float(p @ sp), float(normal_stress), False, -1,
                         N, n_steps, frac, st.set_valued, "")


def simulate_reservoir(texture, psi, model: SpringModel = SpringModel(),
                       contact: str = "all-faces") -> Reservoir:
    """Reservoir points p(psi) from the spring simulation, as a friction.reservoir.Reservoir.

    psi : (m,) radians.  Self-locking rows hold inf; ``set_valued`` as in the closed form
    (windward regime, sliding exactly along the ridges).  The work of all directions is
    checked before the first runs (ResourceError); progress is reported per piece.
    """
    psi = np.array([_check_psi(psi)]) if isinstance(psi, (numbers.Real, bool)) else \
        check_array("psi", psi, ndim=1, min_size=1)
    if psi.size > MAX_DIRECTIONS or np.any(np.abs(psi) > 1e3):
        raise InputError(f"psi must be at most {MAX_DIRECTIONS} angles within +-1000 rad, got "
                         f"{psi.size} up to {np.abs(psi).max():g}")
    model = _check_model(model)
    check_cost_early(_check_texture(texture), psi.size, model)
    st = _setup(texture, float(psi[0]), model, contact)
    pl = plan(st, psi, model)
    check_resolution(st, psi, pl, model)
    tracker = Tracker(check_cost(pl, st, model))
    res = [_slide(st if k == 0 else _setup(texture, float(a), model, contact), float(a), model,
                  *pl.take(k), tracker) for k, a in enumerate(psi)]
    return Reservoir(psi=psi, p=np.array([r.p for r in res]).reshape(-1, 2),
                     locked=np.array([r.locked for r in res], dtype=bool),
                     locked_face=np.array([r.locked_face for r in res], dtype=np.int64),
                     set_valued=np.array([r.set_valued for r in res], dtype=bool),
                     contact=contact)


def simulate_loading_curve(texture, psi: float, model: SpringModel, distance: float | None = None,
                           n_steps: int = 2000, contact: str = "all-faces") -> LoadingCurve:
    """Tangential force-displacement curve from rest to full sliding (finite k_f only).

    The body starts at rest (step 0: every tip lands under its base and relaxes into its
    cone, so tips on faces steeper than their friction angle slide down first); then it
    moves by ``distance`` along s(psi) in ``n_steps`` steps: n_steps//2 equal steps over
    the first 3 elastic slip lengths (stick to full sliding), the rest equal steps over
    the remaining distance (uniform steps if the distance is shorter than 6 slip lengths).  While every tip in
    contact sticks, d sigma_t / d u = density k_f x (fraction of tips in contact): the
    model's k_t = density k_f when all tips touch (preload > 0).  Default distance:
    3 elastic slip lengths (module docstring) plus one period of the profile along t_a
    (L/|cos psi|, at most 10 L), over which ``mu_steady`` is averaged; a distance is at
    most 1e6 profile periods.
    """
    psi = _check_psi(psi)
    model = _check_model(model)
    if model.rigid:
        raise InputError("k_f must be finite for a loading curve (k_f = inf has no elastic stage)")
    n_steps = check_int("n_steps", n_steps, 2, 100_000_000)
    check_memory(LOADING_BYTES_PER_STEP * (n_steps + 1.0), f"a loading curve of {n_steps} steps",
                 "lower n_steps")
    check_cost_early(_check_texture(texture), 1, model, n_steps + 1)
    st = _setup(texture, psi, model, contact)
    L_s = min(st.period / abs(st.c), 10.0 * st.period) if abs(st.c) > 0.1 else 10.0 * st.period
    if distance is None:
        distance = 3.0 * _slip_length(st, model) + L_s
        if distance > 1e6 * st.period:
            raise InputError(f"the default distance, 3 elastic slip lengths and one period "
                             f"({distance:.3g} m), is more than 1e6 profile periods: raise "
                             "k_f/k_n, lower the preload or give a distance")
    distance = check_range("distance", distance, 0.0, 1e6 * st.period, low_open=True, unit="m")
    N = model.n_springs * st.n_pitch
    tracker = Tracker(check_cost(_loading_plan(N, n_steps), st, model,
                                 "lower n_steps or n_springs"))
    # displacement grid: half the steps over the stick-to-slide transition (3 slip
    # lengths) so that the elastic stage is resolved, the other half over the rest
    d3 = 3.0 * _slip_length(st, model)
    if d3 < 0.5 * distance and n_steps >= 4:
        n1 = n_steps // 2
        d = np.concatenate([np.linspace(0.0, d3, n1 + 1),
                            np.linspace(d3, distance, n_steps - n1 + 1)[1:]])
    else:
        d = np.linspace(0.0, distance, n_steps + 1)
    out = run_loading(st, model, N, d, tracker)
    if out.code:
        raise InputError(f"spring simulation failed at psi = {math.degrees(psi):g} deg: "
                         f"{_STATUS_TEXT.get(out.code, 'status %d' % out.code)}")
    tot = out.total  # (n_steps + 1, 5)
    s = np.array([st.c, st.sn])
    sp = np.array([-st.sn, st.c])
    scale = model.density * scale_of_forces(st, model) / N
    sig_t = -scale * tot[:, :2] @ s
    sig_l = -scale * tot[:, :2] @ sp
    sig_n = scale * tot[:, 2]
    frac = np.divide(tot[:, 4], tot[:, 3], out=np.zeros(tot.shape[0]), where=tot[:, 3] > 0)
    frac[0] = 0.0  # rest state: the relaxation of step 0 is not part of the motion
    k_meas = float((sig_t[1] - sig_t[0]) / (d[1] - d[0]))
    locked = out.locked
    last = d > distance - min(L_s, distance) + 1e-12 * distance
    w = np.gradient(d)[last]  # travel-weighted average over the last period
    num, den = (w * sig_t[last]).sum(), (w * sig_n[last]).sum()
    mu_steady = math.inf if locked or not den > 0 else float(num / den)
    face = _face_of_segment(st, np.array([out.lock_seg])) if locked else -1
    return LoadingCurve(psi, d, sig_t, sig_l, sig_n, frac, model.k_t, k_meas, mu_steady,
                        locked, face)


def _loading_plan(N: int, n_steps: int):
    from .spring_runs import Plan
    one = np.ones(1)
    return Plan(np.array([N]), one.astype(int), one, np.array([n_steps + 1.0]), one[:, None])
