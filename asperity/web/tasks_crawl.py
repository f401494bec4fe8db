"""The Motion page's crawl (issue 26): :func:`asperity.crawling.solver.crawl` of a curvature
wave on a law, as ``asperity crawl`` runs it, its JSON (``crawl.json``: the command's
``--json``) and CSV (``path.csv``: its ``--csv``) kept for download, and the figures.

The *law* of a job: ``{"kind": "coefficients", "mu_f", "mu_b", "mu_t", "rule"}``,
``{"kind": "job", "job": ID}`` (a Law result's gauge file) or ``{"kind": "upload",
"upload": ID, "name"}`` (a gauge file), either with ``pressure`` for a law family, or
``{"kind": "texture", "source": {...}, "fit": "star"|"ellipse"}`` (a wedge or an uploaded
texture or surface file, :func:`asperity.web.tasks_surface.load_source`, fitted on the fly
as ``asperity crawl FILE`` fits it: all faces, closed form, 720 directions)."""
from __future__ import annotations

import json

from ..errors import InputError
from ..io import json_ready, write_text_atomic

def crawl_law(spec: dict, ctx: dict, bar):
    """The PlanarLaw of a crawl job's law (see the module docstring)."""
    kind = spec.get("kind")
    if kind == "coefficients":
        from ..crawling.solver import coefficient_law
        return coefficient_law(spec.get("mu_f"), spec.get("mu_b"), spec.get("mu_t"),
                               spec.get("rule") or "componentwise")
    if kind in ("job", "upload"):
        from .tasks_motion import build_law
        return build_law(spec, ctx)
    if kind == "texture":
        from ..crawling.solver import FIT_LAWS, fitted_law
        from .job_progress import phase
        from .tasks_surface import load_source
        texture = load_source(spec.get("source") or {}, ctx)[0]
        fit = spec.get("fit") or "star"
        if fit not in FIT_LAWS:
            raise InputError("law fitted must be star or ellipse")
        with phase(bar, 0.0, 0.3, "fitting the law"):
            return fitted_law(texture, fit, progress=bar)
    raise InputError("law must be three coefficients, a Law result, a gauge file or a "
                     "texture")


def crawl_task(params: dict, ctx: dict, bar) -> dict:
    from ..crawling.gait import CurvatureWave
    from ..crawling.output import csv_text, summary
    from ..crawling.solver import crawl
    from .figures_crawl import crawl_figures
    from .job_progress import phase
    spec = params["law"]
    law = crawl_law(spec, ctx, bar)
    gait = CurvatureWave(**params["gait"])
    lo = 0.3 if spec.get("kind") == "texture" else 0.0
    with phase(bar, lo, 0.9, "crawling"):
        res = crawl(law, gait=gait, points=params["points"], periods=params["periods"],
                    quasi_static=params["quasi_static"], g=params["g"],
                    steps_per_period=params["steps_per_period"],
                    texture_on=params["texture_on"],
                    texture_angle_deg=params["texture_angle_deg"])
    bar(0.9, "figures")
    obj = summary(res, law)
    if spec.get("kind") == "upload":
        obj["source"] = str(spec.get("name"))
    elif spec.get("kind") == "texture":
        obj["source"] = str((spec.get("source") or {}).get("name") or params.get("law_text"))
    if ctx.get("family"):
        obj["family"] = ctx["family"]
    obj = json_ready(obj)
    write_text_atomic(ctx["job_dir"] / "crawl.json", json.dumps(obj, indent=1))
    write_text_atomic(ctx["job_dir"] / "path.csv", csv_text(res))
    base = _stem(spec, params)
    return {"crawl": obj, "law_text": params.get("law_text") or obj["law"],
            "family": ctx.get("family"), "figures": crawl_figures(res, gait, obj),
            "files": ["crawl.json", "path.csv"],
            "downloads": {"crawl.json": f"{base}_crawl.json",
                          "path.csv": f"{base}_crawl-path.csv"}}


def _stem(spec: dict, params: dict) -> str:
    """The stem of a crawl's download names: its law and gait."""
    from .labels import clean, pressure_stem, source_stem, stem
    kind = spec.get("kind")
    if kind == "coefficients":
        law = clean(f"{spec.get('rule')}-mu" + "-".join(f"{spec.get(k):g}" for k in
                                                        ("mu_f", "mu_b", "mu_t")))
    elif kind == "upload":
        law = stem(spec.get("name"))
    elif kind == "job":
        law = clean(f"law-of-{spec.get('job')}")
    else:
        law = source_stem(spec.get("source") or {}) + f"_{spec.get('fit', 'star')}"
    if spec.get("pressure") is not None:
        law += "_" + pressure_stem(spec["pressure"])
    g = params.get("gait") or {}
    return f"{law}_A{g.get('amplitude', 7):g}-k{g.get('waves', 1):g}"


TASKS = {"crawl": crawl_task}
