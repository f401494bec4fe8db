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
ridges) the level faces, as in closed_form.py (the direction is flagged set-valued).
Tips over unloaded faces hang free.

Self-locking: with k_f = inf a tip on a loaded face with F_z <= 0 (closed_form.LOCK_TOL);
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
plus one window precedes the window, so every tip has left its rest state.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .closed_form import LEVEL_SLOPE_TOL, LOCK_TOL, Reservoir, check_contact
from .errors import InputError, check_int, check_range

#: horizontal force of one tip, in units of k_n (z_max - z_r), above which the tip is
#: reported self-locking
LOCK_FORCE_RATIO = 1.0e4
#: run-in travel in units of the elastic slip length (1 + max|p_f| + max mu) k_n dz / k_f
RUN_IN_SLIP_LENGTHS = 20.0

_STATUS_TEXT = {
    1: "self-locking: a spring tip cannot climb its face",
    2: "the tip return mapping did not converge",
    3: "too many face changes in one step (reduce the step)",
}


@dataclass(frozen=True)
class SpringModel:
    """Springs carried by the sliding body (see module docstring).

    k_n      : N/m, normal stiffness of one spring, (0, inf)
    k_f      : N/m, flexural (tangential) stiffness of one spring, (0, inf]; inf = rigid
    density  : springs per m^2, (0, inf); stresses = density x mean spring force
    preload  : N, force of a spring whose tip is at z = 0; rest level z_r = -preload/k_n
    n_springs: springs per wedge pitch (stratified along t_a), [1, 1e6]
    steps_per_period : samples per wedge pitch of travel along t_a, [1, 1e8]
    """

    k_n: float = 1.0e3
    k_f: float = math.inf
    density: float = 1.0e10
    preload: float = 0.0
    n_springs: int = 64
    steps_per_period: int = 8000

    def __post_init__(self):
        def finite_pos(name):
            x = check_range(name, getattr(self, name), 0.0, None, low_open=True)
            if not math.isfinite(x):
                raise InputError(f"{name} must be in (0, inf) and finite, got {x:g}")
            object.__setattr__(self, name, x)

        finite_pos("k_n")
        finite_pos("density")
        kf = self.k_f
        if isinstance(kf, str) and kf.strip().lower() in ("inf", "infinity"):
            kf = math.inf
        object.__setattr__(self, "k_f", check_range("k_f", kf, 0.0, None, low_open=True))
        pre = check_range("preload", self.preload)
        if not math.isfinite(pre):
            raise InputError(f"preload must be finite, got {pre:g}")
        object.__setattr__(self, "preload", pre)
        object.__setattr__(self, "n_springs", check_int("n_springs", self.n_springs, 1, 1_000_000))
        object.__setattr__(self, "steps_per_period",
                           check_int("steps_per_period", self.steps_per_period, 1, 100_000_000))

    @property
    def rigid(self) -> bool:
        """True when k_f = inf (tips follow their bases)."""
        return math.isinf(self.k_f)

    @property
    def k_t(self) -> float:
        """Tangential stiffness per unit area, density x k_f (Pa/m)."""
        return self.density * self.k_f

    @classmethod
    def from_dict(cls, d: dict) -> "SpringModel":
        """From the ``[springs]`` table of a texture file (k_f may be the string "inf")."""
        if not isinstance(d, dict):
            raise InputError("springs must be a table")
        allowed = [f.name for f in fields(cls)]
        for key in d:
            if key not in allowed:
                raise InputError(f"unknown key springs.{key}; allowed: {', '.join(allowed)}")
        from .texture import build_from_table
        return build_from_table(cls, d, "springs")


@dataclass(frozen=True)
class SlidingResult:
    """Steady sliding in direction psi.

    p : (2,) averaged -lambda_T/lambda_N in (t_a, t_b) (inf entries if locked)
    tangential, lateral : p . s and p . s_perp
    normal_stress : Pa, density x mean vertical spring force
    sliding_fraction : fraction of tip-steps in contact that were sliding (window)
    """

    psi: float
    p: np.ndarray
    tangential: float
    lateral: float
    normal_stress: float
    locked: bool
    locked_face: int
    n_springs: int
    n_steps: int
    sliding_fraction: float
    set_valued: bool = False
    message: str = ""


