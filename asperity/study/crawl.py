"""Crawling in studies: the ``[crawl]`` table of a study file ranks textures (a library, a
sweep over wedge angles) or gaits by how fast a body crawls on them.

::

    [crawl]                    # every case crawls (the stage "crawl"); defaults: asperity crawl's
    amplitude = 7.0            # the curvature wave kappa L = A cos 2 pi (k s / L + t / T)
    waves = 1.0
    points = 60                # contact points, 3 to 1e5 (default 100)
    steps_per_period = 100     # 8 to 1e5 (default 200)
    periods = 1                # default 1 quasi-static, 8 dynamic
    quasi_static = true        # default false (Newton-Euler, as asperity crawl)
    texture_on = "body"        # body | ground
    texture_angle_deg = 0.0
    fit_law = "star"           # the law fitted to each case's texture: star | ellipse
    # length, period, gravity  # m, s, m/s^2 (defaults 1, 1, 9.81)
    # mu_f, mu_b, mu_t, rule   # a law of three coefficients instead of a texture

    [parameters]
    "crawl.amplitude" = { values = [5.0, 7.0, 9.0] }   # varied like any parameter

The law of a case is its texture's (the study's texture with the case's ``texture.*``
values, or the file of a library), derived and fitted exactly as ``asperity crawl
TEXTURE`` does (all faces, closed form, 720 directions, the ``fit_law`` fit); cached in
the worker per texture, so the gaits of one texture fit it once.  A study without texture
crawls on mu_f, mu_b, mu_t by ``rule`` (each may be a parameter ``crawl.mu_t``...).
Outputs per case: the speed in body lengths per period (head-ward positive), the cost of
transport (None when the body does not move) and the heading drift; the summary ranks the
cases by speed.  A gait that crosses itself, or a crawl whose solve did not converge, is a
failed case with its reason.
"""
from __future__ import annotations

import json

from ..errors import AsperityError, InputError, check_choice, check_int, check_range

#: key -> (low, high) of numbers; choices; booleans
NUMBERS = {"amplitude": (0.0, 100.0), "waves": (0.0, 20.0), "length": (1e-6, 1e6),
           "period": (1e-6, 1e6), "gravity": (1e-6, 1e4), "texture_angle_deg": (-360.0, 360.0),
           "mu_f": (1e-6, 100.0), "mu_b": (1e-6, 100.0), "mu_t": (1e-6, 100.0)}
WHOLE = {"points": (3, 100_000), "steps_per_period": (8, 100_000), "periods": (1, 100_000)}
CHOICES = {"texture_on": ("body", "ground"), "fit_law": ("star", "ellipse"),
           "rule": ("componentwise", "associated", "colinear")}
KEYS = tuple(NUMBERS) + tuple(WHOLE) + tuple(CHOICES) + ("quasi_static",)
#: the keys that may vary (parameters "crawl.KEY")
VARIED = ("amplitude", "waves", "texture_angle_deg", "mu_f", "mu_b", "mu_t")
COEFFICIENTS = ("mu_f", "mu_b", "mu_t")
#: fitted laws a worker keeps
LAW_CACHE_SIZE = 256
_LAWS: dict = {}


class CrawlFailed(AsperityError):
    """A case's crawl did not converge (the message says where)."""


def crawl_spec(data: dict, params, stages, has_texture: bool) -> dict | None:
    """The checked ``[crawl]`` table ({key: value}), or None without the crawl stage (no
    table, no ``crawl.*`` parameter, "crawl" not in study.stages); one line naming the
    key and its range."""
    table = data.get("crawl")
    varied = {p.name.split(".", 1)[1]: p for p in params if p.name.startswith("crawl.")}
    if table is None and not varied and "crawl" not in stages:
        return None
    table = {} if table is None else table
    if not isinstance(table, dict):
        raise InputError("crawl must be a table [crawl] (amplitude, waves, points, ...)")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise InputError(f"unknown key crawl.{unknown[0]}; allowed: {', '.join(KEYS)}")
    for key, p in varied.items():
        if key not in VARIED:
            raise InputError(f"parameters: {p.name!r}: the crawl parameters are "
                             f"{', '.join('crawl.' + k for k in VARIED)} (the other "
                             f"[crawl] keys are fixed)")
    spec = {}
    for k, v in table.items():
        if k in NUMBERS:
            spec[k] = check_range(f"crawl.{k}", v, *NUMBERS[k], low_open=k == "waves")
        elif k in WHOLE:
            spec[k] = check_int(f"crawl.{k}", v, *WHOLE[k])
        elif k in CHOICES:
            spec[k] = check_choice(f"crawl.{k}", v, CHOICES[k])
        elif not isinstance(v, bool):
            raise InputError(f"crawl.quasi_static must be true or false, got {v!r}")
        else:
            spec[k] = v
    coeffs = [k for k in COEFFICIENTS if k in spec or k in varied]
    if has_texture:
        if coeffs or "rule" in spec:
            raise InputError(f"crawl.{(coeffs or ['rule'])[0]} makes a law of three "
                             f"coefficients; this study's cases take their law from their "
                             f"texture (crawl.fit_law)")
    else:
        if "fit_law" in spec:
            raise InputError("crawl.fit_law fits a texture: the study has none (study."
                             "texture, a [texture] table or kind = \"files\")")
        missing = [k for k in COEFFICIENTS if k not in coeffs]
        if missing:
            raise InputError(f"crawl.{missing[0]} missing: without a texture the crawl needs "
                             f"a law of three coefficients crawl.mu_f, crawl.mu_b, crawl.mu_t "
                             f"(in [crawl] or as parameters)")
    return spec


