"""A slide in numbers: the JSON summary of ``asperity slide`` and the path as a CSV table."""
from __future__ import annotations

import math

from .moreau import Result, deflection_deg


def slide_summary(law, res: Result, *, u0: float, angle_deg: float, mass: float, g: float,
                  dt: float, t_end: float | None, tol: float) -> dict:
    """The JSON object of ``asperity slide --json`` for a point mass launched at ``u0`` (m/s)
    in direction ``angle_deg`` on ``law`` (a PlanarLaw); ``t_end`` None: run until rest."""
    x, y = (float(v) for v in res.q_final)
    stopped = res.stop_step is not None
    return {
        "law": law.name, "description": law.description,
        "u0": u0, "angle_deg": angle_deg, "mass": mass, "g": g, "dt": dt,
        "t_end": t_end,
        "rest": [x, y] if stopped else None,
        "final_position": [x, y],
        "final_velocity": [float(v) for v in res.u_final],
        "distance": math.hypot(x, y),
        "stop_time": res.stop_time,
        "deflection_deg": deflection_deg(angle_deg, (x, y)),
        "steps": res.steps,
        "max_iterations_used": res.max_iterations_used,
        "mean_iterations": res.mean_iterations,
        "tolerance": tol,
        "status": res.status,
        "status_message": res.status_message(),
        "fail_step": res.fail_step,
        "fail_residual": res.fail_residual,
        "units": {"rest": "m (t_a, t_b)", "stop_time": "s", "deflection_deg": "deg, "
                  "counter-clockwise (towards t_b) from the initial velocity"},
    }


def path_csv(res: Result) -> str:
    """``t_s,x_m,y_m,vx_m_s,vy_m_s`` rows of the recorded states (CSV text)."""
    lines = ["t_s,x_m,y_m,vx_m_s,vy_m_s"]
    for t, q, u in zip(res.t, res.q, res.u):
        lines.append(",".join(repr(float(v)) for v in (t, q[0], q[1], u[0], u[1])))
    return "\n".join(lines) + "\n"
