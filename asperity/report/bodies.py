"""Report section on planar rigid bodies (issue 20; SPEC.md section 8): the sampled disc's
force and torque against the closed forms, the terminal ratio v / (R omega) of a disc and a
ring that slide and spin to rest (both stop together), a disc spinning from rest on the
shipped asymmetric wedge law and drifting, a rectangle turning as it slides on an
anisotropic law, and MuJoCo's disc beside ours (from a committed benchmark JSON).

``section(folder, quick=False)``: ``quick`` samples the footprints more coarsely and takes
fewer steps per stage of the terminal-ratio runs (the tests' setting); the closed-form
checks are the same.
"""
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


@dataclass(frozen=True)
class Sizes:
    """Contact points and steps of the section's runs (full or quick)."""

    disc_points: int
    ring_points: int
    rect_points: int
    steps_per_stage: int


FULL = Sizes(disc_points=1024, ring_points=128, rect_points=256, steps_per_stage=1000)
QUICK = Sizes(disc_points=64, ring_points=64, rect_points=60, steps_per_stage=800)


def _fp_f_m():
    from ..bodies.closed_forms import disc_f_m
    return disc_f_m


# ----------------------------------------------------------------------------- 1. sampling

def sampling_table(points=(None, 256, 64), eps=None) -> tuple[np.ndarray, dict]:
    """The eps grid and, per contact-point count (None: the default), the sampled disc's
    worst relative force and torque errors at each eps (``sampling_errors``: over 48
    velocity directions)."""
    from ..bodies.footprint import DEFAULT_CONTACT_POINTS, disc, sampling_errors
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


