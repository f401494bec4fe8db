"""The summary of a windowed contact estimate (:mod:`.elastic_windows`): the mean and the
spread between windows, as JSON, text and a figure.  Every line and key says that it is an
estimate from K windows of W pixels, never the whole scan's contact."""
from __future__ import annotations

import math

import numpy as np

from .. import __version__
from ..errors import InputError
from .axes import AXES, aligned, axial_spread

#: a window needs at least this share of its pixels defined
MIN_DEFINED_SHARE = 0.8
#: most redraws of one skipped window (random placement, :mod:`.elastic_windows`)
MAX_REDRAWS = 16
_LABELS = {"area_fraction": "contact fraction", "mu_a_plus": "mu_a+", "mu_a_minus": "mu_a-",
           "mu_b_plus": "mu_b+", "mu_b_minus": "mu_b-"}


def spread(values) -> dict:
    """mean, sd (n - 1; null for one value), min, max and n of the finite values."""
    v = np.array([x for x in values if x is not None and math.isfinite(x)], dtype=float)
    if v.size == 0:
        return {"mean": None, "sd": None, "min": None, "max": None, "n": 0}
    return {"mean": float(v.mean()), "sd": float(v.std(ddof=1)) if v.size > 1 else None,
            "min": float(v.min()), "max": float(v.max()), "n": int(v.size)}


def summarise(plan, results: list, placement: str, seed: int) -> dict:
    """The JSON object of ``asperity derive --window`` (the file formats' outputs)."""
    from .reservoir import directions
    src, w, e = plan.heights, plan.window, plan.elastic
    used = [r for r in results if "skipped" not in r]
    if not used:
        raise _none_used(results, w)
    nx, ny = src.shape
    k = len(used)
    what = _estimate(plan, k)
    psi = np.degrees(directions(plan.n_directions))
    T = np.array([[np.nan if t is None else t for t in r["tangential"]] for r in used])
    dirs = []
    for i, p in enumerate(psi):
        s = spread(T[:, i])
        dirs.append({"psi_deg": round(float(p), 10), **{x: s[x] for x in
                                                        ("mean", "sd", "min", "max")},
                     "self_locking_windows": int(np.count_nonzero(np.isnan(T[:, i])))})
    per = [{x: v for x, v in r.items() if x != "tangential"} for r in results]
    pd = axial_spread([r["principal_direction_deg"] for r in used])
    axes = [aligned(r, pd["mean"]) for r in used]
    for r, (_, flipped) in zip([p for p in per if "skipped" not in p], axes):
        r["reversed"] = flipped
    c0 = used[0]["elastic_contact"]
    return {
        "asperity_version": __version__, "estimate": what,
        "scan": {"file": src.source, "shape": [nx, ny], "pixel_size_m": [src.dx, src.dy]},
        "windows": windows_block(plan, results, placement, seed),
        "E_star_Pa": e.E_star, "pressure_Pa": e.pressure, "p_over_E_star": e.pressure / e.E_star,
        "boundary": c0["boundary"], "hardness_Pa": e.hardness, "contact": plan.contact,
        "area_fraction": spread([r["elastic_contact"]["area_fraction"] for r in used]),
        **{a: spread([ax[a] for ax, _ in axes]) for a in AXES},
        "principal_direction_deg": pd,
        "self_locking_windows": sum(1 for r in used if r["self_locking"]),
        "directions": dirs, "per_window": per}


def windows_block(plan, results: list, placement: str, seed: int) -> dict:
    """The ``windows`` object: the windows asked, used, skipped and redrawn."""
    src, w = plan.heights, plan.window
    used = [r for r in results if "skipped" not in r]
    redrawn = [r for r in results if r.get("redrawn_from")]
    return {"window_px": w, "window_m": [w * src.dx, w * src.dy],
            "asked": plan.asked or len(results),
            "positions": (src.shape[0] - w + 1) * (src.shape[1] - w + 1),
            "solved": len(results), "used": len(used), "skipped": len(results) - len(used),
            "redrawn": sum(1 for r in redrawn if "skipped" not in r),
            "redraws": sum(len(r["redrawn_from"]) for r in redrawn),
            "max_redraws": MAX_REDRAWS if placement == "random" else 0,
            "placement": placement, "seed": seed if placement == "random" else None,
            "overlap": _overlap([r["origin_px"] for r in used], w),
            "min_defined_share": MIN_DEFINED_SHARE}


def _estimate(plan, k: int) -> str:
    src, w = plan.heights, plan.window
    nx, ny = src.shape
    return (f"estimate from {_n(k, 'window')} of {w} x {w} pixels ({w * src.dx:.4g} x "
            f"{w * src.dy:.4g} m) of a {nx} x {ny} scan, each solved on its own: not the "
            f"whole scan's contact")


