"""Plotly figures of an elastic contact on the Surface page (plain dictionaries, as
:mod:`.figures`): the reservoirs p(psi) of every pressure in one force plane, mu_a+/- and
the contact fraction against the pressure, and the contact map (the pressure field, a
heat map; a wedge texture's pressure along its period)."""
from __future__ import annotations

import math

import numpy as np

from .figures import _layout, _r, map_axes
from .units import choose, show

#: largest side of a contact map on the page (pixels), and of all maps together
MAP_SIDE = 256
MAP_PIXELS = 4 * 256 * 256
#: undefined pixels (no data) in the contact map
UNDEFINED = "#9e9e9e"
#: the contact map's colours: out of contact (p = 0) pale blue, not the page's white; the
#: lightest pressures pale yellow, then yellow, red, black (Plotly's Hot, reversed)
OUT_OF_CONTACT = "#cfdcea"
PRESSURE_COLOURS = [[0.0, OUT_OF_CONTACT], [1e-4, "rgb(255,250,205)"], [0.4, "rgb(255,210,0)"],
                    [0.7, "rgb(230,0,0)"], [1.0, "rgb(0,0,0)"]]
#: contact fractions all below this are drawn on a log axis
LOG_FRACTION = 0.2


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
    unit = choose(pressures, "Pa", smallest=True)
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
    unit = choose([r["pressure_Pa"] for r in rows], "Pa", smallest=True)
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
    fr = [r["area_fraction"] for r in rows if r["area_fraction"] > 0]
    if fr and max(fr) < LOG_FRACTION:          # 1e-4 to 1e-2 are flat on a 0-1 axis
        lay["yaxis2"] = {"title": {"text": "contact area fraction (log)"}, "type": "log",
                         "overlaying": "y", "side": "right", "showgrid": False,
                         "exponentformat": "power"}
    else:
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
        if hasattr(bar, "part"):                # each solve fills its n-th of the bar
            bar.part(0, n)

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
                          "extent": extent, "wedge": wedge, "shape": list(p.shape),
                          "top": float(np.nanmax(p)) if np.isfinite(p).any() else 0.0})
        if self.bar is not None:
            k = len(self.maps)
            label = f"elastic contact solved at pressure {k} of {self.n}"
            if hasattr(self.bar, "part"):
                self.bar(1.0, label)
                self.bar.part(k, self.n)
            else:
                self.bar(k / self.n, label)


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
                                                           "Pa", True)) for m in maps]
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
        means = list(z.shape) != list(m["shape"])
        what = "block mean" if means else "pressure"
        bar = f"block means ({unit.name})<br>pixel max {show(m.get('top', 0.0), unit)}" \
            if means else f"pressure ({unit.name})"
        traces.append({"type": "heatmap", "x": x, "y": y, "z": _r(unit(z).T, 5),
                       "name": lab, "visible": shown, "colorscale": PRESSURE_COLOURS,
                       "zmin": 0.0, "colorbar": {"title": {"text": bar}},
                       "hovertemplate": f"x = %{{x:.4g}} {side.name}<br>y = %{{y:.4g}} "
                                        f"{side.name}<br>{what} %{{z:.4g}} {unit.name}"
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
    lay = map_axes(_layout("contact pressure (pale blue: out of contact, p = 0; grey: "
                           "undefined pixels)", f"x ({side.name})", f"y ({side.name})",
                           equal=True), *(side(v) for v in maps[0]["extent"]))
    if len(maps) > 1:
        lay["updatemenus"] = [{"buttons": buttons, "active": len(maps) - 1, "x": 0.0,
                               "xanchor": "left", "y": 1.12, "yanchor": "bottom"}]
    return {"data": traces, "layout": lay}
