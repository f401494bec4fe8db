"""Elastic contact in studies: the ``[contact]`` table of a study file and the
``contact.pressure``, ``contact.E_star``, ``contact.hardness`` parameters.

::

    [contact]                 # the faces weighted by the force of an elastic contact
    E_star = 2.0e11           # Pa (or a parameter "contact.E_star")
    pressure = 1.0e7          # Pa, nominal (or a parameter "contact.pressure")
    # hardness = 5e9          # Pa, a perfectly plastic cap (optional)
    # boundary = "free"       # periodic | free (default: free for scans, periodic for wedges)

    [parameters]
    "contact.pressure" = { values = [1e6, 1e7, 1e8] }    # varied like any parameter

With a ``[contact]`` table (or a ``contact.*`` parameter) every case derives its friction
as ``derive --elastic E_star --pressure P`` does (:func:`weighted`), and the derive stage
adds the outputs ``pressure_Pa``, ``E_star_Pa`` and ``contact_area_fraction``.  A scan
library (kind = "files") takes ``contact.*`` parameters as a grid (``values`` or ``low``,
``high``, ``n``): its cases are every file at every point of that grid.
"""
from __future__ import annotations

from ..errors import InputError, check_choice, check_range

KEYS = ("E_star", "pressure", "hardness", "boundary")
#: the keys that may vary (numbers, Pa)
VARIED = ("E_star", "pressure", "hardness")
#: outputs a study with elastic contact adds (after the derive stage's)
OUTPUTS = [("pressure_Pa", "REAL"), ("E_star_Pa", "REAL"), ("contact_area_fraction", "REAL")]


def contact_spec(data: dict, params) -> dict | None:
    """The checked ``[contact]`` table ({key: value}), or None when the study has neither
    the table nor a ``contact.*`` parameter; one line naming the key."""
    from ..surface.contact_facets import BOUNDARIES
    table = data.get("contact")
    varied = {p.name.split(".", 1)[1]: p for p in params if p.name.startswith("contact.")}
    if table is None and not varied:
        return None
    if table is None:
        table = {}
    if not isinstance(table, dict):
        raise InputError("contact must be a table [contact] (E_star, pressure, hardness, "
                         "boundary)")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise InputError(f"unknown key contact.{unknown[0]}; allowed: {', '.join(KEYS)}")
    for key, p in varied.items():
        if key not in VARIED:
            raise InputError(f"parameters: {p.name!r}: the contact parameters are "
                             f"{', '.join('contact.' + k for k in VARIED)} (contact.boundary "
                             f"is fixed in [contact])")
        check_support(p)
    spec = {}
    for k in VARIED:
        if k in table:
            spec[k] = check_range(f"contact.{k}", table[k], 0.0, None, low_open=True,
                                  unit="Pa")
    if "boundary" in table:
        spec["boundary"] = check_choice("contact.boundary", table["boundary"], BOUNDARIES)
    for k in ("E_star", "pressure"):
        if k not in spec and k not in varied:
            raise InputError(f"contact.{k} missing: an elastic contact needs E_star and "
                             f"pressure (in [contact] or as a parameter \"contact.{k}\")")
    return spec


def check_support(p) -> None:
    """A contact parameter's values must all be above 0: its grid values, or the lower end
    of its distribution (a normal reaches every value: refused)."""
    where = f"parameters.{p.name}"
    if p.distribution == "grid":
        low = min(p.values)
    elif p.distribution == "normal":
        raise InputError(f"{where}: a normal distribution reaches values <= 0; a contact "
                         f"parameter (Pa, > 0) takes lognormal, uniform or truncated-normal "
                         f"with low > 0")
    elif p.distribution == "lognormal":
        return
    else:
        low = p.args[0] if p.distribution == "uniform" else p.args[2]
    check_range(where if p.distribution == "grid" else f"{where}.low", low, 0.0, None,
                low_open=True, unit="Pa")


def elastic_for(spec: dict, values: dict):
    """The ElasticContact of one case: the ``[contact]`` table with the case's
    ``contact.*`` values; one line naming the key."""
    from ..surface.contact_facets import ElasticContact
    d = dict(spec)
    for k, v in values.items():
        if k.startswith("contact."):
            d[k.split(".", 1)[1]] = float(v)
    try:
        return ElasticContact(d["E_star"], d["pressure"], boundary=d.get("boundary"),
                              hardness=d.get("hardness"))
    except InputError as exc:
        raise InputError(f"contact.{exc}") from None


