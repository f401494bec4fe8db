"""The Motion and risk page (slide a body, assess an assembly) and the Studies page."""
from __future__ import annotations

from fastapi import Request
from fastapi.responses import HTMLResponse

from .common import DONE_LIMIT, done_job, post_form, stored_text, wedge_source, wedge_title
from .forms import Form, FormError, at
from .labels import label, pressure_words
from .pages import CONTACTS, UNITS
from .pages_body import BODIES
from .store import UploadError, check_plain_name
from .units import article
from .words import STRIP, TWO_NODE

BUILTIN = (("ellipse", "built in: ellipse (associated orthotropic, mu1 along t_a, mu2 along t_b)"),
           ("coulomb", "built in: coulomb (isotropic, mu1)"),
           ("collinear", "built in: collinear (force along the sliding direction)"),
           ("star", "built in: star (windward wedge reservoir, mu1 / mu2)"),
           ("componentwise", ("built in: componentwise (Hu et al.: forward, backward, "
                              "transverse coefficients)")),
           ("upload", "a gauge file (upload below)"))
#: the Motion page's pressure field, for a law family (a gauge file of version 2)
PRESSURE = "nominal pressure, Pa"


def family_jobs(web, laws_done: list[dict]) -> list[str]:
    """The select values (``job:ID``) of the finished laws that are law families."""
    out = []
    for j in laws_done:
        if j["kind"] == "fit":
            fam = (j.get("params") or {}).get("family")
            if isinstance(fam, dict) and "index" in fam and fam["index"] is None:
                out.append(f"job:{j['id']}")
        elif "family" in (web.store.result(j["id"]) or {}):
            out.append(f"job:{j['id']}")
    return out


def family_upload(web, kept, key: str = "gauge") -> list[str]:
    """``["upload"]`` when the form's kept gauge file is a law family (its pressure field
    then shows for it; for a file chosen in the browser, app.js reads it), else ``[]``."""
    meta = (kept or {}).get(key) if isinstance(kept, dict) else None
    if not isinstance(meta, dict):
        return []
    from .. import read_gauge
    from ..errors import AsperityError
    from ..laws.family import GaugeFamily
    try:
        return ["upload"] if isinstance(read_gauge(web.store.upload_path(meta.get("id"))),
                                        GaugeFamily) else []
    except (AsperityError, OSError):
        return []


def family_pressure(form: Form, path, field: str, shown: str, name: str = "law_pressure"
                    ) -> dict:
    """``{"pressure": P}`` (the field ``name``) when the gauge file at ``path`` (shown
    as ``shown``) holds a law family, required there and within the family's pressures;
    else ``{}`` (the field blank: it applies to a family only)."""
    from .. import read_gauge
    from ..errors import InputError
    from ..laws.family import GaugeFamily
    p = form.optional(name, label=PRESSURE)
    try:
        gauge = read_gauge(path)
    except InputError as exc:
        raise FormError(str(exc).replace(str(path), shown), field) from None
    if not isinstance(gauge, GaugeFamily):
        if p is not None:
            raise FormError(f"{PRESSURE}: {shown} is one law, not a law family over pressures; "
                            "leave the pressure blank", name)
        return {}
    lo, hi = gauge.pressures[0], gauge.pressures[-1]
    if p is None or not lo <= p <= hi:
        raise FormError(f"{PRESSURE}: the law is a family over the pressures {lo:g} to "
                        f"{hi:g} Pa; give the nominal contact pressure within them"
                        + ("" if p is None else f" (got {p:g} Pa)"), name)
    try:
        gauge.at(p, PRESSURE)
    except InputError as exc:
        raise FormError(str(exc), name) from None
    return {"pressure": p}


def render_motion(web, request: Request, status: int = 200, **ctx) -> HTMLResponse:
    laws_done, surfaces, jobs = web.store.select(
        (("fit", "gauge"), ("done",), DONE_LIMIT), (("derive",), ("done",), DONE_LIMIT),
        (("slide", "risk", "crawl"), None, 20))
    q = request.query_params
    laws = [(f"job:{j['id']}", f"{j['id']}: {label(j)}") for j in laws_done] + list(BUILTIN)
    default_law = f"job:{q['law']}" if q.get("law") and any(
        j["id"] == q["law"] for j in laws_done) else (laws[0][0] if laws else "ellipse")
    frictions = [("wedge", "a wedge texture (below)")]
    frictions += [(f"job:{j['id']}", f"surface {j['id']}: {label(j)}") for j in surfaces]
    frictions += [(f"law:{j['id']}", f"law {j['id']}: {label(j)}") for j in laws_done]
    frictions += [("file", "a texture or surface file (upload below)"),
                  ("mu", "two coefficients mu+ and mu- (below)"),
                  ("assembly", "the assembly file's own [friction] (mu_plus, mu_minus)")]
    default_friction = "wedge"
    if q.get("texture") and any(j["id"] == q["texture"] for j in surfaces):
        default_friction = f"job:{q['texture']}"
    elif q.get("law") and any(j["id"] == q["law"] for j in laws_done):
        default_friction = f"law:{q['law']}"
    families = family_jobs(web, laws_done) + family_upload(web, ctx.get("kept"))
    from .words import CRAWL_LAWS, CRAWL_RULES
    crawl = {"laws": [(f"job:{j['id']}", f"{j['id']}: {label(j)}") for j in laws_done]
             + list(CRAWL_LAWS), "rules": CRAWL_RULES, "families": family_jobs(web, laws_done)
             + family_upload(web, ctx.get("kept"), "crawl_gauge")}
    return web.page(request, "motion.html", status, page="motion", laws=laws, crawl=crawl,
                    default_law=default_law, family_laws=families, frictions=frictions,
                    default_friction=default_friction, jobs=jobs, bodies=BODIES, **ctx)


