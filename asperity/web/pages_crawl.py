"""The Motion page's crawl form (issue 26): a body that bends with a curvature wave crawls
on a friction law -- three coefficients with their rule, a Law result or a gauge file, a
wedge texture or a texture or surface file fitted on the fly -- its texture on the body or
on the ground, quasi-static or with inertia.  Every field is checked here with the
library's ranges (the gait's self-crossing and the run's work limit too), each refusal one
line at its field in the page's words; the job (:mod:`.tasks_crawl`) runs
:func:`asperity.crawling.solver.crawl`, as ``asperity crawl`` does."""
from __future__ import annotations

from fastapi import Request

from ..errors import AsperityError, InputError, check_range
from .common import done_job, post_form, wedge_title
from .forms import Form, FormError
from .words import CRAWL_RULES as RULES

#: labels of the fields (the refusals name them)
LABELS = {"c_law": "friction law", "c_mu_f": "mu_f (forward)", "c_mu_b": "mu_b (backward)",
          "c_mu_t": "mu_t (transverse)", "c_rule": "rule", "c_alpha_deg": "alpha (deg)",
          "c_beta_deg": "beta (deg)", "c_mu_alpha": "mu_alpha", "c_mu_beta": "mu_beta",
          "c_fit_law": "law fitted", "c_unit": "length unit", "c_mu": "local friction mu",
          "c_law_pressure": "nominal pressure, Pa", "c_texture_on": "texture on the",
          "c_texture_angle": "texture angle (deg)", "c_amplitude": "amplitude A",
          "c_waves": "waves k", "c_length": "body length L (m)",
          "c_period": "gait period T (s)", "c_points": "contact points",
          "c_periods": "periods", "c_mode": "inertia", "c_g": "g (m/s^2)",
          "c_steps": "steps per period"}
#: the library's names of the gait's and the run's values -> form field
GAIT = {"amplitude": "c_amplitude", "waves": "c_waves", "length": "c_length",
        "period": "c_period"}
WEDGE = ("alpha_deg", "beta_deg", "mu_alpha", "mu_beta")
#: most periods on the page (the work limit refuses long runs of many points first)
MAX_PERIODS = 1000


def _number(form: Form, name: str, default, low: float, high: float, **kw) -> float:
    x = form.number(name, default, label=LABELS[name])
    try:
        return check_range(LABELS[name], x, low, high, **kw)
    except InputError as exc:
        raise FormError(str(exc), name) from None


def _coefficients(form: Form) -> tuple[dict, str]:
    from ..crawling.solver import coefficient_law
    mu = {k: form.number(f"c_{k}", label=LABELS[f"c_{k}"]) for k in ("mu_f", "mu_b", "mu_t")}
    rule = form.choice("c_rule", [v for v, _ in RULES], "componentwise", label="rule")
    try:
        coefficient_law(mu["mu_f"], mu["mu_b"], mu["mu_t"], rule)
    except InputError as exc:
        msg = str(exc)
        key = next((k for k in mu if msg.startswith(k)), "mu_f")
        raise FormError(msg.replace(key, LABELS[f"c_{key}"], 1), f"c_{key}") from None
    return {"kind": "coefficients", **mu, "rule": rule}, \
        "mu_f = {mu_f:g}, mu_b = {mu_b:g}, mu_t = {mu_t:g} ({rule})".format(**mu, rule=rule)


def _gauge(web, form: Form, kept: dict, choice: str) -> tuple[dict, str]:
    from .pages_motion import family_pressure
    if choice.startswith("job:"):
        jid = choice[4:]
        rec = done_job(web, jid, ("fit", "gauge"), "law", "c_law")
        spec = {"kind": "job", "job": jid}
        spec.update(family_pressure(form, web.store.job_dir(jid) / "gauge.json", "c_law",
                                    f"the law of result {jid}", name="c_law_pressure"))
        return spec, f"the {rec['title']} (law {jid})"
    meta = kept.get("crawl_gauge")
    if meta is None:
        raise FormError("choose a gauge file (.json) to upload, or another law", "c_gauge")
    spec = {"kind": "upload", "upload": meta["id"], "name": meta["name"]}
    spec.update(family_pressure(form, web.store.upload_path(meta["id"]), "c_gauge",
                                meta["name"], name="c_law_pressure"))
    return spec, meta["name"]


