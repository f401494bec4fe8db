"""Figures of the microslip analysis: node displacements against cycles (and the strip's
slip profiles), and the risk map over two texture parameters.
"""
from __future__ import annotations

import numpy as np


def assembly_history(chain, loading, *, cycles: int = 6, substeps: int = 24) -> dict:
    """What :func:`plot_assembly_history` draws, as arrays (the web page draws the same
    with Plotly): ``t`` (cycles), ``dT`` (K), ``nodes`` -- ``(label, u, x)`` of the nodes
    shown, u and x in m --, ``drift`` (m per cycle) and, for a strip, ``x`` (m),
    ``profiles`` -- ``(label, u(x))`` at the end of each cycle -- and ``hot`` (the last
    cycle at its hottest point)."""
    from .loading import Loading
    from .quasi_static import simulate
    L = Loading(loading.dT, loading.F, max(loading.substeps, substeps))
    n = chain.n
    strip = chain.kind == "strip"
    if strip:
        nodes = np.unique(np.linspace(0, n - 1, min(n, 401)).astype(int))
    else:
        nodes = np.arange(n)
    r = simulate(chain, L, cycles, until_stable=False, record_nodes=nodes)
    tr = r.trace
    show = [0, n // 2, n - 1] if strip else list(range(n))
    out = {"t": np.asarray(tr["t"]), "dT": np.asarray(tr["dT"]), "drift": r.drift_per_cycle,
           "strip": strip, "nodes": [], "profiles": []}
    for k in show:
        j = int(np.searchsorted(nodes, k))
        out["nodes"].append((f"node {k + 1} (x = {chain.x[k]:.3g} m)", tr["u"][:, j],
                             float(chain.x[k])))
    if strip:
        out["x"] = np.asarray(chain.x)
        out["x_nodes"] = np.asarray(chain.x[nodes])
        for c in range(1, r.cycles_run + 1):
            out["profiles"].append((f"end of cycle {c}", np.asarray(r.u_end[c])))
        per = L.cycle_points()[0].size
        hot = int(np.argmax(L.cycle_points()[0]))
        j = 1 + (r.cycles_run - 1) * per + hot + (len(tr["t"]) - 1 - r.cycles_run * per)
        out["hot"] = (f"cycle {r.cycles_run} at dT = {tr['dT'][j]:g} K", tr["u"][j])
    return out


def plot_assembly_history(chain, loading, path, *, title: str = "", cycles: int = 6,
                          substeps: int = 24, history: dict | None = None,
                          fe: dict | None = None) -> None:
    """Node displacement against cycles (Antoni et al. figure 3 redrawn from the model,
    temperature on a second axis); for a strip also the displacement profiles u(x) at the
    end of each cycle and at the hottest point of the last one (``history``: what
    :func:`assembly_history` gave, else it is computed).  ``fe``: the ``fe`` block of
    ``risk --fe``, drawn as its mean displacement at the cycle ends and its last profile."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    h = history or assembly_history(chain, loading, cycles=cycles, substeps=substeps)
    strip = h["strip"]
    if strip:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12.5, 4.6))
    else:
        fig, ax = plt.subplots(figsize=(7.5, 4.6))
    for (lab, u, _), col in zip(h["nodes"], ["tab:blue", "tab:green", "tab:red"] * chain.n):
        ax.plot(h["t"], u * 1e6, color=col, lw=1.6, label=lab)
    ax.set_xlabel("cycles")
    ax.set_ylabel("node displacement u (um)")
    ax.grid(alpha=0.3)
    axT = ax.twinx()
    axT.plot(h["t"], h["dT"], color="0.6", lw=0.8, ls=":")
    axT.set_ylabel("dT (K, dotted)", color="0.4")
    d = h["drift"]
    ax.set_title((title + ": " if title else "") + f"mu+={chain.mu_plus:.4g}, "
                 f"mu-={chain.mu_minus:.4g}; drift {d * 1e6:+.4g} um/cycle", fontsize=10)
    fe = fe if fe and "mean_u_m" in fe else None
    if fe:
        ax.plot(range(len(fe["mean_u_m"])), np.asarray(fe["mean_u_m"]) * 1e6, "ks", ms=4,
                mfc="none", label=f"FE (GetFEM) mean u at cycle ends, "
                                  f"{fe['drift_per_cycle_m'] * 1e6:+.4g} um/cycle")
    ax.legend(fontsize=8, loc="best")
    if strip and fe:
        pr = fe["_profile"]
        ax2.plot(np.asarray(pr["x_m"]) * 1e3, np.asarray(pr["u_m"]) * 1e6, "k--", lw=1.0,
                 label=f"FE bottom face, end of cycle {fe['cycles_run']}")
    if strip:
        cmap = plt.get_cmap("viridis")
        k = len(h["profiles"])
        for c, (lab, u) in enumerate(h["profiles"], 1):
            ax2.plot(h["x"] * 1e3, u * 1e6, color=cmap(c / (k + 1)), lw=1.4, label=lab)
        lab, u = h["hot"]
        ax2.plot(h["x_nodes"] * 1e3, u * 1e6, color="tab:red", ls="--", lw=1.2, label=lab)
        ax2.set_xlabel("x (mm)")
        ax2.set_ylabel("displacement u(x) (um)")
        ax2.set_title("strip displacement profiles", fontsize=10)
        ax2.grid(alpha=0.3)
        ax2.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def plot_risk_map(out: dict, path) -> None:
    """Drift per cycle over the grid of ``asperity risk --map`` (signed colour, um/cycle),
    shakedown cells hatched grey (//), alternating-slip cells cross-hatched (xx), slide-off
    cells black."""
    from matplotlib.colors import TwoSlopeNorm

    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    m = out["map"]
    xs, ys = np.array(m["x"]["values"]), np.array(m["y"]["values"])
    d = np.array([[np.nan if v is None else v for v in row] for row in m["drift_per_cycle_m"]])
    verdict = np.array(m["verdict"], dtype=object)
    fig, ax = plt.subplots(figsize=(7.2, 5.4))
    z = d * 1e6
    lim = np.nanmax(np.abs(z)) if np.isfinite(z).any() and np.nanmax(np.abs(z)) > 0 else 1.0
    im = ax.pcolormesh(_edges(xs), _edges(ys), np.where(verdict == "ratchet", z, np.nan),
                       cmap="coolwarm", norm=TwoSlopeNorm(0.0, -lim, lim), shading="flat")
    fig.colorbar(im, ax=ax, label="drift per cycle (um; < 0: towards -x)")
    style = {"shakedown": {"facecolor": "0.9", "edgecolor": "0.6", "hatch": "//", "lw": 0.3},
             "alternating-slip": {"facecolor": "0.75", "edgecolor": "0.45", "hatch": "xx",
                                  "lw": 0.3},
             "slides-off": {"facecolor": "k"}}
    ex, ey = _edges(xs), _edges(ys)
    for j in range(ys.size):
        for i in range(xs.size):
            v = verdict[j, i]
            if v != "ratchet":
                ax.add_patch(plt.Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j],
                                           **style.get(v, style["slides-off"])))
    for v, label in (("shakedown", "shakedown (//)"), ("alternating-slip",
                                                       "alternating slip, no drift (xx)"),
                     ("slides-off", "slides off")):
        if np.any(verdict == v):
            ax.plot([], [], marker="s", ls="", color=style[v]["facecolor"], label=label)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper right")
    unit = {"alpha": " (deg)", "beta": " (deg)"}
    ax.set_xlabel(m["x"]["parameter"] + unit.get(m["x"]["parameter"], ""))
    ax.set_ylabel(m["y"]["parameter"] + unit.get(m["y"]["parameter"], ""))
    ax.set_title(f"risk map: {out['assembly']['name']}, {out['contact']}, texture on the "
                 f"{out['textured']}", fontsize=10)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def _edges(v: np.ndarray) -> np.ndarray:
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
