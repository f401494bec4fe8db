"""Plotly figures of an elastic contact on the Surface page (plain dictionaries, as
:mod:`.figures`): the reservoirs p(psi) of every pressure in one force plane, mu_a+/- and
the contact fraction against the pressure, and the contact map (the pressure field, a
heat map; a wedge texture's pressure along its period)."""
from __future__ import annotations

import math

import numpy as np

from .figures import _layout, _r
from .units import choose, show

#: largest side of a contact map on the page (pixels), and of all maps together
MAP_SIDE = 256
MAP_PIXELS = 4 * 256 * 256
#: undefined pixels (no data) in the contact map
UNDEFINED = "#9e9e9e"


def colour(k: int, n: int) -> str:
    """The colour of the k-th of n pressures (blue: the lightest, red: the heaviest)."""
    t = k / max(n - 1, 1)
    return f"hsl({int(240 - 240 * t)}, 70%, 42%)"


def pressure_label(p: float, E_star: float, unit=None) -> str:
    unit = unit or choose(p, "Pa")
    return f"p = {show(p, unit)} (p/E* = {p / E_star:.3g})"


def family_polar(members: list[dict], pressures: list[float], E_star: float) -> dict:
    """p(psi) of each pressure (``members``: the derive JSON of each) in one force plane,
    coloured by pressure, with a legend."""
    unit = choose(pressures, "Pa")
    traces = []
    for k, (d, p) in enumerate(zip(members, pressures)):
        dirs = d["directions"] + d["directions"][:1]
        xs = [None if e["p"] is None else round(e["p"][0], 7) for e in dirs]
        ys = [None if e["p"] is None else round(e["p"][1], 7) for e in dirs]
        name = pressure_label(p, E_star, unit)
        traces.append({"type": "scatter", "mode": "lines", "x": xs, "y": ys, "name": name,
                       "customdata": [round(e["psi_deg"], 3) for e in dirs],
                       "line": {"width": 2, "color": colour(k, len(pressures))},
                       "hovertemplate": f"{name}<br>psi = %{{customdata:.2f}} deg<br>"
                                        "p = (%{x:.5f}, %{y:.5f})<extra></extra>"})
    surface = "data_quality" in members[0]
    a, b = ("p_x", "p_y") if surface else ("p_a (along t_a)", "p_b (along t_b)")
    return {"data": traces, "layout": _layout(
        "friction force p(psi) at each pressure (hover a curve)", a, b, equal=True,
        legend={"orientation": "v", "x": 1.02, "y": 1.0})}


def axes_figure(rows: list[dict], E_star: float, reference_deg: float | None = None) -> dict:
    """mu_a+ and mu_a- (left) and the contact area fraction (right, dotted) against the
    pressure (log axis; ``rows``: the family's summary rows)."""
    unit = choose([r["pressure_Pa"] for r in rows], "Pa")
    x = [round(unit(r["pressure_Pa"]), 9) for r in rows]
    ratio = [f"p/E* = {r['p_over_E_star']:.3g}" for r in rows]
    traces = [{"type": "scatter", "mode": "lines+markers", "x": x, "y": [r[k] for r in rows],
               "name": name, "text": ratio, "line": {"dash": dash},
               "hovertemplate": f"{name}<br>p = %{{x:.4g}} {unit.name} (%{{text}})<br>"
                                "%{y:.5f}<extra></extra>"}
              for k, name, dash in (("mu_a_plus", "mu_a+", "solid"),
                                    ("mu_a_minus", "mu_a-", "dash"))]
    traces.append({"type": "scatter", "mode": "lines+markers", "yaxis": "y2", "x": x,
                   "y": [r["area_fraction"] for r in rows], "text": ratio,
                   "name": "contact area fraction (right)",
                   "line": {"dash": "dot", "color": "#555"},
                   "hovertemplate": f"p = %{{x:.4g}} {unit.name} (%{{text}})<br>contact "
                                    "%{y:.4f}<extra></extra>"})
    axis = "t_a found at each" if reference_deg is None else \
        f"along the common axis t_a = {reference_deg:.2f} deg"
    lay = _layout(f"mu_a+ and mu_a- against the pressure ({axis})",
                  f"nominal pressure p ({unit.name})", "friction coefficient")
    lay["xaxis"]["type"] = "log"
    lay["yaxis2"] = {"title": {"text": "contact area fraction"}, "overlaying": "y",
                     "side": "right", "range": [0, 1.05], "dtick": 0.2,
                     "showgrid": False}
    lay["margin"] = {**lay["margin"], "r": 60}
    return {"data": traces, "layout": lay}


