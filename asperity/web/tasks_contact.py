"""Surface and Law jobs with load shares from an elastic contact (``params["elastic"]``,
read by :mod:`.elastic`): what ``asperity derive ... --elastic E* --pressure P [P ...]``
computes, with the contact figures and the contact map for the page.

* :func:`elastic_textures_of` -- a job's source weighted by the contact force, one texture
  a pressure (and the small pressure maps the page draws);
* :func:`derive_elastic` -- the Surface job: one pressure gives derive's JSON with its
  ``elastic_contact``, several a law family (``family_json``);
* :func:`family_law` -- the law family of a result with several pressures (a gauge file
  of version 2, :mod:`.law_family`); the Law page fits it, or the law at one pressure
  chosen.
"""
from __future__ import annotations

import json

from ..io import json_ready, write_text_atomic
from . import tasks_surface
from .elastic import contact_of
from .figures_contact import MapKeeper, axes_figure, contact_map, family_polar
from .labels import pressure_stem, pressure_words, source_stem
from .results import rename
from .tasks_surface import describe, load_source, source_job, surface_kwargs, upload_file
from .units import choose, show

#: the share of a job's progress bar that the contact solves take
CONTACT_SHARE = 0.5
#: what the weighting assumes and where it stops being right (shown under the results)
ASSUMES = ("The load shares come from a normal, frictionless elastic contact: the surface "
           "is pressed onto an elastic half-space of modulus E* (Polonsky-Keer solution) and "
           "each facet weighs the normal force it carries; the facet law is unchanged.",
           "It stops being right where the pressure reaches the hardness (plastic flow: the "
           "hardness only caps the pressure), where sliding redistributes the load "
           "(tangential tractions, ploughing, the tilt of the contact), and where the "
           "contact spots are not resolved (give each spot tens of pixels).")


def not_converged(exc) -> str:
    r = exc.result
    return (f"the elastic contact did not converge at pressure {r.pressure_asked:g} Pa in "
            f"{r.iterations} iteration{'s' * (r.iterations != 1)} (residual "
            f"{r.residual:.3g}); nothing computed")


def elastic_textures_of(src: dict, params: dict, ctx: dict, bar):
    """(textures weighted at each pressure, the MapKeeper of their contact maps); the
    solves fill the first :data:`CONTACT_SHARE` of the job's progress bar."""
    from .job_progress import phase
    elastic = contact_of(params)
    with phase(bar, 0.0, CONTACT_SHARE, f"solving the elastic contact at "
               f"{len(elastic.pressures)} pressure(s)"):
        keep = MapKeeper(len(elastic.pressures), bar)
        return _solved(src, elastic, keep, ctx), keep


def _solved(src: dict, elastic, keep, ctx: dict) -> list:
    from ..contact.solver import ContactNotConverged
    from ..errors import InputError
    try:
        if src.get("kind") == "file" and not str(src.get("upload", "")).endswith(".toml"):
            from ..surface.contact_facets import load_elastic
            path = upload_file(ctx, src.get("upload"), str(src.get("name")))
            opts = {k: v for k, v in surface_kwargs(src, ctx).items()
                    if k not in ("rest_level", "bearing_fraction")}
            return load_elastic(path, elastic, **opts, observe=keep)
        from ..friction.elastic import elastic_textures
        texture, _, _ = load_source(src, ctx)
        return elastic_textures(texture, elastic, observe=keep)
    except ContactNotConverged as exc:
        raise InputError(not_converged(exc)) from None


def _derived(textures, contact: str, n: int, bar) -> list:
    """derive() of each contact-weighted texture (what derive_family does), each filling
    its part of the job's progress bar after the contact solves."""
    from ..friction.derive import derive
    from .job_progress import part, phase
    out = []
    with phase(bar, CONTACT_SHARE, 0.95, "sliding directions"):
        for k, t in enumerate(textures):
            part(bar, k, len(textures))
            out.append(derive(t, contact, "closed-form", n, progress=bar))
            bar(1.0, f"sliding directions at pressure {k + 1} of {len(textures)}")
    return out


