"""Report section of the GetFEM runs (issue 27, item 5): the plan-view plate dragged in 24
directions against the law, the slender strip against the slider chain, and how the FE and
chain drifts part as the strip thickens (figure ``fe_getfem_hl.png``).  About half a
minute of GetFEM; skipped with the reason when GetFEM is unavailable."""
from __future__ import annotations

from pathlib import Path

#: the slender strip of tests/test_fe_getfem.py and the sweep's base (h varies)
STRIP = {"model": "strip", "h": 2e-3, "E": 1e11, "p": 5e6, "l": 0.1, "k_t": 1e12,
         "alpha_T": 1e-5, "n": 401, "nu": 0.3}
MU = (0.2, 0.1)
DT = (0.0, 30.0)
H_OVER_L = (1 / 100, 1 / 50, 1 / 20, 1 / 10, 1 / 5, 1 / 2)
#: the sweep's cycles: every strip of it ratchets
SWEEP_DT = (0.0, 60.0)
SWEEP_MESH = 100


def _asm(h=None, dT=DT):
    from ..microslip.assembly import assembly_from_dict
    a = dict(STRIP, **({} if h is None else {"h": h}))
    return assembly_from_dict({"assembly": a, "friction": {"mu_plus": MU[0],
                                                           "mu_minus": MU[1]},
                               "loading": {"dT_min": dT[0], "dT_max": dT[1]}},
                              Path("strip.toml"))


def _laws():
    from dataclasses import replace

    from ..friction.derive import derive
    from ..laws.fitting import fit_derivation
    from ..laws.sets import TruncatedEllipse
    from ..laws.walker_leine import associated
    from ..texture.wedges import WedgeTexture
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360)
    ellipse = replace(fit_derivation(d, "truncated-ellipse"),
                      law=associated(TruncatedEllipse(0.2, 0.08, 0.12, 0.15)))
    return [("star law of the wedge (alpha 30, beta 10, mu 0.1 / 0.2)",
             fit_derivation(d, "star")),
            ("truncated ellipse 0.2 / 0.08 / 0.12 / 0.15 (Antoni fig. 7)", ellipse)]


def sweep(h_over_l=H_OVER_L, mesh: int = SWEEP_MESH) -> list[dict]:
    """FE and chain drift per cycle as h / l grows (l, E, k_t, p fixed)."""
    from ..fe.strip import run_strip_fe
    rows = []
    for r in h_over_l:
        fe = run_strip_fe(_asm(r * STRIP["l"], SWEEP_DT), *MU, mesh=mesh)
        h = r * STRIP["l"]
        rows.append({"h_over_l": r, "fe": fe["drift_per_cycle_m"],
                     "lam_h": (STRIP["k_t"] * h / STRIP["E"]) ** 0.5,
                     "chain": fe["chain_drift_per_cycle_m"],
                     "corrected": fe["chain_shear_corrected"]["drift_per_cycle_m"],
                     "elements": fe["elements"], "seconds": fe["seconds"]})
    return rows