@dataclass(frozen=True)
class LoadingCurve:
    """Tangential loading from rest to full sliding (finite k_f)."""

    psi: float
    displacement: np.ndarray
    tangential_stress: np.ndarray
    lateral_stress: np.ndarray
    normal_stress: np.ndarray
    sliding_fraction: np.ndarray
    k_t: float
    k_t_measured: float
    mu_steady: float
    locked: bool = False
    locked_face: int = -1


# --------------------------------------------------------------------------- setup


@dataclass(frozen=True)
class _Setup:
    xs: np.ndarray
    zs: np.ndarray
    seg_mu: np.ndarray
    seg_face: np.ndarray
    seg_g: np.ndarray
    seg_loaded: np.ndarray
    seg_px: np.ndarray
    seg_py: np.ndarray
    seg_lock: np.ndarray
    period: float
    n_pitch: int
    z_rest: float
    set_valued: bool
    c: float
    sn: float


def _check_model(model) -> SpringModel:
    if not isinstance(model, SpringModel):
        raise InputError(f"model must be a SpringModel, got {type(model).__name__}")
    return model


def _check_psi(psi) -> float:
    x = check_range("psi", psi)
    if not math.isfinite(x):
        raise InputError(f"psi must be finite (radians), got {x:g}")
    return x


def _setup(texture, psi: float, model: SpringModel, contact: str) -> _Setup:
    check_contact(contact)
    if not hasattr(texture, "profile"):
        raise InputError(f"texture must be a WedgeTexture or GaussianWedgeTexture, "
                         f"got {type(texture).__name__}")
    prof = texture.profile()
    xs = np.ascontiguousarray(prof.x, dtype=np.float64)
    zs = np.ascontiguousarray(prof.z, dtype=np.float64)
    dx = np.diff(xs)
    if np.any(dx <= 0):
        raise InputError("texture profile nodes must be strictly increasing")
    seg_mu = np.ascontiguousarray(prof.mu, dtype=np.float64)
    seg_face = np.asarray(prof.face, dtype=np.int64)
    g = np.diff(zs) / dx
    z_rest = -model.preload / model.k_n
    zmax = float(zs.max())
    if not z_rest < zmax:
        raise InputError(
            f"preload must exceed {-model.k_n * zmax:g} N (rest level z_r = -preload/k_n "
            f"= {z_rest:g} m must lie below the highest point {zmax:g} m), got {model.preload:g}")
    c, sn = math.cos(psi), math.sin(psi)
    slope = g * c
    set_valued = False
    if contact == "all-faces":
        loaded = np.ones(g.size, dtype=np.int8)
    else:
        windward = slope > LEVEL_SLOPE_TOL
        if windward.any():
            loaded = windward.astype(np.int8)
        else:
            level = np.abs(slope) <= LEVEL_SLOPE_TOL
            loaded = level.astype(np.int8)
            set_valued = bool(np.any(level & (np.abs(g) > LEVEL_SLOPE_TOL)))
    # closed-form per-face reservoir point (closed_form.compute_face_reservoir)
    nrm = np.sqrt(1.0 + g * g)
    vlen = np.sqrt(1.0 + slope * slope)
    fz = 1.0 / nrm - seg_mu * slope / vlen
    hx = g / nrm + seg_mu * c / vlen
    hy = seg_mu * sn / vlen
    lock = fz <= LOCK_TOL
    safe = np.where(lock, 1.0, fz)
    n_pitch = max(1, int(np.count_nonzero(seg_face == 0)))
    return _Setup(xs, zs, seg_mu, seg_face, g, loaded, hx / safe, hy / safe,
                  lock.astype(np.int8), float(xs[-1]), n_pitch, z_rest, set_valued, c, sn)


def _slip_length(st: _Setup, model: SpringModel) -> float:
    """Elastic slip length (1 + max|p_f| + max mu) k_n (z_max - z_r) / k_f, m."""
    pf = np.hypot(st.seg_px, st.seg_py)[st.seg_lock == 0]
    pmax = float(pf.max()) if pf.size else 1.0
    return (1.0 + pmax + float(st.seg_mu.max())) * model.k_n * (st.zs.max() - st.z_rest) / model.k_f