def derive_elastic(src: dict, params: dict, ctx: dict, bar) -> dict:
    """The Surface job with an elastic contact (``src``: the source itself, not a job)."""
    from ..friction.derive import format_text, to_json
    from ..friction.family import LawFamily, family_json, family_text
    from .figures import height_figure, largest_friction, reservoir_figures
    textures, keep = elastic_textures_of(src, params, ctx, bar)
    elastic = contact_of(params)
    contact, n = params.get("contact", "all-faces"), params.get("directions", 360)
    E = elastic.E_star
    if elastic.family:
        fam = LawFamily(tuple(elastic.pressures), tuple(_derived(textures, contact, n, bar)),
                        elastic)
        obj = rename(family_json(fam), ctx["names"])
        d, text = fam.members[-1], family_text(fam)
        members = obj["members"]
        figs = {"polar": family_polar(members, list(fam.pressures), E),
                "axes": axes_figure(obj["summary"], E, obj.get("reference_direction_deg"))}
    else:
        d = _derived(textures, contact, n, bar)[0]
        obj = rename(to_json(d), ctx["names"])
        text, members = format_text(d), [obj]
        figs = reservoir_figures(obj)
    if "data_quality" in members[0]:
        h = height_figure(d.texture, members[-1]["principal_direction_deg"])
        if h is not None:
            figs["heights"] = h
    cmap = contact_map(keep.maps, E)
    if cmap is not None:
        figs["contact_map"] = cmap
    write_text_atomic(ctx["job_dir"] / "derive.json", json.dumps(json_ready(obj), indent=1))
    contacts = [m["elastic_contact"] for m in members]
    return {("family" if elastic.family else "derive"): obj,
            "derive": members[-1], "contacts": contacts,
            "largest": None if elastic.family else largest_friction(obj),
            "maps": [{"pressure": m["pressure"], "shape": m["shape"],
                      "shown": list(m["map"].shape)} for m in keep.maps],
            "assumes": list(ASSUMES), "text": rename(text, ctx["names"]),
            "source": describe(src, d.texture), "figures": figs, "files": ["derive.json"],
            "downloads": {"derive.json": f"{source_stem(src)}_friction.json"}}


def family_law(members, elastic, law: str):
    """The GaugeFamily of the derivations ``members`` at the pressures of ``elastic`` (one
    law of kind ``law`` a pressure, sorted by pressure, as ``asperity fit --pressure P1 P2
    ...``), or None for one pressure."""
    if len(elastic.pressures) < 2:
        return None
    from .law_family import fit_family
    return fit_family(members, list(elastic.pressures), law)


def fit_elastic(params: dict, ctx: dict, bar) -> dict:
    """The Law job for a Surface result with an elastic contact: the law family over all
    its pressures (``params["family"]["index"]`` None), or the law at the one pressure
    chosen (``params["elastic"]["pressures"]``: that one)."""
    from .. import fit_derivation
    from .law_family import family_outputs
    src = source_job(ctx, params["source"]["job"])
    textures, _ = elastic_textures_of(src, params, ctx, bar)
    elastic = contact_of(params)
    members = _derived(textures, params.get("contact", "all-faces"),
                       params.get("directions", 720), bar)
    bar(0.95, "fitting the law" + ("s" if len(members) > 1 else ""))
    fam = family_law(members, elastic, params.get("law", "star"))
    jid = params["source"]["job"]
    if fam is not None:
        out = family_outputs(fam, ctx, source_stem(src))
        out["source"] = describe(src, members[0].texture)
        u = choose(list(fam.pressures), "Pa", smallest=True)
        out["note"] = (f"a law family: one {fam.kind} law at each of the {len(fam.members)} "
                       f"pressures of result {jid}, {show(fam.pressures[0], u)} to "
                       f"{show(fam.pressures[-1], u)} (E* = {pressure_words(elastic.E_star)}); "
                       "between them the law is interpolated linearly in ln p")
        return out
    gl = fit_derivation(members[0], params.get("law", "star"))
    p = elastic.pressures[0]
    out = tasks_surface.law_outputs(gl, ctx, f"{source_stem(src)}_{pressure_stem(p)}")
    out["source"] = describe(src, members[0].texture)
    out["elastic_contact"] = members[0].texture.elastic
    fam = params.get("family") or {}
    out["note"] = (f"fitted at the pressure p = {pressure_words(p)} (p/E* = "
                   f"{p / elastic.E_star:.3g})"
                   + (f", one of the {fam['count']} pressures of result {jid}: the law of "
                      "that pressure alone (choose the law family at the pressure to fit "
                      "one law a pressure)" if fam.get("count", 1) > 1 else ""))
    return out


def derive_task(params: dict, ctx: dict, bar) -> dict:
    """The Surface job: with an elastic contact here, else :mod:`.tasks_surface`'s."""
    if not params.get("elastic"):
        return tasks_surface.derive_task(params, ctx, bar)
    src = params["source"]
    return derive_elastic(source_job(ctx, src["job"]) if src.get("kind") == "job" else src,
                          params, ctx, bar)


def fit_task(params: dict, ctx: dict, bar) -> dict:
    """The Law job: a Surface result with an elastic contact here, else
    :mod:`.tasks_surface`'s."""
    if not params.get("elastic"):
        return tasks_surface.fit_task(params, ctx, bar)
    return fit_elastic(params, ctx, bar)


#: the jobs of this module (they replace tasks_surface's of the same kinds)
TASKS = {"derive": derive_task, "fit": fit_task}
