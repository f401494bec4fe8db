"""What a crawling study found: its cases ranked by speed (summary, text lines) and the
figure of the speed over the study's parameters (or per file of a library)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

#: rows of the ranking the summary keeps (all of them: --export)
MAX_ROWS = 100
OUT = ("speed_body_lengths_per_period", "cost_of_transport", "heading_drift_rad_per_period")


def crawl_ranking(store, limit: int | None = MAX_ROWS) -> list[dict] | None:
    """The cases, fastest first (failed last, with their message): rank, case_id, the
    inputs (file, parameters), speed, cost of transport, heading drift; None without the
    crawl stage."""
    if OUT[0] not in dict(store.outputs):
        return None
    inputs = list(store.meta["inputs"])
    cols = ["case_id", *inputs, "status", "message", *OUT]
    q = ", ".join(f'"{c}"' for c in cols)
    cur = store.con.execute(
        f"SELECT {q} FROM cases ORDER BY (status != 'ok'), "
        f"speed_body_lengths_per_period IS NULL, speed_body_lengths_per_period DESC, case_id"
        + ("" if limit is None else f" LIMIT {int(limit)}"))
    rows = [dict(zip(cols, r)) for r in cur]
    for i, r in enumerate(rows):
        r["rank"] = i + 1
    return rows


def crawl_summary(store) -> dict | None:
    """{"speed": p05/p50/p95, "ranking": the fastest cases, "ranked": cases ranked}."""
    rows = crawl_ranking(store)
    if rows is None:
        return None
    ok = store.column("status", dtype=object) == "ok"
    speed = store.column(OUT[0])[ok]
    speed = speed[np.isfinite(speed)]
    q = None if speed.size == 0 else {
        f"p{round(100 * p):02d}": float(np.quantile(speed, p, method="inverted_cdf"))
        for p in (0.05, 0.5, 0.95)}
    return {"speed_body_lengths_per_period": q, "ranked": int(ok.sum()),
            "rule": "the crawl's speed, head-ward positive; fastest first",
            "inputs": list(store.meta["inputs"]),
            "ranking": rows}


def _inputs(r: dict, names) -> str:
    parts = []
    for n in names:
        v = r.get(n)
        parts.append(f"{Path(v).name}" if n == "file" else f"{n} = {v:.4g}")
    return ", ".join(parts)


def crawl_lines(c: dict, names, limit: int = 20) -> list[str]:
    """The ranking of the summary's text."""
    out = []
    q = c.get("speed_body_lengths_per_period")
    if q:
        out.append(f"crawling speed (body lengths per period, head-ward +): p05 "
                   f"{q['p05']:+.4g}, p50 {q['p50']:+.4g}, p95 {q['p95']:+.4g}")
    out.append("ranked by crawling speed (fastest first):")
    for r in c["ranking"][:limit]:
        head = f"  {r['rank']:>4}. case {r['case_id']}: {_inputs(r, names)}"
        if r["status"] != "ok":
            out.append(f"{head}: {r['status']}: {r['message']}")
            continue
        cot = r["cost_of_transport"]
        out.append(f"{head}: speed {r[OUT[0]]:+.5g}, cost of transport "
                   + ("none" if cot is None else f"{cot:.4g}")
                   + f", drift {r[OUT[2]]:+.3g} rad/period")
    more = c["ranked"] - min(limit, len(c["ranking"]))
    if more > 0:
        out.append(f"  ... {more} more (summary.json holds {len(c['ranking'])}; --export all)")
    return out


def plot_crawl(store, path) -> bool:
    """The speed over the parameters: a map over the first two (one panel per value of a
    third, at most four), else the speed against each; a library's files as bars."""
    from ..io import pyplot, save_figure_atomic
    rows = crawl_ranking(store, None)
    ok = [r for r in rows if r["status"] == "ok" and r[OUT[0]] is not None]
    if not ok:
        return False
    names = [n for n in store.meta["inputs"] if n != "file"]
    plt = pyplot()
    if "file" in store.meta["inputs"]:
        fig, ax = plt.subplots(figsize=(7, 0.5 + 0.35 * len(ok)))
        label = [Path(r["file"]).name + ("" if not names else " " + _inputs(r, names))
                 for r in ok][::-1]
        ax.barh(label, [r[OUT[0]] for r in ok][::-1], color="C0")
        ax.set_xlabel("speed (body lengths per period)")
        axes = [ax]
    elif len(names) >= 2 and _panels(rows, names) is not None:
        panels = _panels(rows, names)
        fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.4),
                                 squeeze=False)
        axes = list(axes[0])
        allv = [r[OUT[0]] for r in ok]
        lim = max(abs(min(allv)), abs(max(allv))) or 1.0
        for ax, (title, sel) in zip(axes, panels):
            x = np.array([r[names[1]] for r in sel])
            y = np.array([r[names[0]] for r in sel])
            v = np.array([math.nan if r[OUT[0]] is None else r[OUT[0]] for r in sel])
            m = ax.scatter(x, y, c=v, cmap="RdBu", vmin=-lim, vmax=lim, marker="s",
                           s=max(20, 9000 / max(len(sel), 1)))
            bad = ~np.isfinite(v)
            if bad.any():
                ax.plot(x[bad], y[bad], "kx", label="failed")
                ax.legend(fontsize=7)
            best = int(np.nanargmax(v)) if np.isfinite(v).any() else None
            if best is not None:
                ax.plot(x[best], y[best], "*", color="gold", ms=14, mec="k")
            ax.set_xlabel(names[1])
            ax.set_ylabel(names[0])
            ax.set_title(title, fontsize=9)
        fig.colorbar(m, ax=axes, label="speed (body lengths per period, head-ward +)")
    else:
        fig, axes = plt.subplots(1, len(names), figsize=(4.5 * len(names), 4), squeeze=False)
        axes = list(axes[0])
        for ax, n in zip(axes, names):
            ax.plot([r[n] for r in ok], [r[OUT[0]] for r in ok], "o", ms=3)
            ax.axhline(0, color="0.7", lw=0.5)
            ax.set_xlabel(n)
            ax.set_ylabel("speed (body lengths per period)")
            ax.grid(True, alpha=0.3)
    fig.suptitle(f"{store.meta['study']['name']}: crawling speed of {len(ok)} cases "
                 f"(star: the fastest of a panel)", fontsize=10)
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
    return True


def _panels(rows, names):
    """[(title, rows)] of the map: one panel per value of the third parameter (all values
    of the rest together must be one), at most four; None if the rows do not fit."""
    if len(names) == 2:
        return [("", rows)]
    if len(names) > 3:
        return None
    values = sorted({r[names[2]] for r in rows})
    if len(values) > 4:
        return None
    return [(f"{names[2]} = {v:g}", [r for r in rows if r[names[2]] == v]) for v in values]