def render_studies(web, request: Request, status: int = 200, **ctx) -> HTMLResponse:
    return web.page(request, "studies.html", status, page="studies",
                    jobs=web.store.jobs(kinds=("study",), limit=20), **ctx)


async def _slide_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    choice = form.text("law") or "ellipse"
    if choice.startswith("job:"):
        jid = choice[4:]
        rec = done_job(web, jid, ("fit", "gauge"), "law", "law")
        spec, what = {"kind": "job", "job": jid}, f"the {rec['title']} (law {jid})"
        spec.update(family_pressure(form, web.store.job_dir(jid) / "gauge.json", "law",
                                    f"the law of result {jid}"))
    elif choice == "upload":
        meta = kept.get("gauge")
        if meta is None:
            raise FormError("choose a gauge file (.json) to upload, or another law", "gauge")
        spec, what = {"kind": "upload", "upload": meta["id"], "name": meta["name"]}, meta["name"]
        spec.update(family_pressure(form, web.store.upload_path(meta["id"]), "gauge",
                                    meta["name"]))
    elif choice in ("coulomb", "ellipse", "collinear", "star"):
        mu1 = form.number("mu1", label="mu1")
        mu2 = form.optional("mu2", label="mu2") if choice == "coulomb" else \
            form.number("mu2", label="mu2")
        spec = {"kind": "builtin", "law": choice, "mu1": mu1, "mu2": mu2}
        what = f"{article(choice)} law, mu1 = {mu1:g}" + ("" if mu2 is None else
                                                         f", mu2 = {mu2:g}")
    elif choice == "componentwise":
        mu = {k: form.number(k, label=k) for k in ("mu_f", "mu_b", "mu_t")}
        spec = {"kind": "builtin", "law": choice, **mu}
        what = ("the componentwise law, " + ", ".join(f"{k} = {v:g}" for k, v in mu.items()))
    else:
        raise FormError(f"unknown friction law {choice[:40]!r}; pick one from the list", "law")
    if spec.get("pressure") is not None:
        what += f" at p = {pressure_words(spec['pressure'])}"
    params = {"law": spec, "u0": form.number("u0", label="u0 (m/s)"),
              "angle_deg": form.number("angle_deg", label="direction (deg)"),
              "mass": form.number("mass", 1.0, label="mass (kg)"),
              "g": form.number("g", 9.81, label="g (m/s^2)"),
              "dt": form.number("dt", 1e-4, label="time step (s)"), "law_text": what}
    from .pages_body import body_params
    body = body_params(web, form, kept, dt=params["dt"], mass=params["mass"])
    if body is None:
        return params, f"slide on {what}"
    params["body"] = body
    shown = body.get("name") or {"disc": "a disc", "ring": "a ring",
                                 "rectangle": "a rectangle"}[body["shape"]]
    return params, f"{shown} sliding on {what}"


def _assembly_from_form(form: Form) -> dict:
    model = form.choice("model", ("strip", "two-node"), "strip")
    if model == "strip":
        a = {k: form.number(f"strip_{k}", label=label) for k, label in STRIP.items()}
        from ..microslip.limits import NODES
        a["n"] = form.whole("strip_n", 201, low=NODES[0], high=NODES[1], label="nodes")
    else:
        a = {k: form.number(f"two_{k}", label=label) for k, label in TWO_NODE.items()}
    loading = {"dT_min": form.number("dT_min", 0.0, label="dT min (K)"),
               "dT_max": form.number("dT_max", label="dT max (K)"),
               "force": form.number("force", 0.0, label="tangential force"),
               "cycles": 1e6, "tolerance": 1e-4}
    return {"name": f"{model} assembly (form)", "assembly": {"model": model, **a},
            "loading": loading}


def _toml(data: dict) -> str:
    """A flat assembly table as TOML (numbers and strings only)."""
    import json
    out = []
    for key, value in data.items():
        if not isinstance(value, dict):
            out.append(f"{key} = {json.dumps(value)}")
    for key, table in data.items():
        if isinstance(table, dict):
            out.append(f"\n[{key}]")
            out += [f"{k} = {_value(v)}" for k, v in table.items()]
    return "\n".join(out) + "\n"


