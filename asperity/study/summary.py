"""What a study found, from its store: the numbers behind the engineer's questions.

* How likely is a ratchet?  ``p_ratchet``: the share of completed cases whose verdict is
  ratchet, with a 95 % Wilson score interval (binomial: the cases are independent draws;
  for Sobol designs the share is over the design).  A grid is a design, not a sample: its
  share has no interval (``low`` and ``high`` are None).
* How far does it creep?  Quantiles of the signed drift per cycle, of its magnitude, of
  the drift after the assessed life, and of the cycles until the tolerance is reached
  (a case that never reaches it counts as never).
* What matters most?  Sobol first-order and total indices with bootstrap confidence
  intervals (kind = "sobol", through SALib); for other samples the Spearman rank
  correlation of each parameter with the output -- or why no parameter can be named
  (an output that does not vary, too few cases, an interrupted design): see
  :mod:`asperity.study.influence`.
* Scan libraries: a table ranked by ratchet risk (verdict, then drift magnitude), with
  anisotropy and asymmetry.
"""
from __future__ import annotations

import math

import numpy as np

from .influence import sobol_indices  # noqa: F401  (the summary's API since issue 12)

SEVERITY = {"slides-off": 3, "ratchet": 2, "alternating-slip": 1, "shakedown": 0}
Z95 = 1.959963984540054


def wilson(k: int, n: int, z: float = Z95) -> dict | None:
    """95 % Wilson score interval of a binomial share k / n."""
    if n <= 0:
        return None
    p = k / n
    d = 1.0 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return {"estimate": p, "low": max(0.0, c - h), "high": min(1.0, c + h)}


def _q(x: np.ndarray, qs=(0.05, 0.5, 0.95)) -> dict | None:
    """Quantiles (inverted CDF: an observed value, infinities kept), None -> never."""
    x = x[~np.isnan(x)]
    if x.size == 0:
        return None
    out = {}
    for q in qs:
        v = float(np.quantile(x, q, method="inverted_cdf"))
        out[f"p{round(100 * q):02d}"] = v if math.isfinite(v) else None
    return out


def summarise(store) -> dict:
    """The summary of a study store (the JSON object of ``asperity study --json``)."""
    meta = store.meta
    st = meta["study"]
    spec = meta["spec"]
    stages = spec["stages"]
    counts = store.count()
    stored = sum(counts.values())
    completed = counts.get("ok", 0)
    out = {"name": st["name"], "kind": st["kind"], "seed": st["seed"],
           "stages": stages, "parameters": st["parameters"], "cases": meta["n_cases"],
           "stored": stored, "completed": completed,
           "failed": counts.get("failed", 0) + counts.get("error", 0),
           "missing": meta["n_cases"] - stored, "store": str(store.path)}
    out.update({"verdicts": {}, "p_ratchet": None, "drift_per_cycle_m": None, "sobol": None})
    status = store.column("status", dtype=object)
    ok = status == "ok"
    out["failures"] = _failures(store)
    if any(c == "solved_by" for c, _ in store.outputs):     # stores from before: no column
        cur = store.con.execute("SELECT solved_by, COUNT(*) FROM cases WHERE status = 'ok' "
                                "GROUP BY solved_by ORDER BY solved_by")
        out["solved_by"] = {k: n for k, n in cur if k is not None}
    if "risk" in stages:
        verdict = store.column("verdict", dtype=object)[ok]
        out["verdicts"] = {v: int(np.sum(verdict == v)) for v in SEVERITY
                           if np.any(verdict == v)}
        k = out["verdicts"].get("ratchet", 0)
        if st["kind"] == "grid":
            out["p_ratchet"] = {"estimate": k / completed, "low": None, "high": None} \
                if completed else None
        else:
            out["p_ratchet"] = wilson(k, completed)
        drift = store.column("drift_per_cycle_m")[ok]
        out["drift_per_cycle_m"] = _q(drift)
        out["creep_per_cycle_m"] = _q(np.abs(drift), (0.5, 0.95, 0.99))
        out["drift_after_cycles_m"] = _q(np.abs(store.column("drift_after_cycles_m")[ok]),
                                         (0.5, 0.95, 0.99))
        ctt = store.column("cycles_to_tolerance")[ok]
        ctt = np.where(np.isnan(ctt), np.inf, ctt)
        out["cycles_to_tolerance"] = _q(ctt, (0.05, 0.5))
        asm = spec.get("assembly") or {}
        lo = asm.get("loading") if isinstance(asm.get("loading"), dict) else {}
        out["tolerance_m"] = spec.get("tolerance") if spec.get("tolerance") is not None \
            else lo.get("tolerance")
        out["life_cycles"] = spec.get("cycles")
    if "derive" in stages or "fit" in stages:
        for k in ("anisotropy", "asymmetry", "principal_direction_deg"):
            out[k] = _q(store.column(k)[ok])
    _influence(store, meta, ok, out)
    if st["kind"] == "files":
        out["ranking"] = ranking(store, stages)
    from .contact import load_dependence
    rows = load_dependence(store)
    if rows is not None:
        out["load_dependence"] = rows
    from .crawl_summary import crawl_summary
    crawl = crawl_summary(store)
    if crawl is not None:
        out["crawl"] = crawl
    return out


def _failures(store, top: int = 5) -> list[dict]:
    cur = store.con.execute(
        "SELECT message, COUNT(*), MIN(case_id) FROM cases WHERE status != 'ok' "
        "GROUP BY message ORDER BY COUNT(*) DESC LIMIT ?", (top,))
    return [{"message": m, "cases": n, "first_case": c} for m, n, c in cur]


def _influence(store, meta, ok, out) -> None:
    from .influence import influence
    kind = meta["study"]["kind"]
    names = meta["inputs"] if kind != "files" else []
    output = meta["spec"].get("output")
    if not names or output is None:
        return
    X = np.stack([store.column(n) for n in names], axis=1)
    out.update(influence(kind, names, X, store.column(output), ok, store.done_ids(),
                         meta["n_cases"], output, int(meta["study"]["seed"])))


def most_influential(summary: dict) -> list[str]:
    """Parameters that can be said to matter, most first (Sobol ST, else |rank
    correlation|); empty when none can (see ``influence_note``)."""
    return list(summary.get("most_influential") or [])


def ranking(store, stages, limit: int | None = None) -> list[dict]:
    """Scan-library table, most at risk first (verdict severity, |drift|), else by
    anisotropy; failed files last with their message."""
    cols = ["case_id", "file", "status", "message"]
    extra = [c for c in ("pressure_Pa", "verdict", "drift_per_cycle_m", "anisotropy", "asymmetry",
                         "principal_direction_deg", "mu_a_plus", "mu_a_minus", "mu_plus",
                         "mu_minus") if c in dict(store.outputs)]
    cur = store.con.execute(f"SELECT {', '.join(cols + extra)} FROM cases ORDER BY case_id")
    rows = [dict(zip(cols + extra, r)) for r in cur]

    def key(r):
        if r["status"] != "ok":
            return (1, 0, 0, 0)
        sev = SEVERITY.get(r.get("verdict"), -1)
        return (0, -sev, -abs(r.get("drift_per_cycle_m") or 0.0), -(r.get("anisotropy") or 0.0))
    rows.sort(key=key)
    for i, r in enumerate(rows):
        r["rank"] = i + 1
    return rows[:limit] if limit else rows