def _texture(form: Form, kept: dict, choice: str) -> tuple[dict, str]:
    from .pages import UNITS
    fit = form.choice("c_fit_law", ("star", "ellipse"), "star", label=LABELS["c_fit_law"])
    if choice == "wedge":
        from .. import WedgeTexture
        w = {k: form.number(f"c_{k}", label=LABELS[f"c_{k}"]) for k in WEDGE}
        try:
            WedgeTexture(**w)
        except InputError as exc:
            msg = str(exc)
            key = next((k for k in WEDGE if msg.startswith(k)), "alpha_deg")
            raise FormError(msg.replace(key, LABELS[f"c_{key}"], 1), f"c_{key}") from None
        src = {"kind": "wedge", **w}
        return {"kind": "texture", "source": src, "fit": fit}, wedge_title(src)
    tex = kept.get("crawl_texture")
    if tex is None:
        raise FormError("choose the texture or surface file to upload (or another law)",
                        "c_texture_file")
    src = {"kind": "file", "upload": tex["id"], "name": tex["name"],
           "options": {"unit": form.choice("c_unit", UNITS, "", label=LABELS["c_unit"])
                       or None, "mu": form.optional("c_mu", label=LABELS["c_mu"])}}
    return {"kind": "texture", "source": src, "fit": fit}, tex["name"]


def crawl_law(web, form: Form, kept: dict) -> tuple[dict, str]:
    """(the law of a crawl job, what the page calls it)."""
    choice = form.text("c_law") or "coefficients"
    if choice == "coefficients":
        return _coefficients(form)
    if choice.startswith("job:") or choice == "upload":
        return _gauge(web, form, kept, choice)
    if choice in ("wedge", "file"):
        return _texture(form, kept, choice)
    raise FormError(f"unknown friction law {choice[:40]!r}; pick one from the list", "c_law")


def gait_params(form: Form) -> dict:
    """The curvature wave of the form (checked by the library, refusals at their field)."""
    from ..crawling.gait import CurvatureWave
    g = {"amplitude": form.number("c_amplitude", 7.0, label=LABELS["c_amplitude"]),
         "waves": form.number("c_waves", 1.0, label=LABELS["c_waves"]),
         "length": form.number("c_length", 1.0, label=LABELS["c_length"]),
         "period": form.number("c_period", 1.0, label=LABELS["c_period"])}
    try:
        CurvatureWave(**g)
    except InputError as exc:
        raise FormError(*_gait_words(str(exc))) from None
    return g


def _gait_words(msg: str) -> tuple[str, str]:
    for key, field in GAIT.items():
        if msg.startswith(key + " "):
            return LABELS[field] + msg[len(key):], field
    return msg, "c_amplitude"


async def crawl_params(web, form: Form, kept: dict) -> tuple[dict, str]:
    from ..crawling.gait import POINTS_RANGE, CurvatureWave
    from ..crawling.gait_crossing import check_self_crossing
    from ..crawling.solver import MAX_WORK
    law, what = crawl_law(web, form, kept)
    gait = gait_params(form)
    mode = form.choice("c_mode", ("dynamic", "quasi-static"), "dynamic",
                       label=LABELS["c_mode"])
    qs = mode == "quasi-static"
    params = {"law": law, "law_text": what, "gait": gait, "quasi_static": qs,
              "texture_on": form.choice("c_texture_on", ("body", "ground"), "body",
                                        label=LABELS["c_texture_on"]),
              "texture_angle_deg": _number(form, "c_texture_angle", 0.0, -360.0, 360.0),
              "points": form.whole("c_points", 100, low=POINTS_RANGE[0], high=POINTS_RANGE[1],
                                   label=LABELS["c_points"]),
              "periods": form.whole("c_periods", 1 if qs else 8, low=1, high=MAX_PERIODS,
                                    label=LABELS["c_periods"]),
              "g": 9.81 if qs else _number(form, "c_g", 9.81, 1e-6, 1e4),
              "steps_per_period": form.whole("c_steps", 200, low=8, high=100_000,
                                             label=LABELS["c_steps"])}
    work = params["steps_per_period"] * params["periods"] * max(1.0, params["points"] / 16)
    if work > MAX_WORK:
        raise FormError(f"{LABELS['c_periods']}: {params['periods']} periods of "
                        f"{params['steps_per_period']} steps with {params['points']} contact "
                        f"points is more than a crawl runs ({MAX_WORK:.3g} steps of 16 "
                        "points); ask for fewer periods, points or steps per period",
                        "c_periods")
    try:
        check_self_crossing(CurvatureWave(**gait), n_points=params["points"])
    except AsperityError as exc:
        raise FormError(str(exc), "c_amplitude") from None
    mode_words = "quasi-static" if qs else "dynamic"
    return params, (f"crawl (A {gait['amplitude']:g}, k {gait['waves']:g}, {mode_words}) on "
                    f"{what}")


def register(app, web) -> None:
    from .pages_motion import render_motion
    web.renderers.update(crawl=render_motion)

    @app.post("/motion/crawl")
    async def crawl_post(request: Request):
        return await post_form(web, request, "crawl", crawl_params, render_motion)
