"""The figure of a gait optimisation: the objective over the coarse grid (the (A, k) plane,
or a line for one parameter), infeasible gaits hatched, the optimiser's evaluations and
path, the optimum marked."""
from __future__ import annotations

import numpy as np

LABELS = {"amplitude": "amplitude A = kappa L", "waves": "waves k"}
TITLES = {"speed": "speed (body lengths per period)", "cost": "cost of transport"}


def plot_design(path, design, obj: dict | None = None) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    names = design.params
    values = design.grid["values"]
    z = np.asarray(design.grid["objective"], dtype=float)
    opt = design.optimum
    if len(names) == 2:
        a, k = np.asarray(values[names[0]]), np.asarray(values[names[1]])
        mesh = ax.pcolormesh(k, a, np.ma.masked_invalid(z), shading="nearest",
                             cmap="viridis" if design.objective == "speed" else "viridis_r")
        bad = np.isnan(z)
        if bad.any():
            from matplotlib.colors import ListedColormap
            ax.pcolormesh(k, a, np.ma.masked_where(~bad, bad.astype(float)),
                          shading="nearest", cmap=ListedColormap(["0.8"]), hatch="///")
            ax.plot([], [], "s", mfc="0.8", mec="0.3", label="crosses itself / infeasible")
        fig.colorbar(mesh, ax=ax, label=TITLES[design.objective] + " (grid)")
        pk = [p[names[1]] for p in design.path]
        pa = [p[names[0]] for p in design.path]
        ax.plot(pk, pa, ".", color="w", ms=3, mec="k", mew=0.3, label="Nelder-Mead evaluations")
        bk = [p[names[1]] for p in design.best_path]
        ba = [p[names[0]] for p in design.best_path]
        ax.plot(bk, ba, "-", color="C3", lw=1.5, label="best point per iteration")
        ax.plot(opt[names[1]], opt[names[0]], "*", color="C3", ms=16, mec="k",
                label=f"optimum A = {opt['amplitude']:.4g}, k = {opt['waves']:.4g}")
        ax.set_xlabel(LABELS[names[1]])
        ax.set_ylabel(LABELS[names[0]])
    else:
        name = names[0]
        x = np.asarray(values[name])
        ax.plot(x, z, "o-", color="C0", label="grid")
        bad = np.isnan(z)
        for xb in x[bad]:
            ax.axvspan(xb - 0.5 * (x[1] - x[0]), xb + 0.5 * (x[1] - x[0]), color="0.85")
        pts = [(p[name], p["objective"]) for p in design.path if p["objective"] is not None]
        if pts:
            px, pf = np.array(pts).T
            pf = -pf if design.objective == "speed" else pf
            ax.plot(px, pf, ".", color="C1", label="Nelder-Mead evaluations")
        fv = design.speed if design.objective == "speed" else design.cost
        ax.plot(opt[name], fv, "*", color="C3", ms=16, mec="k",
                label=f"optimum {name} = {opt[name]:.4g}")
        ax.set_xlabel(LABELS[name])
        ax.set_ylabel(TITLES[design.objective])
        ax.grid(True, alpha=0.3)
    fixed = ", ".join(f"{k} = {v:g}" for k, v in design.fixed.items())
    mode = "quasi-static" if design.quasi_static else "dynamic"
    ax.set_title(f"{'fastest' if design.objective == 'speed' else 'cheapest'} gait, rule "
                 f"{design.rule}, {mode}" + (f", {fixed}" if fixed else "") +
                 f"\n{design.evaluations} crawls at {design.points} points, "
                 f"{design.steps_per_period} steps a period, {design.seconds:.3g} s",
                 fontsize=9)
    ax.legend(loc="best", fontsize=7)
    if obj is not None and obj.get("law"):
        fig.suptitle(obj["law"], fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)