def plot_sampling(path, eps, errors) -> None:
    from ..bodies.footprint import coulomb_wrench, disc
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    f, m = _fp_f_m()(eps)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10.5, 4.2))
    pos = eps > 0
    ax.semilogx(eps[pos], f[pos], color="tab:blue", label="f(eps), closed form")
    ax.semilogx(eps[pos], m[pos], color="tab:red", label="m(eps), closed form")
    n_def = max(errors)
    fp = disc(R, contact_points=n_def)
    fs, ms = [], []
    for e in eps[pos][::4]:
        F, T = coulomb_wrench(fp, float(e))
        fs.append(-F[0])
        ms.append(-T)
    ax.semilogx(eps[pos][::4], fs, "o", color="tab:blue", ms=3.5, mfc="none",
                label=f"sampled force, {n_def} points")
    ax.semilogx(eps[pos][::4], ms, "s", color="tab:red", ms=3.5, mfc="none",
                label=f"sampled torque, {n_def} points")
    ax.set_xlabel("eps = v / (R omega)")
    ax.set_ylabel("force / (mu N), torque / (mu N R)")
    ax.set_title("Uniformly loaded disc: friction force and torque", fontsize=9)
    ax.legend(fontsize=7)
    colors = ("tab:green", "tab:orange", "tab:purple", "tab:gray")
    for (n, (ef, em)), c in zip(sorted(errors.items(), reverse=True), colors):
        ax2.loglog(eps[pos], np.maximum(ef[pos], 1e-17), color=c, lw=1.3,
                   label=f"force, {n} points")
        ax2.loglog(eps[pos], np.maximum(em[pos], 1e-17), color=c, lw=1.0, ls="--",
                   label=f"torque, {n} points")
    ax2.axhline(5e-3, color="k", lw=0.8, ls=":", label="0.5 %")
    ax2.set_xlabel("eps = v / (R omega)")
    ax2.set_ylabel("largest relative error over 48 directions")
    ax2.set_ylim(1e-17, 1.0)
    ax2.set_title("Sampled footprint against the closed forms", fontsize=9)
    ax2.legend(fontsize=7, ncol=2)
    for a in (ax, ax2):
        a.grid(alpha=0.3, which="both")
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- 2. terminal ratio

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
    (k = I / (m R^2)), from ``footprint.coulomb_wrench``.  The closed forms' fixed point
    (0.653 disc, 1 ring) is its limit for many points; a sampled disc's depends a little
    on the orientation of the velocity relative to the body."""
    from scipy.optimize import brentq

    from ..bodies.footprint import coulomb_wrench
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


def plot_terminal(path, rows) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.3), sharey=False)
    colors = {"fast spin": "tab:red", "slow spin": "tab:blue"}
    for ax, kind in zip(axes, ("disc", "ring")):
        for r in (x for x in rows if x["kind"] == kind):
            st, ref = r["staged"], r["ref"]
            c = colors[r["spin"]]
            left = st.t_stop - st.t
            ok = (left > 0) & (st.u[:, 2] != 0)
            ax.semilogx(left[ok], np.hypot(st.u[ok, 0], st.u[ok, 1]) / (R * st.u[ok, 2]),
                        color=c, lw=2.2, alpha=0.55,
                        label=f"simulated, {r['spin']} (eps0 = {r['eps0']:g})")
            rl = ref.stop_time - ref.t
            ok = (rl > 0) & (ref.omega > 0)
            ax.semilogx(rl[ok], ref.v[ok] / (R * ref.omega[ok]), color=c, lw=0.9, ls="--",
                        label=f"reference ODE, {r['spin']}")
        term = next((x["terminal"] for x in rows if x["kind"] == kind), None)
        if term is not None:
            ax.axhline(term, color="k", lw=0.8, ls=":", label=f"terminal ratio {term:.4g}")
        ax.invert_xaxis()
        ax.set_xlabel("time left until rest (s)")
        ax.set_ylabel("v / (R omega)")
        ax.set_yscale("log")
        ax.set_title(f"{kind.capitalize()}, R = {R:g} m, mu = {MU:g}, v0 = {V0:g} m/s",
                     fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- 3. spin drift

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


#: the spinning disc of the drift runs: omega0 (rad/s) per law (the windward law is rougher)
DRIFT_OMEGA0 = 40.0
DRIFT_DT = 1e-4


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


def _outline_at(outline: np.ndarray, q) -> np.ndarray:
    c, s = math.cos(q[2]), math.sin(q[2])
    return outline @ np.array([[c, s], [-s, c]]) + np.asarray(q[:2])


def plot_drift(path, rows, outline) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, axes = plt.subplots(1, len(rows), figsize=(4.0 * len(rows), 4.2))
    for ax, row in zip(axes, rows):
        r = row["result"]
        ax.plot(r.q[:, 0] * 1e3, r.q[:, 1] * 1e3, color="tab:red", lw=2.5, label="centre",
                zorder=3)
        for k in np.linspace(0, len(r.t) - 1, 5).astype(int):
            o = _outline_at(outline, r.q[k]) * 1e3
            ax.plot(o[:, 0], o[:, 1], color="0.6", lw=0.7)
            mark = _outline_at(np.array([[0.0, 0.0], [R, 0.0]]), r.q[k]) * 1e3
            ax.plot(mark[:, 0], mark[:, 1], color="0.6", lw=0.7)
        a = row["a_ref"]
        if np.hypot(*a) > 1e-9:
            d = 0.8 * R * 1e3 * a / np.hypot(*a)
            ax.annotate("", xy=d, xytext=(0, 0),
                        arrowprops={"arrowstyle": "->", "color": "tab:green", "lw": 1.5})
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x along t_a (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"{row['law']}\nrest at ({row['rest'][0] * 1e3:.2f}, "
                     f"{row['rest'][1] * 1e3:.2f}) mm", fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- 4. rectangle

RECT_A, RECT_B = 0.10, 0.04
RECT_OMEGA0 = 10.0


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


def plot_rectangle(path, rows) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    colors = ("tab:gray", "tab:red", "tab:blue")
    for row, c in zip(rows, colors):
        r = row["result"]
        ax.plot(r.q[:, 0], r.q[:, 1], color=c, lw=1.5, label=row["case"])
        for k in np.linspace(0, len(r.t) - 1, 7).astype(int):
            o = _outline_at(row["outline"], r.q[k])
            ax.plot(o[:, 0], o[:, 1], color=c, lw=0.8, alpha=0.8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x along t_a (m)")
    ax.set_ylabel("y along t_b (m)")
    ax.set_title("Rectangle 0.10 x 0.04 m launched at 30 deg on the ellipse law "
                 "mu1 = 0.6, mu2 = 0.3: outline every 1/6 of the run", fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- 5. MuJoCo

def bench_json(folder: Path):
    """(the benchmark's body part or None, where it was read): ``body-bench.json`` in the
    report folder, else in the repository's reports/."""
    from ..errors import InputError
    from ..io import read_json
    root = Path(__file__).resolve().parents[2] / "reports"
    for p in (Path(folder) / BENCH_JSON, root / BENCH_JSON):
        if p.is_file():
            try:
                data = read_json(p, "benchmark JSON")
            except InputError:
                continue
            if isinstance(data, dict):
                body = data.get("body", data)
                if isinstance(body, dict) and isinstance(body.get("mujoco_disc"), dict):
                    return body, p
    return None, None


def crossing_times(t, v, w, stop_speed: float, end_fraction: float):
    """The benchmark's criteria on a path: (slide stop: first v < stop_speed, spin stop:
    first R |omega| < stop_speed, v / (R omega) where v + R |omega| first falls below
    end_fraction of its start)."""
    def first(mask):
        k = np.flatnonzero(mask)
        return float(t[k[0]]) if k.size else None
    s = v + w
    k = np.flatnonzero(s < end_fraction * s[0])
    ratio = None
    if k.size:
        ratio = float(v[k[0]] / w[k[0]]) if w[k[0]] > 0 else math.inf
    return first(v < stop_speed), first(w < stop_speed), ratio


def our_bench_disc(spec: dict, sizes: Sizes = FULL) -> dict:
    """Our disc with the benchmark's numbers and criteria, and the reference ODE's."""
    from ..bodies.closed_forms import disc_reference
    from ..bodies.footprint import disc
    from ..dynamics.body import simulate_body
    from ..laws.planar import coulomb_law
    Rb = spec["radius"]
    fp = disc(Rb, contact_points=sizes.disc_points)
    r = simulate_body(fp.points, fp.weights, coulomb_law(spec["mu"]), mass=MASS,
                      inertia=MASS * fp.inertia_per_mass, u0=(spec["v0"], 0.0, spec["omega0"]),
                      dt=spec["dt"])
    v, w = np.hypot(r.u[:, 0], r.u[:, 1]), Rb * np.abs(r.u[:, 2])
    ours = crossing_times(r.t, v, w, spec["stop_speed"], spec["end_fraction"])
    ref = disc_reference(spec["v0"], spec["omega0"], spec["mu"], G, Rb, "disc")
    rw = Rb * ref.omega
    exact = crossing_times(ref.t, ref.v, rw, spec["stop_speed"], spec["end_fraction"])
    return {"result": r, "ref": ref, "ours": ours, "exact": exact, "points": fp.n}


def plot_bench(path, spec, mine, mujoco) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.3))
    r, ref = mine["result"], mine["ref"]
    Rb = spec["radius"]
    ax.plot(r.t, np.hypot(r.u[:, 0], r.u[:, 1]), color="tab:blue", lw=2.2, alpha=0.5,
            label="asperity: v")
    ax.plot(r.t, Rb * np.abs(r.u[:, 2]), color="tab:red", lw=2.2, alpha=0.5,
            label="asperity: R omega")
    ax.plot(ref.t, ref.v, "k--", lw=0.8, label="closed forms (reference ODE)")
    ax.plot(ref.t, Rb * ref.omega, "k--", lw=0.8)
    if mujoco is not None:
        path_rows = mujoco.get("path")
        try:
            p = np.asarray(path_rows, dtype=float)
        except (TypeError, ValueError):
            p = np.empty((0, 0))
        if p.ndim == 2 and p.shape[0] > 1 and p.shape[1] == 3 and np.all(np.isfinite(p)):
            ax.plot(p[:, 0], p[:, 1], color="tab:blue", lw=1.0, ls=":", label="MuJoCo: v")
            ax.plot(p[:, 0], p[:, 2], color="tab:red", lw=1.0, ls=":",
                    label="MuJoCo: R omega")
        for key, c, what in (("slide_stop_time", "tab:blue", "slide"),
                             ("spin_stop_time", "tab:red", "spin")):
            t = _num(mujoco.get(key))
            if t is not None:
                ax.axvline(t, color=c, lw=0.9, ls="-.", label=f"MuJoCo {what} stops")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("m/s")
    ax.set_title(f"Disc R = {Rb:g} m, mu = {spec['mu']:g}, v0 = {spec['v0']:g} m/s, "
                 f"omega0 = {spec['omega0']:g} rad/s", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def bench_section(folder: Path, sizes: Sizes = FULL) -> list[str]:
    """The MuJoCo part: our disc with the benchmark's numbers, MuJoCo's from
    ``body-bench.json`` when present; writes bodies_mujoco.png."""
    folder = Path(folder)
    lines = []
    bench, where = bench_json(folder)
    mj = bench.get("mujoco_disc") if bench else None
    have = isinstance(mj, dict) and "slide_stop_time" in mj
    spec = dict(BENCH_DISC)
    if have:
        for k in spec:
            if _num(mj.get(k)) is not None and mj[k] > 0:
                spec[k] = float(mj[k])
    mine = our_bench_disc(spec, sizes)
    plot_bench(folder / "bodies_mujoco.png", spec, mine, mj if have else None)
    r = mine["result"]
    lines += ["### MuJoCo's disc beside ours", "",
              f"The disc of `asperity bench --only body`: R = {spec['radius']:g} m, mu = "
              f"{spec['mu']:g}, v0 = {spec['v0']:g} m/s, omega0 = {spec['omega0']:g} rad/s, "
              f"dt = {spec['dt']:g} s.  MuJoCo models it as a cylinder with condim 6 and the "
              "torsional coefficient of a uniformly loaded disc spinning in place (2 mu R / 3), "
              "decoupled from sliding; ours samples the footprint "
              f"({mine['points']} points).  Same criteria for all: sliding stops when v < "
              f"{spec['stop_speed']:g} m/s, spinning when R omega < {spec['stop_speed']:g} "
              f"m/s; v / (R omega) where v + R omega first falls below "
              f"{spec['end_fraction']:g} of its start.", "",
              "| model | slide stops (s) | spin stops (s) | spin before slide by (s) | "
              "v / (R omega) near the end |", "|---|---|---|---|---|"]

    def row(name, s, w, ratio):
        gap = "" if s is None or w is None else f"{s - w:+.4f}"
        rt = "n/a" if ratio is None else f"{ratio:.3g}"
        return f"| {name} | {_t(s)} | {_t(w)} | {gap} | {rt} |"
    lines.append(row("closed forms (reference ODE)", *mine["exact"]))
    lines.append(row(f"asperity body solver ({r.status})", *mine["ours"]))
    if have:
        lines.append(row(f"MuJoCo {mj.get('version', '?')} (condim 6)",
                         *(_num(mj.get(k)) for k in ("slide_stop_time", "spin_stop_time",
                                                     "terminal_ratio"))))
        la = bench.get("load_average")
        la = _num(la[0]) if isinstance(la, list) and la else None
        lines += ["", f"MuJoCo's figures from `{where.name}` (written by `{BENCH_COMMAND}`"
                  + ("" if la is None else f"; load average {la:.2f} then") + ")."]
    else:
        lines += ["", "MuJoCo's disc not measured here: the report does not need MuJoCo.  "
                  f"Run `{BENCH_COMMAND}` (installs MuJoCo with pip in a child process) and "
                  "regenerate the report to add its row."]
    lines += ["", "![MuJoCo's disc beside ours](bodies_mujoco.png)", ""]
    return lines


# ----------------------------------------------------------------------------- the section

def _t(x) -> str:
    return "never" if x is None else f"{x:.4f}"


def _ratio(x) -> str:
    return "n/a" if x is None else f"{x:.4f}"


def _num(x) -> float | None:
    """A finite number of a JSON file, else None."""
    ok = isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
    return float(x) if ok else None


def section(folder: Path, quick: bool = False, surfaces: Path | None = None) -> list[str]:
    """Markdown lines of the section; writes bodies_sampling.png, bodies_terminal.png,
    bodies_drift.png, bodies_rectangle.png and bodies_mujoco.png.  ``surfaces``: the folder
    of ``wedge-asymmetric.toml`` (default: the repository's surfaces/)."""
    from ..bodies.closed_forms import terminal_ratio
    from ..bodies.footprint import DEFAULT_CONTACT_POINTS
    folder = Path(folder)
    sizes = QUICK if quick else FULL
    lines = ["## Bodies: footprints that slide, spin and turn", "",
             "Planar rigid bodies (x, y, theta) whose footprint is sampled at N contact "
             "points, each with the law of the support at its own slip velocity "
             "(`asperity.bodies`, `asperity.dynamics.body.simulate_body`, issue 20)."
             + (" *Quick run: coarser footprints and stages.*" if quick else ""), ""]
    # 1. sampling
    eps, errors = sampling_table()
    plot_sampling(folder / "bodies_sampling.png", eps, errors)
    n_def = DEFAULT_CONTACT_POINTS["disc"]
    lines += ["### A uniformly loaded disc: sampled force and torque", "",
              "Force `-mu N f(eps)` along the velocity and torque `-mu N R m(eps)` against the "
              "spin, eps = v / (R omega) (SPEC.md 8, `closed_forms.disc_f_m`), against the "
              "disc's contact points (`footprint.disc`, Gauss rings) summed point by point "
              "(`footprint.sampling_errors`: the worst over 48 velocity directions; force "
              "error as a vector, |F + f e_v| / f; at eps = 0 the sampled force's magnitude, "
              "the exact one being 0).  Largest relative errors over each range of eps:", "",
              "| contact points | force, largest error | torque, largest error | "
              + " | ".join(f"eps in [{lo:g}, {hi:g}]: force / torque" for lo, hi in EPS_RANGES)
              + " |", "|---|---|---|" + "---|" * len(EPS_RANGES)]
    for n, (ef, em) in sorted(errors.items(), reverse=True):
        mf, mm = range_maxima(eps, ef), range_maxima(eps, em)
        lines.append(f"| {n}{' (default)' if n == n_def else ''} | {ef.max():.2e} | "
                     f"{em.max():.2e} | "
                     + " | ".join(f"{a:.1e} / {b:.1e}" for a, b in zip(mf, mm)) + " |")
    worst = max(max(e.max() for e in errors[n_def]), 0.0)
    lines += ["", f"The default ({n_def} points): largest error {100 * worst:.2f} % over "
              f"eps in [0, {eps.max():g}] (the aim: 0.5 %).  Beyond "
              "eps = 1 the instantaneous centre of rotation lies outside the disc, the "
              "integrands are smooth and Gauss's rule is exact to rounding.", "",
              "![disc force and torque](bodies_sampling.png)", ""]
    # 2. terminal ratio
    rows = terminal_rows(sizes)
    plot_terminal(folder / "bodies_terminal.png", rows)
    e0 = terminal_ratio("disc")
    lines += ["### The terminal ratio: slide and spin stop together", "",
              f"A disc and a thin ring (R = {R:g} m, m = {MASS:g} kg, I = m R^2 / 2 and m R^2) "
              f"launched at v0 = {V0:g} m/s with a fast and a slow spin on Coulomb friction "
              f"mu = {MU:g}.  The closed forms give d eps/dt = (mu g / (R omega)) "
              "(eps m / k - f): eps flows to the fixed point f = eps m / k, "
              f"{e0:.6f} for the disc and 1 for the ring (Farkas et al., PRL 90, 248302, "
              "2003), and both motions stop at the same instant.  The approach is slow in "
              "the speed (the disc's eps0 - eps falls like (omega / omega0)^0.615), and "
              f"one step dt resolves speeds only down to a few mu g dt, so after the run to "
              f"rest at dt = {DT0:g} s (the stop times below) the end is followed in stages: "
              f"where the speed v + R |omega| has fallen {DROP:g}-fold, the run restarts "
              f"from that state with {sizes.steps_per_stage} steps to its rest "
              f"({STAGES} stages; the solver is scale-free).  Reference: "
              "`closed_forms.disc_reference` (solve_ivp, rtol 1e-12).", "",
              "| footprint | spin | eps0 | points | stop time (s) | slide stops (s) | "
              "spin stops (s) | reference stop (s) | speed at the end / start | "
              "v / (R omega) there | reference there | the footprint's own, over "
              "orientations | closed form | difference | one run's last moving step |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lo, hi = r["own_range"]
        lines.append(f"| {r['kind']} | {r['spin']} | {r['eps0']:g} | {r['points']} | "
                     f"{_t(r['stop_time'])} | {_t(r['slide_stop_time'])} | "
                     f"{_t(r['spin_stop_time'])} | {r['ref_stop_time']:.4f} | "
                     f"{r['depth']:.1e} | {r['eps_end']:.4f} | {r['eps_ref_end']:.4f} | "
                     f"{lo:.4f} to {hi:.4f} | {r['terminal']:.4f} | "
                     f"{100 * (r['eps_end'] / r['terminal'] - 1):+.2f} % | "
                     f"{_ratio(r['single_run_ratio'])} |")
    lines += ["", "*Reference there*: the ODE's eps where R omega has fallen as far; *the "
              "footprint's own*: the terminal ratio of the sampled footprint itself (its "
              "Coulomb force along the velocity = eps torque / k) for a velocity at each "
              "orientation relative to the body: the sampling error of the terminal ratio.  "
              "(A sampled disc also pushes slightly across the velocity, which keeps turning "
              "the velocity relative to the body by about that share per e-fold of speed, so "
              "its end lies inside this range rather than at one orientation's value.)  "
              "Slide and spin stop times are where v, resp. R omega, stay below 1e-10 of the "
              "launch's speed scale (`BodyResult`).  *One run's last moving step*: "
              f"`BodyResult.terminal_ratio` of the run at dt = {DT0:g} s, v / "
              "(R omega) of its last step before rest, where the speeds are a few mu g dt: "
              "set by the step, not by the limit (the ring's fixed point attracts fast "
              "enough to be reached anyway, the disc's does not)."]
    lines += ["", "![terminal ratio](bodies_terminal.png)", ""]
    # 3. spin drift
    drows = drift_rows(sizes, surfaces=surfaces)
    from ..bodies.footprint import disc
    plot_drift(folder / "bodies_drift.png", drows, disc(R, contact_points=8).outline)
    lines += ["### A disc spinning from rest drifts on an asymmetric law", "",
              f"A disc (R = {R:g} m, {drows[0]['points']} contact points, uniform load) "
              f"spun at omega0 = {DRIFT_OMEGA0:g} rad/s with no velocity, on the star laws "
              "fitted to the shipped asymmetric wedge texture `surfaces/wedge-asymmetric.toml` "
              "(derive, closed form, 360 directions -> fit star), in both contact regimes, "
              "and on an ellipse law.  Each point slides in the direction psi of omega x r "
              "and, with uniform pressure, every direction carries the same share of the "
              "load: the net force is -N/(2 pi) times the integral of p(psi) "
              "(`closed_forms.spin_drift_force`), zero for a centrally symmetric law.  "
              f"Initial acceleration = the first step's velocity change / dt (dt = "
              f"{DRIFT_DT:g} s); then the run to rest (arrow: the predicted drift "
              "direction; outline at five instants).", "",
              "| law | acceleration, simulated (m/s^2) | -g/(2 pi) int p dpsi (m/s^2) | "
              "relative difference | the footprint's own -g sum w_i p(psi_i) | relative "
              "difference | rest x (mm) | rest y (mm) | stop time (s) | status |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for d in drows:
        lines.append(f"| {d['law']} | ({d['a_sim'][0]:+.5f}, {d['a_sim'][1]:+.1e}) | "
                     f"({d['a_ref'][0]:+.5f}, {d['a_ref'][1]:+.1e}) | {d['error']:.1e} | "
                     f"({d['a_own'][0]:+.5f}, {d['a_own'][1]:+.1e}) | {d['error_own']:.1e} | "
                     f"{d['rest'][0] * 1e3:+.3f} | {d['rest'][1] * 1e3:+.3f} | "
                     f"{_t(d['stop_time'])} | {d['status']} |")
    lines += ["", "The footprint's own force sums the law over its contact points (psi_i the "
              "direction of omega x r_i): the simulated first step meets it to O(dt), and the "
              "integral to the sampling error (largest for the windward law, whose force jumps "
              "where the sliding direction crosses the ridges).  On the ellipse law both "
              "differences are taken relative to 1e-3 g mu_min, the predicted force being "
              "zero: what is left is the sampling's (a ring with an odd number of points is not "
              "centrally symmetric).", "",
              "![spin drift](bodies_drift.png)", ""]
    # 4. rectangle
    rrows = rectangle_rows(sizes)
    plot_rectangle(folder / "bodies_rectangle.png", rrows)
    from .moreau import MU1, MU2, U0
    lines += ["### A rectangle turning on an anisotropic law", "",
              f"A rectangle {RECT_A:g} x {RECT_B:g} m ({rrows[0]['points']} contact points, "
              f"long side along x) launched at {U0:g} m/s at 30 deg from t_a on the "
              f"associated ellipse mu1 = {MU1:g}, mu2 = {MU2:g} (dt = 1e-4 s).  Without spin "
              "and with uniform load every point slips alike: the body follows the point "
              "mass of `asperity slide` (gap below) and does not turn.  With spin the "
              "anisotropy couples turning and sliding; an eccentric load (linear pressure, "
              "centre of pressure a/10 ahead of the centroid) turns it with no spin at all.",
              "", "| case | rest x (m) | rest y (m) | final angle (deg) | stop time (s) | "
              "gap to the point mass's rest (m) | status |", "|---|---|---|---|---|---|---|"]
    for r in rrows:
        lines.append(f"| {r['case']} | {r['rest'][0]:.5f} | {r['rest'][1]:.5f} | "
                     f"{r['angle_deg']:+.3f} | {_t(r['stop_time'])} | "
                     f"{r['point_mass_gap']:.1e} | {r['status']} |")
    lines += ["", "![rectangle](bodies_rectangle.png)", ""]
    lines += bench_section(folder, sizes)
    return lines
