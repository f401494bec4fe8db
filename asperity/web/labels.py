"""What tells two results apart: the settings that change the answer of a job (shown in
every list of results and on the result's page), and the names its files download under
(after the source and the law kind, never a bare ``gauge.json``)."""
from __future__ import annotations

import re

from .units import choose, cycles, show

#: file-name characters kept in a download name (others become '-')
UNSAFE = re.compile(r"[^A-Za-z0-9._+-]+")
#: format suffixes dropped from a source's name to make a stem (longest first)
SUFFIXES = (".gauge.json", ".txt.gz", ".csv.gz", ".asc.gz", ".dat.gz", ".npy.gz", ".stl.gz",
            ".x3p.gz")
MAX_STEM = 100


def clean(text) -> str:
    """``text`` made fit for a file name (other characters become '-')."""
    text = UNSAFE.sub("-", str(text)).strip("-.")
    return text[:MAX_STEM].rstrip("-.") or "result"


def stem(name) -> str:
    """A file-name stem from a shown name, its format suffix dropped: ``scan 1.x3p`` ->
    ``scan-1``."""
    text = str(name or "").rsplit("/", 1)[-1]
    low = text.lower()
    for suf in SUFFIXES:
        if low.endswith(suf):
            text = text[: -len(suf)]
            break
    else:
        if "." in text.strip("."):
            text = text.rsplit(".", 1)[0]
    return clean(text)


def wedge_stem(src: dict) -> str:
    return clean(f"wedge-{src['alpha_deg']:g}-{src['beta_deg']:g}-mu{src['mu_alpha']:g}-"
                 f"{src['mu_beta']:g}")


def source_stem(src: dict) -> str:
    """The stem of a texture source (:mod:`.tasks_surface`): a wedge, a file."""
    if src.get("kind") == "wedge":
        return wedge_stem(src)
    return stem(src.get("name") or "surface")


def pressure_stem(p) -> str:
    """A nominal pressure in a file name: ``p10MPa`` (its unit as the pages show it)."""
    return clean("p" + show(float(p), choose(float(p), "Pa")).replace(" ", ""))


def pressure_words(p) -> str:
    """``10 MPa``: a pressure as the pages write it (one unit chosen for it)."""
    return show(float(p), choose(float(p), "Pa"))


#: a number as %g and Python write it, and " Pa" after it (not Pa/m, not Pa^2)
_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_PA = r" Pa(?![\w/^])"
_PRESSURES = re.compile(rf"\[(?P<lo>{_NUM}), (?P<hi>{_NUM})\]{_PA}"
                        rf"|(?<![\w.+-])(?P<a>{_NUM}) (?P<w>to|and) (?P<b>{_NUM}){_PA}"
                        rf"|(?<![\w.+-])(?P<x>{_NUM}){_PA}")


def _pressures(m: re.Match) -> str:
    if m["x"] is not None:
        xs = [float(m["x"])]
        u = choose(xs, "Pa")
        out = show(xs[0], u)
    else:
        xs = [float(m["lo"]), float(m["hi"])] if m["lo"] is not None else \
            [float(m["a"]), float(m["b"])]
        u = choose(xs, "Pa", smallest=True)
        out = (f"[{show(xs[0], u)}, {show(xs[1], u)}]" if m["lo"] is not None else
               f"{show(xs[0], u)} {m['w']} {show(xs[1], u)}")
    # a value the unit cannot show without an exponent (a modulus range of 1 to 1e13 Pa)
    # reads better as it was
    return m[0] if "x 10^" in out or "inf" in out else out


def page_pressures(text: str) -> str:
    """``text`` (a refusal, the form's or the library's) with its pressures written as the
    pages write them: ``2e+07 Pa`` -> ``20 MPa``; a range or a pair (``5e+07 to 8e+08 Pa``,
    ``[5e+07, 8e+08] Pa``, ``1e+07 and 2e+07 Pa``) in one unit, that of the smallest, as a
    column of pressures on a page (``50 MPa to 800 MPa``)."""
    return _PRESSURES.sub(_pressures, text)


def law_stem(source: str, kind: str) -> str:
    """``<source>_<law kind>`` (the kind not repeated when the source ends with it)."""
    kind = clean(kind)
    return source if source.endswith("_" + kind) else f"{source}_{kind}"


