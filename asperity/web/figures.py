"""Plotly figures of the pages, as plain dictionaries (``{"data": [...], "layout": {...}}``)
drawn in the browser by ``plotly.min.js``.  They are built in the worker process from the
library's results (the Python ``plotly`` package is not needed for them)."""
from __future__ import annotations

import math

import numpy as np

HOVER_P = ("psi = %{customdata[0]:.2f} deg<br>p = (%{x:.5f}, %{y:.5f})<br>"
           "T = p.s = %{customdata[1]:.5f}<br>L = p.s_perp = %{customdata[2]:.5f}<extra></extra>")


def _layout(title: str, xlabel: str, ylabel: str, *, equal: bool = False, **extra) -> dict:
    lay = {"title": {"text": title, "font": {"size": 14}},
           "margin": {"l": 60, "r": 20, "t": 40, "b": 50},
           "xaxis": {"title": {"text": xlabel}, "zeroline": True, "zerolinecolor": "#bbb"},
           "yaxis": {"title": {"text": ylabel}, "zeroline": True, "zerolinecolor": "#bbb"},
           "legend": {"orientation": "h", "y": -0.18}, "hovermode": "closest",
           "plot_bgcolor": "#fff", "paper_bgcolor": "#fff"}
    if equal:
        lay["yaxis"].update(scaleanchor="x", scaleratio=1)
    lay.update(extra)
    return lay


def _r(x, digits: int = 6):
    """Rounded copy for the page (NaN becomes None with the rest of the job's result, in
    io.json_ready)."""
    return np.round(np.asarray(x, dtype=float), digits).tolist()


def largest_friction(obj: dict) -> dict | None:
    """The sliding direction of largest finite friction T = p . s of a derive JSON
    (``{"psi_deg", "T", "p"}``), None when no direction slides: named on the page apart
    from t_a, the axis of T's cos 2psi term (an asymmetric T may peak elsewhere)."""
    best = None
    for d in obj.get("directions") or []:
        t = d.get("tangential")
        if t is not None and d.get("p") is not None and (best is None or t > best["T"]):
            best = {"psi_deg": float(d["psi_deg"]) % 360.0, "T": float(t), "p": d["p"]}
    return best


def map_axes(lay: dict, lx: float, ly: float) -> dict:
    """Axes of a map drawn to scale that span the map itself: with equal scales Plotly
    widens the range of the roomier axis beyond the data (a 64 um map drawn from -75 to
    140 um); constraining the domain shrinks the plot instead."""
    lay["xaxis"].update(range=[0.0, lx], constrain="domain")
    lay["yaxis"].update(range=[0.0, ly], constrain="domain")
    return lay


def reservoir_figures(obj: dict) -> dict:
    """The force-plane plot p(psi) (hover: psi, p, T, L) and T, L against psi, from the
    JSON of :func:`asperity.friction.derive.to_json`."""
    dirs = obj["directions"]
    surface = "data_quality" in obj
    xs, ys, cd = [], [], []
    for d in dirs + dirs[:1]:                       # closed curve
        p = d["p"]
        xs.append(None if p is None else round(p[0], 7))
        ys.append(None if p is None else round(p[1], 7))
        cd.append([round(d["psi_deg"], 4)] + [None if v is None else round(v, 7)
                                               for v in (d["tangential"], d["lateral"])])
    locked = [d["psi_deg"] for d in dirs if d["self_locking"]]
    traces = [{"type": "scatter", "mode": "lines+markers", "x": xs, "y": ys, "customdata": cd,
               "name": "p(psi): friction force per unit normal load", "hovertemplate": HOVER_P,
               "marker": {"size": 4}, "line": {"width": 2}}]
    theta = math.radians(obj.get("principal_direction_deg") or 0.0)
    mags = [math.hypot(x, y) for x, y in zip(xs, ys) if x is not None]
    r = 1.15 * max(mags) if mags else 1.0
    traces.append({"type": "scatter", "mode": "lines", "name": "t_a (principal axis)",
                   "x": [-r * math.cos(theta), r * math.cos(theta)],
                   "y": [-r * math.sin(theta), r * math.sin(theta)],
                   "line": {"dash": "dash", "width": 1, "color": "#e67e22"}, "hoverinfo": "skip"})
    top = largest_friction(obj)
    if top is not None:
        traces.append({"type": "scatter", "mode": "markers", "x": [round(top["p"][0], 7)],
                       "y": [round(top["p"][1], 7)],
                       "name": f"largest friction T = {top['T']:.4f} (psi = "
                               f"{top['psi_deg']:.1f} deg)",
                       "marker": {"size": 11, "color": "#d62728", "symbol": "diamond-open",
                                  "line": {"width": 2}}, "hoverinfo": "skip"})
    a, b = ("p_x", "p_y") if surface else ("p_a (along t_a)", "p_b (along t_b)")
    polar = {"data": traces, "layout": _layout("friction force p(psi) for every sliding "
                                               "direction (hover a point)", a, b, equal=True)}
    psi = [d["psi_deg"] for d in dirs]
    tl = {"data": [
        {"type": "scatter", "mode": "lines", "x": psi, "y": [d["tangential"] for d in dirs],
         "name": "T = p.s (resists the motion)", "hovertemplate":
         "psi = %{x:.2f} deg<br>T = %{y:.5f}<extra></extra>"},
        {"type": "scatter", "mode": "lines", "x": psi, "y": [d["lateral"] for d in dirs],
         "name": "L = p.s_perp (pushes sideways)", "hovertemplate":
         "psi = %{x:.2f} deg<br>L = %{y:.5f}<extra></extra>"}],
        "layout": _layout("tangential and lateral parts against the sliding direction", None,
                          "force / normal load",
                          xaxis={"title": {"text": "sliding direction psi (deg" + (
                              ", from +x)" if surface else ", from t_a)")},
                              "tickvals": list(range(0, 361, 45))})}
    if locked:
        tl["layout"]["title"]["text"] += f" -- self-locking at {len(locked)} directions"
    return {"polar": polar, "tl": tl}