def plot_sweep(rows, path) -> None:
    import numpy as np

    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    x = np.array([r["h_over_l"] for r in rows])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11.5, 4.2))
    for key, lab, st in (("fe", "FE (GetFEM, plane stress)", "ko-"),
                         ("chain", "slider chain (bar E h on the bed)", "s--"),
                         ("corrected", "chain, k_t in series with h/(3G)", "^:")):
        ax.plot(x, [-r[key] * 1e6 for r in rows], st, label=lab)
    ax.set_xscale("log")
    ax.set_xlabel("h / l")
    ax.set_ylabel("drift per cycle towards -x (um)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    for key, lab, st in (("chain", "chain", "s--"), ("corrected", "shear-corrected chain",
                                                     "^:")):
        ax2.plot(x, [100 * abs(r["fe"] / r[key] - 1) if r[key] else np.nan for r in rows],
                 st, label=lab)
    ax2.axhline(5.0, color="0.5", lw=0.8)
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    ax2.set_xlabel("h / l")
    ax2.set_ylabel("|FE / chain - 1| (%)")
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    fig.suptitle("strip: FE against the chain as it thickens", fontsize=10)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def section(folder) -> list[str]:
    from ..fe.getfem_runner import getfem_status
    out = ["## Finite elements: the law and the strip in GetFEM", ""]
    ok, why = getfem_status()
    if not ok:
        return out + [f"(skipped: {why})", ""]
    from ..fe.checks import drag_check
    from ..fe.strip import run_strip_fe
    out += [(f"GetFEM {why} under the system Python (`asperity risk ASSEMBLY --fe getfem`, "
            "`asperity law GAUGE --gwfl FILE`; the documentation's gauge-export tutorial)."), "",
            "### Plate dragged in 24 directions (plan view)", "",
            ("A 10 mm square plate (6 x 6 Q1, E = 200 GPa) on the textured support, the "
            "friction an area term written by `law --gwfl` (p(psi) a piecewise-linear table "
            "within 1e-4 of the law), dragged by its left edge 0.1 mm per increment along "
            "each direction; the pull of the edge per unit normal load against p(psi):"), "",
            "| law | largest relative error | Newton iterations | seconds |",
            "|---|---|---|---|"]
    for name, gl in _laws():
        r = drag_check(gl, 24)
        out.append(f"| {name} | {r['max_relative_error']:.2e} | {r['newton_iterations']} | "
                   f"{r['seconds']:.2f} |")
    fe = run_strip_fe(_asm(), *MU, mesh=200)
    c = fe["chain_shear_corrected"]
    s = STRIP
    out += ["", "### Slender strip (h / l = 1/50) against the chain", "",
            (f"h = {s['h']:g} m, l = {s['l']:g} m, E = {s['E']:g} Pa, nu = {s['nu']}, k_t = "
            f"{s['k_t']:g} Pa/m, p = {s['p']:g} Pa, alpha_T = {s['alpha_T']:g} 1/K, mu+ = "
            f"{MU[0]}, mu- = {MU[1]}, dT {DT[0]:g} -> {DT[1]:g} K; FE {fe['elements_along_l']}"
            f" x {fe['elements_through_h']} Q1 elements, chain {s['n']} nodes."), "",
            "| quantity | FE | chain | shear-corrected chain |", "|---|---|---|---|",
            (f"| drift per cycle (m) | {fe['drift_per_cycle_m']:.6e} | "
            f"{fe['chain_drift_per_cycle_m']:.6e} | {c['drift_per_cycle_m']:.6e} |"),
            (f"| relative difference to FE | - | {fe['relative_difference']:.2e} | "
            f"{c['relative_difference']:.2e} |"),
            (f"| elastic limit dT_c (K) | {fe['elastic_limit_K']:.6g} | "
            f"{fe['elastic_limit_closed_form_K']:.6g} (closed form) | "
             f"{fe['elastic_limit_shear_corrected_K']:.6g} (closed form, k_t,eff) |"), "",
            (f"Why they differ: {fe['explanation']}. First slip: x = "
            f"{fe['first_slip_x_m']:g} m towards {fe['first_slip_towards']} (SPEC.md 5). "
            f"{fe['cycles_run']} cycles, {fe['increments']} increments, "
            f"{fe['newton_iterations']} Newton iterations, {fe['seconds']:.2f} s."), ""]
    rows = sweep()
    plot_sweep(rows, Path(folder) / "fe_getfem_hl.png")
    out += ["### How FE and chain part as h / l grows", "",
            (f"The same strip with h varied (l, E, k_t, p fixed, dT {SWEEP_DT[0]:g} -> "
            f"{SWEEP_DT[1]:g} K; FE {SWEEP_MESH} elements along l, ceil({SWEEP_MESH} h / l) "
            "through h, at least 2). The chain's bar has no height: the FE body's shear "
            "through h softens the bed (k_t h / G grows with h), so the two part as the strip "
            "thickens. What matters is lam h = sqrt(k_t h / E) (the height against the "
            "shear-lag length 1/lam), not h / l: while it stays below 1 the traction spreads "
            "through the height linearly and the chain with k_t in series with h/(3G) follows "
            "the FE model. The drift is least sensitive at large margins (it tends to "
            "-alpha_T l (mu+ - mu-)/(mu+ + mu-) per kelvin whatever k_t), most near the "
            "ratchet's onset: the slender strip above, at 30 K, parts by "
            f"{100 * fe['relative_difference']:.2g} %."), "",
            ("| h / l | lam h | FE drift (m) | chain (m) | FE/chain - 1 | shear-corrected (m) "
             "| FE/corrected - 1 | elements | s |"), "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['h_over_l']:.3g} | {r['lam_h']:.3g} | {r['fe']:.4e} | "
                   f"{r['chain']:.4e} | {r['fe'] / r['chain'] - 1:+.2e} | "
                   f"{r['corrected']:.4e} | {r['fe'] / r['corrected'] - 1:+.2e} | "
                   f"{r['elements']} | {r['seconds']:.2f} |")
    out += ["", "![FE and chain against h / l](fe_getfem_hl.png)", ""]
    return out