def weighted(texture, source, elastic, surface: dict):
    """``texture`` (a wedge texture) or the scan file ``source`` (read here) with its faces
    weighted by the contact force of ``elastic``."""
    if source is not None:
        from ..surface.contact_facets import load_elastic
        px = surface.get("pixel_size")
        return load_elastic(source, elastic, unit=surface.get("unit"),
                            pixel_size=tuple(px) if isinstance(px, list) else px,
                            height_scale=surface.get("height_scale", 1.0),
                            detrend=surface.get("detrend", "slope"), mu=surface.get("mu"),
                            max_slope=surface.get("max_slope"),
                            despike=surface.get("despike"),
                            despike_window=surface.get("despike_window"))[0]
    from ..friction.elastic import elastic_textures
    return elastic_textures(texture, elastic)[0]


def outputs(texture) -> dict:
    """The contact outputs of a case whose texture was :func:`weighted`."""
    c = texture.elastic
    return {"pressure_Pa": float(c["pressure_Pa"]), "E_star_Pa": float(c["E_star_Pa"]),
            "contact_area_fraction": float(c["area_fraction"])}


#: rows of the load-dependence table at most (the summary stays small)
MAX_ROWS = 2000


def load_dependence(store) -> list[dict] | None:
    """The completed cases' contact outputs and axis coefficients, by file then pressure:
    ``file`` (libraries), ``pressure_Pa``, ``E_star_Pa``, ``p_over_E_star``,
    ``contact_area_fraction``, ``mu_a_plus``, ``mu_a_minus``; None without a contact."""
    outs = dict(store.outputs)
    if "contact_area_fraction" not in outs:
        return None
    cols = (["file"] if "file" in store.inputs else []) + \
        [c for c in ("pressure_Pa", "E_star_Pa", "contact_area_fraction", "mu_a_plus",
                     "mu_a_minus") if c in outs]
    cur = store.con.execute(f"SELECT {', '.join(cols)} FROM cases WHERE status = 'ok' "
                            f"ORDER BY case_id")
    rows = [dict(zip(cols, r)) for r in cur]
    for r in rows:
        r["p_over_E_star"] = r["pressure_Pa"] / r["E_star_Pa"]
    rows.sort(key=lambda r: (r.get("file") or "", r["pressure_Pa"]))
    return rows[:MAX_ROWS]


def plot_load_dependence(rows: list[dict], path) -> None:
    """mu_a+ and mu_a- against the pressure, the contact fraction against p / E*: one
    line a file (or a texture)."""
    from pathlib import Path

    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    groups: dict = {}
    for r in rows:
        groups.setdefault(r.get("file") or "", []).append(r)
    nan = float("nan")
    for i, (name, g) in enumerate(groups.items()):
        colour = f"C{i % 10}"
        label = Path(name).name or "texture"
        p = [r["pressure_Pa"] for r in g]
        if "mu_a_plus" in g[0]:
            ax.plot(p, [nan if r["mu_a_plus"] is None else r["mu_a_plus"] for r in g], "-o",
                    color=colour, label=f"{label} mu_a+")
            ax.plot(p, [nan if r["mu_a_minus"] is None else r["mu_a_minus"] for r in g],
                    "--s", color=colour, label=f"{label} mu_a-")
        bx.plot([r["p_over_E_star"] for r in g], [r["contact_area_fraction"] for r in g],
                "-o", color=colour, label=label)
    ax.set_xlabel("nominal pressure p (Pa)")
    ax.set_ylabel("friction coefficient")
    bx.set_xlabel("p / E*")
    bx.set_ylabel("contact area fraction")
    for a in (ax, bx):
        a.set_xscale("log")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    ax.set_title("Friction along and against t_a against the load", fontsize=9)
    bx.set_title("Contact area fraction", fontsize=9)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def load_lines(rows: list[dict], limit: int = 30) -> list[str]:
    """The load-dependence table of the summary's text."""
    from pathlib import Path
    out = ["load dependence (elastic contact):",
           f"  {'file':<28}{'p (Pa)':<12}{'p/E*':<11}{'contact':<10}{'mu_a+':<10}mu_a-"]
    for r in rows[:limit]:
        mus = "".join("-".ljust(10) if r.get(k) is None else f"{r[k]:<10.5f}"
                      for k in ("mu_a_plus", "mu_a_minus"))
        out.append(f"  {Path(r.get('file') or 'texture').name[:27]:<28}"
                   f"{r['pressure_Pa']:<12.4g}{r['p_over_E_star']:<11.3g}"
                   f"{r['contact_area_fraction']:<10.4f}{mus}".rstrip())
    if len(rows) > limit:
        out.append(f"  ... {len(rows) - limit} more (summary.json, --export)")
    return out
