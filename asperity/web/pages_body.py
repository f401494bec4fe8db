"""The body of the Motion page's slide form (issue 20): a point mass, a disc, a ring, a
rectangle or an uploaded body file, its spin, contact points, pressure profile, the angle of
the texture, and an optional external force and torque.

Every field is checked here with the library's ranges, each refusal one line at its field
in the page's words.  An uploaded body file comes alone: a body file naming another file (a
mesh or a pressure file) is refused, since the server reads no file a user names."""
from __future__ import annotations

import math

from ..errors import InputError, check_range
from .forms import Form, FormError, at
from .store import UploadError

#: the body select: value -> what the page calls it
BODIES = (("point", "a point mass"), ("disc", "a disc (radius below)"),
          ("ring", "a thin ring (radius below)"),
          ("rectangle", "a rectangle (size below)"),
          ("upload", "a body file (TOML, upload below)"))
#: pressure profiles the page offers for each shape
PROFILES = {"disc": ("uniform", "hertz", "linear"), "rectangle": ("uniform", "linear"),
            "ring": ("uniform",)}
#: waveforms of the external force: value -> the library's waveform (asperity.dynamics.moreau)
WAVES = {"": None, "constant": "none", "square": "square", "sine": "sine"}
#: most contact points on the page: the solver behind simulate_body takes at most 10000
#: contacts (asperity.dynamics.moreau.Body) until the fast one lands
MAX_POINTS = 10_000
#: labels of the fields (the refusals name them)
LABELS = {"radius": "radius (m)", "size_a": "size a (m)", "size_b": "size b (m)",
          "omega0": "initial spin omega0 (rad/s)", "contact_points": "contact points",
          "pressure_profile": "pressure profile", "cop_x": "centre of pressure x (m)",
          "cop_y": "centre of pressure y (m)", "texture_angle_deg": "texture angle (deg)",
          "force_wave": "external force", "force_x": "force x (N)", "force_y": "force y (N)",
          "torque": "torque (N m)", "period": "period (s)", "t_end": "end time (s)",
          "body_file": "body file (TOML)"}
BODY_FILE_NAMES = "may not name other files"


def _number(form: Form, name: str, default, low: float, high: float) -> float:
    """The field ``name`` as a number within [low, high] (blank: ``default``)."""
    x = form.number(name, default, label=LABELS[name])
    try:
        return check_range(LABELS[name], x, low, high)
    except InputError as exc:
        raise FormError(str(exc), name) from None


def _length(form: Form, name: str, default) -> float:
    from ..bodies.footprint import LENGTH_RANGE
    return _number(form, name, default, *LENGTH_RANGE)


def body_params(web, form: Form, kept: dict, *, dt: float, mass: float) -> dict | None:
    """The ``body`` of a slide job (None: the point mass of ``asperity slide``), its
    footprint built once here so that a refusal is at its field."""
    shape = form.choice("body", [v for v, _ in BODIES], "point", label="body")
    if shape == "point":
        return None
    spec: dict = {"shape": shape}
    if shape in ("disc", "ring"):
        spec["radius"] = _length(form, "radius", 0.05)
    elif shape == "rectangle":
        spec["size"] = [_length(form, "size_a", 0.08), _length(form, "size_b", 0.04)]
    from ..dynamics.moreau import LIMITS
    lo, hi = LIMITS["inertia"]
    if shape == "upload":
        upload, body = _body_file(web, kept)
        spec.update(upload)
        fp = body.footprint
        if not lo <= body.inertia <= hi:
            raise FormError(f"{upload['name']}: the body's inertia {body.inertia:.3g} kg m^2 is "
                            f"outside {lo:g} to {hi:g} (the solver's range)", "body_file")
    else:
        spec["contact_points"] = form.whole("contact_points", None, low=1, high=MAX_POINTS,
                                            label=LABELS["contact_points"])
        allowed = PROFILES[shape]
        spec["pressure_profile"] = form.choice("pressure_profile", allowed, "uniform",
                                               label=LABELS["pressure_profile"]) \
            if shape != "ring" else "uniform"
        if spec["pressure_profile"] == "linear":
            spec["centre_of_pressure"] = [_number(form, k, 0.0, -1e3, 1e3)
                                          for k in ("cop_x", "cop_y")]
        from .tasks_body import make
        try:
            fp = make(spec, mass).footprint
        except InputError as exc:
            raise FormError(_page_words(str(exc)), _field_of(str(exc), spec)) from None
        inertia = mass * fp.inertia_per_mass
        if not lo <= inertia <= hi:
            raise FormError(f"the body's inertia (mass times {fp.inertia_per_mass:.3g} m^2) "
                            f"is {inertia:.3g} kg m^2, outside {lo:g} to {hi:g}: change its "
                            "size or the mass", "size_a" if shape == "rectangle" else "radius")
    spec["omega0"] = _number(form, "omega0", 0.0, -1e6, 1e6)
    spec["texture_angle_deg"] = _number(form, "texture_angle_deg", 0.0, -360.0, 360.0)
    spec.update(_force(form, dt, fp.n))
    return spec