def height_figure(surface, principal_deg: float) -> dict | None:
    """The height-map preview (about 256 x 256 points) with t_a drawn through it; heights
    and sizes each in the unit their magnitude calls for (:func:`.units.choose`)."""
    from .units import choose
    z = getattr(surface, "preview", None)
    ext = getattr(surface, "extent", None)
    if z is None or ext is None:
        return None
    z = np.asarray(z, dtype=float)
    if z.size == 0 or not np.isfinite(z).any():
        return None
    side = choose([float(v) for v in ext])
    lx, ly = (side(v) for v in ext)
    nx, ny = z.shape
    zm = (z - np.nanmean(z)).T
    up = choose([float(np.nanmax(np.abs(zm)))])
    zz = up(zm)
    x = (np.arange(nx) + 0.5) * lx / nx
    y = (np.arange(ny) + 0.5) * ly / ny
    t = math.radians(principal_deg)
    cx, cy, r = 0.5 * lx, 0.5 * ly, 0.4 * min(lx, ly)
    return {"data": [
        {"type": "heatmap", "x": _r(x, 6), "y": _r(y, 6), "z": _r(zz, 4),
         "colorscale": "Viridis", "colorbar": {"title": {"text": f"height ({up.name})"}},
         "hovertemplate": f"x = %{{x:.4g}} {side.name}<br>y = %{{y:.4g}} {side.name}<br>"
                          f"z = %{{z:.4g}} {up.name}<extra></extra>"},
        {"type": "scatter", "mode": "lines+text",
         "x": [cx - r * math.cos(t), cx + r * math.cos(t)],
         "y": [cy - r * math.sin(t), cy + r * math.sin(t)],
         "text": ["", f"t_a {principal_deg:.1f} deg"], "textposition": "top center",
         "line": {"color": "#e67e22", "width": 3}, "textfont": {"color": "#e67e22"},
         "name": "t_a", "hoverinfo": "skip", "showlegend": False}],
        "layout": map_axes(_layout("height map (mean removed) and the principal direction "
                                   "t_a", f"x ({side.name})", f"y ({side.name})", equal=True),
                           lx, ly)}


