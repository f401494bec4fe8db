"""The block path of a risk study: a block of cases as arrays, no Python per case.

:func:`asperity.study.cases.run_batch` hands a block here when the study only assesses risk
(``stages = ["risk"]``, no ``[contact]``) of a two-node or strip assembly and varies only
numbers of the assembly, its explicit friction, its loading or the wedge texture.  Then:

1. the block's assembly is parsed once (the file's values); each case's numbers are put in
   arrays and range-checked as arrays, with the checks of the per-case path
   (:mod:`asperity.microslip.limits`);
2. mu+ and mu- come once for the block (a fixed friction source), from the case's columns
   (``friction.mu_plus``/``mu_minus``) or from the textures in one vectorised call
   (:func:`asperity.microslip.friction_batch.texture_friction_batch`);
3. the closed forms answer what they cover: every two-node case
   (:mod:`asperity.microslip.two_node_batch`) and the strips that shake down below their
   elastic limit (:mod:`asperity.microslip.strip_batch`); the exact event solver over the
   whole block (:func:`asperity.microslip.batch.assess_batch`) takes what they leave;
4. every case the arrays cannot answer exactly as the per-case path -- a value outside its
   range (the per-case path then names the case's field), a refusal, a solver failure --
   is left without a status, and :func:`asperity.study.cases.run_batch` runs it through
   :func:`asperity.study.cases.run_case`, the reference.  The store's ``solved_by`` column
   says which path answered each case (``closed-form`` or ``exact``).

The block's results equal the per-case path's: discrete outputs identically, numbers to
1e-12 of their scale (``tests/test_study_blocks.py``).
"""
from __future__ import annotations

import time

import numpy as np

from ..microslip import limits as L

#: the numbers of each model, and of the loading, a block may vary
ASSEMBLY_FIELDS = {"two-node": {"k", "l0", "k_t", "N", "alpha_T"},
                   "strip": {"h", "E", "p", "l", "k_t", "alpha_T"}}
LOADING_FIELDS = {"dT_min", "dT_max", "force", "force_min", "force_max", "cycles",
                  "tolerance"}


class BlockResult:
    """The results of a block, by column (the store writes them in one insert); iterating
    gives the per-case tuples (case_id, status, message, seconds, outputs) of
    :func:`asperity.study.cases.run_batch`."""

    def __init__(self, ids, status, message, seconds, outputs: dict):
        self.ids = [int(i) for i in ids]
        self.status, self.message = list(status), list(message)
        self.seconds = [float(s) for s in seconds]
        self.outputs = outputs                  # name -> list (None: no value)
        self.inputs = None                      # the client's input rows (store.write)

    def __len__(self):
        return len(self.ids)

    def __iter__(self):
        return (self[i] for i in range(len(self.ids)))

    def __getitem__(self, i):
        names = list(self.outputs)
        ok = self.status[i] == "ok"
        return (self.ids[i], self.status[i], self.message[i], self.seconds[i],
                {n: self.outputs[n][i] for n in names if self.outputs[n][i] is not None or ok})

    def todo(self) -> list[int]:
        """Positions of the cases the block left to the per-case path (no status yet)."""
        return [i for i, st in enumerate(self.status) if st is None]

    def put(self, i: int, status: str, message: str, seconds: float, out: dict) -> None:
        """The per-case path's answer for the case at position ``i``."""
        self.status[i], self.message[i], self.seconds[i] = status, message, float(seconds)
        for n, col in self.outputs.items():
            col[i] = out.get(n)

    @property
    def total_seconds(self) -> float:
        return float(sum(self.seconds))


def plan(spec: dict, names) -> str | None:
    """Why the block path does not take this study (None: it does)."""
    if spec.get("stages") != ["risk"] or spec.get("elastic") is not None:
        return "stages other than risk"
    asm = spec.get("assembly")
    if not isinstance(asm, dict) or not isinstance(asm.get("assembly"), dict):
        return "no assembly table"
    model = asm["assembly"].get("model")
    if model not in ASSEMBLY_FIELDS:
        return "unknown model"
    fr = asm.get("friction") if isinstance(asm.get("friction"), dict) else {}
    for n in names:
        table, key = n.split(".", 1)
        if table == "assembly" and key not in ASSEMBLY_FIELDS[model]:
            return f"{n} varies"
        if table == "loading" and key not in LOADING_FIELDS:
            return f"{n} varies"
        if table == "friction" and key not in ("mu_plus", "mu_minus"):
            return f"{n} varies"
        if table == "texture" and not isinstance(spec.get("texture"), dict):
            return "texture varies but is not a table"
        if table == "assembly" and "gauge" in fr and key in ("N", "p"):
            return "a gauge's law may depend on the pressure"
    return None


