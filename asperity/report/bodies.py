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
from pathlib import Path

import numpy as np

from .bodies_bench import _t, bench_json, bench_section, crossing_times  # noqa: F401

# the section's runs (named here also for tests/test_report_bodies.py)
from .bodies_runs import (  # noqa: F401
    BENCH_COMMAND, BENCH_JSON, DRIFT_DT, DRIFT_OMEGA0, DROP, DT0, EPS_RANGES, FULL, MASS, MU,
    QUICK, RECT_A, RECT_B, STAGES, V0, R, drift_rows, own_drift, own_fixed_range,
    range_maxima, rectangle_rows, reference_eps_at, sampling_table, staged_run, terminal_rows)


def _fp_f_m():
    from ..bodies.closed_forms import disc_f_m
    return disc_f_m


# ----------------------------------------------------------------------------- 1. sampling


def plot_sampling(path, eps, errors) -> None:
    from ..bodies.accuracy import coulomb_wrench
    from ..bodies.footprint import disc
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


# ----------------------------------------------------------------------------- the section


def _ratio(x) -> str:
    return "n/a" if x is None else f"{x:.4f}"


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
              "(`accuracy.sampling_errors`: the worst over 48 velocity directions; force "
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
