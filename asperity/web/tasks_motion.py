"""Jobs of the Motion and risk page: a body sliding on a law (``slide``) and the ratchet
verdict of an assembly under load cycles (``risk``).

A *law* for ``slide``: ``{"kind": "job", "job": ID}`` (the gauge file of a Law result),
``{"kind": "upload", "upload": ID, "name": ...}`` (a gauge file) or ``{"kind": "builtin",
"law": coulomb|ellipse|collinear|star, "mu1", "mu2"}`` or ``{"kind": "builtin", "law":
"componentwise", "mu_f", "mu_b", "mu_t"}``.  The *friction* of ``risk``:
``{"kind": "wedge", ...}``, ``{"kind": "job", "job": ID}`` (a Surface result's source),
``{"kind": "file", ...}`` (an uploaded texture or surface), ``{"kind": "law", "job": ID}``
(a Law result's gauge file), ``{"kind": "mu", "mu_plus", "mu_minus"}`` or ``{"kind":
"assembly"}`` (the assembly's own ``[friction]``: explicit coefficients only).
"""
from __future__ import annotations

import math
import shutil

from ..errors import InputError
from ..io import json_ready
from .results import rename
from .store import JOB_ID
from .tasks_surface import job_params, load_source, upload_file

#: the Motion page's pressure field of a law family (as pages_motion's)
PRESSURE = "nominal pressure, Pa"
#: points of a path kept for the page and the CSV table at most
MAX_POINTS = 4000


def _gauge_of_job(ctx: dict, jid) -> "object":
    if not isinstance(jid, str) or not JOB_ID.match(jid):
        raise InputError("no such law; pick one from the list")
    p = ctx["jobs"] / jid / "gauge.json"
    if not p.is_file():
        raise InputError(f"result {jid} holds no fitted law (gauge file)")
    ctx["names"][str(p)] = f"the law of result {jid}"
    return p


def build_law(spec: dict, ctx: dict):
    """The PlanarLaw of a law description (see the module docstring)."""
    from .. import coulomb_law, collinear_law, ellipse_law, law_from_gauge, read_gauge, star_law
    from ..laws.family import law_at
    kind = spec.get("kind")
    if kind in ("job", "upload"):
        path = _gauge_of_job(ctx, spec.get("job")) if kind == "job" else \
            upload_file(ctx, spec.get("upload"), str(spec.get("name")))
        gauge = read_gauge(path)
        gl, how = law_at(gauge, spec.get("pressure"), PRESSURE, "the law")
        if how is not None:             # a law family: the page says at which pressure
            ctx["family"] = {**how, "range_Pa": [gauge.pressures[0], gauge.pressures[-1]]}
        return law_from_gauge(gl)
    name, mu1, mu2 = spec.get("law"), spec.get("mu1"), spec.get("mu2")
    if name == "coulomb":
        return coulomb_law(mu1)
    if name == "ellipse":
        return ellipse_law(mu1, mu2)
    if name == "collinear":
        return collinear_law(mu1=mu1, mu2=mu2)
    if name == "star":
        return star_law(mu1, mu2)
    if name == "componentwise":
        from .. import componentwise_law
        return componentwise_law(spec.get("mu_f"), spec.get("mu_b"), spec.get("mu_t"))
    raise InputError("law must be one of coulomb, ellipse, collinear, star, componentwise")


