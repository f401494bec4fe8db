"""The exact verdicts of a whole block of assemblies in one numba call (issue 28, item 1).

:func:`assess_batch` takes a block of cases of one model (two-node or strip, one node
count, one load-cycle shape) as arrays and returns, for each case, what
:func:`asperity.microslip.risk.assess_assembly` with explicit coefficients gives and a
study stores (``study/cases.py:evaluate``): the verdict, dT_c, the margin, the drift per
cycle, the drift after the life's cycles, the cycles to the tolerance, the stabilised
cycle and whether the drift was extrapolated -- bit for bit (the displacements to the
rounding of a dot product), no Python per case.  The kernel
(:mod:`._batch_kernels`) builds each chain, computes its elastic limit and marches its
cycles exactly as the per-case path does, with the same march kernel.

The caller validates the inputs (every scalar in its range, as the per-case checks of
:mod:`asperity.microslip.limits`); a case the per-case path would refuse or fail (a chain
beyond what double precision resolves, a margin beyond :data:`limits.MARGIN`, a march too
large, a solver failure) comes back with code :data:`NOT_HANDLED`: run that case through
:func:`~asperity.microslip.risk.assess_assembly`, which gives the outcome or the message.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError

#: code of a case: solved here; slides off (a physical outcome, also solved here); not
#: handled here (run it through the per-case path)
OK, SLIDES_OFF, NOT_HANDLED = 0, 1, 2
#: the parameters of each model, in the order the kernel takes them
PARAMS = {"two-node": ("k", "l0", "alpha_T", "k_t", "N"),
          "strip": ("h", "E", "p", "l", "k_t", "alpha_T")}
FORCE_AT = ("uniform", "start", "end")
#: node-passes of one case's march (about 1.5e7 a second) above which the block leaves the
#: case to the per-case path, which marches in pieces (progress, Ctrl-C): one block call
#: never runs long on one case
MAX_CASE_WORK = 1e8
#: share of the free memory the block's work arrays may take (else every case is left to
#: the per-case path, which checks its own memory)
BLOCK_MEMORY_SHARE = 0.5
_FLOATS = ("dT_c", "margin", "drift_per_cycle", "drift_after_cycles",
           "cycles_to_tolerance", "mu_plus", "mu_minus")
_INTS = ("code", "verdict", "stabilised_at", "extrapolated", "cycles_marched")


def assess_batch(model: str, params: dict, mu_plus, mu_minus, dT, F, *, substeps: int,
                 force_at: str, cycles, tolerance, max_marched: int = 200,
                 max_case_work: float = MAX_CASE_WORK) -> dict:
    """The verdicts of m cases of one model (arrays in, arrays out; inputs validated by the
    caller).

    model      : "two-node" (params k, l0, alpha_T, k_t, N: (m,) each) or "strip" (h, E,
                 p, l, k_t, alpha_T: (m,) each, and n: one int for the block)
    mu_plus, mu_minus : (m,) coefficients (+inf: self-locking)
    dT, F      : (m, P) breakpoints of each case's closed load cycle (F in N, strip N/m)
    substeps, force_at : the block's (force_at "uniform", "start" or "end")
    cycles     : (m,) life to assess;  tolerance: (m,) m, NaN = no tolerance
    max_marched: cycles marched at most while looking for the stabilised cycle
    max_case_work : node-passes of a case's march above which it is left to the per-case
                 path (code 2)

    Returns a dict of (m,) arrays: ``code`` (0 solved, 1 slides off, 2 not handled here:
    run the case through :func:`~asperity.microslip.risk.assess_assembly`); ``verdict``
    (index into :data:`asperity.microslip.verdict.VERDICTS`, -1 if code 2); ``dT_c``
    (K, inf if nothing ever slips), ``margin``, ``drift_per_cycle``,
    ``drift_after_cycles`` (m), ``cycles_to_tolerance`` (NaN: None; 0 for a case that
    slides off with a tolerance, as the per-case path), ``stabilised_at`` (-1: None),
    ``extrapolated`` (0/1; -1: None, the per-case path stores none when it slides off),
    ``cycles_marched``, ``mu_plus`` and ``mu_minus`` as the chain holds them (mu- = mu+
    when they are the same but for rounding: :func:`limits.same_friction`; +inf:
    self-locking).  Floats of a case with code 2 are NaN, its integers -1 (and the
    numbers the per-case path does not give for a case that slides off: NaN)."""
    from ..resources import available_memory
    from ._batch_kernels import assess_block
    if model not in PARAMS:
        raise InputError(f"model must be one of {', '.join(PARAMS)}, got {model!r}")
    if force_at not in FORCE_AT:
        raise InputError(f"force_at must be one of {', '.join(FORCE_AT)}, got {force_at!r}")
    mu_p = _column("mu_plus", mu_plus)
    m = mu_p.size
    mu_m = _column("mu_minus", mu_minus, m)
    par = np.zeros((6, m))
    for i, name in enumerate(PARAMS[model]):
        if name not in params:
            raise InputError(f"params.{name} missing (model {model!r} needs "
                             f"{', '.join(PARAMS[model])})")
        par[i] = _column(f"params.{name}", params[name], m)
    n = int(params.get("n", 201)) if model == "strip" else 2
    dT = _table("dT", dT, m)
    F = _table("F", F, m, dT.shape[1])
    cyc = _column("cycles", cycles, m)
    tol = _column("tolerance", tolerance, m)
    s, mm = int(substeps), int(max_marched)
    fout = np.full((len(_FLOATS), m), np.nan)
    iout = np.full((len(_INTS), m), -1, np.int64)
    iout[0] = NOT_HANDLED
    points = dT.shape[1] * s               # a cycle's and the lead-in's load points
    block_bytes = 2 * points * n * 8 + 24 * n * 8 + 8 * mm
    free = available_memory()
    if m and block_bytes <= BLOCK_MEMORY_SHARE * free:
        from ..resources import MEMORY_SHARE
        assess_block(model == "strip", par, n, mu_p, mu_m, dT, F, s,
                     FORCE_AT.index(force_at), cyc, tol, mm, MEMORY_SHARE * free,
                     float(max_case_work), fout, iout)
    out = {k: fout[i] for i, k in enumerate(_FLOATS)}
    out.update({k: iout[i] for i, k in enumerate(_INTS)})
    return out


def risk_columns(out: dict, solved_by="exact") -> dict[str, list]:
    """The risk stage's study outputs (``study.cases.OUTPUTS["risk"]``) of every case of
    :func:`assess_batch`'s answer, as ``study.cases.evaluate`` stores them: numbers as
    floats, None for no number (NaN; inf, as ``_finite``), the verdict's word,
    ``stabilised_at_cycle`` and ``extrapolated`` as ints or None.  A case with code 2 gets
    None everywhere (its row comes from the per-case path).  ``solved_by``: the store's
    word for the path of each case (one word, or one per case)."""
    from .verdict import VERDICTS
    done = (out["code"] != NOT_HANDLED).tolist()

    def floats(a):
        return [x if ok and math.isfinite(x) else None
                for x, ok in zip(a.tolist(), done)]

    def ints(a):
        return [x if ok and x >= 0 else None for x, ok in zip(a.tolist(), done)]

    cols = {k: floats(out[name]) for k, name in (
        ("mu_plus", "mu_plus"), ("mu_minus", "mu_minus"), ("dT_c_K", "dT_c"),
        ("margin", "margin"), ("drift_per_cycle_m", "drift_per_cycle"),
        ("drift_after_cycles_m", "drift_after_cycles"),
        ("cycles_to_tolerance", "cycles_to_tolerance"))}
    cols["verdict"] = [VERDICTS[v] if ok else None
                       for v, ok in zip(out["verdict"].tolist(), done)]
    cols["stabilised_at_cycle"] = ints(out["stabilised_at"])
    cols["extrapolated"] = ints(out["extrapolated"])
    by = [solved_by] * len(done) if isinstance(solved_by, str) else list(solved_by)
    cols["solved_by"] = [b if ok else None for b, ok in zip(by, done)]
    return cols


def _column(name: str, value, m: int | None = None) -> np.ndarray:
    a = np.ascontiguousarray(value, dtype=np.float64)
    if a.ndim != 1 or (m is not None and a.size != m):
        raise InputError(f"{name} must be one number per case ({m if m is not None else 'm'}"
                         f",), got shape {a.shape}")
    return a


def _table(name: str, value, m: int, P: int | None = None) -> np.ndarray:
    a = np.ascontiguousarray(value, dtype=np.float64)
    if a.ndim != 2 or a.shape[0] != m or a.shape[1] < 2 or (P is not None and a.shape[1] != P):
        raise InputError(f"{name} must be one row of breakpoints per case ({m}, "
                         f"{P if P is not None else 'P >= 2'}), got shape {a.shape}")
    return a