def _value(v) -> str:
    """A TOML value: a string quoted, a float as Python writes it (1e-05, inf), an int."""
    import json
    if isinstance(v, str):
        return json.dumps(v)
    return repr(float(v)) if isinstance(v, float) else str(v)


async def _risk_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    from ..io import parse_toml
    meta = kept.get("assembly")
    if meta is not None:
        with at("assembly_file"):
            text = stored_text(web, meta, "an assembly file")
            data = parse_toml(text, meta["name"], UploadError)
        what = meta["name"]
    else:
        data = _assembly_from_form(form)
        text = _toml(data)
        what = data["name"]
    choice = form.text("friction") or "wedge"
    if choice == "wedge":
        spec = wedge_source(form, "r_")
        src_what = wedge_title(spec)
    elif choice.startswith("job:"):
        done_job(web, choice[4:], ("derive",), "surface result", "friction")
        spec, src_what = {"kind": "job", "job": choice[4:]}, f"result {choice[4:]}"
    elif choice.startswith("law:"):
        done_job(web, choice[4:], ("fit", "gauge"), "law", "friction")
        spec, src_what = {"kind": "law", "job": choice[4:]}, f"the law of {choice[4:]}"
    elif choice == "file":
        tex = kept.get("texture")
        if tex is None:
            raise FormError("choose the texture or surface file to upload (or another source "
                            "of friction)", "texture_file")
        spec = {"kind": "file", "upload": tex["id"], "name": tex["name"],
                "options": {"unit": form.choice("r_unit", UNITS, "", label="length unit")
                            or None,
                            "mu": form.optional("r_mu", label="local friction mu")}}
        src_what = tex["name"]
    elif choice == "mu":
        spec = {"kind": "mu", "mu_plus": form.number("mu_plus", label="mu+"),
                "mu_minus": form.number("mu_minus", label="mu-")}
        src_what = f"mu+ = {spec['mu_plus']:g}, mu- = {spec['mu_minus']:g}"
    elif choice == "assembly":
        if meta is None:
            raise FormError("the assembly file's own friction needs an assembly file",
                            "assembly_file")
        spec, src_what = {"kind": "assembly"}, "its own friction"
    else:
        raise FormError(f"unknown friction source {choice[:40]!r}; pick one from the list",
                        "friction")
    tol = form.optional("tolerance", label="tolerance (m)")
    params = {"assembly": data, "friction": spec, "assembly_toml": text, "assembly_name": what,
              "slip_axis_deg": form.optional("slip_axis_deg", label="slip axis (deg)"),
              "textured": form.choice("textured", ("", "support", "part"), "",
                                      label="texture on the") or None,
              "contact": form.choice("r_contact", ("",) + CONTACTS, "", label="contact")
              or None,
              "cycles": form.optional("cycles", label="cycles"),
              "tolerance": tol}
    return params, f"risk of {what} on {src_what}"


def register(app, web) -> None:
    web.renderers.update(slide=render_motion, risk=render_motion, study=render_studies)

    @app.get("/motion", response_class=HTMLResponse)
    async def motion(request: Request):
        return render_motion(web, request)

    @app.post("/motion/slide")
    async def slide_post(request: Request):
        return await post_form(web, request, "slide", _slide_params, render_motion)

    @app.post("/motion/risk")
    async def risk_post(request: Request):
        return await post_form(web, request, "risk", _risk_params, render_motion)

    @app.get("/studies", response_class=HTMLResponse)
    async def studies(request: Request):
        return render_studies(web, request)

    @app.post("/studies")
    async def studies_post(request: Request):
        return await post_form(web, request, "study", _study_params, render_studies)


async def _study_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    from .tasks_study import MISSING, OUTSIDE, check_references
    study = kept.get("study")
    if study is None:
        raise FormError("choose the study file (.toml) to upload", "study")
    with at("study"):
        name = check_plain_name(study["name"], "study file name")
        if not name.lower().endswith(".toml"):
            raise UploadError(f"the study file must be a .toml file, got {name!r}")
    companions = kept.get("companions", [])
    with at("companions"):
        names = [check_plain_name(m["name"]) for m in companions]
        if name in names:
            raise UploadError(f"{name!r} is the study file; upload each file once, please")
        texts = {n: stored_text(web, m, "a study, texture or assembly file")
                 if n.lower().endswith(".toml") else None for m, n in zip(companions, names)}
    workers = form.whole("workers", 0, low=0, high=64, label="local worker processes")
    try:
        check_references(stored_text(web, study, "a study file"), texts)
    except UploadError as exc:
        exc.field = "companions" if MISSING in str(exc) else "study"   # add the file there
        exc.discard = OUTSIDE in str(exc)     # names a file of its own choosing: none kept
        raise
    return ({"study": {"upload": study["id"], "name": name},
             "companions": [{"upload": m["id"], "name": n} for m, n in zip(companions, names)],
             "workers": workers}, f"study {name}")