def run_block(spec: dict, names: list[str], ids, rows) -> BlockResult:
    """The results of the cases ``ids`` (parameter values ``rows``) of a study that
    :func:`plan` accepts; the cases it cannot answer exactly have no status yet
    (:meth:`BlockResult.todo`: :func:`asperity.study.cases.run_batch` runs them one by
    one)."""
    t0 = time.perf_counter()
    ids = np.asarray(ids, dtype=np.int64)
    rows = np.asarray(rows, dtype=float).reshape(ids.size, len(names))
    m = ids.size
    cols = {n: rows[:, i] for i, n in enumerate(names)}
    outputs = {n: [None] * m for n in OUT_NAMES}
    done = np.zeros(m, bool)
    base = _base(spec, names, rows)
    if base is not None:
        try:
            arrays, valid = _arrays(spec, base, cols, m)
            solved = _solve(spec, base, arrays, valid)
        except Exception:                   # noqa: BLE001 - never worse than per case
            solved = None
        if solved is not None:
            done, outputs = solved
    n_block = int(done.sum())
    seconds = np.zeros(m)
    if n_block:
        seconds[done] = (time.perf_counter() - t0) / n_block
    status = np.where(done, "ok", None).tolist()
    message = np.where(done, "", None).tolist()
    return BlockResult(ids.tolist(), status, message, seconds, outputs)


def _base(spec: dict, names, rows):
    """The block's assembly at the file's values, once a case shows that the varied tables
    keep their structure (a value out of range in the first cases is the arrays' to find);
    None: the per-case path answers every case (and says why)."""
    from .builders import _assembly
    try:
        base = _assembly(spec, {})
    except Exception:                       # noqa: BLE001 - the per-case path says why
        return None
    for row in rows[:4]:
        try:
            _assembly(spec, {n: float(v) for n, v in zip(names, row)})
            return base
        except Exception:                   # noqa: BLE001, S112 - a bad value: try the next
            continue
    return None


OUT_NAMES = ("mu_plus", "mu_minus", "verdict", "dT_c_K", "margin", "drift_per_cycle_m",
             "drift_after_cycles_m", "cycles_to_tolerance", "stabilised_at_cycle",
             "extrapolated", "solved_by")


def _in(x, lo, hi):
    return (x >= lo) & (x <= hi)


def _arrays(spec: dict, base, cols: dict, m: int):
    """(the case arrays, the mask of cases whose every number is in its range)."""
    p = base.params
    valid = np.ones(m, bool)
    params = {}
    ranges = L.TWO_NODE if base.model == "two-node" else L.STRIP
    for key in ASSEMBLY_FIELDS[base.model]:
        x = cols.get(f"assembly.{key}")
        if x is None:
            params[key] = np.full(m, float(p[key]))
            continue
        if key == "alpha_T":
            valid &= _in(np.abs(x), *L.ALPHA_T)
        else:
            valid &= _in(x, ranges[key][0], ranges[key][1])
        params[key] = x
    if base.model == "strip":
        params["n"] = int(p["n"])
    lo = spec["assembly"].get("loading") or {}
    dT = np.tile(base.loading.dT, (m, 1))
    F = np.tile(base.loading.F, (m, 1))
    if "loading.dT_min" in cols or "loading.dT_max" in cols:
        # (the table has both: the first cases' build proved its structure)
        a = cols.get("loading.dT_min", np.full(m, float(lo.get("dT_min", np.nan))))
        b = cols.get("loading.dT_max", np.full(m, float(lo.get("dT_max", np.nan))))
        valid &= _in(a, *L.DT) & _in(b, *L.DT) & (b >= a)
        dT = np.column_stack([a, b, a])
    if "loading.force" in cols:
        x = cols["loading.force"]
        valid &= _in(x, *L.FORCE)
        F = np.repeat(x[:, None], dT.shape[1], axis=1)
    if "loading.force_min" in cols or "loading.force_max" in cols:
        f0 = cols.get("loading.force_min", np.full(m, float(lo.get("force_min", np.nan))))
        f1 = cols.get("loading.force_max")
        if f1 is None:                      # the file's, else force_min's (a constant force)
            f1 = np.full(m, float(lo["force_max"])) if "force_max" in lo else f0
        valid &= _in(f0, *L.FORCE) & _in(f1, *L.FORCE)
        F = np.column_stack([f0, f1, f0])
    cycles = cols.get("loading.cycles")
    if cycles is not None:
        valid &= _in(cycles, *L.CYCLES)
    if spec.get("cycles") is not None:
        cycles = np.full(m, float(spec["cycles"]))
    elif cycles is None:
        cycles = np.full(m, float(base.cycles or 1e6))
    tol = cols.get("loading.tolerance")
    if tol is not None:
        valid &= _in(tol, *L.TOLERANCE)
    if spec.get("tolerance") is not None:
        tol = np.full(m, float(spec["tolerance"]))
        valid &= _in(tol, *L.TOLERANCE)
    elif tol is None:
        tol = np.full(m, np.nan if base.tolerance is None else float(base.tolerance))
    mp, mm, ok = _friction(spec, base, cols, m)
    valid &= ok
    return {"params": params, "dT": dT, "F": F, "cycles": cycles, "tolerance": tol,
            "mu_plus": mp, "mu_minus": mm}, valid


