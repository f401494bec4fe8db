"""Which parameter matters -- and when that cannot be said.

* Sobol designs: first-order and total indices of a complete Saltelli design with 95 %
  bootstrap intervals (SALib).  The indices need every case of the design: N blocks of
  D + 2 cases (A, the D columns of A with one column from B, then B).  A study that was
  interrupted (cases missing) or has failed cases or cases without a finite output gets
  no indices and a note saying how many cases are missing or failed.  An interval the
  bootstrap cannot estimate (zero or undefined width) is reported as such, never as
  "+- 0"; a parameter whose change alone never changed the output is reported as exactly
  0; an index whose whole interval lies outside [0, 1] gets a warning about the sample
  size.
* Other samples: Spearman rank correlation of each parameter with the output.  For random
  samples (Monte Carlo, Latin hypercube) with its 95 % interval (Fisher's z with the
  Bonett-Wright variance (1 + r^2/2) / (n - 3)), only from MIN_RANK_CASES completed cases
  on (with fewer, no rank correlation can differ from 0 at the 95 % level), and a
  parameter is named as mattering only when its interval excludes 0.  For grids (a
  design, not a sample) the rank correlation over the grid, without an interval.
* An output that does not vary: no parameter matters, whatever the kind.
"""
from __future__ import annotations

import math

import numpy as np

#: fewest completed cases for a rank correlation of a random sample: with 4, even a
#: perfect rank order has a two-sided permutation p-value of 2/24 = 0.083 > 0.05
MIN_RANK_CASES = 5
#: an output whose spread is below this share of its magnitude does not vary (rounding)
CONSTANT_RTOL = 1e-12
#: a bootstrap half-width below this is a collapsed bootstrap (every resample the same,
#: up to rounding: SALib returns 0 or ~1e-17), not an interval of an index in [0, 1]
COLLAPSED = 1e-9
Z95 = 1.959963984540054


def _g(x: float) -> str:
    return f"{x:.6g}"


def sobol_indices(Y: np.ndarray, names: list[str], seed: int = 0) -> dict:
    """First-order and total Sobol indices of the outputs Y of a complete Saltelli design
    (case order), with 95 % bootstrap confidence half-widths, through SALib.  ``seed``
    seeds the bootstrap (SALib ignores a seed of 0: 1 is added)."""
    import warnings

    from SALib.analyze import sobol

    from .sampling import sobol_problem
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        si = sobol.analyze(sobol_problem(len(names)), np.asarray(Y, dtype=float),
                           calc_second_order=False, conf_level=0.95, seed=int(seed) + 1)
    return {n: {"S1": float(si["S1"][j]), "S1_conf": float(si["S1_conf"][j]),
                "ST": float(si["ST"][j]), "ST_conf": float(si["ST_conf"][j])}
            for j, n in enumerate(names)}


def spearman_interval(rho: float, n: int) -> tuple[float, float] | None:
    """95 % interval of a Spearman rank correlation of n independent cases (Fisher's z,
    Bonett-Wright variance); None when |rho| = 1 (every case in the same order: no spread
    to estimate) or n < 4."""
    if n < 4 or not abs(rho) < 1.0:
        return None
    z = math.atanh(rho)
    h = Z95 * math.sqrt((1.0 + rho * rho / 2.0) / (n - 3))
    return math.tanh(z - h), math.tanh(z + h)


def influence(kind: str, names: list[str], X: np.ndarray, y: np.ndarray, ok: np.ndarray,
              ids: np.ndarray, n_cases: int, output: str, seed: int) -> dict:
    """The influence part of a study's summary.  X: (stored cases, parameters) inputs, y
    the output and ok the completed cases, both over the stored cases in case order;
    ids: their case ids."""
    out = {"output": output, "output_varies": None, "influence_note": None,
           "most_influential": [], "sobol": None, "rank_correlation": None}
    fin = ok & np.isfinite(y)
    if not fin.any():
        out["influence_note"] = f"no completed case has a finite {output} yet"
        if kind == "sobol":
            out["sobol_note"] = _sobol_waits(ok, y, n_cases, output) or out["influence_note"]
        return out
    vals = y[fin]
    if not np.any(np.ptp(X[fin], axis=0) > 0):
        out["influence_note"] = (f"no parameter varies in the {int(fin.sum())} completed "
                                 f"case(s) with a finite {output}: nothing to rank")
        if kind == "sobol":
            out["sobol_note"] = _sobol_waits(ok, y, n_cases, output) or out["influence_note"]
        else:
            out["rank_correlation"] = {n: None for n in names}
        return out
    if np.ptp(vals) <= CONSTANT_RTOL * np.max(np.abs(vals)):
        v = float(np.median(vals))
        every = "every case" if fin.sum() == n_cases else f"all {int(fin.sum())} cases that have one"
        out["output_varies"] = False
        out["influence_note"] = (f"no parameter matters: the output does not vary ({output} = "
                                 f"{_g(v)} in {every})")
        if kind == "sobol":
            out["sobol_note"] = out["influence_note"]
        else:
            out["rank_correlation"] = {n: None for n in names}
        return out
    out["output_varies"] = True
    if kind == "sobol":
        _sobol(out, names, y, ok, ids, n_cases, output, seed)
    else:
        _ranks(out, kind, names, X[fin], vals, output)
    return out