def _none_used(results, w):
    k = len(results)
    return InputError(f"--window: {'the' if k == 1 else f'none of the {k}'} window"
                      f"{'s' * (k != 1)} of {w} x {w} pixels has{' not' * (k == 1)} enough "
                      f"defined pixels (at least "
                      f"{100 * MIN_DEFINED_SHARE:.0f} %); place them elsewhere (--windows, "
                      f"--window-placement) or lower --window")


def summarise_family(plan, results: list, placement: str, seed: int) -> dict:
    """The JSON object of ``asperity derive --window ... --pressure P1 P2 ...``: the
    summary of :func:`summarise` at each pressure (``per_pressure``), each window's
    members (one a pressure) in ``per_window``."""
    from dataclasses import replace
    e = plan.elastic
    ps = e.pressures
    rows, per_window = [], []
    for i, p in enumerate(ps):
        res_i = [r if "skipped" in r else
                 {**{k: v for k, v in r.items() if k != "members"}, **r["members"][i]}
                 for r in results]
        s = summarise(replace(plan, elastic=replace(e, pressure=p)), res_i, placement, seed)
        if i == 0:
            head = {k: s[k] for k in ("asperity_version", "estimate", "scan", "windows",
                                      "E_star_Pa", "boundary", "hardness_Pa", "contact")}
        rows.append({k: v for k, v in s.items() if k not in head and k != "per_window"})
        per_window.append(s["per_window"])
    windows = []
    for j, r in enumerate(results):
        row = {k: v for k, v in r.items() if k != "members"}
        if "skipped" not in r:
            row["members"] = [{k: v for k, v in pw[j].items() if k not in row}
                              for pw in per_window]
        windows.append(row)
    return {**head, "family": "pressure", "pressures_Pa": list(ps), "per_pressure": rows,
            "per_window": windows}


CONTACT_KEYS = ("area_fraction", "max_pressure_Pa", "mean_gap_m")


def contact_summary(plan, results: list, placement: str, seed: int) -> dict:
    """The JSON object of ``asperity contact --window``: each window's contact figures
    and, at each pressure, their spread (mean, sd, min, max, n of the windows used) of
    the area fraction, the largest pressure and the mean gap."""
    e = plan.elastic
    used = [r for r in results if "skipped" not in r]
    if not used:
        raise _none_used(results, plan.window)
    src = plan.heights
    members = [r["members"] if e.family else [r] for r in used]
    rows = []
    for i, p in enumerate(e.pressures):
        cs = [m[i]["elastic_contact"] for m in members]
        rows.append({"pressure_Pa": p, "p_over_E_star": p / e.E_star,
                     **{k: spread([c[k] for c in cs]) for k in CONTACT_KEYS},
                     "full_contact_windows": sum(1 for c in cs if c["area_fraction"] >= 1.0),
                     "iterations_max": max(c["iterations"] for c in cs)})
    out = {"asperity_version": __version__, "estimate": _estimate(plan, len(used)),
           "scan": {"file": src.source, "shape": list(src.shape),
                    "pixel_size_m": [src.dx, src.dy]},
           "windows": windows_block(plan, results, placement, seed),
           "E_star_Pa": e.E_star, "boundary": e.boundary_or("free"),
           "hardness_Pa": e.hardness}
    if e.family:
        out.update(family="pressure", pressures_Pa=list(e.pressures), per_pressure=rows)
    else:
        out.update(rows[0])
    return {**out, "per_window": results}


def contact_window_text(s: dict) -> str:
    """The summary of ``asperity contact --window``."""
    wi = s["windows"]
    H = s["hardness_Pa"]
    rows = s["per_pressure"] if "per_pressure" in s else [s]
    lines = [f"scan: {s['scan']['file']}, {s['scan']['shape'][0]} x {s['scan']['shape'][1]} "
             f"pixels", _estimate_line(wi)]
    for r in rows:
        lines += [f"elastic contact: p = {r['pressure_Pa']:.4g} Pa (p/E* = "
                  f"{r['p_over_E_star']:.3g}), E* = {s['E_star_Pa']:.4g} Pa, boundary "
                  f"{s['boundary']}, hardness " + ("none" if H is None else f"{H:.4g} Pa"),
                  f"  {'':<22}{'mean':<12}{'sd':<12}{'min':<12}{'max':<12}windows"]
        for key, label, fmt in (("area_fraction", "contact fraction", ".6f"),
                                ("max_pressure_Pa", "max pressure (Pa)", ".4g"),
                                ("mean_gap_m", "mean gap (m)", ".4g")):
            x = r[key]
            lines.append(f"  {label:<22}{_f(x['mean'], fmt):<12}{_f(x['sd'], fmt):<12}"
                         f"{_f(x['min'], fmt):<12}{_f(x['max'], fmt):<12}{x['n']}")
        if r["full_contact_windows"]:
            lines.append(f"  full contact in {_n(r['full_contact_windows'], 'window')} (a "
                         "result)")
    return "\n".join(lines + _window_notes(s))


