"""The Surface page (a wedge or a file -> its friction) and the Law page (a law fitted to
it, or a gauge file opened)."""
from __future__ import annotations

from fastapi import Request
from fastapi.responses import HTMLResponse

from .common import DONE_LIMIT, done_job, post_form, wedge_source, wedge_title
from .forms import Form, FormError
from .labels import label, surface_options

CONTACTS = ("all-faces", "windward")
DETREND = ("slope", "none", "mean", "plane", "poly2", "poly3")
#: the length units the forms offer ("" : the file's own)
UNITS = ("", "m", "mm", "um", "nm")


def render_surface(web, request: Request, status: int = 200, **ctx) -> HTMLResponse:
    return web.page(request, "surface.html", status, page="surface",
                    jobs=web.store.jobs(kinds=("derive",), limit=20), **ctx)


def render_law(web, request: Request, status: int = 200, **ctx) -> HTMLResponse:
    surfaces, jobs = web.store.select((("derive",), ("done",), DONE_LIMIT),
                                      (("fit", "gauge"), None, 20))
    sources = [("wedge", "the wedge below")] + [(j["id"], f"{j['id']}: {label(j)}")
                                                for j in surfaces]
    wanted = request.query_params.get("source", "")
    default = wanted if any(s == wanted for s, _ in sources) else \
        (surfaces[0]["id"] if surfaces else "wedge")
    from .elastic import pressure_choices
    ctx.setdefault("pressures", pressure_choices(surfaces))
    ctx.setdefault("default_pressure", next((v for v, _, j in ctx["pressures"]
                                             if j == default), ""))
    return web.page(request, "law.html", status, page="law", sources=sources,
                    default_source=default, jobs=jobs, **ctx)


def pixel_size(text: str):
    """'0.5' -> 0.5; '0.5 0.25' or '0.5, 0.25' -> (0.5, 0.25); '' -> None."""
    parts = text.replace(",", " ").split()
    if not parts:
        return None
    if len(parts) > 2:
        raise FormError(f"pixel size takes one number or two (dx dy), got {text[:40]!r}",
                        "pixel_size")
    vals = [Form({"pixel_size": p}).number("pixel_size", label="pixel size") for p in parts]
    return vals[0] if len(vals) == 1 else tuple(vals)


def surface_source(form: Form, meta: dict, fmap: dict | None) -> dict:
    from ..surface.quality import DESPIKE_WINDOWS
    opts = {"unit": form.choice("unit", UNITS, "", label="length unit") or None,
            "pixel_size": pixel_size(form.text("pixel_size")),
            "mu": None if fmap else form.optional("mu", label="local friction mu"),
            "detrend": form.choice("detrend", DETREND, "slope", label="form removal"),
            "height_scale": form.number("height_scale", 1.0, label="height scale"),
            "max_slope": form.optional("max_slope", label="max slope (deg)"),
            "despike": form.optional("despike", label="spike filter K"),
            "despike_window": form.whole("despike_window", None, low=DESPIKE_WINDOWS[0],
                                         high=DESPIKE_WINDOWS[1], label="spike filter window"),
            "rest_level": form.optional("rest_level", label="rest level (m)"),
            "bearing_fraction": form.optional("bearing_fraction", label="bearing fraction")}
    src = {"kind": "file", "upload": meta["id"], "name": meta["name"], "options": opts}
    if fmap:
        src["options"]["friction_map"] = fmap["id"]
        src["map_name"] = fmap["name"]
    return src


def register(app, web) -> None:
    web.renderers.update(derive=render_surface, fit=render_law, gauge=render_law)

    @app.get("/surface", response_class=HTMLResponse)
    async def surface(request: Request):
        return render_surface(web, request)

    @app.post("/surface")
    async def surface_post(request: Request):
        return await post_form(web, request, "derive", _surface_params, render_surface)

    @app.get("/law", response_class=HTMLResponse)
    async def law(request: Request):
        return render_law(web, request)

    @app.post("/law")
    async def law_post(request: Request):
        return await post_form(web, request, "fit", _law_params, render_law)

    @app.post("/law/open")
    async def law_open(request: Request):
        return await post_form(web, request, "gauge", _gauge_params, render_law)


async def _surface_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    source = form.choice("source", ("wedge", "file"), "wedge")
    params = {"contact": form.choice("contact", CONTACTS, "all-faces"),
              "directions": form.whole("directions", 360, low=8, high=100_000,
                                       label="sliding directions"),
              "method": form.choice("method", ("closed-form", "springs"), "closed-form")}
    if source == "wedge":
        src = wedge_source(form)
        title = wedge_title(src)
    else:
        meta = kept.get("file")
        if meta is None:
            raise FormError("choose a file to upload (or enter a wedge in the other form)",
                            "file")
        src = surface_source(form, meta, kept.get("friction_map"))
        title = f"{'texture file' if meta['id'].endswith('.toml') else 'surface'} " \
                f"{meta['name']}"
    params["source"] = src
    from .elastic import elastic_params
    texture = source == "wedge" or src["upload"].endswith(".toml")
    elastic = elastic_params(form, texture, params["method"],
                             () if source == "wedge" else
                             (("rest_level", "rest level (m)"),
                              ("bearing_fraction", "bearing fraction")))
    if elastic is not None:
        params["elastic"] = elastic
    return params, f"friction of {title}"


async def _law_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    choice = form.text("source") or "wedge"
    contact = form.choice("contact", ("",) + CONTACTS, "")
    if choice == "wedge":
        src = wedge_source(form)
        what = wedge_title(src)
    else:
        rec = done_job(web, choice, ("derive",), "surface result", "source")
        src = {"kind": "job", "job": choice}
        what = f"{rec['title'].removeprefix('friction of ')} (result {choice})"
        contact = contact or rec["params"].get("contact", "all-faces")
    kind = form.choice("law", ("star", "ellipse"), "star")
    law = "star" if kind == "star" else "truncated-ellipse"
    params = {"source": src, "law": law,
              "contact": contact or "all-faces",
              "directions": form.whole("directions", 720, low=8, high=100_000,
                                       label="sliding directions fitted")}
    if choice != "wedge":                # the surface's own settings (max slope, ...)
        params["source_settings"] = ", ".join(surface_options(
            rec["params"].get("source", {}).get("options") or {}))
        if rec["params"].get("elastic"):   # one pressure of its elastic contact
            from .elastic import chosen_pressure
            params.update(chosen_pressure(form, rec))
            ps = params["elastic"]["pressures"]
            from .labels import pressure_words
            what += f" at p = {pressure_words(ps[0])}" if len(ps) == 1 else \
                f", family over {len(ps)} pressures"
    return params, f"{law} law of {what}"


async def _gauge_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    meta = kept.get("gauge")
    if meta is None:
        raise FormError("choose a gauge file (.json) to open", "gauge")
    return {"upload": meta["id"], "name": meta["name"]}, f"gauge file {meta['name']}"
