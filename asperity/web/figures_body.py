"""Plotly figures of a body's slide (issue 20): its path with the body's outline and
orientation at intervals, and its speed and spin against time with the stop times marked."""
from __future__ import annotations

import math

import numpy as np

from .figures import _layout, _r

#: outlines drawn along the path
OUTLINES = 12


def _turned(xy: np.ndarray, q) -> np.ndarray:
    """Body-frame points ``xy`` (k, 2) placed at the state q = (x, y, theta)."""
    c, s = math.cos(q[2]), math.sin(q[2])
    return np.column_stack([q[0] + c * xy[:, 0] - s * xy[:, 1],
                            q[1] + s * xy[:, 0] + c * xy[:, 1]])


def _joined(parts: list) -> tuple[list, list]:
    """x and y of several polylines in one trace (None between them)."""
    xs, ys = [], []
    for p in parts:
        xs += p[:, 0].tolist() + [None]
        ys += p[:, 1].tolist() + [None]
    return xs, ys


def _scaled(values, k: float, digits: int = 9) -> list:
    return [None if v is None or not math.isfinite(v) else round(k * v, digits) for v in values]


def path_figure(fp, res) -> dict:
    """The path of the centre of mass, the outline of the body at OUTLINES times along it
    (a line from the centre to the body's +x edge shows its orientation), start and end."""
    from .units import choose
    q, t = res.q, res.t
    outline = np.asarray(fp.outline, dtype=float)
    reach = float(np.nanmax(np.hypot(outline[:, 0], outline[:, 1]))) if outline.size else 0.0
    size = max(float(np.max(np.abs(q[:, :2]))) if q.size else 0.0, reach, 1e-12)
    un = choose([size])
    k = un(1)
    idx = np.unique(np.linspace(0, q.shape[0] - 1, OUTLINES).round().astype(int))
    edge = max(reach, 1e-12)
    shapes, arms = [], []
    for i in idx:
        if outline.shape[0] > 1:
            shapes.append(_turned(outline, q[i]))
        arms.append(_turned(np.array([[0.0, 0.0], [edge, 0.0]]), q[i]))
    ox, oy = _joined(shapes)
    ax, ay = _joined(arms)
    n = un.name
    step = max(1, q.shape[0] // 2000)
    sel = np.r_[np.arange(0, q.shape[0], step), q.shape[0] - 1]
    speed = np.hypot(res.u[sel, 0], res.u[sel, 1])
    traces = [
        {"type": "scatter", "mode": "lines", "x": _scaled(ox, k), "y": _scaled(oy, k),
         "name": f"outline at {idx.size} times", "line": {"width": 1, "color": "#7f7f7f"},
         "hoverinfo": "skip"},
        {"type": "scatter", "mode": "lines", "x": _scaled(ax, k), "y": _scaled(ay, k),
         "name": "orientation (body's +x)", "line": {"width": 2, "color": "#e67e22"},
         "hoverinfo": "skip"},
        {"type": "scatter", "mode": "lines", "x": _r(k * q[sel, 0], 9), "y": _r(k * q[sel, 1], 9),
         "customdata": np.column_stack([np.round(t[sel], 6), np.round(speed, 6),
                                        np.round(np.degrees(q[sel, 2]), 4)]).tolist(),
         "name": "path of the centre", "line": {"width": 3, "color": "#1f77b4"},
         "hovertemplate": f"t = %{{customdata[0]:.4f}} s<br>x = %{{x:.5g}} {n}<br>"
                          f"y = %{{y:.5g}} {n}<br>speed = %{{customdata[1]:.4g}} m/s<br>"
                          "angle = %{customdata[2]:.2f} deg<extra></extra>"},
        {"type": "scatter", "mode": "markers", "x": [round(k * float(q[0, 0]), 9)],
         "y": [round(k * float(q[0, 1]), 9)], "name": "start",
         "marker": {"size": 10, "color": "#2ca02c"}},
        {"type": "scatter", "mode": "markers", "x": [round(k * float(q[-1, 0]), 9)],
         "y": [round(k * float(q[-1, 1]), 9)],
         "name": "rest point" if res.rest else "end (still moving)",
         "marker": {"size": 12, "color": "#d62728", "symbol": "x"}}]
    return {"data": traces, "layout": _layout("path of the body, its outline and orientation "
                                              "at intervals", f"x ({n})", f"y ({n})",
                                              equal=True)}


def motion_figure(res, obj: dict) -> dict:
    """Speed |v| and spin omega against time, the slide and spin stop times marked."""
    step = max(1, res.t.size // 3000)
    sel = np.r_[np.arange(0, res.t.size, step), res.t.size - 1]
    t = res.t[sel]
    v = np.hypot(res.u[sel, 0], res.u[sel, 1])
    w = res.u[sel, 2]
    traces = [{"type": "scatter", "mode": "lines", "x": _r(t, 7), "y": _r(v, 7),
               "name": "speed |v| (m/s)", "line": {"color": "#1f77b4", "width": 2},
               "hovertemplate": "t = %{x:.4f} s<br>|v| = %{y:.4g} m/s<extra></extra>"},
              {"type": "scatter", "mode": "lines", "x": _r(t, 7), "y": _r(w, 7), "yaxis": "y2",
               "name": "spin omega (rad/s, dashed)",
               "line": {"color": "#d62728", "width": 2, "dash": "dash"},
               "hovertemplate": "t = %{x:.4f} s<br>omega = %{y:.4g} rad/s<extra></extra>"}]
    shapes, notes = [], []
    for key, words, colour, y in (("slide_stop_time", "slide stops", "#1f77b4", 1.0),
                                  ("spin_stop_time", "spin stops", "#d62728", 0.9)):
        ts = obj.get(key)
        if ts is None:
            continue
        shapes.append({"type": "line", "xref": "x", "yref": "paper", "x0": ts, "x1": ts,
                       "y0": 0, "y1": 1, "line": {"color": colour, "dash": "dot", "width": 1.5}})
        notes.append({"x": ts, "y": y, "xref": "x", "yref": "paper", "showarrow": False,
                      "text": f"{words} {ts:.4g} s", "font": {"color": colour},
                      "xanchor": "left" if key == "slide_stop_time" else "right"})
    lay = _layout("speed and spin against time", "time t (s)", "speed |v| (m/s)",
                  shapes=shapes, annotations=notes)
    lay["yaxis2"] = {"title": {"text": "spin omega (rad/s)"}, "overlaying": "y", "side": "right",
                     "showgrid": False, "zeroline": True}
    lay["margin"] = {**lay["margin"], "r": 60}
    return {"data": traces, "layout": lay}


def body_figures(fp, res, obj: dict) -> dict:
    return {"path": path_figure(fp, res), "motion": motion_figure(res, obj)}