def _face_of_segment(st: _Setup, seg: np.ndarray) -> int:
    seg = seg[seg >= 0]
    if seg.size == 0:
        return -1
    return int(st.seg_face[int(seg[0])])


# --------------------------------------------------------------------------- sliding


def simulate_sliding(texture, psi: float, model: SpringModel = SpringModel(),
                     contact: str = "all-faces") -> SlidingResult:
    """Steady quasi-static sliding in direction psi (radians from t_a towards t_b).

    Returns the averaged reservoir point p = -lambda_T/lambda_N (eq. 2 of the module
    docstring) and its tangential/lateral parts; ``locked`` (p = inf) if a tip
    self-locks.  Raises InputError for bad input or a kernel failure other than locking.
    """
    from . import _spring_kernels as K

    psi = _check_psi(psi)
    model = _check_model(model)
    st = _setup(texture, psi, model, contact)
    N = model.n_springs * st.n_pitch
    W = st.period / N
    m = -(-model.steps_per_period // model.n_springs)
    pitch = st.period / st.n_pitch
    ac = abs(st.c)
    if ac * pitch * m <= W:
        # (nearly) along the ridges the body does not travel across the texture: only
        # the springs' positions sample the period, so use steps_per_period of them per
        # pitch (one window step) instead of n_springs.
        N = max(N, model.steps_per_period * st.n_pitch)
        W = st.period / N
        m = 1
    ds = pitch if ac * pitch * m <= W else W / (m * ac)
    X0 = (np.arange(N) + 0.5) * W
    if model.rigid:
        ux = np.arange(1, m + 1) * ds * st.c
        sums, status, lock_seg = K.run_rigid(st.xs, st.zs, st.seg_px, st.seg_py, st.seg_lock,
                                             st.seg_loaded, X0, ux, model.k_n, st.z_rest)
        n_steps = m
    else:
        run_in = RUN_IN_SLIP_LENGTHS * _slip_length(st, model) + m * ds
        n_run = int(math.ceil(run_in / ds))
        n_steps = n_run + m + 1
        d = np.arange(n_steps) * ds  # step 0: rest
        dz_scale = model.k_n * (st.zs.max() - st.z_rest)
        sums, _, status, lock_seg, _ = K.run_elastic(
            st.xs, st.zs, st.seg_mu, st.seg_loaded, X0, d * st.c, d * st.sn, model.k_n,
            model.k_f, st.z_rest, st.c, m, False, LOCK_FORCE_RATIO * dz_scale)
    return _result(st, psi, model, sums, status, lock_seg, N, n_steps, m)


def _result(st, psi, model, sums, status, lock_seg, N, n_steps, m) -> SlidingResult:
    """Turn kernel sums/status into a SlidingResult (m = steps in the averaging window)."""
    bad = status[(status != 0) & (status != 1)]
    if bad.size:
        raise InputError(f"spring simulation failed at psi = {math.degrees(psi):g} deg: "
                         f"{_STATUS_TEXT.get(int(bad[0]), 'status %d' % bad[0])}")
    if np.any(status == 1):
        face = _face_of_segment(st, lock_seg[status == 1])
        return SlidingResult(psi, np.array([np.inf, np.inf]), math.inf, 0.0, math.inf, True,
                             face, N, n_steps, 0.0, st.set_valued, _STATUS_TEXT[1])
    tot = sums.sum(axis=0)
    if not tot[2] > 0.0:
        raise InputError("no spring tip touched the texture (check preload)")
    p = -tot[:2] / tot[2]
    s = np.array([st.c, st.sn])
    sp = np.array([-st.sn, st.c])
    normal_stress = model.density * tot[2] / (N * m)
    frac = float(tot[4] / tot[3]) if tot[3] > 0 else 0.0
    return SlidingResult(psi, p, float(p @ s), float(p @ sp), float(normal_stress), False, -1,
                         N, n_steps, frac, st.set_valued, "")


def simulate_reservoir(texture, psi, model: SpringModel = SpringModel(),
                       contact: str = "all-faces") -> Reservoir:
    """Reservoir points p(psi) from the spring simulation, as closed_form.Reservoir.

    psi : (m,) radians.  Self-locking rows hold inf; ``set_valued`` as in the closed form
    (windward regime, sliding exactly along the ridges).
    """
    psi = np.atleast_1d(np.asarray(psi, dtype=float))
    if psi.ndim != 1:
        raise InputError(f"psi must be a 1-D array of angles, got shape {psi.shape}")
    if not np.all(np.isfinite(psi)):
        raise InputError("psi must be finite (radians)")
    res = [simulate_sliding(texture, float(a), model, contact) for a in psi]
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
    (L/|cos psi|, at most 10 L), over which ``mu_steady`` is averaged.
    """
    from . import _spring_kernels as K

    psi = _check_psi(psi)
    model = _check_model(model)
    if model.rigid:
        raise InputError("k_f must be finite for a loading curve (k_f = inf has no elastic stage)")
    n_steps = check_int("n_steps", n_steps, 2, 100_000_000)
    st = _setup(texture, psi, model, contact)
    L_s = min(st.period / abs(st.c), 10.0 * st.period) if abs(st.c) > 0.1 else 10.0 * st.period
    if distance is None:
        distance = 3.0 * _slip_length(st, model) + L_s
    else:
        distance = check_range("distance", distance, 0.0, None, low_open=True, unit="m")
        if not math.isfinite(distance):
            raise InputError(f"distance must be finite, got {distance:g}")
    N = model.n_springs * st.n_pitch
    W = st.period / N
    X0 = (np.arange(N) + 0.5) * W
    # displacement grid: half the steps over the stick-to-slide transition (3 slip
    # lengths) so that the elastic stage is resolved, the other half over the rest
    d3 = 3.0 * _slip_length(st, model)
    if d3 < 0.5 * distance and n_steps >= 4:
        n1 = n_steps // 2
        d = np.concatenate([np.linspace(0.0, d3, n1 + 1),
                            np.linspace(d3, distance, n_steps - n1 + 1)[1:]])
    else:
        d = np.linspace(0.0, distance, n_steps + 1)
    dz_scale = model.k_n * (st.zs.max() - st.z_rest)
    _, steps, status, lock_seg, _ = K.run_elastic(
        st.xs, st.zs, st.seg_mu, st.seg_loaded, X0, d * st.c, d * st.sn, model.k_n, model.k_f,
        st.z_rest, st.c, 1, True, LOCK_FORCE_RATIO * dz_scale)
    bad = status[(status != 0) & (status != 1)]
    if bad.size:
        raise InputError(f"spring simulation failed at psi = {math.degrees(psi):g} deg: "
                         f"{_STATUS_TEXT.get(int(bad[0]), 'status %d' % bad[0])}")
    tot = steps.sum(axis=0)  # (n_steps + 1, 5)
    s = np.array([st.c, st.sn])
    sp = np.array([-st.sn, st.c])
    scale = model.density / N
    sig_t = -scale * tot[:, :2] @ s
    sig_l = -scale * tot[:, :2] @ sp
    sig_n = scale * tot[:, 2]
    frac = np.divide(tot[:, 4], tot[:, 3], out=np.zeros(tot.shape[0]), where=tot[:, 3] > 0)
    frac[0] = 0.0  # rest state: the relaxation of step 0 is not part of the motion
    k_meas = float((sig_t[1] - sig_t[0]) / (d[1] - d[0]))
    locked = bool(np.any(status == 1))
    last = d > distance - min(L_s, distance) + 1e-12 * distance
    w = np.gradient(d)[last]  # travel-weighted average over the last period
    num, den = (w * sig_t[last]).sum(), (w * sig_n[last]).sum()
    mu_steady = math.inf if locked or not den > 0 else float(num / den)
    face = _face_of_segment(st, lock_seg[status == 1]) if locked else -1
    return LoadingCurve(psi, d, sig_t, sig_l, sig_n, frac, model.k_t, k_meas, mu_steady,
                        locked, face)