def settings_for(spec: dict, values: dict) -> dict:
    """The crawl's settings of one case: the table with the case's ``crawl.*`` values."""
    d = dict(spec)
    for k, v in values.items():
        if k.startswith("crawl."):
            key = k.split(".", 1)[1]
            d[key] = check_range(f"crawl.{key}", float(v), *NUMBERS[key],
                                 low_open=key == "waves")
    return d


def check_case(spec: dict, values: dict) -> None:
    """The gait and the coefficients of the case at ``values`` built (not crawled)."""
    from ..crawling.gait import CurvatureWave
    s = settings_for(spec, values)
    _gait(s, CurvatureWave)
    if "mu_f" in s:
        _coefficients(s)


def _gait(s: dict, cls):
    try:
        return cls(amplitude=s.get("amplitude", 7.0), waves=s.get("waves", 1.0),
                   period=s.get("period", 1.0), length=s.get("length", 1.0))
    except InputError as exc:
        raise InputError(f"crawl.{exc}") from None


def _coefficients(s: dict):
    from ..crawling.solver import coefficient_law
    try:
        return coefficient_law(s["mu_f"], s["mu_b"], s["mu_t"],
                               s.get("rule", "componentwise"))
    except InputError as exc:
        raise InputError(f"crawl.{exc}") from None


def law_of_texture(texture, fit_law: str = "star"):
    """The PlanarLaw ``asperity crawl TEXTURE --fit-law FIT_LAW`` crawls on."""
    from ..crawling.solver import fitted_law
    return fitted_law(texture, fit_law)


def _law(s: dict, texture, key):
    if texture is None:
        return _coefficients(s)
    fit = s.get("fit_law", "star")
    k = (key, fit)
    if k not in _LAWS:
        if len(_LAWS) >= LAW_CACHE_SIZE:
            _LAWS.pop(next(iter(_LAWS)))
        _LAWS[k] = law_of_texture(texture, fit)
    return _LAWS[k]


def texture_key(spec: dict, values: dict, file) -> str:
    """What decides a case's texture: the study's texture, the case's texture values or
    its file (with the scan-reading options and elastic contact), as text."""
    return json.dumps([spec.get("texture"), file, spec.get("surface"), spec.get("elastic"),
                       {k: v for k, v in values.items() if not k.startswith("crawl.")}],
                      sort_keys=True, default=str)


def outputs(spec: dict, values: dict, texture, file=None) -> dict:
    """The crawl outputs of one case (its law fitted from ``texture``, or of three
    coefficients); raises on a gait that crosses itself or a crawl that fails."""
    from ..crawling.gait import CurvatureWave
    from ..crawling.solver import crawl
    s = settings_for(spec["crawl"], values)
    gait = _gait(s, CurvatureWave)
    law = _law(s, texture, texture_key(spec, values, file))
    try:
        res = crawl(law, gait=gait, points=s.get("points", 100), periods=s.get("periods"),
                    quasi_static=s.get("quasi_static", False), g=s.get("gravity", 9.81),
                    steps_per_period=s.get("steps_per_period", 200),
                    texture_on=s.get("texture_on", "body"),
                    texture_angle_deg=s.get("texture_angle_deg", 0.0))
    except InputError as exc:
        raise InputError(f"crawl: {exc}") from None
    if not res.ok:
        raise CrawlFailed(f"crawl: {res.message}")
    return {"speed_body_lengths_per_period": res.speed_body_lengths_per_period,
            "cost_of_transport": res.cost_of_transport,
            "heading_drift_rad_per_period": res.heading_drift_rad_per_period}