def _estimate_line(wi) -> str:
    place = "a regular grid" if wi["placement"] == "grid" else \
        f"stratified random (seed {wi['seed']})"
    return (f"ESTIMATE from {_n(wi['used'], 'window')} of {wi['window_px']} x {wi['window_px']} "
            f"pixels ({wi['window_m'][0]:.4g} x {wi['window_m'][1]:.4g} m), placed on "
            f"{place}; each window is solved on its own: not the whole scan's contact")


def _window_notes(s: dict) -> list[str]:
    wi = s["windows"]
    lines = []
    if wi.get("solved", wi["asked"]) < wi["asked"]:
        pos = wi.get("positions")
        lines.append(f"{wi['asked']} windows asked, {wi['solved']} solved: "
                     + (f"the scan holds {pos} distinct position{'s' * (pos != 1)} of a "
                        f"window of {wi['window_px']} pixels" if pos is not None
                        and pos <= wi["asked"] else "the others fell on a position already "
                        "solved (windows closer than a pixel)")
                     + " (the same window twice gives the same result)")
    if wi["redraws"]:
        lines.append(f"{_n(wi['redraws'], 'random draw')} had too few defined pixels and "
                     f"were redrawn in their stratum: {_n(wi['redrawn'], 'window')} found a "
                     "place so "
                     f"(at most {wi['max_redraws']} redraws a window)")
    if wi["skipped"]:
        bad = [w for w in s["per_window"] if "skipped" in w]
        lines.append(f"{wi['skipped']} of {_n(wi.get('solved', wi['asked']), 'window')} "
                     "skipped: "
                     + "; ".join(f"at pixel {b['origin_px']}: {b['skipped']}" for b in bad[:3])
                     + (" ..." if len(bad) > 3 else ""))
    if wi["overlap"]:
        lines.append("windows overlap (the scan holds fewer than that many windows of that "
                     "size): they are not independent samples")
    return lines


