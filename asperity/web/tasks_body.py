"""The Motion page's slide of a body (issue 20): a footprint (disc, ring, rectangle, or an
uploaded body file) sliding and spinning on a law, by
:func:`asperity.dynamics.body_api.slide_body` (what ``asperity slide --body`` runs).

The body of a job (``params["body"]``, built by :mod:`.pages_body`): ``shape`` (disc, ring,
rectangle, upload), ``radius`` or ``size`` (m), ``contact_points``, ``pressure_profile``,
``centre_of_pressure`` (a linear profile) -- or ``upload``/``name`` of a body file --,
``omega0`` (rad/s), ``texture_angle_deg``, and optionally ``force`` (``force_x``, ``force_y``
N, ``torque`` N m, ``waveform`` none|square|sine, ``period`` s) with ``t_end`` (s).
"""
from __future__ import annotations

from ..errors import InputError
from ..io import write_text_atomic

#: keys of a body file that name other files: refused on the page (the form checks them;
#: a job checks again before the body file is read)
NAMED_FILES = ("mesh", "pressure_file")


def make(spec: dict, mass: float):
    """The Body of a disc, ring or rectangle of the page (:func:`asperity.dynamics.body_api.
    make_body` checks it), of mass ``mass`` (kg)."""
    from ..dynamics.body_api import make_body
    shape = spec.get("shape")
    if shape not in ("disc", "ring", "rectangle"):
        raise InputError("body must be one of disc, ring, rectangle or a body file")
    profile = spec.get("pressure_profile") if shape != "ring" else None
    return make_body(shape, radius=spec.get("radius"), size=spec.get("size"),
                     contact_points=spec.get("contact_points"), pressure_profile=profile,
                     centre_of_pressure=spec.get("centre_of_pressure"), mass=mass)


def read_uploaded_body(path, shown: str):
    """:func:`asperity.bodies.read_body` of a stored upload, its messages naming ``shown``
    (the file's name on the user's computer), not the stored path."""
    from ..bodies.body_file import read_body
    try:
        return read_body(path)
    except InputError as exc:
        raise type(exc)(str(exc).replace(str(path), shown)) from None


def body_of(spec: dict, mass: float, ctx: dict):
    """The Body of a job; a body file gives its own mass."""
    if spec.get("shape") != "upload":
        return make(spec, mass)
    from ..io import read_toml
    from .tasks_surface import upload_file
    path = upload_file(ctx, spec.get("upload"), str(spec.get("name")))
    table = read_toml(path, "body file", {"name", "description", "body"}, InputError).get("body")
    if isinstance(table, dict) and any(k in table for k in NAMED_FILES):
        raise InputError(f"{spec.get('name')}: a body file naming other files is refused "
                         "on this page")                # checked on the form: never read
    return read_uploaded_body(path, str(spec.get("name")))


def force_of(spec: dict):
    """The :class:`asperity.dynamics.moreau.Force` of the body's ``force`` (None: none)."""
    f = spec.get("force")
    if not f:
        return None
    from ..dynamics.moreau import Force
    v = (f["force_x"], f["force_y"], f["torque"])
    if f["waveform"] == "none":
        return Force(constant=v)
    return Force(amplitude=v, period=f["period"], waveform=f["waveform"])


def simulate(spec: dict, law, *, u0: float, angle_deg: float, mass: float, g: float,
             dt: float, ctx: dict):
    """The :class:`asperity.dynamics.body_api.BodySlide` of a job's body launched at ``u0``
    (m/s) towards ``angle_deg`` (from +x) with the spin ``omega0``."""
    from ..dynamics.body_api import slide_body
    return slide_body(law, body_of(spec, mass, ctx), u0, angle_deg, spec.get("omega0", 0.0),
                      g=g, dt=dt, t_end=spec.get("t_end"), force=force_of(spec),
                      texture_angle_deg=spec.get("texture_angle_deg", 0.0))


def terminal_reference(body: dict) -> dict | None:
    """The closed form's terminal ratio v / (R omega) for this body (``body``: the summary's
    ``body``): a uniformly loaded disc's 0.653, a thin ring's 1; None for any other body
    (another pressure profile, a rectangle, a polygon: no closed form to compare with)."""
    from ..bodies.closed_forms import TERMINAL_RATIO
    kind, profile = body.get("kind"), body.get("profile")
    if kind == "disc" and profile == "uniform":
        return {"ratio": round(TERMINAL_RATIO["disc"], 3), "words": "A uniformly loaded disc"}
    if kind == "ring":
        return {"ratio": round(TERMINAL_RATIO["ring"], 3), "words": "A thin ring"}
    return None


def body_task(params: dict, ctx: dict, bar, law, law_text: str, law_name: str) -> dict:
    """The result of a slide job with a body (see the module docstring): the summary of
    ``asperity slide --body --json`` (``body``), the form's body (``spec``), the figures."""
    import json

    from ..dynamics.body_api import body_csv
    from ..io import json_ready
    from .figures_body import body_figures
    from .labels import clean, stem
    spec = params["body"]
    from .job_progress import phase
    with phase(bar, 0.0, 0.9, "sliding and spinning"):
        run = simulate(spec, law, u0=params["u0"], angle_deg=params["angle_deg"],
                       mass=params["mass"], g=params["g"], dt=params["dt"], ctx=ctx)
    bar(0.9, "figures")
    obj = json_ready(run.summary)
    write_text_atomic(ctx["job_dir"] / "path.csv", body_csv(run.result))
    write_text_atomic(ctx["job_dir"] / "body.json", json.dumps(obj, indent=1))
    name = stem(spec["name"]) if spec.get("shape") == "upload" else clean(spec["shape"])
    base = f"{law_name}_{name}"
    return {"slide": obj, "body": obj, "spec": spec, "law_text": law_text,
            "terminal_reference": terminal_reference(obj["body"]),
            "figures": body_figures(run.body.footprint, run.result, obj),
            "files": ["path.csv", "body.json"],
            "downloads": {"path.csv": f"{base}_body-path.csv", "body.json": f"{base}_body.json"}}