def _sobol_waits(ok, y, n_cases: int, output: str) -> str | None:
    """Why a Saltelli design cannot give indices yet (or ever), or None."""
    missing = n_cases - ok.size
    if missing:
        return (f"{missing} of {n_cases} cases not run yet (the study was interrupted): the "
                f"Sobol indices wait for every case of the Saltelli design (run the same "
                f"command again to resume)")
    bad = int(np.sum(~ok)) + int(np.sum(~np.isfinite(y[ok])))
    if bad:
        return (f"{bad} of {n_cases} cases failed or have no finite {output} (e.g. "
                f"slides-off): Sobol indices need every case of the design (choose another "
                f"study.output or narrow the parameters)")
    return None


def _sobol(out, names, y, ok, ids, n_cases, output, seed) -> None:
    note = _sobol_waits(ok, y, n_cases, output)
    full = np.full(n_cases, np.nan)
    full[ids[ok]] = y[ok]                 # placed by case id: a hole can never shift a block
    if note is None and not np.all(np.isfinite(full)):
        note = f"the store's cases do not fill the Saltelli design of {n_cases} cases"
    if note is not None:
        out["sobol_note"] = out["influence_note"] = note
        return
    d = len(names)
    si = sobol_indices(full, names, seed)
    base = full[0::d + 2]
    warn = []
    for j, n in enumerate(names):
        v = si[n]
        v["note"] = None
        if np.array_equal(full[j + 1::d + 2], base):
            v.update(S1=0.0, ST=0.0, S1_conf=None, ST_conf=None,
                     note=f"exactly 0: changing {n} alone never changed {output} "
                          f"(in {base.size} samples)")
            continue
        for k in ("S1", "ST"):
            c = v[f"{k}_conf"]
            if not (math.isfinite(c) and c > COLLAPSED):
                v[f"{k}_conf"] = None
                v["note"] = "the bootstrap collapsed: an interval cannot be estimated"
            c = v[f"{k}_conf"] or 0.0
            if v[k] - c > 1.0 or v[k] + c < 0.0 or not math.isfinite(v[k]):
                warn.append(f"{k} of {n} = {v[k]:.3g} lies outside [0, 1], where an index "
                                f"must be, beyond its interval: the base sample N = "
                                f"{base.size} is too small for this output (raise "
                                f"study.samples)")
    out["sobol"] = si
    out["sobol_warnings"] = warn
    ranked = sorted(names, key=lambda n: -si[n]["ST"])
    out["most_influential"] = [n for n in ranked if si[n]["ST"] > 0]


def _ranks(out, kind, names, X, y, output) -> None:
    from scipy.stats import rankdata
    random = kind != "grid"
    n = y.size
    rho = {m: None for m in names}
    out["rank_correlation"] = rho
    if random:
        out["rank_correlation_interval"] = {m: None for m in names}
        out["rank_correlation_cases"] = n
        if n < MIN_RANK_CASES:
            out["influence_note"] = (f"rank correlations need at least {MIN_RANK_CASES} "
                                     f"completed cases with a finite {output}, got {n} (with "
                                     f"fewer, none can differ from 0 at the 95 % level)")
            return
    ry = rankdata(y)
    stands = []
    for j, m in enumerate(names):
        rx = rankdata(X[:, j])
        if np.ptp(rx) == 0:
            continue
        r = float(np.clip(np.corrcoef(rx, ry)[0, 1], -1.0, 1.0))
        rho[m] = r
        if not random:
            if r != 0.0:
                stands.append(m)
            continue
        ci = spearman_interval(r, n)
        out["rank_correlation_interval"][m] = None if ci is None else \
            {"low": ci[0], "high": ci[1]}
        if ci is None or ci[0] > 0.0 or ci[1] < 0.0:
            stands.append(m)
    out["most_influential"] = sorted(stands, key=lambda m: -abs(rho[m]))
    if not stands:
        if random:
            out["influence_note"] = (f"no parameter's rank correlation with {output} differs "
                                     f"from 0 at the 95 % level ({n} cases): none can be "
                                     f"named as mattering (raise study.samples)")
        else:
            out["influence_note"] = f"no parameter changes {output} monotonically over the grid"
