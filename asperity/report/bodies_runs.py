"""The runs behind the report's section on bodies (:mod:`asperity.report.bodies`): the sampled
disc against the closed forms, the terminal ratio followed in scale-free stages, the spin
drift, the turning rectangle and MuJoCo's disc beside ours."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

G = 9.81
#: the disc and ring of the dynamics: radius (m), Coulomb mu, mass (kg), launch speed (m/s)
R, MU, MASS, V0 = 0.05, 0.3, 1.0, 1.0
#: eps ranges of the sampling table (the largest errors over each)
EPS_RANGES = ((0.0, 0.1), (0.1, 1.0), (1.0, 10.0), (10.0, 100.0))
#: initial eps0 = v0 / (R omega0) of the terminal-ratio runs: a fast and a slow spin
SPINS = (("fast spin", 0.1), ("slow spin", 10.0))
#: the terminal-ratio runs: step of the first stage (s), speed drop per stage, stages
DT0, DROP, STAGES = 1e-4, 10.0, 9
#: MuJoCo's disc of ``asperity bench --only body`` (used when its JSON is absent)
BENCH_DISC = {"radius": 0.05, "mu": 0.3, "v0": 1.0, "omega0": 20.0, "dt": 1e-4,
              "stop_speed": 1e-3, "end_fraction": 0.02}
BENCH_JSON = "body-bench.json"
BENCH_COMMAND = "asperity bench --only body --json > reports/body-bench.json"


#: the spinning disc of the drift runs: omega0 (rad/s) per law (the windward law is rougher)
DRIFT_OMEGA0 = 40.0
DRIFT_DT = 1e-4
RECT_A, RECT_B = 0.10, 0.04
RECT_OMEGA0 = 10.0


@dataclass(frozen=True)
class Sizes:
    """Contact points and steps of the section's runs (full or quick)."""

    disc_points: int
    ring_points: int
    rect_points: int
    steps_per_stage: int


FULL = Sizes(disc_points=1024, ring_points=128, rect_points=256, steps_per_stage=1000)
QUICK = Sizes(disc_points=64, ring_points=64, rect_points=60, steps_per_stage=800)


def sampling_table(points=(None, 256, 64), eps=None) -> tuple[np.ndarray, dict]:
    """The eps grid and, per contact-point count (None: the default), the sampled disc's
    worst relative force and torque errors at each eps (``sampling_errors``: over 48
    velocity directions)."""
    from ..bodies.accuracy import sampling_errors
    from ..bodies.footprint import DEFAULT_CONTACT_POINTS, disc
    if eps is None:
        eps = np.concatenate([[0.0], np.logspace(-3.0, 2.0, 81)])
    out = {}
    for n in points:
        fp = disc(R, contact_points=n)
        rows = sampling_errors(fp, eps)
        out[DEFAULT_CONTACT_POINTS["disc"] if n is None else n] = (
            np.array([r["force"] for r in rows]), np.array([r["torque"] for r in rows]))
    return np.asarray(eps, dtype=float), out


def range_maxima(eps: np.ndarray, err: np.ndarray) -> list[float]:
    """The largest of ``err`` over each range of EPS_RANGES (both ends included)."""
    return [float(err[(eps >= lo) & (eps <= hi)].max()) for lo, hi in EPS_RANGES]


@dataclass(frozen=True)
class Staged:
    """A run to rest in stages (see :func:`staged_run`).

    first : the BodyResult of the first stage (step DT0, run to rest: the stop times)
    t, u  : the stages' records up to each cut, end to end (t from the launch)
    t_stop : launch to rest through the stages
    depth : (v + R |omega|) at the last cut over its value at the launch
    eps_end : v / (R omega) at the last cut
    w_end : R |omega| at the last cut over R |omega0|
    direction_end : direction of the velocity at the last cut in the body frame (rad)
    dts : the step of each stage (physical time)
    """

    first: object
    t: np.ndarray
    u: np.ndarray
    t_stop: float
    depth: float
    eps_end: float
    w_end: float
    direction_end: float
    dts: tuple


