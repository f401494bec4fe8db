"""The Motion page's slide of a body (issue 20): a footprint (disc, ring, rectangle, or an
uploaded body file) sliding and spinning on a law, by :func:`asperity.dynamics.body.simulate_body`.

The body of a job (``params["body"]``, built by :mod:`.pages_body`): ``shape`` (disc, ring,
rectangle, upload), ``radius`` or ``size`` (m), ``contact_points``, ``pressure_profile``,
``centre_of_pressure`` (a linear profile) -- or ``upload``/``name`` of a body file --,
``omega0`` (rad/s), ``texture_angle_deg``, and optionally ``force`` (``force_x``, ``force_y``
N, ``torque`` N m, ``waveform`` none|square|sine, ``period`` s) with ``t_end`` (s).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..io import write_text_atomic

#: states of a path kept for the page and the CSV at most (as tasks_motion.MAX_POINTS)
MAX_RECORDS = 4000
#: the CSV's columns
CSV_HEADER = "t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s"


def footprint_of(spec: dict):
    """The Footprint of a disc, ring or rectangle of the page (the library checks it)."""
    from ..bodies.footprint import disc, rectangle, ring
    shape = spec.get("shape")
    n = spec.get("contact_points")
    profile = spec.get("pressure_profile", "uniform")
    cop = spec.get("centre_of_pressure", (0.0, 0.0))
    if shape == "disc":
        return disc(spec.get("radius"), contact_points=n, profile=profile,
                    centre_of_pressure=cop)
    if shape == "ring":
        return ring(spec.get("radius"), contact_points=n)
    if shape == "rectangle":
        a, b = spec.get("size") or (None, None)
        return rectangle(a, b, contact_points=n, profile=profile, centre_of_pressure=cop)
    raise InputError("body must be one of disc, ring, rectangle or a body file")


def read_uploaded_body(path, shown: str):
    """:func:`asperity.bodies.read_body` of a stored upload, its messages naming ``shown``
    (the file's name on the user's computer), not the stored path."""
    from ..bodies.body_file import read_body
    try:
        return read_body(path)
    except InputError as exc:
        raise type(exc)(str(exc).replace(str(path), shown)) from None


def body_of(spec: dict, mass: float, ctx: dict):
    """(footprint, mass, inertia, name) of a job's body; a body file gives its own mass."""
    if spec.get("shape") == "upload":
        from .pages_body import NAMED_FILES
        from .tasks_surface import upload_file
        path = upload_file(ctx, spec.get("upload"), str(spec.get("name")))
        from ..io import read_toml
        table = read_toml(path, "body file", {"name", "description", "body"},
                          InputError).get("body")
        if isinstance(table, dict) and any(k in table for k in NAMED_FILES):
            raise InputError(f"{spec.get('name')}: a body file naming other files is refused "
                             "on this page")            # checked on the form: never read
        body = read_uploaded_body(path, str(spec.get("name")))
        return body.footprint, body.mass, body.inertia, body.name
    fp = footprint_of(spec)
    inertia = mass * fp.inertia_per_mass
    if inertia <= 0:
        raise InputError("the body has no area to give its inertia")
    return fp, mass, inertia, spec["shape"]


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


def record_every(fp, law, mass: float, inertia: float, u0, g: float, dt: float,
                 t_end: float | None) -> int:
    """Steps between recorded states so that at most about MAX_RECORDS are kept."""
    from ..dynamics.body import HORIZON_FACTOR, rest_horizon
    if t_end is None:
        t_end = HORIZON_FACTOR * rest_horizon(fp.points, fp.weights, law, mass, inertia, u0,
                                              g) + 10 * dt
    steps = t_end / dt
    return max(1, math.ceil(steps / MAX_RECORDS)) if math.isfinite(steps) else 1


