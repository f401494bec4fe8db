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
    """Steady quasi-static sliding of the spring model over a wedge texture in one direction.

    The micro-model behind the closed form (SPEC.md section 2; the docstring of
    ``asperity.texture.springs`` gives the model, the Coulomb law per tip and the
    sampling): the reservoir point is
    ``p = -lambda_T / lambda_N`` from the spring forces summed over a window of steady
    sliding (eq. 2 there).

    Parameters
    ----------
    texture : WedgeTexture or GaussianWedgeTexture
        The texture the springs slide over (its ``profile()``).
    psi : float
        Sliding direction, radians from ``t_a`` towards ``t_b``, within +-1000.
    model : SpringModel, default SpringModel()
        The springs and the numerics.
    contact : {"all-faces", "windward"}, default "all-faces"
        Every face can carry load, or only the faces the motion climbs.

    Returns
    -------
    SlidingResult
        ``p`` (2,), the averaged ``-lambda_T / lambda_N`` in (t_a, t_b); ``tangential`` and
        ``lateral``, ``p . s`` and ``p . s_perp``; ``normal_stress``, Pa (``density`` x the
        mean vertical spring force); ``sliding_fraction`` of the tip-steps in contact;
        ``locked`` (``p`` = inf, ``locked_face``) if a tip self-locks; ``set_valued``.

    Raises
    ------
    asperity.InputError
        Bad input, a sampling too coarse for the texture, or a kernel failure other than
        self-locking; a ``ResourceError`` (before any work) for more spring-tip updates than
        ``asperity.texture.spring_model.MAX_UPDATES``.

    See Also
    --------
    asperity.simulate_reservoir, asperity.compute_reservoir, asperity.SpringModel

    Examples
    --------
    Rigid springs on the SPEC.md wedge give the closed form's mu_a+ = 0.185697 to the
    sampling's resolution; with no preload the mean spring force is ``k_n h / 2``:

    >>> tex = asperity.WedgeTexture(30.0, 10.0, 0.1, 0.2)
    >>> res = asperity.simulate_sliding(tex, 0.0, asperity.SpringModel(n_springs=16,
    ...                                                              steps_per_period=1000))
    >>> print(f"T = {res.tangential:.4f}, L = {res.lateral:.4f}, "
    ...       f"normal stress {res.normal_stress / 1e6:.4f} MPa, locked {res.locked}")
    T = 0.1859, L = 0.0000, normal stress 5.0000 MPa, locked False
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
    """Reservoir points p(psi) of a wedge texture from the spring simulation.

    :func:`asperity.simulate_sliding` for each direction, returned as the closed form's
    result is (:func:`asperity.compute_reservoir`).  The work of all directions is checked
    before the first runs; progress is reported per piece.

    Parameters
    ----------
    texture : WedgeTexture or GaussianWedgeTexture
        The texture the springs slide over.
    psi : float or array_like
        Sliding directions, radians from ``t_a`` towards ``t_b``: a number or a 1-d array
        of at most 1e6 angles within +-1000.
    model : SpringModel, default SpringModel()
        The springs and the numerics.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.

    Returns
    -------
    Reservoir
        ``psi``, ``p`` (m, 2) (``inf`` rows where self-locking), ``locked``,
        ``locked_face``, ``set_valued`` (windward, sliding exactly along the ridges, as in
        the closed form), ``contact``; ``tangential`` and ``lateral`` as properties.

    Raises
    ------
    asperity.InputError
        As for :func:`asperity.simulate_sliding` (a ``ResourceError`` for too much work,
        before any run).

    See Also
    --------
    asperity.simulate_sliding, asperity.compute_reservoir, asperity.derive

    Examples
    --------
    Along ``+t_a``, ``+t_b`` and ``-t_a`` (closed form: 0.1857, 0.1826, 0.1932):

    >>> tex = asperity.WedgeTexture(30.0, 10.0, 0.1, 0.2)
    >>> model = asperity.SpringModel(n_springs=16, steps_per_period=1000)
    >>> r = asperity.simulate_reservoir(tex, np.radians([0.0, 90.0, 180.0]), model)
    >>> print(" ".join(f"{t:.4f}" for t in r.tangential))
    0.1859 0.1826 0.1929
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
    """Tangential force-displacement curve from rest to full sliding (finite ``k_f`` only).

    The body starts at rest (step 0: every tip lands under its base and relaxes into its
    cone, so tips on faces steeper than their friction angle slide down first); then it moves
    by ``distance`` along s(psi) in ``n_steps`` steps: half of them over the first 3 elastic
    slip lengths (stick to full sliding), the rest over the remaining distance (uniform steps
    if the distance is shorter than 6 slip lengths).

    Parameters
    ----------
    texture : WedgeTexture or GaussianWedgeTexture
        The texture the springs slide over.
    psi : float
        Sliding direction, radians from ``t_a`` towards ``t_b``, within +-1000.
    model : SpringModel
        The springs; ``k_f`` must be finite (``inf`` has no elastic stage).
    distance : float or None, default None
        Travel, m, in (0, 1e6 profile periods]; None: 3 elastic slip lengths
        ``(1 + max|p_f| + max mu) k_n (z_max - z_r) / k_f`` plus one period of the profile
        along ``t_a`` (``L/|cos psi|``, at most 10 L).
    n_steps : int, default 2000
        Steps of the motion, in [2, 1e8].
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.

    Returns
    -------
    LoadingCurve
        ``displacement`` (n_steps + 1,), m; ``tangential_stress``, ``lateral_stress``,
        ``normal_stress``, Pa, and ``sliding_fraction`` at each; ``k_t`` (the model's
        ``density k_f``, Pa/m) and ``k_t_measured`` (the first step's slope); ``mu_steady``,
        the travel-weighted ratio of tangential to normal stress over the last period;
        ``locked`` and ``locked_face``.

    Raises
    ------
    asperity.InputError
        Bad input, ``k_f`` infinite, or a default distance beyond 1e6 periods; a
        ``ResourceError`` for too many steps for the memory or the work limit.

    See Also
    --------
    asperity.SpringModel, asperity.simulate_sliding

    Notes
    -----
    While every tip in contact sticks, ``d sigma_t / d u = density k_f`` x the fraction of
    tips in contact: the model's ``k_t`` when all tips touch (preload > 0), Antoni et al.
    eq. 10-12 (SPEC.md section 2).

    Examples
    --------
    A gentle wedge (5 deg faces, mu = 0.3 > tan 5 deg: every tip sticks at first) with every
    tip preloaded: the initial slope is ``k_t``, the steady friction the closed form's 0.3025
    to within ``k_n/k_f``:

    >>> tex = asperity.WedgeTexture(5.0, 5.0, 0.3, 0.3)
    >>> model = asperity.SpringModel(k_f=1e5, preload=1e-3, n_springs=16)
    >>> c = asperity.simulate_loading_curve(tex, 0.0, model, n_steps=200)
    >>> print(f"k_t measured / k_t = {c.k_t_measured / c.k_t:.4f}, mu = {c.mu_steady:.4f}")
    k_t measured / k_t = 1.0000, mu = 0.3024
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
