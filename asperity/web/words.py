"""The page's words for the library's: a job refused by the library (a wedge angle out of
range, a pixel size a file cannot have) comes back to its form with the message in the
words of the form's labels instead of the keyword arguments and file keys of the command
line (``pixel_size``, ``height_scale``, ``assembly.h``), and with the field it is about,
so that the page shows it next to that field.

A key a user wrote in a file (an uploaded assembly or study file) is the user's word and
stays; the message is then about the file's field.
"""
from __future__ import annotations

import re

from .labels import page_pressures

#: form fields of a wedge -> label
WEDGE = {"alpha_deg": "alpha (deg)", "beta_deg": "beta (deg)", "mu_alpha": "mu_alpha",
         "mu_beta": "mu_beta"}
#: the risk form's assembly fields (strip_KEY, two_KEY) -> label
STRIP = {"h": "h (m)", "E": "E (Pa)", "p": "p (Pa)", "l": "l (m)", "k_t": "k_t (Pa/m)",
         "alpha_T": "alpha_T (1/K)"}
TWO_NODE = {"k": "k (N/m)", "l0": "l0 (m)", "alpha_T": "alpha_T (1/K)", "k_t": "k_t (N/m)",
            "N": "N (N)"}
#: the crawl form's law select (besides the Law results): value -> what the page calls it
CRAWL_LAWS = (("coefficients", "three coefficients mu_f, mu_b, mu_t with a rule (below)"),
              ("wedge", "a wedge texture, fitted on the fly (below)"),
              ("file", "a texture or surface file, fitted on the fly (upload below)"),
              ("upload", "a gauge file (upload below)"))
#: the rules that make a law of three coefficients: value -> what the page calls it
CRAWL_RULES = (("componentwise", ("componentwise (Hu et al.: each slip component scaled by "
                                  "its own coefficient)")),
               ("associated", "associated (maximum dissipation on the truncated ellipse)"),
               ("colinear", "colinear (force opposite to the slip)"))
#: file fields of the forms -> (key in a form's ``kept`` uploads, the hidden field that
#: sends a kept upload back)
FILE_FIELDS = {"file": ("file", "upload"), "friction_map": ("friction_map", "map_upload"),
               "gauge": ("gauge", "gauge_upload"),
               "assembly_file": ("assembly", "assembly_upload"),
               "texture_file": ("texture", "texture_upload"),
               "body_file": ("body", "body_upload"),
               "c_gauge": ("crawl_gauge", "c_gauge_upload"),
               "c_texture_file": ("crawl_texture", "c_texture_upload"),
               "study": ("study", "study_upload"),
               "companions": ("companions", "companion_uploads")}
#: file fields that take several files
MULTIPLE = ("companions",)
#: keyword arguments of load_surface -> (form field, label) on the Surface page
SURFACE = {"unit": ("unit", "length unit"), "pixel_size": ("pixel_size", "pixel size"),
           "height_scale": ("height_scale", "height scale"),
           "mu": ("mu", "local friction mu"), "detrend": ("detrend", "form removal"),
           "max_slope": ("max_slope", "max slope (deg)"),
           "despike_window": ("despike_window", "spike filter window"),
           "despike": ("despike", "spike filter K"),
           "rest_level": ("rest_level", "rest level (m)"),
           "bearing_fraction": ("bearing_fraction", "bearing fraction"),
           "friction_map": ("friction_map", "friction map")}
SLIDE = {"u0": ("u0", "u0 (m/s)"), "angle": ("angle_deg", "direction (deg)"),
         "angle_deg": ("angle_deg", "direction (deg)"), "mass": ("mass", "mass (kg)"),
         "g": ("g", "g (m/s^2)"), "dt": ("dt", "time step (s)"), "mu1": ("mu1", "mu1"),
         "mu2": ("mu2", "mu2"), "mu_f": ("mu_f", "mu_f"), "mu_b": ("mu_b", "mu_b"),
         "mu_t": ("mu_t", "mu_t")}
#: what the command line's advice becomes on a page: (pattern, words, the key of the
#: field it is about)
PHRASES = ((re.compile(r" ?\(on the command line --[\w-]+\)"), "", None),
           (re.compile(r"[;,]? ?on the command line --[\w-]+"), "", None),
           (re.compile(r"\bdo not pass unit or pixel_size\b"), "leave the length unit and the "
                                                               "pixel size blank", "unit"),
           (re.compile(r"\bpass unit and pixel_size\b"), "give the length unit and the pixel "
                                                          "size", "unit"),
           (re.compile(r"\bpass unit\b"), "give the length unit", "unit"),
           (re.compile(r"\bpass pixel_size\b"), "give the pixel size", "pixel_size"),
           (re.compile(r"\(in unit,"), "(in the length unit,", None),
           (re.compile(r"a local friction mu above 0$"), "a local friction mu above 0", "mu"),
           (re.compile(r"^the margin dT range / \(2 dT_c\)"),
            "the margin (the temperature range over twice the one the friction holds)", None))
#: keys that are also plain words: taken for a key only as the subject of the message
PLAIN = ("directions", "contact", "method", "mu", "unit", "g", "mass", "angle", "cycles",
         "textured", "detrend", "tolerance", "pressure", "hardness", "boundary")
#: the library's words of an elastic contact -> (form field, label) on the Surface page
ELASTIC = {"pressure / E_star": ("pressure", "p/E*"), "E_star": ("E_star", "E* (Pa)"),
           "pressure": ("pressure", "pressure (Pa)"), "hardness": ("hardness", "hardness (Pa)"),
           "boundary": ("boundary", "boundary")}


