"""Report section on the Moreau solver (SPEC.md section 4): Walker & Leine's comparison of
sliding paths redrawn, the convergence of the path with dt against a tight ODE reference, and
the ratchet drift of a block on an asymmetric law against its closed form."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

G = 9.81
#: Walker & Leine's comparison: same mu along the axes for all laws, mu1 > mu2
MU1, MU2, U0 = 0.6, 0.3, 2.0
ANGLES = (30.0, 45.0, 60.0)
CONVERGENCE_DT = (4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4)


def comparison_laws():
    from ..laws import planar as L
    return {"collinear": L.collinear_law(mu1=MU1, mu2=MU2),
            "associated ellipse": L.ellipse_law(MU1, MU2),
            "star-shaped (Walker-Leine)": L.star_law(MU1, MU2)}


def plot_comparison(path, dt: float = 1e-4) -> list[dict]:
    """Paths until stick of the three laws for launches at ANGLES; returns the rows."""
    from ..dynamics.moreau import deflection_deg, slide
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    colors = {"collinear": "tab:gray", "associated ellipse": "tab:blue",
              "star-shaped (Walker-Leine)": "tab:red"}
    fig, ax = plt.subplots(figsize=(6.8, 6.0))
    rows = []
    for name, law in comparison_laws().items():
        for k, ang in enumerate(ANGLES):
            r = slide(law, U0, ang, dt=dt, record_every=10)
            ax.plot(r.q[:, 0], r.q[:, 1], color=colors[name], lw=2.0 if ang == 45 else 1.0,
                    label=name if k == 1 else None)
            ax.plot(*r.q_final, "o", color=colors[name], ms=4)
            rows.append({"law": name, "angle": ang, "rest": r.q_final.copy(),
                         "stop_time": r.stop_time, "deflection": deflection_deg(ang, r.q_final),
                         "iterations": r.max_iterations_used})
    d = max(abs(row["rest"]).max() for row in rows)
    for ang in ANGLES:
        a = math.radians(ang)
        ax.plot([0, 1.1 * d * math.cos(a)], [0, 1.1 * d * math.sin(a)], color="0.75", ls=":",
                lw=0.8)
    ax.plot(0, 0, "ko", ms=4)
    ax.set_xlabel("x along t_a (m), mu1 = %.2g" % MU1)
    ax.set_ylabel("y along t_b (m), mu2 = %.2g" % MU2)
    ax.set_title(f"Sliding paths until stick, u0 = {U0:g} m/s launched at "
                 f"{', '.join(f'{a:g}' for a in ANGLES)} deg (dotted)", fontsize=9)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)
    return rows


def convergence_rows(cases=None, dts=CONVERGENCE_DT) -> list[tuple]:
    """(case, dt, path error (m), order, rest-point error (m), stop-time error (s))."""
    from ..dynamics.moreau import slide
    from ..dynamics.references import path_error, reference_path
    from ..laws import planar as L
    if cases is None:
        cases = (("associated ellipse mu1 = 0.6, mu2 = 0.3, launched at 30 deg",
                  L.ellipse_law(MU1, MU2), 30.0),
                 ("star: windward wedge 30/30 deg, mu = 0.3 (gauge fit), launched at 45 deg",
                  L.windward_star_law(), 45.0))
    rows = []
    for name, law, ang in cases:
        t_stop, rest, dense = reference_path(law, U0, ang)
        prev = None
        for dt in dts:
            r = slide(law, U0, ang, dt=dt)
            e = path_error(r, dense)
            order = math.log2(prev / e) if prev else None
            rows.append((name, dt, e, order, float(np.hypot(*(r.q_final - rest))),
                         abs(r.stop_time - t_stop)))
            prev = e
    return rows


def ratchet_rows(dt: float = 1e-4, cycles: int = 10) -> list[tuple]:
    """(mu+, mu-, F0/(m g), analytic drift per cycle, simulated, relative difference)."""
    from ..dynamics.moreau import Force, point_mass, simulate
    from ..dynamics.references import ratchet_drift_square
    from ..laws import planar as L
    m, T = 1.0, 0.4
    rows = []
    for mp, mm, f0 in ((0.3, 0.15, 0.2), (0.3, 0.15, 0.29), (0.2, 0.1, 0.15),
                       (0.12, 0.25, 0.18), (0.2, 0.2, 0.19)):
        law = L.truncated_ellipse_law(mp, mm, 0.2, 0.2)
        F = f0 * m * G
        # measured between two instants of rest: (k + 1/2) T when the block slips in the
        # -F0 half (mu- < mu+), k T when it slips in the +F0 half (x = 0 at rest before)
        half = 0.5 if mm < mp else 0.0
        r = simulate(point_mass(law, m), [0.0, 0.0], dt=dt, t_end=(cycles + half) * T,
                     force=Force(amplitude=(F, 0.0), period=T, waveform="square"))
        sim = float(r.q_final[0]) / cycles
        ref = ratchet_drift_square(F, m, T, mp, mm)
        rel = abs(sim - ref) / abs(ref) if ref else abs(sim)
        rows.append((mp, mm, f0, ref, sim, rel))
    return rows


def plot_ratchet(path, dt: float = 1e-4) -> None:
    """x(t) of the block and the force over a few cycles, with the closed-form drift."""
    from ..dynamics.moreau import Force, point_mass, simulate
    from ..dynamics.references import ratchet_drift_square
    from ..io import pyplot, save_figure_atomic
    from ..laws import planar as L
    plt = pyplot()
    m, T, F = 1.0, 0.4, 0.2 * G
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.0, 5.2), sharex=True,
                                  gridspec_kw={"height_ratios": [2.2, 1]})
    for mp, mm, color in ((0.3, 0.15, "tab:red"), (0.15, 0.15, "tab:gray")):
        law = L.truncated_ellipse_law(mp, mm, 0.2, 0.2)
        f = Force(amplitude=(F, 0.0), period=T, waveform="square")
        r = simulate(point_mass(law, m), [0.0, 0.0], dt=dt, t_end=6 * T, force=f,
                     record_every=10)
        ax.plot(r.t, r.q[:, 0] * 1e3, color=color, lw=1.5,
                label=f"mu+ = {mp:g}, mu- = {mm:g}")
        if mp != mm:
            d = ratchet_drift_square(F, m, T, mp, mm)
            k = np.arange(7)
            ax.plot((k + 0.5) * T, np.maximum(k, 0) * d * 1e3, "k+", ms=8,
                    label="closed form, at rest (t = (k + 1/2) T)")
    t = np.linspace(0, 6 * T, 2000)
    ax2.plot(t, Force(amplitude=(F, 0.0), period=T, waveform="square")(t)[:, 0] / (m * G),
             color="tab:green")
    ax2.set_ylabel("f / (m g)")
    ax2.set_xlabel("t (s)")
    ax.set_ylabel("x (mm)")
    ax.set_title("Ratcheting under a zero-mean square-wave force, F0 = 0.2 m g", fontsize=9)
    ax.legend(fontsize=8)
    for a in (ax, ax2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)


def section(folder: Path) -> list[str]:
    """Markdown lines of the section; writes moreau_paths.png and moreau_ratchet.png."""
    folder = Path(folder)
    lines = ["## Law -> motion: Moreau time-stepping", "",
             "Moreau midpoint scheme (SPEC.md section 4) with the friction impulses from the "
             "implicit proximal equations `alpha P = prox_{Lambda_N D}(alpha (P + r gamma_E))`, "
             "solved by fixed-point iteration with `r = 1 / max eig(W^T M^-1 W)` (r = m for a "
             "point mass), alpha updated in every iteration, tolerance 1e-12 on the change of "
             "the impulse per normal impulse.  Stick is exact (u = 0 bit for bit).", ""]
    rows = plot_comparison(folder / "moreau_paths.png")
    lines += ["### Walker & Leine's comparison, redrawn", "",
              f"A point mass launched at u0 = {U0:g} m/s on an orthotropic surface, mu1 = "
              f"{MU1:g} along t_a and mu2 = {MU2:g} along t_b for every law: the collinear law "
              "(force along the sliding direction, |p| from the ellipse), the associated "
              "ellipse and the star-shaped Walker-Leine law (non-convex windward wedge "
              "reservoir stretched to the same axis values, convex D).  As in their figure 2, "
              "the collinear path is straight and the others bend towards the low-friction "
              "axis t_b; the star law ends sliding exactly along t_b (set-valued law: a "
              "sliding mode along the ridges).", "",
              "![sliding paths](moreau_paths.png)", "",
              "| law | launch (deg) | rest x (m) | rest y (m) | stop time (s) | deflection (deg) |",
              "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['law']} | {r['angle']:g} | {r['rest'][0]:.5f} | {r['rest'][1]:.5f} "
                     f"| {r['stop_time']:.4f} | {r['deflection']:+.3f} |")
    lines += ["", "### Convergence of the path with dt", "",
              f"u0 = {U0:g} m/s; reference: the sliding-phase ODE dv/dt = -g p(angle v) "
              "integrated with solve_ivp (DOP853, rtol 1e-12) until |v| = 1e-9 u0 (the "
              "windward law switches to the sliding mode along the ridges when the velocity "
              "direction reaches them).  Path error: max over the steps of |q_n - q_ref(t_n)|.",
              "", "| law | dt (s) | path error (m) | order | rest-point error (m) | "
              "stop-time error (s) |", "|---|---|---|---|---|---|"]
    for name, dt, e, order, erest, et in convergence_rows():
        o = f"{order:.3f}" if order is not None else ""
        lines.append(f"| {name} | {dt:g} | {e:.3e} | {o} | {erest:.2e} | {et:.2e} |")
    lines += ["", "### Ratcheting of a block on an asymmetric law", "",
              "A block (m = 1 kg) on a truncated ellipse with mu_a+ (resisting motion towards "
              "+t_a) and mu_a- under the zero-mean square wave f = +-F0 along t_a, period "
              "T = 0.4 s.  With mu_- m g < F0 <= mu_+ m g it sticks while pushed towards +t_a "
              "and slips while pulled, stopping in the next half: drift per cycle "
              "`-(a1 tau^2/2)(1 + a1/a2)`, tau = T/2, a1 = F0/m - mu_- g, a2 = F0/m + mu_- g "
              "(towards the low-friction side; `moreau.ratchet_drift_square`).  Simulated: "
              "10 cycles, dt = 1e-4 s.", "",
              "| mu+ | mu- | F0 / (m g) | drift per cycle, closed form (m) | simulated (m) | "
              "relative difference |", "|---|---|---|---|---|---|"]
    for mp, mm, f0, ref, sim, rel in ratchet_rows():
        lines.append(f"| {mp:g} | {mm:g} | {f0:g} | {ref:.6e} | {sim:.6e} | {rel:.1e} |")
    plot_ratchet(folder / "moreau_ratchet.png")
    lines += ["", "With mu+ = mu- and F0 below the threshold the block does not move at all "
              "(last row); above it, it slips both ways and the drift per cycle dies out "
              "(tests/test_dynamics_moreau.py).", "", "![ratchet](moreau_ratchet.png)", ""]
    return lines
