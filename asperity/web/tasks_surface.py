"""Jobs of the Surface and Law pages: a texture or surface -> its directional friction
(``derive``), a friction law fitted to it (``fit``) and a gauge file opened (``gauge``).

A *source* is a plain dictionary, stored in the job's parameters so that a later job (a
fit, a risk verdict) can load the same texture again:

* ``{"kind": "wedge", "alpha_deg", "beta_deg", "mu_alpha", "mu_beta"}``;
* ``{"kind": "file", "upload": UPLOAD_ID, "name": shown name, "options": {...}}`` -- an
  uploaded texture TOML, mesh, height map or instrument file, with the keyword arguments
  of :func:`asperity.load_surface` (``friction_map`` an upload id too).
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ..errors import InputError
from ..io import json_ready
from .labels import law_downloads, source_stem, stem
from .results import rename
from .store import UPLOAD_ID

#: the share of a Surface job's progress bar that reading its file takes
READING = 0.25
#: options of a surface file the pages send (keyword arguments of load_surface)
SURFACE_OPTIONS = ("unit", "pixel_size", "height_scale", "detrend", "mu", "friction_map",
                   "max_slope", "despike", "despike_window", "rest_level", "bearing_fraction")


def upload_file(ctx: dict, uid: str, shown: str) -> Path:
    """The stored path of upload ``uid``; messages will name it ``shown``."""
    if not isinstance(uid, str) or not UPLOAD_ID.match(uid):
        raise InputError("no such upload; choose the file again")
    p = ctx["uploads"] / uid
    if not p.is_file():
        raise InputError(f"the upload {shown!r} is no longer in the data folder; choose the "
                         f"file again")
    ctx["names"][str(p)] = shown
    ctx["names"][uid] = shown
    return p


def job_params(ctx: dict, jid: str) -> dict:
    """The parameters of an earlier Surface job (with its ``source``)."""
    import json

    from .store import JOB_ID
    if not isinstance(jid, str) or not JOB_ID.match(jid):
        raise InputError("no such result; pick one from the list")
    try:
        rec = json.loads((ctx["jobs"] / jid / "job.json").read_text(encoding="utf-8"))
        rec["params"]["source"]
        return rec["params"]
    except (OSError, ValueError, KeyError, TypeError):
        raise InputError(f"result {jid} has no texture or surface to reuse") from None


def source_job(ctx: dict, jid: str) -> dict:
    """The source of an earlier Surface job (its parameters' ``source``)."""
    return job_params(ctx, jid)["source"]


def load_source(src: dict, ctx: dict, *, options: bool = True):
    """(texture or FacetSurface, springs table, stored path or None) of a source."""
    from .. import WedgeTexture
    if src.get("kind") == "job":
        src = source_job(ctx, src.get("job"))
    if src.get("kind") == "wedge":
        keys = ("alpha_deg", "beta_deg", "mu_alpha", "mu_beta")
        return WedgeTexture(**{k: src[k] for k in keys}), {}, None
    if src.get("kind") != "file":
        raise InputError("no texture given: enter a wedge or upload a file")
    shown = str(src.get("name") or "the file")
    path = upload_file(ctx, src.get("upload"), shown)
    if path.name.endswith(".toml"):
        from ..texture.wedges import load_texture_file
        tf = load_texture_file(path)
        return tf.texture, tf.springs, None
    from .. import load_surface
    opts = surface_kwargs(src, ctx) if options else {}
    return load_surface(path, **opts), {}, path


def surface_kwargs(src: dict, ctx: dict) -> dict:
    opts = {k: v for k, v in (src.get("options") or {}).items()
            if k in SURFACE_OPTIONS and v is not None}
    if "friction_map" in opts:
        opts["friction_map"] = upload_file(ctx, opts["friction_map"],
                                           str(src.get("map_name") or "the friction map"))
    return opts


def describe(src: dict, texture) -> dict:
    """What the page says the source is."""
    if src.get("kind") == "wedge":
        return {"kind": "wedge", "text": (f"wedge texture alpha = {src['alpha_deg']:g} deg, "
                                          f"beta = {src['beta_deg']:g} deg, mu_alpha = "
                                          f"{src['mu_alpha']:g}, mu_beta = {src['mu_beta']:g}")}
    what = getattr(texture, "kind", "")
    kind = "surface" if what == "surface" else "texture file"
    return {"kind": kind, "text": f"{kind} {src.get('name')}"}


def _derivation(src: dict, params: dict, ctx: dict, bar):
    """derive() of a source with the page's contact, method and directions; a height map
    of more than 2048 x 2048 pixels in a format read in lines goes in tiles."""
    from .. import derive
    contact = params.get("contact", "all-faces")
    n = params.get("directions", 360)
    method = params.get("method", "closed-form")
    real = source_job(ctx, src["job"]) if src.get("kind") == "job" else src
    if real.get("kind") == "file" and not str(real.get("upload", "")).endswith(".toml") \
            and method == "closed-form" and params.get("allow_tiles", True):
        from ..friction.tiled import derive_scan, tiles_wanted
        path = upload_file(ctx, real.get("upload"), str(real.get("name")))
        opts = surface_kwargs(real, ctx)
        tiled = tiles_wanted(path, unit=opts.get("unit"), pixel_size=opts.get("pixel_size"),
                             height_scale=opts.get("height_scale", 1.0))
        if tiled is not None:
            return derive_scan(path, **opts, contact=contact, n_directions=n, source=tiled), real
    from .job_progress import phase
    with phase(bar, 0.0, READING, "reading the file" if real.get("kind") == "file" else None):
        texture, springs, _ = load_source(real, ctx)
    model = None
    if method == "springs":
        from ..texture.spring_model import SpringModel
        model = SpringModel.from_dict(dict(springs))
    with phase(bar, READING, 1.0, "sliding directions"):
        return derive(texture, contact, method, n, model, progress=bar), real


def derive_task(params: dict, ctx: dict, bar) -> dict:
    from ..friction.derive import format_text, to_json
    from .figures import height_figure, largest_friction, reservoir_figures
    d, real = _derivation(params["source"], params, ctx, bar)
    obj = rename(to_json(d), ctx["names"])
    figs = reservoir_figures(obj)
    if obj.get("data_quality") is not None:
        h = height_figure(d.texture, d.principal_direction_deg)
        if h is not None:
            figs["heights"] = h
    import json

    from ..io import write_text_atomic
    write_text_atomic(ctx["job_dir"] / "derive.json", json.dumps(json_ready(obj), indent=1))
    return {"derive": obj, "largest": largest_friction(obj),
            "text": rename(format_text(d), ctx["names"]),
            "source": describe(real, d.texture), "figures": figs, "files": ["derive.json"],
            "downloads": {"derive.json": f"{source_stem(real)}_friction.json"}}


def _law_outputs(gl, ctx: dict, source: str, n_csv: int = 360) -> dict:
    """The gauge file, CSV table and Abaqus block of a law into the job folder (they
    download under names made of ``source``, a stem, and the law kind), and what the page
    shows of it."""
    from .. import write_gauge
    from ..io import write_text_atomic
    from ..laws.export import abaqus_block, orthotropic_approximation, write_csv
    from ..laws.summary import format_fit, summary
    from .figures import law_figures
    folder = ctx["job_dir"]
    gl = replace(gl, source=rename(gl.source, ctx["names"]))
    write_gauge(folder / "gauge.json", gl)
    write_csv(folder / "law.csv", gl, n_csv)
    abaqus = abaqus_block(gl)
    write_text_atomic(folder / "law.inp", abaqus)
    a = orthotropic_approximation(gl)
    return {"summary": summary(gl), "largest": law_largest(gl), "report": format_fit(gl), "figures": law_figures(gl),
            "kind": gl.kind, "principal_direction_deg": gl.principal_direction_deg,
            "axes": a.axes, "abaqus": abaqus,
            "files": ["gauge.json", "law.csv", "law.inp"],
            "downloads": law_downloads(source, gl.kind)}


def law_largest(gl, n: int = 3600) -> dict | None:
    """The sliding direction of largest friction T = p . s of the law itself (``{"psi_deg"
    (from the law's x axis), "T"}``, over ``n`` directions; None if it has none)."""
    import numpy as np
    psi = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    f = gl.force(psi)
    T = np.where(f.set_valued | ~np.isfinite(f.tangential), -np.inf, f.tangential)
    k = int(np.argmax(T))
    return None if not np.isfinite(T[k]) else {"psi_deg": float(np.degrees(psi[k])),
                                                "T": float(T[k])}


def fit_task(params: dict, ctx: dict, bar) -> dict:
    from .. import fit_derivation
    from .job_progress import phase
    with phase(bar, 0.0, 0.9):
        d, real = _derivation(params["source"], {**params, "method": "closed-form",
                                                 "allow_tiles": False}, ctx, bar)
    bar(0.95, "fitting the law")
    gl = fit_derivation(d, params.get("law", "star"))
    out = _law_outputs(gl, ctx, source_stem(real))
    out["source"] = describe(real, d.texture)
    return out


def gauge_task(params: dict, ctx: dict, bar) -> dict:
    from .. import read_gauge
    from .law_family import gauge_outputs
    gl = read_gauge(upload_file(ctx, params["upload"], str(params.get("name"))))
    out = gauge_outputs(gl, ctx, stem(params.get("name"))) or \
        _law_outputs(gl, ctx, stem(params.get("name")))
    out["source"] = {"kind": "gauge file", "text": f"gauge file {params.get('name')}"}
    return out


#: the law outputs, for the Law page's other jobs (:mod:`.tasks_contact`)
law_outputs = _law_outputs

TASKS = {"derive": derive_task, "fit": fit_task, "gauge": gauge_task}
