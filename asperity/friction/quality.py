"""The data-quality report of a surface's derivation: what the instrument left undefined,
what the spike filter and ``--max-slope`` removed, and -- when the result self-locks on a
tiny share of the load -- the flag that gives a finite law and what it costs.

The surface's figures come from :func:`asperity.surface.quality.quality_stats` (the
``quality`` of a FacetSurface or of a tiled scan); this module adds the verdict that
needs the derivation (``finite_with``) and writes the text.
"""
from __future__ import annotations

#: a self-locking result whose locking faces carry at most this share of the load is
#: reported as caused by a few steep facets (artefacts), with the flag that removes them
SMALL_LOCKING_SHARE = 0.01


def finite_with(d, q: dict) -> dict | None:
    """``{"flag", "max_slope_deg", "facets_dropped", "load_share"}``: the --max-slope that
    gives a finite law when ``d`` self-locks on a small share of the load, else None."""
    if not d.self_locking or not q or not q.get("facets_above_locking_limit"):
        return None
    share = d.locking_share
    if not share <= SMALL_LOCKING_SHARE:          # NaN-safe: a large share is physics
        return None
    lim = q["locking_limit_deg"]
    return {"flag": f"--max-slope {lim:g}", "max_slope_deg": lim,
            "facets_dropped": q["facets_above_locking_limit"],
            "load_share": q["load_share_above_locking_limit"]}


def data_quality(d) -> dict | None:
    """The ``data_quality`` JSON block of a surface's derivation (None for wedges)."""
    q = getattr(d.texture, "quality", None)
    if q is None:
        return None
    return {**q, "finite_with": finite_with(d, q)}


def _pct(x: float) -> str:
    return f"{100 * x:.3g} %"


def quality_lines(d) -> list[str]:
    """Text lines of the data-quality block (empty for wedges)."""
    q = data_quality(d)
    if q is None:
        return []
    head = "data quality: "
    if q["pixels"]:
        head += (f"{q['pixels']} pixels, {q['undefined_pixels']} undefined as measured "
                 f"({_pct(q['undefined_share'])})")
    else:
        head += "mesh"
    sf = q["spike_filter"]
    if sf is not None:
        head += (f", {q['spikes_removed']} spikes marked undefined (--despike {sf['threshold']:g}"
                 f", window {sf['window']})")
    lines = [head]
    if q["max_slope_deg"] is not None:
        lines.append(f"  --max-slope {q['max_slope_deg']:g}: {q['facets_dropped_by_slope']} "
                     f"steeper facets dropped, {_pct(q['dropped_load_share'])} of the load")
    lines.append(f"  steepest facet used {q['steepest_facet_deg']:.2f} deg; "
                 f"{q['facets_above_locking_limit']} facets "
                 f"({_pct(q['load_share_above_locking_limit'])} of the load) steeper than "
                 f"{q['locking_limit_deg']:g} deg, the locking limit atan(1/mu) for mu = "
                 f"{q['largest_mu']:g}")
    return lines


def locking_advice(d) -> list[str]:
    """Lines after a self-locking verdict that a few steep facets cause: the flag and its
    cost."""
    q = data_quality(d)
    fw = None if q is None else q["finite_with"]
    if fw is None:
        return []
    return [f"  it comes from {fw['facets_dropped']} facets steeper than the locking limit "
            f"{fw['max_slope_deg']:g} deg ({_pct(fw['load_share'])} of the load), typically "
            "instrument artefacts at dropout edges and spikes, slopes the instrument cannot "
            "have measured;",
            f"  {fw['flag']} drops them and gives a finite law (cost: {fw['facets_dropped']} "
            f"facets, {_pct(fw['load_share'])} of the load); facets just below the limit "
            "still weigh heavily: compare a lower value, e.g. the instrument's maximum "
            "measurable slope"]