def _speed(u: np.ndarray, radius: float) -> np.ndarray:
    return np.hypot(u[:, 0], u[:, 1]) + radius * np.abs(u[:, 2])


def staged_run(fp, law, u0, *, dt0: float = DT0, stages: int = STAGES, drop: float = DROP,
               steps_per_stage: int = 2000) -> Staged:
    """Slide and spin ``fp`` (a disc or ring, mass MASS) from u0 to rest, then resolve the end.

    The ODE of eps = v / (R omega) is singular at the stop (d eps/dt ~ 1/omega): a run with
    one step sees eps only down to speeds of a few mu g dt.  A rate-independent law is
    scale-free (if u(t) is a motion, so is S u(t / S)), so the end is followed in stages:
    stage k runs to rest; where its speed v + R |omega| has fallen to 1/drop of the stage's
    start, stage k+1 restarts from that state magnified to the stage's starting speed, with
    the step (rest time - cut time) x magnification / steps_per_stage, and its records are
    scaled back (u / S, t / S).  After ``stages`` stages the speed is about drop^-stages of
    the launch's, each stage resolved as well as the first."""
    from ..dynamics.body import simulate_body
    radius = fp.radius

    def run(u, theta, dt):
        r = simulate_body(fp.points, fp.weights, law, mass=MASS,
                          inertia=MASS * fp.inertia_per_mass, u0=u, q0=(0.0, 0.0, theta),
                          dt=dt)
        if r.stop_time is None:
            raise RuntimeError(f"the body did not come to rest ({r.status_message()})")
        return r

    first = r = run(u0, 0.0, dt0)
    theta = 0.0
    ts, us, dts = [], [], [dt0]
    offset, scale = 0.0, 1.0                   # physical t = offset + scale t_stage, u = scale u
    for k in range(stages):
        s = _speed(r.u, radius)
        j = int(np.argmax(s < s[0] / drop))
        if s[j] == 0.0:                          # the stage stopped within one cut: too coarse
            raise RuntimeError(f"stage {k}: the speed fell from {s[0]:g} to rest in one "
                               "step; take more steps per stage")
        first_row = 0 if k == 0 else 1          # a stage's first state is the last cut
        ts.append(offset + scale * r.t[first_row:j + 1])
        us.append(scale * r.u[first_row:j + 1])
        theta = float(r.q[j, 2])
        if k == stages - 1:
            break
        mag = s[0] / s[j]
        dt = (r.stop_time - r.t[j]) * mag / steps_per_stage
        offset += scale * r.t[j]
        dts.append(dt * scale / mag)
        u_next = mag * r.u[j]
        scale /= mag
        r = run(u_next, theta, dt)
    t, u = np.concatenate(ts), np.concatenate(us)
    end = u[-1]
    s0 = _speed(np.asarray([u0], dtype=float), radius)[0]
    return Staged(first, t, u, offset + scale * r.stop_time,
                  float(_speed(u[-1:], radius)[0] / s0),
                  float(math.hypot(end[0], end[1]) / (radius * abs(end[2]))),
                  float(abs(end[2]) / abs(u0[2])), math.atan2(end[1], end[0]) - theta,
                  tuple(dts))


def own_fixed_point(fp, direction: float) -> float:
    """The terminal ratio of the sampled footprint ``fp`` (disc or ring) itself, sliding
    along ``direction`` (rad, body frame) while spinning counter-clockwise: the eps in
    [0.3, 1.5] where its Coulomb force along the velocity equals eps times its torque / k
    (k = I / (m R^2)), from ``accuracy.coulomb_wrench``.  The closed forms' fixed point
    (0.653 disc, 1 ring) is its limit for many points; a sampled disc's depends a little
    on the orientation of the velocity relative to the body."""
    from scipy.optimize import brentq

    from ..bodies.accuracy import coulomb_wrench
    k = fp.inertia_per_mass / fp.radius ** 2
    e_v = np.array([math.cos(direction), math.sin(direction)])

    def gap(eps):
        F, T = coulomb_wrench(fp, eps, direction=direction)
        return -float(F @ e_v) - eps * (-T) / k
    return float(brentq(gap, 0.3, 1.5, xtol=1e-12))


