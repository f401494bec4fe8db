"""One case of a study, and a batch of them: what runs on a worker.

A case is the study's base texture and assembly with the case's parameter values put in
their tables (or one file of a scan library), pushed through the public API exactly as a
single command would: :func:`asperity.derive`, :func:`asperity.fit_derivation`,
:func:`asperity.assembly_friction` and :func:`asperity.assess_assembly`.  So a case's
outputs are those of the single-case API for the same inputs, bit for bit.

A case that fails (a self-locking sample, a value outside a physical range, an unreadable
scan, a solver that does not converge) is returned with its status and one-line message;
the batch goes on.  Statuses: ``ok``, ``failed`` (the input or outcome the message names),
``error`` (an unexpected exception: its type and message; please report it).
"""
from __future__ import annotations

import math
import time
from pathlib import Path

from ..errors import AsperityError, one_line
from .builders import build_inputs

#: output columns of each stage: (name, SQLite type)
OUTPUTS = {
    "derive": [("mu_a_plus", "REAL"), ("mu_a_minus", "REAL"), ("mu_b_plus", "REAL"),
               ("mu_b_minus", "REAL"), ("asymmetry", "REAL"),
               ("principal_direction_deg", "REAL"), ("anisotropy", "REAL"),
               ("self_locking", "INTEGER"), ("self_locking_load_share", "REAL"),
               ("admissible", "INTEGER")],
    "fit": [("fit_law", "TEXT"), ("fit_max_radial_error", "REAL"),
            ("fit_max_angle_error_deg", "REAL"), ("fit_holdout_magnitude_error", "REAL"),
            ("fit_holdout_angle_deg", "REAL")],
    "risk": [("mu_plus", "REAL"), ("mu_minus", "REAL"), ("verdict", "TEXT"),
             ("dT_c_K", "REAL"), ("margin", "REAL"), ("drift_per_cycle_m", "REAL"),
             ("drift_after_cycles_m", "REAL"), ("cycles_to_tolerance", "REAL"),
             ("stabilised_at_cycle", "INTEGER"), ("extrapolated", "INTEGER"),
             ("solved_by", "TEXT")],
    "crawl": [("speed_body_lengths_per_period", "REAL"), ("cost_of_transport", "REAL"),
              ("heading_drift_rad_per_period", "REAL")],
}
STATUSES = ("ok", "failed", "error")
#: study.law -> the fit's kind (as ``asperity fit --law``)
LAWS = {"star": "star", "ellipse": "truncated-ellipse"}


def output_columns(stages, elastic: bool = False) -> list[tuple[str, str]]:
    """The output columns of the stages a study runs (fit implies derive); ``elastic``: the
    study weights the faces by an elastic contact (its outputs follow)."""
    from .contact import OUTPUTS as CONTACT
    run = set(stages) | ({"derive"} if "fit" in stages else set())
    return [c for s in ("derive", "fit", "risk") if s in run for c in OUTPUTS[s]] + \
        (CONTACT if elastic else []) + (OUTPUTS["crawl"] if "crawl" in run else [])


