"""Figures of a study: the distribution of the drift, the verdict over the two most
influential parameters, the Sobol indices, and the ranking of a scan library."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io import pyplot, save_figure_atomic
from .summary import SEVERITY, most_influential

COLOURS = {"shakedown": "tab:green", "alternating-slip": "tab:olive", "ratchet": "tab:red",
           "slides-off": "black"}
MAX_POINTS = 20_000


def figures(store, summary: dict, folder, prefix: str = "") -> list[str]:
    """Write the figures that apply into ``folder`` (names prefixed by ``prefix``); their
    file names."""
    folder = Path(folder)
    out = []
    ok = store.column("status", dtype=object) == "ok"
    if "risk" in summary["stages"] and ok.any():
        _drift(store, ok, folder / f"{prefix}drift.png")
        out.append(f"{prefix}drift.png")
        top = most_influential(summary)
        names = (top + [n for n in summary.get("parameters") or {} if n not in top])[:2]
        if len(names) == 2:
            _verdict_map(store, ok, names, summary, folder / f"{prefix}verdicts.png",
                         ranked=min(len(top), 2))
            out.append(f"{prefix}verdicts.png")
    if summary.get("sobol"):
        _sobol(summary, folder / f"{prefix}sobol.png")
        out.append(f"{prefix}sobol.png")
    if summary.get("ranking"):
        _ranking(summary["ranking"], folder / f"{prefix}ranking.png")
        out.append(f"{prefix}ranking.png")
    if summary.get("load_dependence"):
        from .contact import plot_load_dependence
        plot_load_dependence(summary["load_dependence"], folder / f"{prefix}load.png")
        out.append(f"{prefix}load.png")
    if summary.get("crawl"):
        from .crawl_summary import plot_crawl
        if plot_crawl(store, folder / f"{prefix}crawl.png"):
            out.append(f"{prefix}crawl.png")
    return out


def _drift(store, ok, path) -> None:
    plt = pyplot()
    verdict = store.column("verdict", dtype=object)[ok]
    drift = store.column("drift_per_cycle_m")[ok] * 1e6
    fin = np.isfinite(drift)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    if fin.any():
        lo, hi = np.min(drift[fin]), np.max(drift[fin])
        bins = np.linspace(lo, hi if hi > lo else lo + 1e-9, 41)
        data, labels, colours = [], [], []
        for v in SEVERITY:
            sel = (verdict == v) & fin
            if sel.any():
                data.append(drift[sel])
                labels.append(f"{v} ({sel.sum()})")
                colours.append(COLOURS[v])
        ax.hist(data, bins=bins, stacked=True, label=labels, color=colours)
        ax.legend(fontsize=8)
    ax.set_xlabel("drift per cycle (um, + towards +x)")
    ax.set_ylabel("cases")
    ax.set_title("Distribution of the drift per cycle")
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def _verdict_map(store, ok, names, summary, path, ranked: int = 2) -> None:
    """The verdicts over two parameters: the two most influential (``ranked`` = 2), the
    most influential and another (1), or two with no ranking to claim (0)."""
    plt = pyplot()
    x, y = (store.column(n)[ok] for n in names)
    verdict = store.column("verdict", dtype=object)[ok]
    if x.size > MAX_POINTS:
        pick = np.random.default_rng(0).choice(x.size, MAX_POINTS, replace=False)
        x, y, verdict = x[pick], y[pick], verdict[pick]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for v in SEVERITY:
        sel = verdict == v
        if sel.any():
            ax.scatter(x[sel], y[sel], s=6, color=COLOURS[v], label=v, alpha=0.7, lw=0)
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    how = "Sobol ST" if summary.get("sobol") else "rank correlation"
    if ranked == 2:
        title = f"Verdict over the two most influential parameters ({how})"
    elif ranked == 1:
        title = f"Verdict over {names[0]}, the only parameter shown to matter ({how})"
    else:
        why = summary.get("influence_note") or "no influence ranking"
        title = f"Verdict over two parameters ({why})"
    ax.set_title(_wrap(title), fontsize=9)
    ax.legend(fontsize=8, markerscale=2)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def _sobol(summary, path) -> None:
    plt = pyplot()
    s = summary["sobol"]
    names = sorted(s, key=lambda n: -s[n]["ST"])
    i = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(6.4, 0.6 * len(names) + 1.6))
    for k, dy, label, colour in (("S1", -0.2, "first order S1", "tab:blue"),
                                 ("ST", 0.2, "total ST", "tab:orange")):
        ax.barh(i + dy, [s[n][k] for n in names], 0.4, label=label, color=colour,
                xerr=[s[n][f"{k}_conf"] or 0.0 for n in names])
        for j, n in enumerate(names):      # no error bar is not a zero-width interval
            if s[n][f"{k}_conf"] is None:
                ax.annotate("exactly 0" if (s[n].get("note") or "").startswith("exactly")
                            else "no interval", (max(s[n][k], 0.0), j + dy), fontsize=7,
                            xytext=(3, -3), textcoords="offset points")
    ax.set_yticks(i, names)
    ax.invert_yaxis()
    ax.set_xlabel(f"Sobol index of {summary['output']} (95 % intervals)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def _wrap(text: str, width: int = 80) -> str:
    import textwrap
    return "\n".join(textwrap.wrap(text, width))


def _ranking(rows, path, top: int = 40) -> None:
    plt = pyplot()
    rows = [r for r in rows if r["status"] == "ok"][:top]
    key = "drift_per_cycle_m" if rows and rows[0].get("verdict") is not None else "anisotropy"
    vals = [(r.get(key) or 0.0) * (1e6 if key == "drift_per_cycle_m" else 1.0) for r in rows]
    fig, ax = plt.subplots(figsize=(6.4, 0.3 * len(rows) + 1.5))
    colours = [COLOURS.get(r.get("verdict"), "tab:blue") for r in rows]
    ax.barh(np.arange(len(rows)), vals, color=colours)
    ax.set_yticks(np.arange(len(rows)), [Path(r["file"]).name for r in rows], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("drift per cycle (um)" if key == "drift_per_cycle_m" else "anisotropy")
    ax.set_title("Scans ranked, most at risk first", fontsize=10)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