def own_fixed_range(fp, directions: int = 90) -> tuple[float, float]:
    """(least, largest) of :func:`own_fixed_point` over ``directions`` orientations."""
    v = [own_fixed_point(fp, d) for d in 2 * math.pi * np.arange(directions) / directions]
    return min(v), max(v)


def reference_eps_at(ref, w_fraction: float) -> float:
    """eps of the reference ODE where R omega has fallen to ``w_fraction`` of its start
    (interpolated in ln omega)."""
    lw = np.log(ref.omega / ref.omega[0])
    eps = ref.v / (R * ref.omega)
    return float(np.interp(math.log(w_fraction), lw[::-1], eps[::-1]))


def terminal_rows(sizes: Sizes = FULL, kinds=("disc", "ring")) -> list[dict]:
    """Disc and ring (``kinds``), fast and slow spin: staged simulation beside the
    reference ODE."""
    from ..bodies.closed_forms import TERMINAL_RATIO, disc_reference
    from ..bodies.footprint import disc, ring
    from ..laws.planar import coulomb_law
    law = coulomb_law(MU)
    rows = []
    for kind in kinds:
        fp = (disc(R, contact_points=sizes.disc_points) if kind == "disc" else
              ring(R, contact_points=sizes.ring_points))
        own_range = own_fixed_range(fp)
        for name, eps0 in SPINS:
            omega0 = V0 / (R * eps0)
            st = staged_run(fp, law, (V0, 0.0, omega0), steps_per_stage=sizes.steps_per_stage)
            ref = disc_reference(V0, omega0, MU, G, R, kind)
            first = st.first
            rows.append({"kind": kind, "spin": name, "eps0": eps0, "omega0": omega0,
                         "points": fp.n, "staged": st, "ref": ref,
                         "stop_time": first.stop_time,
                         "slide_stop_time": first.slide_stop_time,
                         "spin_stop_time": first.spin_stop_time,
                         "single_run_ratio": first.terminal_ratio(R),
                         "ref_stop_time": ref.stop_time,
                         "eps_end": st.eps_end, "depth": st.depth,
                         "eps_ref_end": reference_eps_at(ref, st.w_end),
                         "own_range": own_range,
                         "terminal": TERMINAL_RATIO[kind]})
    return rows


def wedge_laws(surfaces: Path | None = None) -> dict:
    """The star laws of the shipped asymmetric wedge texture (derive -> fit; the file
    ``wedge-asymmetric.toml`` of ``surfaces``, by default the repository's surfaces/), both
    contact regimes, and an ellipse law (centrally symmetric: no drift)."""
    from ..friction.derive import derive
    from ..laws.fitting import fit_derivation
    from ..laws.planar import ellipse_law, from_gauge
    from ..texture.wedges import load_texture_file
    from .gauges import SURFACES
    src = Path(SURFACES) if surfaces is None else Path(surfaces)
    tf = load_texture_file(src / "wedge-asymmetric.toml")
    out = {}
    for contact in ("all-faces", "windward"):
        d = derive(tf.texture, contact, "closed-form", 360)
        out[f"wedge-asymmetric, {contact} (star fit)"] = from_gauge(fit_derivation(
            d, "star", holdout=False))
    out["ellipse mu1 = 0.3, mu2 = 0.15"] = ellipse_law(0.3, 0.15)
    return out