def plot_contact_windows(s: dict, path) -> None:
    """Each window's contact fraction and largest pressure (their mean dashed)."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    used = [w for w in s["per_window"] if "skipped" not in w]
    rows = s["per_pressure"] if "per_pressure" in s else [s]
    for i, r in enumerate(rows):
        for ax, key, label in ((axs[0], "area_fraction", "contact area fraction"),
                               (axs[1], "max_pressure_Pa", "max pressure (Pa)")):
            ys = [(w["members"][i] if "members" in w else w)["elastic_contact"][key]
                  for w in used]
            line, = ax.plot([w["index"] for w in used], ys, "o",
                            label=f"p = {r['pressure_Pa']:.3g} Pa")
            ax.axhline(r[key]["mean"], ls="--", color=line.get_color())
            ax.set_xlabel("window")
            ax.set_ylabel(label)
    for ax in axs:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(s["estimate"], fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def family_window_text(s: dict) -> str:
    """The summary of ``asperity derive --window ... --pressure P1 P2 ...``."""
    from ..surface.contact_facets import ASSUMPTIONS
    wi = s["windows"]
    H = s["hardness_Pa"]
    lines = [f"scan: {s['scan']['file']}, {s['scan']['shape'][0]} x {s['scan']['shape'][1]} "
             f"pixels", _estimate_line(wi),
             f"law family over {len(s['pressures_Pa'])} pressures (each window solved as a "
             f"load curve): E* = {s['E_star_Pa']:.4g} Pa, boundary {s['boundary']}, hardness "
             + ("none" if H is None else f"{H:.4g} Pa"),
             *("  " + a for a in ASSUMPTIONS),
             f"contact: {s['contact']}   (mean [min, max] over the windows; each window's "
             f"axes turned to point as the mean t_a at that pressure)", "",
             (f"  {'p (Pa)':<11}{'p/E*':<10}{'contact':<24}" + "".join(
                 f"{_LABELS[k]:<24}" for k in AXES)).rstrip()]
    for r in s["per_pressure"]:
        cells = [r["area_fraction"], *(r[k] for k in AXES)]
        lines.append((f"  {r['pressure_Pa']:<11.4g}{r['p_over_E_star']:<10.3g}" + "".join(
            f"{_f(c['mean'], '.4f')} [{_f(c['min'], '.4f')}, {_f(c['max'], '.4f')}]".ljust(24)
            for c in cells)).rstrip())
    return "\n".join(lines + _window_notes(s))


def plot_window_family(s: dict, path) -> None:
    """mu_a+/- and the contact fraction against p / E*: the windows' mean and min-max."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    rows = s["per_pressure"]
    x = [r["p_over_E_star"] for r in rows]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    nan = float("nan")

    def band(a, key, style, label):
        m = [nan if r[key]["mean"] is None else r[key]["mean"] for r in rows]
        lo = [nan if r[key]["min"] is None else r[key]["min"] for r in rows]
        hi = [nan if r[key]["max"] is None else r[key]["max"] for r in rows]
        line, = a.plot(x, m, style, label=label)
        a.fill_between(x, lo, hi, alpha=0.2, color=line.get_color())
    for k, style in zip(AXES, ("-o", "--o", "-s", "--s")):
        band(ax, k, style, k)
    band(bx, "area_fraction", "-o", "contact fraction")
    for a, label in ((ax, "friction coefficient"), (bx, "contact area fraction")):
        a.set_xscale("log")
        a.set_xlabel("p / E*")
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(s["estimate"], fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def _overlap(origins, w: int) -> bool:
    o = np.asarray(origins)
    for a in range(len(o)):
        d = np.abs(o[a + 1:] - o[a])
        if ((d[:, 0] < w) & (d[:, 1] < w)).any():
            return True
    return False


def _n(k: int, noun: str) -> str:
    """'1 window', '2 windows'."""
    return f"{k} {noun}{'s' * (k != 1)}"


def _f(x, fmt=".6f") -> str:
    return "-" if x is None else format(x, fmt)


def window_text(s: dict) -> str:
    """The summary of ``asperity derive --window``."""
    from ..surface.contact_facets import ASSUMPTIONS
    wi = s["windows"]
    H = s["hardness_Pa"]
    place = "a regular grid" if wi["placement"] == "grid" else \
        f"stratified random (seed {wi['seed']})"
    lines = [f"scan: {s['scan']['file']}, {s['scan']['shape'][0]} x {s['scan']['shape'][1]} "
             f"pixels",
             f"ESTIMATE from {_n(wi['used'], 'window')} of {wi['window_px']} x {wi['window_px']} "
             f"pixels ({wi['window_m'][0]:.4g} x {wi['window_m'][1]:.4g} m), placed on "
             f"{place}; each window is solved on its own: not the whole scan's contact",
             f"elastic contact: p = {s['pressure_Pa']:.4g} Pa (p/E* = "
             f"{s['p_over_E_star']:.3g}), E* = {s['E_star_Pa']:.4g} Pa, boundary "
             f"{s['boundary']}, hardness " + ("none" if H is None else f"{H:.4g} Pa"),
             *("  " + a for a in ASSUMPTIONS),
             f"contact: {s['contact']}   (each window's mu_a+/- along and against its own "
             f"principal direction, turned to point as the mean t_a)", "",
             f"  {'':<18}{'mean':<12}{'sd':<12}{'min':<12}{'max':<12}windows"]
    for key in ("area_fraction", *AXES):
        r = s[key]
        lines.append(f"  {_LABELS[key]:<18}{_f(r['mean']):<12}{_f(r['sd']):<12}"
                     f"{_f(r['min']):<12}{_f(r['max']):<12}{r['n']}")
    pd = s["principal_direction_deg"]
    lines.append(f"  t_a (deg)         {pd['mean']:.2f} (axial mean; windows within "
                 f"{pd['max_deviation']:.2f} deg of it)")
    if s["self_locking_windows"]:
        lines.append(f"SELF-LOCKING in {_n(s['self_locking_windows'], 'window')} (in some "
                     "directions; their values are left out of the spread)")
    return "\n".join(lines + _window_notes(s))


def plot_windows(s: dict, path) -> None:
    """T(psi) of the windows (mean, min-max band) and each window's mu_a+/- against its
    contact fraction."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    psi = [d["psi_deg"] for d in s["directions"]]
    nan = float("nan")
    col = {k: [nan if d[k] is None else d[k] for d in s["directions"]] for k in
           ("mean", "min", "max")}
    ax.fill_between(psi, col["min"], col["max"], alpha=0.3, label="min-max of the windows")
    ax.plot(psi, col["mean"], "-", label="mean of the windows")
    ax.set_xlabel("sliding direction psi (deg from +x)")
    ax.set_ylabel("T(psi)")
    used = [w for w in s["per_window"] if "skipped" not in w]
    af = [w["elastic_contact"]["area_fraction"] for w in used]
    for k, m in (("mu_a_plus", "o"), ("mu_a_minus", "s")):
        bx.plot(af, [nan if w[k] is None else w[k] for w in used], m, label=k)
    bx.set_xlabel("contact area fraction of the window")
    bx.set_ylabel("friction coefficient")
    for a in (ax, bx):
        a.grid(True, alpha=0.3)
        a.legend()
    fig.suptitle(s["estimate"], fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
