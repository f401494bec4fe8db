"""Plotly figures of a crawl (issue 26): snapshots of the body over its last period along
the centre's path (:func:`asperity.crawling.output.world_shapes`), and the speed against
time (the centre's velocity on the heading, the speed of each period and their average),
as ``asperity crawl --plot`` draws them."""
from __future__ import annotations

import numpy as np

from .figures import _layout, _r

#: snapshots of the body drawn over the last period
SNAPSHOTS = 9
#: points of a curve sent to the page at most
MAX_CURVE = 3000


def _every(n: int) -> np.ndarray:
    step = max(1, n // MAX_CURVE)
    return np.unique(np.r_[np.arange(0, n, step), n - 1])


def snapshots_figure(res, gait, obj: dict) -> dict:
    """The body at SNAPSHOTS times of its last period (tail to head; a dot at the head)
    and the centre of mass's path over the whole run, in one length unit."""
    from ..crawling.output import world_shapes
    from .units import choose
    k = len(res.t)
    per = (k - 1) // max(res.periods, 1)
    snaps = np.unique(np.linspace(max(k - 1 - per, 0), k - 1, SNAPSHOTS).round().astype(int))
    shapes = world_shapes(res, gait, snaps)
    un = choose([float(np.max(np.abs(shapes))), float(np.max(np.abs(res.q[:, :2])))])
    s, n = un(1), un.name
    traces = []
    for j, (i, sh) in enumerate(zip(snaps, shapes)):
        f = j / max(len(snaps) - 1, 1)
        colour = f"rgb(38,{int(77 + 128 * f)},{int(204 - 128 * f)})"
        traces.append({"type": "scatter", "mode": "lines", "x": _r(s * sh[:, 0], 7),
                       "y": _r(s * sh[:, 1], 7), "line": {"width": 2, "color": colour},
                       "name": f"body at t = {res.t[i]:.4g} s",
                       "showlegend": j in (0, len(snaps) - 1),
                       "hovertemplate": f"t = {res.t[i]:.4g} s<extra></extra>"})
    heads = shapes[:, -1, :]
    traces.append({"type": "scatter", "mode": "markers", "x": _r(s * heads[:, 0], 7),
                   "y": _r(s * heads[:, 1], 7), "name": "head",
                   "marker": {"size": 6, "color": "#111"}, "hoverinfo": "skip"})
    sel = _every(k)
    traces.append({"type": "scatter", "mode": "lines", "x": _r(s * res.q[sel, 0], 7),
                   "y": _r(s * res.q[sel, 1], 7), "name": "path of the centre of mass",
                   "line": {"width": 1.5, "color": "#555", "dash": "dash"},
                   "customdata": _r(res.t[sel], 5),
                   "hovertemplate": f"t = %{{customdata:.4g}} s<br>x = %{{x:.5g}} {n}<br>"
                                    f"y = %{{y:.5g}} {n}<extra></extra>"})
    return {"data": traces, "layout": _layout(
        "the body over its last period along the centre's path (dot: head)", f"x ({n})",
        f"y ({n})", equal=True)}


def speed_figure(res, obj: dict) -> dict:
    """The centre's velocity on the heading (body lengths per period) against time, each
    period's speed (a step) and the speed averaged after the transient (dotted)."""
    from ..crawling.output import heading_speed
    sel = _every(len(res.t))
    v = heading_speed(res)[sel] * res.period / res.length
    edges = np.arange(res.periods + 1) * res.period
    per = np.r_[res.speed_per_period, res.speed_per_period[-1:]] if res.periods else []
    U = obj["speed_body_lengths_per_period"]
    a, b = obj["averaged_periods"]
    traces = [{"type": "scatter", "mode": "lines", "x": _r(res.t[sel], 6), "y": _r(v, 7),
               "name": "centre's velocity on the heading", "line": {"width": 1,
                                                                    "color": "#1f77b4"},
               "hovertemplate": "t = %{x:.4g} s<br>%{y:.4g} L/T<extra></extra>"},
              {"type": "scatter", "mode": "lines", "x": _r(edges, 6), "y": _r(per, 7),
               "line": {"shape": "hv", "width": 2, "color": "#d62728"},
               "name": "speed of each period",
               "hovertemplate": "from t = %{x:.4g} s: %{y:.5g} L/T<extra></extra>"},
              {"type": "scatter", "mode": "lines", "x": _r([edges[a - 1], edges[b]], 6),
               "y": [round(U, 7)] * 2, "line": {"width": 1.5, "dash": "dot",
                                                 "color": "#d62728"},
               "name": f"speed, periods {a}-{b}: {U:+.4g} L/T"}]
    mode = "quasi-static" if res.quasi_static else f"dynamic, Froude number {res.froude:.3g}"
    return {"data": traces, "layout": _layout(
        f"speed (rule {res.rule}, {mode})", "time t (s)", "body lengths per period")}


def crawl_figures(res, gait, obj: dict) -> dict:
    return {"snapshots": snapshots_figure(res, gait, obj), "speed": speed_figure(res, obj)}