def _wedge(prefix: str = "") -> dict:
    return {k: (prefix + k, label) for k, label in WEDGE.items()}


def _assembly(params: dict) -> dict:
    """Keys of an assembly built from the risk form's fields (none for an uploaded file)."""
    if (params.get("kept") or {}).get("assembly"):
        return {}
    model = params.get("assembly", {}).get("assembly", {}).get("model", "strip")
    table, prefix = (STRIP, "strip_") if model == "strip" else (TWO_NODE, "two_")
    out = {f"assembly.{k}": (prefix + k, label) for k, label in table.items()}
    out["assembly.n"] = ("strip_n", "nodes")
    out.update({"loading.dT_min": ("dT_min", "dT min (K)"),
                "loading.dT_max": ("dT_max", "dT max (K)"), "dT_min": ("dT_min", "dT min (K)"),
                "dT_max": ("dT_max", "dT max (K)"),
                "loading.force": ("force", "tangential force"),
                "friction.mu_plus": ("mu_plus", "mu+"),
                "friction.mu_minus": ("mu_minus", "mu-")})
    return out


def words_of(kind: str, params: dict) -> dict:
    """library key -> (form field, label) for a job of ``kind`` with ``params``."""
    src = params.get("source") or {}
    if kind in ("derive", "fit"):
        out = {"directions": ("directions", "sliding directions" if kind == "derive" else
                              "sliding directions fitted"),
               "contact": ("contact", "contact"), "method": ("method", "method")}
        if src.get("kind") == "wedge":
            out.update(_wedge())
        elif src.get("kind") == "file":
            out.update(SURFACE)
        if params.get("elastic"):
            out.update(ELASTIC)
        return out
    if kind == "slide":
        body = params.get("body") if isinstance(params.get("body"), dict) else None
        if body is None:
            return dict(SLIDE)
        # the body solver's limit on the work names t_end (the run's length: the end
        # time with a force, else until rest, set by the time step) and the contact points
        return {**SLIDE, "t_end": ("t_end", "end time (s)") if body.get("force") else
                ("dt", "the run's length"),
                "contact_points": ("contact_points", "contact points")}
    if kind == "risk":
        out = {"cycles": ("cycles", "cycles"), "tolerance": ("tolerance", "tolerance (m)"),
               "slip_axis_deg": ("slip_axis_deg", "slip axis (deg)"),
               "textured": ("textured", "texture on the"), "contact": ("r_contact", "contact")}
        fr = params.get("friction") or {}
        if fr.get("kind") == "wedge":
            out.update(_wedge("r_"))
        elif fr.get("kind") == "file":
            out.update({"unit": ("r_unit", "length unit"), "mu": ("r_mu", "local friction mu")})
        out.update(_assembly(params))
        return out
    if kind == "study":
        return {"workers": ("workers", "local worker processes")}
    if kind == "crawl":
        return {"unit": ("c_unit", "length unit"), "mu": ("c_mu", "local friction mu"),
                "points": ("c_points", "contact points"), "periods": ("c_periods", "periods"),
                "steps_per_period": ("c_steps", "steps per period")}
    return {}


def page_words(message: str, kind: str, params: dict) -> tuple[str, str | None]:
    """(``message`` in the words of the form, the form field it is about or None)."""
    words = words_of(kind, params)
    name = (params.get("assembly") or {}).get("name")
    if name and not (params.get("kept") or {}).get("assembly") and \
            message.startswith(f"{name}: "):
        message = message[len(name) + 2:]          # the form's assembly: no file to name
    field = None
    for pattern, text, key in PHRASES:
        if pattern.search(message):
            message = pattern.sub(text, message)
            if field is None and key in words:
                field = words[key][0]
    if words:
        # a key of the code (pixel_size, assembly.h) anywhere; a plain word (directions,
        # mu) only as the subject, first in the message or after the file's name
        plain = [k for k in words if k in PLAIN]
        code = [k for k in words if k not in PLAIN]

        def label(m):
            nonlocal field
            f, text = words[m.group(2)]
            field = field or f
            return m.group(1) + text
        if plain:
            subj = "|".join(re.escape(k) for k in sorted(plain, key=len, reverse=True))
            message = re.sub(rf"^((?:[^\s:]+: )?)({subj})(?=\s)", label, message, count=1)
        if code:
            alt = "|".join(re.escape(k) for k in sorted(code, key=len, reverse=True))
            message = re.sub(rf"(^|(?<![\w.-]))({alt})(?![\w])", label, message)
    if field is None:
        field = _file_field(message, params)
    return page_pressures(message), field


def _file_field(message: str, params: dict) -> str | None:
    """The file field of the upload the message is about: the last one it names as
    ``name.txt: ...`` (the study's ``study.toml: texture.toml: not UTF-8`` is about the
    texture), else the first one it names."""
    kept = params.get("kept") or {}
    names = {}
    for f, (key, _) in FILE_FIELDS.items():
        for meta in (kept.get(key) if isinstance(kept.get(key), list) else [kept.get(key)]):
            if isinstance(meta, dict) and meta.get("name"):
                names.setdefault(meta["name"], f)
    said = [(message.rfind(n + ": "), f) for n, f in names.items() if n + ": " in message]
    if said:
        return max(said)[1]
    hits = [(message.find(n), f) for n, f in names.items() if n in message]
    return min(hits)[1] if hits else None