def slide_task(params: dict, ctx: dict, bar) -> dict:
    from .. import slide
    from ..dynamics.moreau import Settings
    from ..dynamics.summary import path_csv, slide_summary
    from ..errors import check_range
    from ..io import write_text_atomic
    from .figures import path_figure
    law = build_law(params["law"], ctx)
    u0 = check_range("u0", params["u0"], 0.0, 1e4, unit="m/s")
    g = check_range("g", params["g"], 1e-6, 1e6, unit="m/s^2")
    dt = check_range("dt", params["dt"], 1e-9, 1.0, unit="s")
    if params.get("body"):
        from .tasks_body import body_task
        out = body_task(params, ctx, bar, law, *_law_words(params["law"], law, params, ctx))
        return {**out, "family": ctx.get("family")}
    low = law.min_tangential()
    steps = 1.5 * u0 / (g * low) / dt if low > 0 else MAX_POINTS
    every = max(1, int(steps // MAX_POINTS)) if math.isfinite(steps) else 1
    from .job_progress import phase
    with phase(bar, 0.0, 0.95, "sliding"):
        res = slide(law, u0, params["angle_deg"], mass=params["mass"], g=g, dt=dt,
                    record_every=every)
    obj = slide_summary(law, res, u0=u0, angle_deg=params["angle_deg"], mass=params["mass"],
                        g=g, dt=dt, t_end=None, tol=Settings().tol)
    write_text_atomic(ctx["job_dir"] / "path.csv", path_csv(res))
    text, name = _law_words(params["law"], law, params, ctx)
    return {"slide": obj, "figure": path_figure(res, params["angle_deg"]),
            "law_text": text, "family": ctx.get("family"), "files": ["path.csv"],
            "downloads": {"path.csv": f"{name}_slide-path.csv"}}


def _law_words(spec: dict, law, params: dict, ctx: dict) -> tuple[str, str]:
    """What the page calls the law of a slide, and the stem of its download names: the
    fitted law's own title (``law_text`` of the form), the gauge file's name, or the
    built-in law with its coefficients."""
    from .labels import clean, law_stem, pressure_stem, pressure_words, stem
    kind = spec.get("kind")
    at, tail = "", ""
    if spec.get("pressure") is not None:          # a law family, taken at a pressure
        at = f" at p = {pressure_words(spec['pressure'])}"
        tail = "_" + pressure_stem(spec["pressure"])
    if kind == "job":
        name = _law_job_stem(ctx, spec.get("job")) + tail
        return params.get("law_text") or f"the {law.name} law of result {spec['job']}{at}", \
            name
    if kind == "upload":
        shown = str(spec.get("name"))
        return f"the {law.name} law of gauge file {shown}{at}", \
            law_stem(stem(shown), law.name) + tail
    if spec.get("law") == "componentwise":
        mu = "mu" + "-".join(f"{spec.get(k):g}" for k in ("mu_f", "mu_b", "mu_t"))
        return law.description, clean(f"componentwise-{mu}")
    mu = f"mu{spec.get('mu1'):g}" + ("" if spec.get("mu2") is None else f"-{spec['mu2']:g}")
    return law.description, clean(f"{spec.get('law')}-{mu}")


def _friction_table(asm: dict, spec: dict, ctx: dict, extra: dict) -> dict:
    """The assembly's [friction] table for a friction source that the file names."""
    kind = spec.get("kind")
    if kind == "mu":
        return {"mu_plus": spec["mu_plus"], "mu_minus": spec["mu_minus"]}
    if kind == "law":
        shutil.copyfile(_gauge_of_job(ctx, spec.get("job")), ctx["job_dir"] / "gauge.json")
        return {"gauge": "gauge.json", **extra}
    fr = asm.get("friction", {})
    if not isinstance(fr, dict):
        raise InputError("friction of the assembly file must be a table [friction]")
    for k in ("texture", "gauge"):       # an uploaded assembly comes alone: never read them
        if k in fr:
            raise InputError(f"friction.{k} = {str(fr[k])[:80]!r}: on this page an assembly "
                             f"file may not name other files; upload that file as the "
                             f"friction source (or fit that law) and choose it on this form")
    return fr


def _law_job_stem(ctx: dict, jid) -> str:
    """The stem of a Law result's download names (its source and law kind)."""
    import json

    from .labels import clean, stem
    if not isinstance(jid, str) or not JOB_ID.match(jid):
        return "law"
    try:
        res = json.loads((ctx["jobs"] / jid / "result.json").read_text("utf-8"))
        return stem(res["downloads"]["gauge.json"])
    except (OSError, ValueError, KeyError, TypeError):
        return clean(f"law-of-{jid}")


def _friction_stem(spec: dict, ctx: dict) -> str:
    """The friction source of a risk verdict in its download names ('' for the assembly
    file's own friction)."""
    from .labels import clean, source_stem
    from .tasks_surface import source_job
    kind = spec.get("kind")
    if kind in ("wedge", "file"):
        return source_stem(spec)
    if kind == "job":
        return source_stem(source_job(ctx, spec.get("job")))
    if kind == "law":
        return _law_job_stem(ctx, spec.get("job"))
    if kind == "mu":
        return clean(f"mu{spec['mu_plus']:g}-{spec['mu_minus']:g}")
    return ""


def _elastic_at_assembly(source: dict, elastic: dict, asm, ctx: dict, bar):
    """(texture, the ``contact_pressure`` block): the ``source`` of a Surface result derived
    with an ``elastic`` contact, weighted by the contact solved again at the assembly's
    contact pressure (as ``asperity risk --elastic E`` without --pressure), not the
    area-weighted surface of its source."""
    from .tasks_contact import elastic_textures_of
    p, where = asm.contact_pressure()
    if p is None:
        raise InputError("the surface of this result was weighted by an elastic contact, "
                         "which is solved again at the assembly's contact pressure, and a "
                         "two-node assembly entered on this page gives none: use the strip "
                         "model (its p), or upload an assembly file with "
                         "assembly.contact_area")
    textures, _ = elastic_textures_of(source, {"elastic": {**elastic, "pressures": [p]}},
                                      ctx, bar)
    return textures[0], {"pressure_Pa": p, "from": where, "solved": True}


def risk_task(params: dict, ctx: dict, bar) -> dict:
    from .. import assembly_friction, assess_assembly
    from ..microslip.assembly import assembly_from_dict
    from ..microslip.plot import assembly_history, plot_assembly_history
    from ..microslip.risk_text import format_text, near_symmetric_notes
    from .figures import risk_figures
    from .labels import stem
    data = dict(params["assembly"])
    spec = params["friction"]
    opts = {k: params[k] for k in ("slip_axis_deg", "textured") if params.get(k) is not None}
    texture, name, elastic = None, "", None
    if spec.get("kind") == "job":                    # an elastic result is solved below
        source = job_params(ctx, spec.get("job"))
        elastic = source.get("elastic") or None
        source = source["source"]
    if spec.get("kind") in ("wedge", "job", "file"):
        texture = True if elastic else load_source(source if spec["kind"] == "job" else spec,
                                                   ctx)[0]   # replaces the file's source
        name = {"wedge": "wedge {alpha_deg:g}/{beta_deg:g} deg, mu {mu_alpha:g}/{mu_beta:g}",
                "job": "the surface of result {job}", "file": "{name}"}[spec["kind"]]
        name = name.format(**spec)
    else:
        data["friction"] = _friction_table(data, spec, ctx, opts)
        opts = {}
    if texture is not None:
        fr = data.get("friction") if isinstance(data.get("friction"), dict) else {}
        opts["contact"] = params.get("contact") or fr.get("contact") or "all-faces"
    ctx["names"][str(ctx["job_dir"] / "assembly.toml")] = params.get("assembly_name") or \
        "the assembly"
    asm = assembly_from_dict(data, ctx["job_dir"] / "assembly.toml")
    contact = None
    from .job_progress import phase
    if elastic:
        with phase(bar, 0.0, 0.2):
            texture, contact = _elastic_at_assembly(source, elastic, asm, ctx, bar)
    with phase(bar, 0.2, 0.3, "friction along the slip axis"):
        friction = assembly_friction(asm, texture, texture_name=name, **opts)
    if contact is not None:
        friction.detail["contact_pressure"] = contact
    with phase(bar, 0.3, 0.8, "load cycles"):
        out = assess_assembly(asm, friction, cycles=params.get("cycles"),
                              tolerance=params.get("tolerance"))
    bar(0.8, "plot")
    hist = assembly_history(out["_chain"], asm.loading)
    plot_assembly_history(out["_chain"], asm.loading, ctx["job_dir"] / "risk.png",
                          title=asm.name, history=hist)
    figures = risk_figures(hist, out["_chain"], asm.name)
    text = format_text(out)
    public = {k: v for k, v in out.items() if not k.startswith("_")}
    public = rename(public, {str(ctx["job_dir"]) + "/": "", **ctx["names"]})
    import json

    from ..io import write_text_atomic
    write_text_atomic(ctx["job_dir"] / "risk.json", json.dumps(json_ready(public), indent=1))
    files = ["risk.png", "risk.json"]
    if params.get("assembly_toml"):
        write_text_atomic(ctx["job_dir"] / "assembly.toml", params["assembly_toml"])
        files.append("assembly.toml")
    asm_stem = stem(params.get("assembly_name") or asm.name)
    fr_stem = _friction_stem(spec, ctx)
    base = f"{asm_stem}_{fr_stem}" if fr_stem else asm_stem
    return {"risk": public, "text": rename(text, {str(ctx["job_dir"]) + "/": "",
                                                  **ctx["names"]}), "files": files,
            "figures": figures, "elastic": None if contact is None else {
                "result": spec.get("job"), "result_pressures_Pa": list(elastic["pressures"]),
                "assembly_pressure_Pa": contact["pressure_Pa"], "from": contact["from"]},
            "notes": [x.strip().removeprefix("NOTE: ") for x in near_symmetric_notes(out)],
            "downloads": {"risk.png": f"{base}_risk.png", "risk.json": f"{base}_risk.json",
                          "assembly.toml": f"{asm_stem}.toml"}}


TASKS = {"slide": slide_task, "risk": risk_task}