def _force(form: Form, dt: float, n: int) -> dict:
    """``{"force": {...}, "t_end": s}`` of the external force fields, or ``{}`` (none)."""
    wave = form.choice("force_wave", WAVES, "", label=LABELS["force_wave"])
    if not wave:
        return {}
    f = {k: _number(form, k, 0.0, -1e12, 1e12) for k in ("force_x", "force_y", "torque")}
    f["waveform"] = WAVES[wave]
    f["period"] = _number(form, "period", 1.0, 1e-9, 1e9) if wave != "constant" else 1.0
    t_end = form.number("t_end", label=LABELS["t_end"])
    if not dt <= t_end <= 1e9:
        raise FormError(f"{LABELS['t_end']} must be from the time step ({dt:g} s) to 1e9 s "
                        f"with an external force, got {t_end:g}", "t_end")
    from ..dynamics.moreau import MAX_STEPS
    work = t_end / dt * max(1.0, n / 16.0)
    if work > MAX_STEPS:
        raise FormError(f"{LABELS['t_end']}: {t_end / dt:.3g} time steps of {n} contact points "
                        f"is more than this page runs ({MAX_STEPS:.3g} steps of 16 points); "
                        "shorten the end time or raise the time step", "t_end")
    return {"force": f, "t_end": t_end}


#: the library's words of a footprint -> (form field, the page's words)
WORDS = {"centre_of_pressure": ("cop_x", "centre of pressure"),
         "pressure_profile": ("pressure_profile", "pressure profile"),
         "contact_points": ("contact_points", "contact points"),
         "radius": ("radius", "radius"), "a": ("size_a", "size a"), "b": ("size_b", "size b")}


def _page_words(msg: str) -> str:
    for key, (_, words) in WORDS.items():
        if "_" in key:
            msg = msg.replace(key, words)
    return msg


def _field_of(msg: str, spec: dict) -> str:
    """The form field a footprint's refusal is about (a centre of pressure outside the
    core: the coordinate farther out for the footprint's extent along it)."""
    shape = spec["shape"]
    if "centre_of_pressure" in msg:
        ax, ay = spec.get("size") or (spec.get("radius"), spec.get("radius"))
        cx, cy = spec.get("centre_of_pressure", (0.0, 0.0))
        return "cop_x" if abs(cx) / ax >= abs(cy) / ay else "cop_y"
    for key in ("contact_points", "pressure_profile"):
        if key in msg:
            return WORDS[key][0]
    if msg.startswith("mass "):
        return "mass"
    return "size_a" if shape == "rectangle" else "radius"


def _body_file(web, kept: dict):
    """(``{"upload", "name"}``, its Body) of the uploaded body file: named files refused,
    then read here by the library."""
    meta = kept.get("body")
    if meta is None:
        raise FormError("choose the body file (.toml) to upload, or another body", "body_file")
    with at("body_file"):
        name = str(meta["name"])
        if not name.lower().endswith(".toml"):
            raise UploadError(f"the body file must be a .toml file, got {name!r}")
        from ..io import parse_toml
        from .common import stored_text
        data = parse_toml(stored_text(web, meta, "a body file"), name, UploadError)
        table = data.get("body")
        from .tasks_body import NAMED_FILES
        for key in NAMED_FILES:
            if isinstance(table, dict) and key in table:
                raise UploadError(f"{name}: body.{key} = {str(table[key])[:80]!r}: on this page "
                                  f"a body file {BODY_FILE_NAMES} (a mesh or a pressure file); "
                                  "give the shape by its size or vertices")
        n = table.get("contact_points") if isinstance(table, dict) else None
        if isinstance(n, (int, float)) and not isinstance(n, bool) and \
                math.isfinite(n) and n > MAX_POINTS:
            raise UploadError(f"{name}: body.contact_points = {n:g}: this page runs at most "
                              f"{MAX_POINTS} contact points")
        from .tasks_body import read_uploaded_body
        body = read_uploaded_body(web.store.upload_path(meta["id"]), name)
    return {"upload": meta["id"], "name": name}, body
