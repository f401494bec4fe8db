"""What a crawl reports: the JSON object, the CSV table of the centre's motion and the plot
(snapshots of the body over one period along the centre's path; speed against time)."""
from __future__ import annotations

import numpy as np

RULE_WORDS = {"componentwise": "componentwise (Hu et al.: each component of the unit slip "
                               "scaled by its own coefficient)",
              "associated": "associated (maximum dissipation on the set C)",
              "colinear": "colinear (force opposite to the slip, its size the radius of C)",
              "walker-leine": "Walker-Leine (star-shaped C, convex sliding set D)"}


def summary(res, law=None) -> dict:
    """The JSON object of a crawl (SI units; speeds in body lengths per period, head-ward
    positive, on the period's mean heading); ``law`` (default: the result's own
    description) names the law."""
    avg = res.averaged
    cot = res.cost_of_transport
    return {
        "speed_body_lengths_per_period": res.speed_body_lengths_per_period,
        "speed_m_s": None if res.speed_body_lengths_per_period is None else
        res.speed_body_lengths_per_period * res.length / res.period,
        "speed_per_period": [float(x) for x in res.speed_per_period],
        "heading_drift_rad_per_period": res.heading_drift_rad_per_period,
        "drift_per_period": [float(x) for x in res.drift_per_period],
        "averaged_periods": [int(avg.start) + 1, int(avg.stop)],
        "transient_periods": res.transient_periods,
        "cost_of_transport": cot,
        "cost_of_transport_note": None if cot is not None else
        "the centre did not move over the averaged periods: no distance to divide by",
        "froude": res.froude,
        "rule": res.rule,
        "law": res.law_description if law is None else law.description,
        "law_kind": res.law_name,
        "mu_forward": res.mu_forward,
        "quasi_static": res.quasi_static,
        "texture_on": res.texture_on,
        "texture_angle_deg": res.texture_angle_deg,
        "gait": res.gait,
        "length_m": res.length,
        "period_s": res.period,
        "points": res.points,
        "periods": res.periods,
        "steps_per_period": res.steps_per_period,
        "dt_s": res.dt,
        "g_m_s2": res.g,
        "final_state": {"x_m": float(res.q[-1, 0]), "y_m": float(res.q[-1, 1]),
                        "theta_rad": float(res.q[-1, 2])},
        "work_J": float(res.work[-1]),
        "dissipated_J": float(res.dissipated[-1]),
        "stick_fraction": res.stick_fraction,
        "mean_iterations": res.mean_iterations,
        "max_iterations_used": res.max_iterations_used,
        "status": res.status,
        "message": res.message,
    }


def text(obj: dict) -> str:
    """The lines ``asperity crawl`` prints."""
    mode = "quasi-static" if obj["quasi_static"] else \
        f"dynamic (Froude number {obj['froude']:.4g})"
    a, b = obj["averaged_periods"]
    lines = [f"law: {obj['law']}",
             f"rule: {RULE_WORDS.get(obj['rule'], obj['rule'])}; texture on the "
             f"{obj['texture_on']} at {obj['texture_angle_deg']:g} deg",
             f"gait: {obj['gait']['kind']} " + ", ".join(_words(k, v) for k, v in
                                                        obj["gait"].items() if k != "kind"),
             f"{mode}, {obj['points']} points, {obj['periods']} periods of "
             f"{obj['steps_per_period']} steps",
             "speed: none (no period completed)" if obj["speed_m_s"] is None else
             f"speed: {obj['speed_body_lengths_per_period']:+.6g} body lengths per period "
             f"({obj['speed_m_s']:+.6g} m/s; periods {a}-{b}"
             + (f", after a transient of {obj['transient_periods']}" if
                obj["transient_periods"] else "") + ")",
             "heading drift: none" if obj["heading_drift_rad_per_period"] is None else
             f"heading drift: {obj['heading_drift_rad_per_period']:+.4g} rad per period"]
    cot = obj["cost_of_transport"]
    lines.append("cost of transport: " + (f"{cot:.4g}" if cot is not None else
                                          "none (" + obj["cost_of_transport_note"] + ")"))
    lines.append(f"Newton iterations per step: mean {obj['mean_iterations']:.3g}, max "
                 f"{obj['max_iterations_used']}; points in exact stick "
                 f"{100 * obj['stick_fraction']:.3g} % of point-steps")
    return "\n".join(lines)


def _words(key, value) -> str:
    if isinstance(value, (list, tuple)):
        return f"{len(value)} {key}"
    return f"{key} {value:g}" if isinstance(value, (int, float)) else f"{key} {value}"


def csv_text(res) -> str:
    """t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s of the recorded states."""
    rows = ["t_s,x_m,y_m,theta_rad,vx_m_s,vy_m_s,omega_rad_s"]
    for t, q, u in zip(res.t, res.q, res.u):
        rows.append(",".join(f"{v:.17g}" for v in (t, *q, *u)))
    return "\n".join(rows) + "\n"


def world_shapes(res, gait, times) -> np.ndarray:
    """(k, N, 2) the body's points in the world at recorded ``times`` (indices into res.t)."""
    kin = gait.kinematics(res.t[times], res.points)
    th = res.q[times, 2]
    c, s = np.cos(th)[:, None], np.sin(th)[:, None]
    x = res.q[times, 0][:, None] + c * kin.r[..., 0] - s * kin.r[..., 1]
    y = res.q[times, 1][:, None] + s * kin.r[..., 0] + c * kin.r[..., 1]
    return np.stack([x, y], axis=-1)


def plot(path, res, gait, obj: dict) -> None:
    """Snapshots of the body over its last period along the centre's path, and the speed
    (the centre's velocity on the heading, body lengths per period) against time."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5), width_ratios=(1.3, 1))
    k = len(res.t)
    snaps = np.linspace(max(0, k - 1 - res.records_per_period), k - 1, 9).round().astype(int)
    shapes = world_shapes(res, gait, snaps)
    for j, sh in enumerate(shapes):
        ax.plot(sh[:, 0], sh[:, 1], color=(0.15, 0.3 + 0.5 * j / 8, 0.8 - 0.5 * j / 8), lw=1.5)
        ax.plot(*sh[-1], "o", ms=3, color="k")
    ax.plot(res.q[:, 0], res.q[:, 1], "--", color="0.4", lw=1, label="centre of mass")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("body over the last period (dot: head)")
    ax.legend(loc="best", fontsize=8)
    bx.plot(res.t, heading_speed(res) * res.period / res.length, lw=1, label="centre's velocity on the heading")
    if res.periods:
        edges = np.arange(res.periods + 1) * res.period
        bx.step(edges, np.r_[res.speed_per_period, res.speed_per_period[-1:]], where="post",
                color="C3", label="speed of each period")
        bx.axhline(obj["speed_body_lengths_per_period"], color="C3", ls=":", lw=1)
    bx.set_xlabel("t (s)")
    bx.set_ylabel("body lengths per period")
    mode = "quasi-static" if res.quasi_static else f"dynamic, Fr = {res.froude:.3g}"
    speed = obj["speed_body_lengths_per_period"]
    bx.set_title(f"rule {res.rule}, {mode}: " + ("no period completed" if speed is None
                                                 else f"U = {speed:+.4g}"))
    bx.legend(loc="best", fontsize=8)
    fig.suptitle(f"{obj['law']}", fontsize=9)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)


def heading_speed(res) -> np.ndarray:
    """The centre's velocity on the heading (m/s) of the recorded states."""
    return res.u[:, 0] * np.cos(res.q[:, 2]) + res.u[:, 1] * np.sin(res.q[:, 2])