def simulate(spec: dict, law, *, u0: float, angle_deg: float, mass: float, g: float,
             dt: float, ctx: dict):
    """(footprint, BodyResult, name) of a job's body launched at ``u0`` (m/s) towards
    ``angle_deg`` (from +x) with the spin ``omega0``."""
    from ..dynamics.body import simulate_body
    fp, mass, inertia, name = body_of(spec, mass, ctx)
    a = math.radians(angle_deg)
    u = (u0 * math.cos(a), u0 * math.sin(a), spec.get("omega0", 0.0))
    t_end = spec.get("t_end")
    every = record_every(fp, law, mass, inertia, u, g, dt, t_end)
    res = simulate_body(fp.points, fp.weights, law, mass=mass, inertia=inertia, u0=u, dt=dt,
                        t_end=t_end, force=force_of(spec), g=g,
                        texture_angle_deg=spec.get("texture_angle_deg", 0.0),
                        record_every=every)
    return fp, res, name


def summary(fp, res, spec: dict, law, *, u0: float, angle_deg: float, g: float,
            dt: float, name: str) -> dict:
    """The figures of a body's slide (the page's and the JSON download's)."""
    from ..dynamics.moreau import deflection_deg
    x, y, theta = (float(v) for v in res.q_final)
    ratio = res.terminal_ratio(fp.radius) if fp.kind in ("disc", "ring") else None
    out = {"law": law.name, "description": law.description, "body": name,
           "shape": fp.kind, "radius": fp.radius, "size": spec.get("size"),
           "contact_points": fp.n, "pressure_profile": fp.profile, "mass": res.mass,
           "inertia": res.inertia, "u0": u0, "angle_deg": angle_deg,
           "omega0": spec.get("omega0", 0.0),
           "texture_angle_deg": spec.get("texture_angle_deg", 0.0),
           "force": spec.get("force"), "t_end": spec.get("t_end"), "g": g, "dt": dt,
           "rest": [x, y] if res.rest else None, "final_position": [x, y],
           "final_velocity": [float(v) for v in res.u_final],
           "final_angle_rad": theta, "final_angle_deg": math.degrees(theta),
           "distance": math.hypot(x, y),
           "deflection_deg": deflection_deg(angle_deg, (x, y)) if u0 > 0 else None,
           "stop_time": res.stop_time, "slide_stop_time": res.slide_stop_time,
           "spin_stop_time": res.spin_stop_time, "terminal_ratio": ratio,
           "steps": res.steps, "record_every": _every(res),
           "max_iterations_used": res.max_iterations_used,
           "mean_iterations": res.mean_iterations, "status": res.status,
           "status_message": res.status_message()}
    return out


def _every(res) -> int:
    """Steps between recorded states (the first two records, else 1)."""
    if res.t.size < 2:
        return 1
    return max(1, round((res.t[1] - res.t[0]) / res.dt))


def path_csv(res) -> str:
    """The recorded states as CSV (:data:`CSV_HEADER`)."""
    import io
    buf = io.StringIO()
    table = np.column_stack([res.t, res.q, res.u])
    np.savetxt(buf, table, delimiter=",", fmt="%.10g", header=CSV_HEADER, comments="")
    return buf.getvalue()


def body_task(params: dict, ctx: dict, bar, law, law_text: str, law_name: str) -> dict:
    """The result of a slide job with a body (see the module docstring)."""
    import json

    from ..io import json_ready
    from .figures_body import body_figures
    from .labels import clean, stem
    spec = params["body"]
    bar(0.05, "sliding and spinning")
    fp, res, name = simulate(spec, law, u0=params["u0"], angle_deg=params["angle_deg"],
                             mass=params["mass"], g=params["g"], dt=params["dt"], ctx=ctx)
    bar(0.9, "figures")
    obj = summary(fp, res, spec, law, u0=params["u0"], angle_deg=params["angle_deg"],
                  g=params["g"], dt=params["dt"], name=name)
    write_text_atomic(ctx["job_dir"] / "path.csv", path_csv(res))
    write_text_atomic(ctx["job_dir"] / "body.json", json.dumps(json_ready(obj), indent=1))
    base = f"{law_name}_{stem(spec['name']) if spec.get('shape') == 'upload' else clean(name)}"
    return {"slide": obj, "body": obj, "figures": body_figures(fp, res, obj),
            "law_text": law_text, "files": ["path.csv", "body.json"],
            "downloads": {"path.csv": f"{base}_body-path.csv", "body.json": f"{base}_body.json"}}
