"""What a study found, from its store: the numbers behind the engineer's questions.

* How likely is a ratchet?  ``p_ratchet``: the share of completed cases whose verdict is
  ratchet, with a 95 % Wilson score interval (binomial: the cases are independent draws;
  for grids and Sobol designs the share is over the design, not a probability).
* How far does it creep?  Quantiles of the signed drift per cycle, of its magnitude, of
  the drift after the assessed life, and of the cycles until the tolerance is reached
  (a case that never reaches it counts as never).
* What matters most?  Sobol first-order and total indices with bootstrap confidence
  intervals (kind = "sobol", through SALib); for other samples the Spearman rank
  correlation of each parameter with the output.
* Scan libraries: a table ranked by ratchet risk (verdict, then drift magnitude), with
  anisotropy and asymmetry.
"""
from __future__ import annotations

import math

import numpy as np

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


def sobol_indices(Y: np.ndarray, names: list[str], seed: int = 0) -> dict:
    """First-order and total Sobol indices of the outputs Y of a Saltelli design (case
    order), with 95 % bootstrap confidence half-widths, through SALib."""
    import warnings

    from SALib.analyze import sobol

    from .sampling import sobol_problem
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        si = sobol.analyze(sobol_problem(len(names)), np.asarray(Y, dtype=float),
                           calc_second_order=False, conf_level=0.95, seed=seed)
    return {n: {"S1": float(si["S1"][j]), "S1_conf": float(si["S1_conf"][j]),
                "ST": float(si["ST"][j]), "ST_conf": float(si["ST_conf"][j])}
            for j, n in enumerate(names)}


def rank_correlations(X: np.ndarray, y: np.ndarray, names: list[str]) -> dict:
    """Spearman rank correlation of each input column with y (None where undefined)."""
    from scipy.stats import rankdata
    ok = np.isfinite(y)
    out = {}
    if ok.sum() < 3:
        return {n: None for n in names}
    ry = rankdata(y[ok])
    for j, n in enumerate(names):
        rx = rankdata(X[ok, j])
        if np.ptp(rx) == 0 or np.ptp(ry) == 0:
            out[n] = None
            continue
        out[n] = float(np.corrcoef(rx, ry)[0, 1])
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
    if "risk" in stages:
        verdict = store.column("verdict", dtype=object)[ok]
        out["verdicts"] = {v: int(np.sum(verdict == v)) for v in SEVERITY
                           if np.any(verdict == v)}
        out["p_ratchet"] = wilson(out["verdicts"].get("ratchet", 0), completed)
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
    return out


def _failures(store, top: int = 5) -> list[dict]:
    cur = store.con.execute(
        "SELECT message, COUNT(*), MIN(case_id) FROM cases WHERE status != 'ok' "
        "GROUP BY message ORDER BY COUNT(*) DESC LIMIT ?", (top,))
    return [{"message": m, "cases": n, "first_case": c} for m, n, c in cur]


def _influence(store, meta, ok, out) -> None:
    names = meta["inputs"] if meta["study"]["kind"] != "files" else []
    output = meta["spec"].get("output")
    if not names or output is None:
        return
    y_all = store.column(output)
    out["output"] = output
    if meta["study"]["kind"] == "sobol":
        n = meta["n_cases"]
        bad = int(np.sum(~ok)) + int(np.sum(~np.isfinite(y_all[ok]))) + (n - ok.size)
        if bad:
            out["sobol"] = None
            out["sobol_note"] = (f"{bad} of {n} cases have no finite {output} (failed, "
                                 f"missing or slides-off): Sobol indices need every case of "
                                 f"the design")
        else:
            out["sobol"] = sobol_indices(y_all, names, seed=int(meta["study"]["seed"]))
    if meta["study"]["kind"] in ("monte-carlo", "latin-hypercube", "sobol", "grid"):
        X = np.stack([store.column(n) for n in names], axis=1)[ok]
        out["rank_correlation"] = rank_correlations(X, y_all[ok], names)


def most_influential(summary: dict) -> list[str]:
    """Parameters ordered by influence: Sobol ST when known, else |rank correlation|."""
    if summary.get("sobol"):
        return sorted(summary["sobol"], key=lambda n: -summary["sobol"][n]["ST"])
    rc = summary.get("rank_correlation") or {}
    return sorted(rc, key=lambda n: -(abs(rc[n]) if rc[n] is not None else -1.0))


def ranking(store, stages, limit: int | None = None) -> list[dict]:
    """Scan-library table, most at risk first (verdict severity, |drift|), else by
    anisotropy; failed files last with their message."""
    cols = ["case_id", "file", "status", "message"]
    extra = [c for c in ("verdict", "drift_per_cycle_m", "anisotropy", "asymmetry",
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