def law_downloads(source: str, kind: str) -> dict:
    """Download names of a law's gauge file, CSV table and Abaqus block."""
    s = law_stem(source, kind)
    return {"gauge.json": f"{s}.gauge.json", "law.csv": f"{s}.csv", "law.inp": f"{s}.inp"}


def download_name(rec_files: dict | None, name: str) -> str:
    """The name a job's file ``name`` downloads under (the job's own table, else the stored
    name's last part)."""
    shown = (rec_files or {}).get(name)
    if isinstance(shown, str) and UNSAFE.sub("-", shown).strip("-."):
        return UNSAFE.sub("-", shown).strip("-.")[:160]
    return name.rsplit("/", 1)[-1]


# ----------------------------------------------------------------------- settings of a job
def _num(x, digits: int = 4) -> str:
    return f"{float(x):.{digits}g}"


def _length(x) -> str:
    return show(x, choose(x, "m"))


def _given(d: dict, table) -> list[str]:
    """``fmt(value)`` of every key of ``table`` (key, fmt) that ``d`` gives (not None)."""
    return [fmt(d[key]) for key, fmt in table if d.get(key) is not None]


def _pixel(ps) -> str:
    return "pixel " + (" x ".join(_num(v) for v in ps) if isinstance(ps, (list, tuple))
                       else _num(ps))


#: options of a surface file that change its friction, as the lists show them
SURFACE = (("unit", "unit {}".format), ("pixel_size", _pixel),
           ("max_slope", lambda v: f"max slope {_num(v)} deg"),
           ("despike", lambda v: f"spike filter K {_num(v)}"),
           ("despike_window", "spike window {}".format),
           ("rest_level", lambda v: f"rest level {_length(v)}"),
           ("bearing_fraction", lambda v: f"bearing fraction {_num(v)}"))


def surface_options(opts: dict) -> list[str]:
    out = _given(opts, SURFACE)
    if opts.get("friction_map"):
        out.append("friction map")
    elif opts.get("mu") is not None:
        out.append(f"mu {_num(opts['mu'])}")
    if opts.get("detrend") not in (None, "slope"):
        out.append(f"form removal {opts['detrend']}")
    if opts.get("height_scale") not in (None, 1, 1.0):
        out.append(f"heights x {_num(opts['height_scale'])}")
    return out


def _derive(p: dict) -> list[str]:
    out = [f"{p.get('contact', 'all-faces')} contact"]
    if p.get("method", "closed-form") != "closed-form":
        out.append(p["method"])
    out.append(f"{p.get('directions', 360)} directions")
    src = p.get("source") or {}
    if src.get("kind") == "file":
        out += surface_options(src.get("options") or {})
    if isinstance(p.get("elastic"), dict):
        from .elastic import describe
        out.append(describe(p["elastic"]))
    return out


def _fit(p: dict) -> list[str]:
    out = [f"{p.get('law', 'star')} law", f"{p.get('contact', 'all-faces')} contact",
           f"{p.get('directions', 720)} directions"]
    if p.get("source_settings"):
        out.append(f"surface: {p['source_settings']}")
    return out


def _slide(p: dict) -> list[str]:
    out = [f"u0 {_num(p.get('u0', 0))} m/s", f"towards {_num(p.get('angle_deg', 0))} deg"]
    law = p.get("law") if isinstance(p.get("law"), dict) else {}
    if isinstance(law.get("pressure"), (int, float)):
        out.append(f"law family at p = {pressure_words(law['pressure'])}")
    for key, default, unit in (("mass", 1.0, "kg"), ("g", 9.81, "m/s^2"), ("dt", 1e-4, "s")):
        if p.get(key) not in (None, default):
            out.append(f"{key} {_num(p[key])} {unit}")
    b = p.get("body")
    if isinstance(b, dict):
        out += _body(b)
    return out