def block_means(p: np.ndarray, side: int) -> np.ndarray:
    """``p`` reduced to at most ``side`` pixels a side by block means over its defined
    pixels (a block with none stays NaN: undefined)."""
    step = max(1, int(math.ceil(max(p.shape) / side)))
    if step == 1:
        return np.array(p, dtype=float)
    nx, ny = (-(-n // step) * step for n in p.shape)
    pad = np.full((nx, ny), np.nan)
    pad[:p.shape[0], :p.shape[1]] = p
    b = pad.reshape(nx // step, step, ny // step, step)
    ok = np.isfinite(b)
    n = ok.sum(axis=(1, 3))
    s = np.where(ok, b, 0.0).sum(axis=(1, 3))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, s / np.where(n > 0, n, 1), np.nan)


class MapKeeper:
    """``observe`` of the contact solves: a small copy of each pressure field (at most
    :data:`MAP_SIDE` a side, fewer when there are many pressures), and progress."""

    def __init__(self, n: int, bar=None):
        self.n, self.bar, self.maps = n, bar, []
        self.side = max(32, min(MAP_SIDE, int(math.sqrt(MAP_PIXELS / n))))

    def __call__(self, res) -> None:
        p = np.asarray(res.pressure, dtype=float)
        wedge = p.shape[1] == 2 and np.array_equal(p[:, 0], p[:, 1], equal_nan=True)
        dx, dy = res.pixel_size
        if wedge:                                   # a wedge texture's profile
            step = max(1, int(math.ceil(p.shape[0] / 2048)))
            small = p[::step, 0]
            extent = (p.shape[0] * dx, 0.0)
        else:
            small = block_means(p, self.side)
            extent = (p.shape[0] * dx, p.shape[1] * dy)
        self.maps.append({"pressure": float(res.pressure_asked), "map": small,
                          "extent": extent, "wedge": wedge, "shape": list(p.shape)})
        if self.bar is not None:
            k = len(self.maps)
            self.bar(0.05 + 0.45 * k / self.n, f"elastic contact solved at pressure {k} of "
                                               f"{self.n}")


def contact_map(maps: list[dict], E_star: float) -> dict | None:
    """The pressure field of each pressure (a drop-down picks the pressure when there are
    several): a heat map in the unit the pressures call for, the undefined pixels grey; a
    wedge's pressure along its period as curves."""
    if not maps:
        return None
    unit = choose([float(np.nanmax(m["map"])) if np.isfinite(m["map"]).any() else 0.0
                   for m in maps], "Pa")
    side = choose([float(v) for v in maps[0]["extent"]])
    labels = [pressure_label(m["pressure"], E_star, choose([m["pressure"] for m in maps],
                                                           "Pa")) for m in maps]
    if maps[0]["wedge"]:
        traces = []
        for k, (m, lab) in enumerate(zip(maps, labels)):
            x = np.arange(m["map"].size) * side(m["extent"][0]) / m["map"].size
            traces.append({"type": "scatter", "mode": "lines", "x": _r(x, 6),
                           "y": _r(unit(m["map"]), 5), "name": lab,
                           "line": {"color": colour(k, len(maps))},
                           "hovertemplate": f"{lab}<br>x = %{{x:.4g}} {side.name}<br>"
                                            f"pressure %{{y:.4g}} {unit.name}<extra></extra>"})
        return {"data": traces, "layout": _layout(
            "contact pressure along one period of the texture", f"x across the ridges "
            f"({side.name})", f"contact pressure ({unit.name})")}
    traces, buttons = [], []
    for k, (m, lab) in enumerate(zip(maps, labels)):
        z = m["map"]
        nx, ny = z.shape
        lx, ly = (side(v) for v in m["extent"])
        x = _r((np.arange(nx) + 0.5) * lx / nx, 6)
        y = _r((np.arange(ny) + 0.5) * ly / ny, 6)
        undefined = ~np.isfinite(z)
        shown = k == len(maps) - 1
        traces.append({"type": "heatmap", "x": x, "y": y, "z": _r(unit(z).T, 5),
                       "name": lab, "visible": shown, "colorscale": "Hot", "reversescale": True,
                       "zmin": 0.0, "colorbar": {"title": {"text": f"pressure ({unit.name})"}},
                       "hovertemplate": f"x = %{{x:.4g}} {side.name}<br>y = %{{y:.4g}} "
                                        f"{side.name}<br>pressure %{{z:.4g}} {unit.name}"
                                        "<extra></extra>"})
        traces.append({"type": "heatmap", "x": x, "y": y, "visible": shown,
                       "z": np.where(undefined, 1.0, np.nan).T.tolist(),
                       "name": "undefined pixels (no data)", "showscale": False,
                       "colorscale": [[0, UNDEFINED], [1, UNDEFINED]],
                       "hovertemplate": "undefined pixel (no data: carries nothing)"
                                        "<extra></extra>"})
        vis = [False] * (2 * len(maps))
        vis[2 * k] = vis[2 * k + 1] = True
        buttons.append({"method": "update", "label": lab, "args": [{"visible": vis}]})
    lay = _layout("contact pressure (0 out of contact; grey: undefined pixels)",
                  f"x ({side.name})", f"y ({side.name})", equal=True)
    if len(maps) > 1:
        lay["updatemenus"] = [{"buttons": buttons, "active": len(maps) - 1, "x": 0.0,
                               "xanchor": "left", "y": 1.12, "yanchor": "bottom"}]
    return {"data": traces, "layout": lay}
