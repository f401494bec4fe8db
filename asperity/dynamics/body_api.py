"""A rigid body launched on a friction law, from Python and for ``asperity slide --body``
(issue 20, item 4).

:func:`slide_body` takes a footprint (:mod:`asperity.bodies`) or a body read from a body file,
launches it from the origin at speed ``u0`` in direction ``angle_deg`` spinning at
``omega0`` and runs :func:`asperity.dynamics.body.simulate_body` until it rests (or to
``t_end``, needed with an external load).  The result, :class:`BodySlide`, holds the
solver's :class:`~asperity.dynamics.body.BodyResult` and the summary the command prints
(:func:`body_summary`): rest point and angle, when sliding and spinning stopped, the
terminal ratio v / (R omega) of a disc or ring, and under a load the drift and rotation
per cycle.  :func:`make_body` builds the body from the command line's words (a kind and its
size, or a body file); :func:`body_csv` writes the path table.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, check_instance, check_int, check_range

#: kinds of footprint ``make_body`` builds from a size (besides a body file)
BODY_KINDS = ("disc", "ring", "rectangle")
#: slide and spin stop "together" when their stop times differ by at most this many steps
#: (of the recorded states)
TOGETHER_STEPS = 3
#: most recorded states of a run (every k-th step is kept; the rows of a CSV table are
#: taken from them, at most MAX_ROWS)
MAX_RECORDS = 200_000
MAX_ROWS = 20_000
CSV_COLUMNS = "t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s"


@dataclass(frozen=True)
class BodySlide:
    """A slide of a rigid body, as ``asperity slide --body`` runs it.

    Attributes
    ----------
    body : asperity.bodies.body_file.Body
        The body (footprint, mass, inertia).
    law : asperity.PlanarLaw
        The friction law it slid on.
    result : asperity.dynamics.body.BodyResult
        The solver's result (recorded states, stop times, status).
    summary : dict
        The JSON object of ``asperity slide --body FILE --json``.
    """

    body: object
    law: object
    result: object
    summary: dict

    @property
    def terminal_ratio(self) -> float | None:
        return self.summary["terminal_ratio"]


# ----------------------------------------------------------------------------- the body

_CLI_NAMES = {"radius": "--radius", "contact_points": "--contact-points",
              "pressure_profile": "--pressure-profile", "profile": "--pressure-profile",
              "centre_of_pressure": "--centre-of-pressure"}


def _renamed(exc: InputError, names: dict) -> InputError:
    """The constructor's error with its argument names replaced by ``names``' (the command
    line's options)."""
    if not names:
        return exc
    msg = re.sub(r"(?<![\w.-])(" + "|".join(map(re.escape, names)) + r")(?![\w-])",
                 lambda m: names[m.group(1)], str(exc))
    return type(exc)(msg)


def make_body(kind, *, radius=None, size=None, contact_points=None, pressure_profile=None,
              centre_of_pressure=None, mass=None, inertia=None, cli: bool = False):
    """A :class:`asperity.bodies.body_file.Body` from words: ``kind`` "disc" or "ring" (with
    ``radius``, m), "rectangle" (with ``size`` (a, b), m, a along the body's x) or the path
    of a TOML body file (which gives the size, mass and pressure; ``contact_points``
    replaces its count).  ``mass`` (kg) default 1; ``inertia`` (kg m^2) default the
    footprint's uniform lamina (the thin ring's m R^2).  ``cli``: name the command line's
    options in errors."""
    from ..bodies import footprint as F
    from ..bodies.body_file import INERTIA_RANGE, MASS_RANGE, Body
    names = _CLI_NAMES if cli else {}

    def nm(key):
        return names.get(key, key)
    if isinstance(kind, Path):
        kind = str(kind)
    check_instance(nm("body") if cli else "kind", kind, str, "text (disc, ring, rectangle or "
                   "a body file)")
    if contact_points is not None:
        contact_points = check_int(nm("contact_points"), contact_points, 1,
                                   F.MAX_CONTACT_POINTS)
    if kind not in BODY_KINDS:
        return _file_body(kind, radius, size, contact_points, pressure_profile,
                          centre_of_pressure, mass, inertia, cli)
    if kind in ("disc", "ring"):
        if size is not None:
            raise InputError(f"{'--size' if cli else 'size'} does not apply to a {kind} "
                             f"(give {nm('radius')})")
        if radius is None:
            raise InputError(f"a {kind} needs {nm('radius')} (m, in [{F.LENGTH_RANGE[0]:g}, "
                             f"{F.LENGTH_RANGE[1]:g}])")
        check_range(nm("radius"), radius, *F.LENGTH_RANGE, unit="m")
    else:
        if radius is not None:
            raise InputError(f"{nm('radius')} does not apply to a rectangle (give "
                             f"{'--size A B' if cli else 'size'})")
        if size is None:
            raise InputError(f"a rectangle needs {'--size A B' if cli else 'size (a, b)'} (m, "
                             f"each in [{F.LENGTH_RANGE[0]:g}, {F.LENGTH_RANGE[1]:g}])")
        if isinstance(size, (str, bytes)) or not hasattr(size, "__len__") or len(size) != 2:
            raise InputError(f"{'--size' if cli else 'size'} must be two lengths (a, b) in m, "
                             f"got {size!r}")
        for v in size:
            check_range("--size" if cli else "size", v, *F.LENGTH_RANGE, unit="m")
    mass = 1.0 if mass is None else check_range("--mass" if cli else "mass", mass,
                                                *MASS_RANGE, unit="kg")
    profile = "uniform" if pressure_profile is None else pressure_profile
    cop = (0.0, 0.0) if centre_of_pressure is None else centre_of_pressure
    try:
        if kind == "disc":
            fp = F.disc(radius, contact_points=contact_points, profile=profile,
                        centre_of_pressure=cop)
        elif kind == "ring":
            if profile != "uniform" or centre_of_pressure is not None:
                raise InputError(f"{nm('pressure_profile')} of a ring must be uniform (a thin "
                                 f"ring carries its load evenly), got {profile!r}")
            fp = F.ring(radius, contact_points=contact_points)
        else:
            fp = F.rectangle(size[0], size[1], contact_points=contact_points, profile=profile,
                             centre_of_pressure=cop)
    except InputError as exc:
        raise _renamed(exc, names) from None
    if inertia is None:
        inertia = mass * fp.inertia_per_mass
    else:
        inertia = check_range("inertia", inertia, *INERTIA_RANGE, unit="kg m^2")
    size_words = f"R = {radius:g} m" if kind != "rectangle" else \
        f"{size[0]:g} m x {size[1]:g} m"
    return Body(fp, mass, inertia, kind, f"{kind} {size_words}", "")


def _file_body(path, radius, size, contact_points, pressure_profile, centre_of_pressure,
               mass, inertia, cli):
    from ..bodies.body_file import _body, read_body
    from ..io import read_toml
    opt = "--body" if cli else "kind"
    p = Path(path)
    if not p.suffix.lower() == ".toml" and not p.is_file():
        raise InputError(f"{opt} must be point, disc, ring, rectangle or a body file (.toml), "
                         f"got {path!r}" if cli else
                         f"kind must be disc, ring, rectangle or a body file (.toml), got {path!r}")
    for given, name in ((radius, "--radius" if cli else "radius"),
                        (size, "--size" if cli else "size"),
                        (pressure_profile, "--pressure-profile" if cli else "pressure_profile"),
                        (centre_of_pressure,
                         "--centre-of-pressure" if cli else "centre_of_pressure"),
                        (mass, "--mass" if cli else "mass"),
                        (inertia, "inertia")):
        if given is not None:
            raise InputError(f"{name} does not apply to a body file ({p.name} gives the shape, "
                             "its size, mass and pressure)")
    if contact_points is None:
        return read_body(p)
    # the file's body with another contact count: its table, contact_points replaced, read
    # by the body-file reader itself (every other field checked as read_body checks it)
    from ..bodies.body_file import _TOP
    data = read_toml(p, "body file", _TOP, InputError)
    b = data.get("body")
    if isinstance(b, dict):
        if "pressure_file" in b:
            raise InputError(f"{'--contact-points' if cli else 'contact_points'} does not apply "
                             f"to {p.name}: its pressure_file gives the points")
        data = dict(data, body=dict(b, contact_points=contact_points))
    try:
        return _body(data, p)
    except InputError as exc:
        msg = str(exc)
        raise type(exc)(msg if msg.startswith(str(p)) else f"{p}: {msg}") from None


def body_words(b: dict) -> str:
    """One line: the body of a summary (``summary["body"]``): its shape, contact points,
    pressure, mass and inertia."""
    name = f"{b['name']} ({b['kind']})" if b["name"] and b["name"] != b["kind"] else b["kind"]
    size = f", R = {b['radius']:g} m" if b["radius"] is not None else \
        f", area {b['area']:.4g} m^2"
    return (f"body: {name}{size}, {b['contact_points']} contact points, {b['profile']} "
            f"pressure, mass {b['mass']:.6g} kg, inertia {b['inertia']:.6g} kg m^2")


# ----------------------------------------------------------------------------- the run

def _as_body(body, mass, inertia):
    from ..bodies.body_file import INERTIA_RANGE, MASS_RANGE, Body
    from ..bodies.footprint import Footprint
    check_instance("body", body, (Body, Footprint))
    if isinstance(body, Body):
        for v, name in ((mass, "mass"), (inertia, "inertia")):
            if v is not None:
                raise InputError(f"{name} does not apply to a Body (it holds its own); give a "
                                 "Footprint to set it")
        return body
    if body.kind == "point":
        raise InputError("body must be a footprint with an extent (disc, ring, rectangle, "
                         "polygon, mesh, pressure), got a point: use asperity.slide for a "
                         "point mass")
    from .body import _check_points
    _check_points(body.points, body.weights)    # at one spot: say so, not 'inertia ... got 0'
    mass = 1.0 if mass is None else check_range("mass", mass, *MASS_RANGE, unit="kg")
    if inertia is None:
        inertia = mass * body.inertia_per_mass
    inertia = check_range("inertia", inertia, *INERTIA_RANGE, unit="kg m^2")
    return Body(body, mass, inertia, body.kind, "", "")


def slide_body(law, body, u0: float, angle_deg: float, omega0: float = 0.0, *,
               mass: float | None = None, inertia: float | None = None, g: float = 9.81,
               dt: float = 1e-4, t_end: float | None = None, force=None,
               texture_angle_deg: float = 0.0, settings=None) -> BodySlide:
    """Launch a planar rigid body on a friction law and run it until it rests.

    The body starts from the origin at speed ``u0`` in direction ``angle_deg`` spinning at
    ``omega0``, and runs (``asperity.dynamics.body.simulate_body``, Moreau's midpoint
    scheme of SPEC.md 4 at every contact point) until it rests, or to ``t_end``.

    Parameters
    ----------
    law : PlanarLaw
        The friction law (:func:`asperity.coulomb_law`, :func:`asperity.law_from_gauge`,
        ...), its t_a axis at ``texture_angle_deg`` from x.
    body : Body or Footprint
        A body (footprint, mass, inertia: from :func:`asperity.read_body`), or a
        :class:`asperity.Footprint` with an extent (not a point: use
        :func:`asperity.slide` for a point mass) with ``mass`` and ``inertia``.
    u0 : float
        Initial speed, m/s, in [0, 1e4] (0 or at least 1e-100).
    angle_deg : float
        Direction of the initial velocity, deg from x towards y, in [-360, 360].
    omega0 : float, optional
        Initial spin, rad/s, counter-clockwise, in [-1e6, 1e6] (0 or at least 1e-100 in
        size; default 0).
    mass : float or None, optional
        kg, in [1e-9, 1e9], for a Footprint (default 1); not with a Body.
    inertia : float or None, optional
        About the centroid, kg m^2, for a Footprint (default the footprint's uniform
        lamina, mass x ``inertia_per_mass``); not with a Body.
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4] (default 9.81): the normal load is m g.
    dt : float, optional
        Time step, s, in [1e-9, 1] (default 1e-4); t_end / dt at most 5e8 steps.
    t_end : float or None, optional
        s, in (dt, 1e9]: run to this time; None (default) runs until the body rests.
        Required with ``force``.
    force : Force or None, optional
        An external load (:class:`asperity.Force`: fx, fy, torque, constant or periodic).
    texture_angle_deg : float, optional
        Angle of the law's t_a axis from x, deg, in [-360, 360] (default 0).
    settings : BodySettings or None, optional
        The solver's settings (``asperity.dynamics.body.BodySettings``); None: defaults.

    Returns
    -------
    BodySlide
        ``body``, ``law``, ``result`` (the solver's record: times ``t``, states ``q``
        (x, y, theta) and ``u`` (vx, vy, omega), SI) and ``summary``, the JSON object of
        ``asperity slide --body ... --json`` (rest point, stop times, ``together``,
        ``terminal_ratio`` v / (R omega) of a disc or ring, under a load the drift per
        cycle).

    Raises
    ------
    InputError
        A value outside its range, ``force`` without ``t_end``, more steps than the solver
        allows.

    See Also
    --------
    asperity.disc_reference, asperity.Force, asperity.read_body, asperity.slide

    Examples
    --------
    A disc launched at 0.5 m/s spinning at 20 rad/s on mu = 0.3 stops sliding and spinning
    together, as the closed forms' reference does (0.3233 s; the terminal ratio
    approaches 0.653 as dt -> 0):

    >>> law = asperity.coulomb_law(0.3)
    >>> disc = asperity.disc_footprint(0.05, contact_points=256)
    >>> run = asperity.slide_body(law, disc, 0.5, 0.0, 20.0)
    >>> round(run.summary["stop_time"], 4), run.summary["together"]        # s
    (0.3234, True)
    >>> print(f"{run.summary['distance']:.4f} m, ratio {run.terminal_ratio:.3f}")
    0.0835 m, ratio 0.645
    """
    from ..laws.planar import PlanarLaw
    from .body import BodySettings, _check_points, check_slow, simulate_body
    from .body_horizon import rest_time
    from .moreau import LIMITS, MAX_STEPS, Force, check_t_end
    check_instance("law", law, PlanarLaw)
    b = _as_body(body, mass, inertia)
    u0 = check_range("u0", u0, *LIMITS["u0"], unit="m/s")
    angle = check_range("angle_deg", angle_deg, -360.0, 360.0, unit="deg")
    omega0 = check_range("omega0", omega0, -1e6, 1e6, unit="rad/s")
    g = check_range("g", g, *LIMITS["g"], unit="m/s^2")
    dt = check_range("dt", dt, *LIMITS["dt"], unit="s")
    tex = check_range("texture_angle_deg", texture_angle_deg, -360.0, 360.0, unit="deg")
    settings = BodySettings() if settings is None else \
        check_instance("settings", settings, BodySettings)
    if force is not None:
        check_instance("force", force, Force)
        if t_end is None:
            raise InputError("t_end is required with an external force (the body need not "
                             "come to rest)")
    check_slow("u0", u0, "m/s")
    check_slow("omega0", omega0, "rad/s")
    fp = b.footprint
    # the footprint first: the horizon below divides by its friction torque, nil for points
    # at one spot (a one-point footprint, a pressure file's points at one place)
    _check_points(fp.points, fp.weights)
    a = math.radians(angle)
    u_start = (u0 * math.cos(a), u0 * math.sin(a), omega0)
    if t_end is None:
        horizon = rest_time(fp.points, fp.weights, law, b.mass, b.inertia,
                            np.array(u_start), g, dt)
    else:
        horizon = t_end = check_t_end("t_end", t_end, dt)
    n = round(horizon / dt)
    if n > MAX_STEPS:
        raise InputError(f"t_end / dt gives {n:.3g} steps, at most {MAX_STEPS:.0e}: raise dt "
                         "or lower t_end")
    rec = max(1, -(-n // MAX_RECORDS))
    res = simulate_body(fp.points, fp.weights, law, mass=b.mass, inertia=b.inertia,
                        u0=u_start, dt=dt, t_end=horizon, force=force, g=g,
                        texture_angle_deg=tex, settings=settings, record_every=rec,
                        until_rest=t_end is None)
    summary = body_summary(law, b, res, u0=u0, angle_deg=angle, omega0=omega0, g=g, dt=dt,
                           t_end=t_end, force=force, texture_angle_deg=tex,
                           tol=settings.tol, record_every=rec)
    return BodySlide(b, law, res, summary)


# ----------------------------------------------------------------------------- numbers

def _moved(res) -> bool:
    """Whether the body both slid and spun (neither stop time is 0)."""
    return res.slide_stop_time not in (None, 0.0) and res.spin_stop_time not in (None, 0.0)


def terminal_ratio(res, radius: float) -> float | None:
    """v / (R omega) as the motion ends: of the last moving state before the exact rest
    (:meth:`asperity.dynamics.body.BodyResult.terminal_ratio`, tracked by the solver at every
    step whatever is recorded); None if the body still moves, or it never slid or never spun
    (a pure slide or a pure spin has no ratio).  It approaches the closed forms' 0.653 (disc)
    or 1 (ring) as dt -> 0 from where the motion started: 0.654 from eps0 = 2.5 and 0.641
    from eps0 = 0.1 for a 1024-point disc at dt = 1e-5 s (0.605 at 1e-4 s); the approach to
    the fixed point is slow, so the ratio says little when the launch is far from it."""
    if res.stop_time is None or not _moved(res):
        return None
    return res.terminal_ratio(radius)


def _at(res, t: float) -> np.ndarray:
    """(x, y, theta) at time t, linear between the recorded states."""
    return np.array([np.interp(t, res.t, res.q[:, j]) for j in range(3)])


def load_figures(res, force, t_end: float) -> dict:
    """Drift and rotation of a body under an external load: the mean drift velocity (m/s)
    and rotation rate (rad/s) over the run and, for a periodic load, the drift (m) and
    rotation (rad) per cycle over the whole cycles after the first (the first alone when
    there is only one)."""
    t_last = float(res.t[-1])
    q0, qe = res.q[0], res.q[-1]
    out = {"drift_velocity": None, "rotation_rate": None, "cycles": 0,
           "drift_per_cycle": None, "rotation_per_cycle": None}
    if t_last > 0:
        out["drift_velocity"] = [float((qe[0] - q0[0]) / t_last),
                                 float((qe[1] - q0[1]) / t_last)]
        out["rotation_rate"] = float((qe[2] - q0[2]) / t_last)
    if force.waveform != "none":
        T = force.period
        cycles = math.floor(t_last / T * (1 + 1e-12))
        out["cycles"] = cycles
        if cycles >= 1:
            first = 1 if cycles >= 2 else 0
            qa, qb = _at(res, first * T), _at(res, cycles * T)
            k = cycles - first
            out["drift_per_cycle"] = [float((qb[0] - qa[0]) / k), float((qb[1] - qa[1]) / k)]
            out["rotation_per_cycle"] = float((qb[2] - qa[2]) / k)
    return out


def body_summary(law, body, res, *, u0, angle_deg, omega0, g, dt, t_end, force,
                 texture_angle_deg, tol, record_every) -> dict:
    """The JSON object of ``asperity slide --body ... --json``."""
    from .moreau import deflection_deg
    fp = body.footprint
    x, y, th = (float(v) for v in res.q_final)
    stopped = res.stop_time is not None
    ts, tw = res.slide_stop_time, res.spin_stop_time
    together = None
    if _moved(res):
        together = abs(ts - tw) <= TOGETHER_STEPS * dt * record_every * (1 + 1e-9)
    ratio = None
    if fp.kind in ("disc", "ring"):
        ratio = terminal_ratio(res, fp.radius)
    obj = {
        "law": law.name, "description": law.description,
        "u0": u0, "angle_deg": angle_deg, "omega0": omega0, "mass": body.mass,
        "inertia": body.inertia, "g": g, "dt": dt, "t_end": t_end,
        "texture_angle_deg": texture_angle_deg,
        "body": {"kind": fp.kind, "name": body.name, "source": body.source or None,
                 "contact_points": fp.n, "profile": fp.profile, "mass": body.mass,
                 "inertia": body.inertia, "area": fp.area, "radius": fp.radius,
                 "centre_of_pressure": [float(v) for v in fp.centre_of_pressure]},
        "rest": [x, y] if stopped else None,
        "final_position": [x, y],
        "final_angle_rad": th,
        "final_velocity": [float(v) for v in res.u_final],
        "distance": math.hypot(x, y),
        "stop_time": res.stop_time,
        "slide_stop_time": ts,
        "spin_stop_time": tw,
        "together": together,
        "terminal_ratio": ratio,
        "deflection_deg": deflection_deg(angle_deg, (x, y)),
        "steps": res.steps,
        "max_iterations_used": res.max_iterations_used,
        "mean_iterations": res.mean_iterations,
        "tolerance": tol,
        "status": res.status,
        "status_message": res.status_message(),
        "force": None,
        "load": None,
        "units": {"rest": "m (x, y)", "final_angle_rad": "rad, counter-clockwise",
                  "stop_time": "s", "terminal_ratio": "v / (R omega), the last moving "
                  "state before the rest", "deflection_deg": "deg, counter-clockwise from "
                  "the initial velocity"},
    }
    if force is not None:
        obj["force"] = {"constant": list(force.constant), "amplitude": list(force.amplitude),
                        "period": force.period, "waveform": force.waveform}
        obj["load"] = load_figures(res, force, t_end)
    return obj


def body_csv(res) -> str:
    """``t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s`` rows of the recorded states (at
    most :data:`MAX_ROWS`, every k-th with the last)."""
    k = len(res.t)
    step = max(1, -(-k // MAX_ROWS))
    idx = list(range(0, k, step))
    if idx[-1] != k - 1:
        idx.append(k - 1)
    lines = [CSV_COLUMNS]
    for i in idx:
        q, u = res.q[i], res.u[i]
        lines.append(",".join(repr(float(v)) for v in (res.t[i], q[0], q[1], q[2], u[0], u[1],
                                                       u[2])))
    return "\n".join(lines) + "\n"