def _body(b: dict) -> list[str]:
    """A body's settings that change its motion (the Motion page's body fields)."""
    out = [str(b.get("name") or b.get("shape"))]
    if b.get("radius") is not None:
        out.append(f"R {_length(b['radius'])}")
    if b.get("size"):
        out.append(" x ".join(_length(v) for v in b["size"]))
    if b.get("contact_points"):
        out.append(f"{b['contact_points']} points")
    if b.get("pressure_profile") not in (None, "uniform"):
        out.append(f"{b['pressure_profile']} pressure")
    out.append(f"omega0 {_num(b.get('omega0', 0))} rad/s")
    if b.get("texture_angle_deg"):
        out.append(f"texture at {_num(b['texture_angle_deg'])} deg")
    f = b.get("force")
    if isinstance(f, dict):
        out.append(f"{'constant' if f.get('waveform') == 'none' else f.get('waveform')} "
                   f"force until {_num(b.get('t_end', 0))} s")
    return out


def _risk(p: dict) -> list[str]:
    data = p.get("assembly") or {}
    a = data.get("assembly") if isinstance(data.get("assembly"), dict) else {}
    ld = data.get("loading") if isinstance(data.get("loading"), dict) else {}
    out = []
    if a.get("model"):
        out.append(str(a["model"]))
    if isinstance(a.get("p"), (int, float)):
        out.append(f"p {show(a['p'], choose(a['p'], 'Pa'))}")
    if isinstance(a.get("N"), (int, float)):
        out.append(f"N {show(a['N'], choose(a['N'], 'N'))}")
    lo, hi = ld.get("dT_min", 0.0), ld.get("dT_max")
    if isinstance(hi, (int, float)) and isinstance(lo, (int, float)):
        out.append(f"dT {_num(lo)} to {_num(hi)} K")
    if isinstance(ld.get("force"), (int, float)) and ld["force"]:
        out.append(f"force {_num(ld['force'])}")
    return out + _given(p, RISK)


#: options of the risk form that change the verdict, as the lists show them
RISK = (("slip_axis_deg", lambda v: f"slip axis {_num(v)} deg"),
        ("textured", "texture on the {}".format), ("contact", "{} contact".format),
        ("cycles", lambda v: f"{cycles(v)} cycles"),
        ("tolerance", lambda v: f"tolerance {_length(v)}"))


def _study(p: dict) -> list[str]:
    n = len(p.get("companions") or [])
    out = [f"{n} file{'s' if n != 1 else ''} with it"]
    if p.get("workers"):
        out.append(f"{p['workers']} local workers")
    return out


def _crawl(p: dict) -> list[str]:
    """A crawl's settings that change its speed (the Motion page's crawl fields)."""
    g = p.get("gait") if isinstance(p.get("gait"), dict) else {}
    law = p.get("law") if isinstance(p.get("law"), dict) else {}
    out = [f"A {_num(g.get('amplitude', 7))}, k {_num(g.get('waves', 1))}"]
    if law.get("rule"):
        out.append(f"{law['rule']} rule")
    if isinstance(law.get("pressure"), (int, float)):
        out.append(f"law family at p = {pressure_words(law['pressure'])}")
    for key, unit in (("length", "m"), ("period", "s")):
        if g.get(key) not in (None, 1, 1.0):
            out.append(f"{'L' if key == 'length' else 'T'} {_num(g[key])} {unit}")
    out.append("quasi-static" if p.get("quasi_static") else "dynamic")
    out.append(f"{p.get('points', 100)} points, {p.get('periods')} periods")
    if p.get("texture_on") == "ground" or p.get("texture_angle_deg"):
        out.append(f"texture on the {p.get('texture_on', 'body')} at "
                   f"{_num(p.get('texture_angle_deg', 0))} deg")
    if not p.get("quasi_static") and p.get("g") not in (None, 9.81):
        out.append(f"g {_num(p['g'])} m/s^2")
    if p.get("steps_per_period") not in (None, 400):
        out.append(f"{p['steps_per_period']} steps a period")
    return out


SETTINGS = {"derive": _derive, "fit": _fit, "slide": _slide, "risk": _risk, "study": _study,
            "crawl": _crawl}


def settings(rec: dict) -> str:
    """The settings of job ``rec`` that change its answer, in one short line."""
    fn = SETTINGS.get(rec.get("kind"))
    if fn is None:
        return ""
    try:
        return ", ".join(fn(rec.get("params") or {}))
    except (TypeError, ValueError, KeyError, AttributeError):     # an old or odd record
        return ""


def label(rec: dict) -> str:
    """A job as a list on a form shows it: its title and its settings."""
    s = settings(rec)
    return f"{rec['title']} ({s})" if s else rec["title"]