def own_drift(fp, law) -> np.ndarray:
    """The sampled footprint's own net force per unit load (2,) in a pure counter-clockwise
    spin: -sum_i w_i p(psi_i), psi_i the direction of omega x r_i (the discrete form of
    ``spin_drift_force``'s integral; their difference is the sampling error)."""
    r = np.asarray(fp.points)
    psi = np.arctan2(r[:, 0], -r[:, 1])
    return -(np.asarray(fp.weights) @ law.force(np.mod(psi, 2 * math.pi)))


def drift_rows(sizes: Sizes = FULL, to_rest: bool = True, surfaces: Path | None = None
               ) -> list[dict]:
    """A disc spinning from rest on each law of :func:`wedge_laws`: the first step's
    acceleration against g times ``spin_drift_force`` and the run to rest (with
    ``to_rest`` False: three steps only)."""
    from ..bodies.closed_forms import spin_drift_force
    from ..bodies.footprint import disc
    from ..dynamics.body import simulate_body
    fp = disc(R, contact_points=sizes.disc_points)
    rows = []
    for name, law in wedge_laws(surfaces).items():
        r = simulate_body(fp.points, fp.weights, law, mass=MASS,
                          inertia=MASS * fp.inertia_per_mass, u0=(0.0, 0.0, DRIFT_OMEGA0),
                          dt=DRIFT_DT, t_end=None if to_rest else 3 * DRIFT_DT)
        a_sim = (r.u[1, :2] - r.u[0, :2]) / (r.t[1] - r.t[0])
        a_ref = G * spin_drift_force(law)
        a_own = G * own_drift(fp, law)
        scale = G * law.min_tangential()
        rows.append({"law": name, "result": r, "a_sim": a_sim, "a_ref": a_ref, "a_own": a_own,
                     "error": float(np.hypot(*(a_sim - a_ref)) / max(np.hypot(*a_ref),
                                                                     1e-3 * scale)),
                     "error_own": float(np.hypot(*(a_sim - a_own)) / max(np.hypot(*a_own),
                                                                         1e-3 * scale)),
                     "rest": r.q_final.copy(), "stop_time": r.stop_time,
                     "status": r.status, "points": fp.n})
    return rows


def rectangle_rows(sizes: Sizes = FULL) -> list[dict]:
    """A rectangle launched off-axis (U0 at 30 deg) on the ellipse law mu1 != mu2: without
    spin (it must follow the point mass), with spin, and with an eccentric load."""
    from ..bodies.footprint import rectangle
    from ..dynamics.body import simulate_body
    from ..dynamics.moreau import slide
    from ..laws.planar import ellipse_law
    from .moreau import MU1, MU2, U0
    law = ellipse_law(MU1, MU2)
    ang = math.radians(30.0)
    v = (U0 * math.cos(ang), U0 * math.sin(ang))
    cases = (("no spin, uniform load", rectangle(RECT_A, RECT_B,
                                                 contact_points=sizes.rect_points), 0.0),
             (f"spin {RECT_OMEGA0:g} rad/s, uniform load",
              rectangle(RECT_A, RECT_B, contact_points=sizes.rect_points), RECT_OMEGA0),
             ("no spin, load centred at x = a/10",
              rectangle(RECT_A, RECT_B, contact_points=sizes.rect_points, profile="linear",
                        centre_of_pressure=(RECT_A / 10, 0.0)), 0.0))
    pm = slide(law, U0, 30.0, dt=1e-4)
    rows = []
    for name, fp, om in cases:
        r = simulate_body(fp.points, fp.weights, law, mass=MASS,
                          inertia=MASS * fp.inertia_per_mass, u0=(*v, om), dt=1e-4)
        rows.append({"case": name, "result": r, "outline": fp.outline, "rest": r.q_final,
                     "angle_deg": math.degrees(r.final_angle_rad), "stop_time": r.stop_time,
                     "point_mass_gap": float(np.hypot(*(r.q_final[:2] - pm.q_final))),
                     "points": fp.n, "status": r.status})
    return rows