def _friction(spec: dict, base, cols: dict, m: int):
    """(mu+, mu-, ok) of the block's cases."""
    from ..microslip.risk import assembly_friction
    where = {"slip_axis_deg": spec.get("slip_axis_deg"), "textured": spec.get("textured")}
    contact = spec.get("contact") or "all-faces"
    tex = {n.split(".", 1)[1]: v for n, v in cols.items() if n.startswith("texture.")}
    if tex:
        from ..microslip.friction_batch import resolve_slip_rules, texture_friction_batch
        axis, face = resolve_slip_rules(base.friction_table, **where)
        mp, mm, ok = texture_friction_batch(spec["texture"], tex, contact=contact,
                                            slip_axis_deg=axis, textured=face)
    else:
        if spec.get("texture") is not None:
            from .builders import _texture
            f = assembly_friction(base, _texture(spec, {}),
                                  texture_name=spec.get("texture_name", ""), contact=contact,
                                  **where)
        else:
            f = assembly_friction(base, **where)
        mp, mm, ok = np.full(m, f.mu_plus), np.full(m, f.mu_minus), np.ones(m, bool)
    for key, arr in (("mu_plus", mp), ("mu_minus", mm)):
        x = cols.get(f"friction.{key}")
        if x is not None:                   # checked as the file's; a study's texture
            ok = ok & _in(x, L.MU[0], L.MU_FILE)      # replaces the file's friction
            if spec.get("texture") is None:
                arr[:] = x
    chain_ok = lambda x: np.isposinf(x) | _in(x, *L.MU)
    return mp, mm, ok & chain_ok(mp) & chain_ok(mm)


def _solve(spec: dict, base, a: dict, valid):
    """(cases answered, their outputs by column) or None (the block runs per case)."""
    m = valid.size
    idx = np.flatnonzero(valid)
    if idx.size == 0:
        return None
    sub = lambda x: x[idx]
    kw = {"substeps": base.loading.substeps, "force_at": base.force_at,
              "cycles": sub(a["cycles"]), "tolerance": sub(a["tolerance"]),
              "max_marched": int(spec.get("max_marched", 200))}
    params = {k: (sub(v) if isinstance(v, np.ndarray) else v) for k, v in a["params"].items()}
    mp, mm = sub(a["mu_plus"]), sub(a["mu_minus"])
    from ..microslip.batch import assess_batch, risk_columns
    dT, F = sub(a["dT"]), sub(a["F"])
    if base.model == "two-node":
        from ..microslip.two_node_batch import two_node_closed
        r = two_node_closed(params, mp, mm, dT, F, **kw)
    else:
        from ..microslip.strip_batch import strip_shakedown
        r = strip_shakedown(params, mp, mm, dT, F, cycles=kw["cycles"],
                            max_marched=kw["max_marched"])
    path = np.where(np.asarray(r["code"]) != 2, "closed-form", "exact").astype(object)
    left = np.flatnonzero(path == "exact")     # the exact block solver takes what they leave
    if left.size:
        def pick(x):
            return x[left] if isinstance(x, np.ndarray) else x
        e = assess_batch(base.model, {k: pick(v) for k, v in params.items()}, pick(mp),
                         pick(mm), pick(dT), pick(F), **{k: pick(v) for k, v in kw.items()})
        for key in r:
            r[key][left] = e[key]
    code = np.asarray(r["code"])
    done = np.zeros(m, bool)
    done[idx] = code != 2
    cols = risk_columns(r, path.tolist())
    if idx.size == m:                       # every case valid: the columns as they are
        return done, {name: cols[name] for name in OUT_NAMES}
    out = {}
    for name in OUT_NAMES:
        full = [None] * m
        for i, v in zip(idx.tolist(), cols[name]):
            full[i] = v
        out[name] = full
    return done, out