def law_figures(gl) -> dict:
    """C, D, the data and the sliding rule in the force plane; T and L of the law (lines)
    against the data (dots)."""
    law, data = gl.law, gl.data
    step = max(1, data.psi.size // 360)
    dp = data.p[::step]
    psi_d = np.degrees(data.psi[::step])
    traces = [{"type": "scatter", "mode": "markers", "x": _r(dp[:, 0]), "y": _r(dp[:, 1]),
               "customdata": _r(psi_d, 3), "name": "data p(psi) (fitted)",
               "marker": {"size": 5, "color": "black", "symbol": "circle-open"},
               "hovertemplate": "data<br>psi = %{customdata:.2f} deg<br>"
                                "p = (%{x:.5f}, %{y:.5f})<extra></extra>"}]
    if gl.kind == "star":
        c = np.vstack([law.C.points, law.C.points[:1]])
        dset = np.vstack([law.D.boundary.points, law.D.boundary.points[:1]])
    else:
        phi = np.linspace(0.0, 2.0 * np.pi, 721)
        c = law.C.radial(phi)[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
        dset = None
    traces.append({"type": "scatter", "mode": "lines", "x": _r(c[:, 0]), "y": _r(c[:, 1]),
                   "name": "C: friction reservoir (every force the contact can carry)",
                   "line": {"width": 2.5, "color": "#1f77b4"}, "hoverinfo": "skip"})
    if dset is not None:
        traces.append({"type": "scatter", "mode": "lines", "x": _r(dset[:, 0]),
                       "y": _r(dset[:, 1]), "name": "D: sliding set (its normals give the "
                       "sliding direction; scale arbitrary)",
                       "line": {"dash": "dash", "color": "#e67e22"}, "hoverinfo": "skip"})
    n = 24
    psi = math.radians(gl.principal_direction_deg) + 2 * np.pi * np.arange(n) / n
    f = gl.force(psi)
    mag = np.hypot(f.p[:, 0], f.p[:, 1])
    s = np.column_stack([np.cos(psi), np.sin(psi)])
    ax, ay = [], []
    for k in range(n):
        ax += [mag[k] * s[k, 0], f.p[k, 0], None]
        ay += [mag[k] * s[k, 1], f.p[k, 1], None]
    traces.append({"type": "scatter", "mode": "lines", "x": _r(ax), "y": _r(ay),
                   "name": "sliding rule: |p| s -> p (how far the force turns from s)",
                   "line": {"color": "#2ca02c", "width": 1.5}, "hoverinfo": "skip"})
    frame = ("p_a", "p_b") if gl.principal_direction_deg == 0 else ("p_x", "p_y")
    plane = {"data": traces, "layout": _layout(f"{gl.kind} law: C, D and the data", *frame,
                                               equal=True)}
    grid = np.linspace(0.0, 2.0 * np.pi, 721)
    fl = gl.force(grid)
    T = np.where(fl.set_valued, np.nan, fl.tangential)
    L = np.where(fl.set_valued, np.nan, fl.lateral)
    ok = data.limit == 0
    sd = np.column_stack([np.cos(data.psi[ok]), np.sin(data.psi[ok])])
    sp = np.column_stack([-np.sin(data.psi[ok]), np.cos(data.psi[ok])])
    dT = np.einsum("ij,ij->i", data.p[ok], sd)
    dL = np.einsum("ij,ij->i", data.p[ok], sp)
    k = max(1, int(ok.sum()) // 120)
    deg = np.degrees(data.psi[ok])
    tl = {"data": [
        {"type": "scatter", "mode": "lines", "x": _r(np.degrees(grid), 3), "y": _r(T),
         "name": "law T = p.s", "line": {"color": "black"}},
        {"type": "scatter", "mode": "lines", "x": _r(np.degrees(grid), 3), "y": _r(L),
         "name": "law L = p.s_perp", "line": {"color": "#2ca02c"}},
        {"type": "scatter", "mode": "markers", "x": _r(deg[::k], 3), "y": _r(dT[::k]),
         "name": "data T", "marker": {"symbol": "circle-open", "color": "black", "size": 5}},
        {"type": "scatter", "mode": "markers", "x": _r(deg[::k], 3), "y": _r(dL[::k]),
         "name": "data L", "marker": {"symbol": "circle-open", "color": "#2ca02c", "size": 5}}],
        "layout": _layout("the law against the data, for every sliding direction",
                          "sliding direction psi (deg)", "force / normal load",
                          xaxis={"title": {"text": "sliding direction psi (deg)"},
                                 "tickvals": list(range(0, 361, 45))})}
    return {"plane": plane, "tl": tl}


def path_figure(res, angle_deg: float) -> dict:
    """The path of a sliding body (hover: time, position, speed), start and rest; lengths
    in the unit the path's size calls for."""
    from .units import choose
    q, u, t = np.asarray(res.q), np.asarray(res.u), np.asarray(res.t)
    step = max(1, q.shape[0] // 2000)
    idx = np.unique(np.r_[np.arange(0, q.shape[0], step), q.shape[0] - 1])
    speed = np.hypot(u[idx, 0], u[idx, 1])
    x, y = (float(v) for v in res.q_final)
    d = math.hypot(x, y) or 1.0
    a = math.radians(angle_deg)
    un = choose([float(np.max(np.abs(q[idx]))) if idx.size else 0.0, d])
    n = un.name
    traces = [
        {"type": "scatter", "mode": "lines", "x": [0.0, un(d * math.cos(a))],
         "y": [0.0, un(d * math.sin(a))], "name": "launch direction",
         "line": {"dash": "dot", "color": "#999"}, "hoverinfo": "skip"},
        {"type": "scatter", "mode": "lines", "x": _r(un(1) * q[idx, 0], 9),
         "y": _r(un(1) * q[idx, 1], 9),
         "customdata": np.column_stack([np.round(t[idx], 6), np.round(speed, 6)]).tolist(),
         "name": "path", "line": {"width": 3, "color": "#1f77b4"},
         "hovertemplate": f"t = %{{customdata[0]:.4f}} s<br>x = %{{x:.5g}} {n}<br>"
                          f"y = %{{y:.5g}} {n}<br>speed = %{{customdata[1]:.4g}} m/s"
                          "<extra></extra>"},
        {"type": "scatter", "mode": "markers", "x": [0.0], "y": [0.0], "name": "start",
         "marker": {"size": 10, "color": "#2ca02c"}},
        {"type": "scatter", "mode": "markers", "x": [un(x)], "y": [un(y)],
         "name": "rest point" if res.stop_step is not None else "end (still moving)",
         "marker": {"size": 12, "color": "#d62728", "symbol": "x"}}]
    return {"data": traces, "layout": _layout("path of the sliding body", f"x ({n}, along t_a)",
                                              f"y ({n}, along t_b)", equal=True)}


def risk_figures(h: dict, chain, title: str = "") -> dict:
    """What ``asperity risk --plot`` draws, interactive: the node displacements over the
    first cycles with the temperature (``history``), and for a strip the displacement along
    it at the end of each cycle (``profiles``); from
    :func:`asperity.microslip.plot.assembly_history`.  Each quantity in the unit its values
    call for (the drift in the title as on the page: :func:`.units.show`)."""
    from .units import choose, show
    t = np.asarray(h["t"], dtype=float)
    k = max(1, t.size // 3000)
    un = choose([float(np.max(np.abs(u))) for _, u, _ in h["nodes"]])
    xn = choose([x for _, _, x in h["nodes"]])
    colours = ["#1f77b4", "#2ca02c", "#d62728"]
    traces = []
    for i, (lab, u, x) in enumerate(h["nodes"]):
        lab = f"{lab.split(' (')[0]} (x = {show(x, xn)})"
        traces.append({"type": "scatter", "mode": "lines", "x": _r(t[::k], 5),
                       "y": _r(un(1) * np.asarray(u, dtype=float)[::k], 6), "name": lab,
                       "line": {"width": 1.6, "color": colours[i % 3]},
                       "hovertemplate": f"{lab}<br>cycle %{{x:.3f}}<br>u = %{{y:.4g}} "
                                        f"{un.name}<extra></extra>"})
    traces.append({"type": "scatter", "mode": "lines", "x": _r(t[::k], 5),
                   "y": _r(np.asarray(h["dT"], dtype=float)[::k], 4), "yaxis": "y2",
                   "name": "dT (K, dotted)", "line": {"dash": "dot", "color": "#999",
                                                      "width": 1},
                   "hovertemplate": "cycle %{x:.3f}<br>dT = %{y:.4g} K<extra></extra>"})
    d = h["drift"]
    head = (title + ": " if title else "") + f"mu+ = {chain.mu_plus:.4g}, mu- = " \
        f"{chain.mu_minus:.4g}; drift {show(d, choose(d), sign=True)} per cycle"
    lay = _layout(head, "cycles", f"node displacement u ({un.name})")
    lay["yaxis2"] = {"title": {"text": "dT (K, dotted)"}, "overlaying": "y", "side": "right",
                     "showgrid": False, "zeroline": False, "tickmode": "auto"}
    lay["margin"] = {**lay["margin"], "r": 60}
    out = {"history": {"data": traces, "layout": lay}}
    if h.get("strip") and h.get("profiles"):
        xs = choose(float(np.max(np.abs(h["x"]))))
        us = [u for _, u in h["profiles"]] + [h["hot"][1]]
        uu = choose([float(np.max(np.abs(u))) for u in us])
        n = len(h["profiles"])
        prof = [{"type": "scatter", "mode": "lines", "x": _r(xs(1) * np.asarray(h["x"]), 6),
                 "y": _r(uu(1) * np.asarray(u, dtype=float), 6), "name": lab,
                 "line": {"width": 1.4, "color": f"hsl({int(260 - 200 * c / max(n, 1))}, "
                                                 f"60%, 45%)"},
                 "hovertemplate": f"{lab}<br>x = %{{x:.4g}} {xs.name}<br>u = %{{y:.4g}} "
                                  f"{uu.name}<extra></extra>"}
                for c, (lab, u) in enumerate(h["profiles"], 1)]
        lab, u = h["hot"]
        prof.append({"type": "scatter", "mode": "lines",
                     "x": _r(xs(1) * np.asarray(h["x_nodes"]), 6),
                     "y": _r(uu(1) * np.asarray(u, dtype=float), 6), "name": lab,
                     "line": {"dash": "dash", "color": "#d62728", "width": 1.2},
                     "hovertemplate": f"{lab}<br>x = %{{x:.4g}} {xs.name}<br>u = %{{y:.4g}} "
                                      f"{uu.name}<extra></extra>"})
        out["profiles"] = {"data": prof, "layout": _layout(
            "strip displacement profiles: u(x) at the end of each cycle", f"x ({xs.name})",
            f"displacement u(x) ({uu.name})")}
    return out
