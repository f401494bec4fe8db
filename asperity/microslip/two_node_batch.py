"""The two-node model's verdict in closed form, for a block of cases in one call (the study
engine's block path; the reference is :func:`asperity.microslip.risk.assess_assembly`).

Covered: every load cycle of breakpoints (thermal cycles, any ``history``, constant forces,
forces in phase or any ``force_history``), any ``substeps``, ``force_at`` uniform, start or
end, self-locking sides, the lead-in from the stress-free state; the transient of the first
cycles, the stabilised cycle, the drift after any number of cycles and the cycles to a
tolerance are those of the exact solution at every load point (the kernel's docstring:
:mod:`._two_node_kernels`).  Not covered (``code`` NOT_COVERED: the caller runs the exact
per-case path, which also gives the message of a refusal): mu+ = mu- under a force that
sits at cp - cm while a slider slips (the split of the slip between the two nodes is not
unique; the march's choice decides), refusals (stiffness ratio, asymmetry, margin beyond
what the solvers resolve) and every decision within 1e-9 of its threshold.

Once stabilised the drift per cycle is SPEC.md 5's -alpha_T l0 (dT range - 2 dT_c) under
thermal cycles (tested).
"""
from __future__ import annotations

import numpy as np

from .chains import TOL

#: columns of the kernel's output (the names and conventions of
#: :func:`asperity.microslip.batch.assess_batch`'s answer, so that the two merge and
#: :func:`~asperity.microslip.batch.risk_columns` turns either into a study's row)
FIELDS = ("mu_plus", "mu_minus", "dT_c", "margin", "drift_per_cycle", "drift_after_cycles",
          "cycles_to_tolerance", "stabilised_at", "extrapolated", "verdict")
FORCE_SHARES = {"uniform": (0.5, 0.5), "start": (1.0, 0.0), "end": (0.0, 1.0)}


def two_node_closed(params: dict, mu_plus, mu_minus, dT, F, *, substeps: int, force_at: str,
                    cycles, tolerance, max_marched: int = 200, tol=TOL) -> dict:
    """{field: (m,) array} of :data:`FIELDS` and ``code`` (m,) (0 solved, 1 slides off,
    2 not covered) for m checked two-node cases; ints -1 for none (``stabilised_at``,
    ``extrapolated``), NaN for no number.

    params: {"k", "l0", "alpha_T", "k_t", "N"} (m,) arrays; mu_plus, mu_minus (m,) (inf:
    self-locking); dT, F (m, P): each case's breakpoints (closed cycles); substeps,
    force_at: the block's; cycles (m,); tolerance (m,) with NaN for none.  Inputs are in
    their ranges (the caller checked them)."""
    from ._two_node_kernels import two_node_block
    f = {k: np.ascontiguousarray(params[k], dtype=float) for k in ("k", "l0", "alpha_T", "k_t",
                                                                  "N")}
    m = f["k"].size
    fw0, fw1 = FORCE_SHARES[force_at]
    out = np.zeros((m, len(FIELDS)))
    code = np.zeros(m, np.int64)
    two_node_block(f["k"], f["l0"], f["alpha_T"], f["k_t"], f["N"],
                   np.ascontiguousarray(mu_plus, dtype=float),
                   np.ascontiguousarray(mu_minus, dtype=float),
                   np.ascontiguousarray(dT, dtype=float).reshape(m, -1),
                   np.ascontiguousarray(F, dtype=float).reshape(m, -1), int(substeps),
                   fw0, fw1, np.ascontiguousarray(cycles, dtype=float),
                   np.ascontiguousarray(tolerance, dtype=float), int(max_marched),
                   float(tol.no_drift), float(tol.stabilised), out, code)
    res = {name: out[:, i].copy() for i, name in enumerate(FIELDS)}
    off = code == 1                               # slides off: as the exact solver says it
    tol = np.asarray(tolerance, dtype=float)
    res["cycles_to_tolerance"][off] = np.where(np.isnan(tol[off]), np.nan, 0.0)
    res["extrapolated"][off] = -1.0
    for name in ("stabilised_at", "extrapolated", "verdict"):
        res[name] = np.nan_to_num(res[name], nan=-1.0).astype(np.int64)
    res["code"] = code
    return res