def _finite(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def evaluate(spec: dict, values: dict, file: str | None = None, cache: dict | None = None) -> dict:
    """The outputs of one case (keys of :func:`output_columns`); raises on failure."""
    texture, asm = build_inputs(spec, values, file, cache)
    stages = spec["stages"]
    out: dict = {}
    contact = spec.get("contact") or "all-faces"
    if "derive" in stages or "fit" in stages:
        from ..friction.derive import derive
        d = derive(texture, contact=contact, n_directions=spec.get("directions", 72))
        ax = d.axes
        a_p, a_m = _finite(ax["mu_a_plus"]), _finite(ax["mu_a_minus"])
        out.update({k: _finite(v) for k, v in ax.items()})
        out["asymmetry"] = (a_p - a_m) / (0.5 * (a_p + a_m)) if a_p and a_m else None
        out["principal_direction_deg"] = float(d.principal_direction_deg)
        out["anisotropy"] = _finite(d.anisotropy)
        out["self_locking"] = int(bool(d.self_locking))
        out["self_locking_load_share"] = _finite(d.locking_share)
        out["admissible"] = int(bool(d.admissibility.admissible))
        if "fit" in stages:
            from ..laws.fitting import fit_derivation
            rep = fit_derivation(d, kind=LAWS[spec.get("law", "star")]).fit
            out["fit_law"] = spec.get("law", "star")
            out["fit_max_radial_error"] = _finite(rep.max_radial_error)
            out["fit_max_angle_error_deg"] = _finite(rep.max_angle_error_deg)
            out["fit_holdout_magnitude_error"] = _finite(rep.holdout_max_magnitude_error)
            out["fit_holdout_angle_deg"] = _finite(rep.holdout_max_angle_deg)
    if "risk" in stages:
        from ..microslip.risk import assembly_friction, assess_assembly
        where = {"slip_axis_deg": spec.get("slip_axis_deg"), "textured": spec.get("textured")}
        f = assembly_friction(asm, texture, texture_name=file or spec.get("texture_name", ""),
                              contact=contact, **where) if texture is not None else \
            assembly_friction(asm, **where)
        r = assess_assembly(asm, f, cycles=spec.get("cycles"), tolerance=spec.get("tolerance"),
                            max_marched=spec.get("max_marched", 200))
        for k in ("mu_plus", "mu_minus", "dT_c_K", "margin", "drift_per_cycle_m",
                  "drift_after_cycles_m", "cycles_to_tolerance"):
            out[k] = _finite(r.get(k))
        out["verdict"] = r["verdict"]
        out["stabilised_at_cycle"] = r.get("stabilised_at_cycle")
        out["extrapolated"] = None if r.get("extrapolated") is None else int(r["extrapolated"])
        out["solved_by"] = "exact"             # the block path may answer in closed form
    if spec.get("elastic") is not None:
        from .contact import outputs
        out.update(outputs(texture))
    if "crawl" in stages:
        from .crawl import outputs as crawl_outputs
        out.update(crawl_outputs(spec, values, texture, file))
    return out


def run_case(spec: dict, values: dict, file: str | None = None,
             cache: dict | None = None) -> tuple[str, str, float, dict]:
    """(status, message, seconds, outputs) of one case; never raises (but on Ctrl-C)."""
    t0 = time.perf_counter()
    try:
        out = evaluate(spec, values, file, cache)
        status, msg = "ok", ""
    except AsperityError as exc:
        out, status, msg = {}, "failed", one_line(exc, 500)
    except (KeyboardInterrupt, SystemExit):
        raise
    except MemoryError:
        out, status, msg = {}, "failed", "out of memory for this case"
    except Exception as exc:        # noqa: BLE001 - a case must not stop the study
        out, status, msg = {}, "error", one_line(f"{type(exc).__name__}: {exc}", 500)
    return status, msg, time.perf_counter() - t0, out


def run_batch(spec: dict, names: list[str], ids, rows, files=None) -> list[tuple]:
    """Run cases ``ids`` (parameter values ``rows``, or ``files``) and return one tuple per
    case: (case_id, status, message, seconds, outputs).  The task a worker runs."""
    import warnings

    from ..progress import silenced
    from .blocks import plan, run_block
    if files is None and names and plan(spec, names) is None:   # whatever the batch size:
        # the path of a case never depends on how the cases were batched
        with warnings.catch_warnings(), silenced():
            warnings.simplefilter("ignore")
            block = run_block(spec, names, ids, rows)
            for i in block.todo():               # what the arrays cannot answer exactly
                values = {n: float(v) for n, v in zip(names, rows[i])}
                block.put(i, *run_case(spec, values))
        return block
    res = []
    cache: dict = {}
    with warnings.catch_warnings(), silenced():
        warnings.simplefilter("ignore")            # a worker's warnings reach nobody
        for i, cid in enumerate(ids):
            values = {n: float(v) for n, v in zip(names, rows[i])} if names else {}
            f = None if files is None else str(Path(files[i]))
            status, msg, sec, out = run_case(spec, values, f, cache)
            res.append((int(cid), status, msg, sec, out))
    return res


def warm_up(spec: dict, values: dict | None) -> bool:
    """Import what the stages need and load their compiled kernels by running one case
    (files studies: on a small synthetic scan, :mod:`.warm`), so that the first batches
    are not charged for it."""
    import importlib
    for m in ("asperity.microslip.risk", "asperity.friction.derive", "asperity.laws.fitting",
              "asperity.texture.wedges", "asperity.surface.facets",
              "asperity.crawling.solver"):
        importlib.import_module(m)
    if values:                               # through the block path where it applies
        run_batch(spec, list(values), [0], [list(values.values())])
    elif values is not None:
        run_case(spec, values)
    else:
        from .warm import synthetic_scan
        with synthetic_scan(spec) as (scan_spec, path):
            run_case(scan_spec, {}, path)
    return True
