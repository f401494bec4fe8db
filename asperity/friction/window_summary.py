"""The summary of a windowed contact estimate (:mod:`.elastic_windows`): the mean and the
spread between windows, as JSON, text and a figure.  Every line and key says that it is an
estimate from K windows of W pixels, never the whole scan's contact."""
from __future__ import annotations

import math

import numpy as np

from .. import __version__
from ..errors import InputError

AXES = ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus")
#: a window needs at least this share of its pixels defined
MIN_DEFINED_SHARE = 0.8
_LABELS = {"area_fraction": "contact fraction", "mu_a_plus": "mu_a+", "mu_a_minus": "mu_a-",
           "mu_b_plus": "mu_b+", "mu_b_minus": "mu_b-"}


def spread(values) -> dict:
    """mean, sd (n - 1; null for one value), min, max and n of the finite values."""
    v = np.array([x for x in values if x is not None and math.isfinite(x)], dtype=float)
    if v.size == 0:
        return {"mean": None, "sd": None, "min": None, "max": None, "n": 0}
    return {"mean": float(v.mean()), "sd": float(v.std(ddof=1)) if v.size > 1 else None,
            "min": float(v.min()), "max": float(v.max()), "n": int(v.size)}


def axial_spread(degrees) -> dict:
    """Mean of axes (angles modulo 180 deg) and the largest deviation from it."""
    a = np.radians(np.asarray(degrees, dtype=float))
    if a.size == 0:
        return {"mean": None, "max_deviation": None}
    m = 0.5 * np.angle(np.exp(2j * a).sum())
    dev = np.abs((a - m + 0.5 * np.pi) % np.pi - 0.5 * np.pi)
    return {"mean": float(np.degrees(m) % 180.0), "max_deviation": float(np.degrees(dev.max()))}


def aligned(r: dict, mean_deg: float) -> tuple[dict, bool]:
    """A window's axis coefficients along the common principal direction ``mean_deg``:
    a principal direction is an axis (in [0, 180)), so a window whose t_a points the other
    way (more than 90 deg from the mean's) has its + and - exchanged; (axes, reversed)."""
    d = (r["principal_direction_deg"] - mean_deg + 180.0) % 360.0 - 180.0
    if abs(d) <= 90.0:
        return {a: r[a] for a in AXES}, False
    return {"mu_a_plus": r["mu_a_minus"], "mu_a_minus": r["mu_a_plus"],
            "mu_b_plus": r["mu_b_minus"], "mu_b_minus": r["mu_b_plus"]}, True


def summarise(plan, results: list, placement: str, seed: int) -> dict:
    """The JSON object of ``asperity derive --window`` (README)."""
    from .reservoir import directions
    src, w, e = plan.heights, plan.window, plan.elastic
    used = [r for r in results if "skipped" not in r]
    if not used:
        raise InputError(f"window: none of the {len(results)} windows of {w} x {w} pixels "
                         f"has enough defined pixels (at least "
                         f"{100 * MIN_DEFINED_SHARE:.0f} %); place them elsewhere (--windows, "
                         f"--window-placement) or lower --window")
    nx, ny = src.shape
    k = len(used)
    what = (f"estimate from {k} windows of {w} x {w} pixels ({w * src.dx:.4g} x "
            f"{w * src.dy:.4g} m) of a {nx} x {ny} scan, each solved on its own: not the "
            f"whole scan's contact")
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
        "windows": {"window_px": w, "window_m": [w * src.dx, w * src.dy],
                    "asked": len(results), "used": k, "skipped": len(results) - k,
                    "placement": placement, "seed": seed if placement == "random" else None,
                    "overlap": _overlap(plan.origins, w), "min_defined_share": MIN_DEFINED_SHARE},
        "E_star_Pa": e.E_star, "pressure_Pa": e.pressure, "p_over_E_star": e.pressure / e.E_star,
        "boundary": c0["boundary"], "hardness_Pa": e.hardness, "contact": plan.contact,
        "area_fraction": spread([r["elastic_contact"]["area_fraction"] for r in used]),
        **{a: spread([ax[a] for ax, _ in axes]) for a in AXES},
        "principal_direction_deg": pd,
        "self_locking_windows": sum(1 for r in used if r["self_locking"]),
        "directions": dirs, "per_window": per}


def _overlap(origins, w: int) -> bool:
    o = np.asarray(origins)
    for a in range(len(o)):
        d = np.abs(o[a + 1:] - o[a])
        if ((d[:, 0] < w) & (d[:, 1] < w)).any():
            return True
    return False


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
             f"ESTIMATE from {wi['used']} windows of {wi['window_px']} x {wi['window_px']} "
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
        lines.append(f"SELF-LOCKING in {s['self_locking_windows']} windows (in some "
                     "directions; their values are left out of the spread)")
    if wi["skipped"]:
        bad = [w for w in s["per_window"] if "skipped" in w]
        lines.append(f"{wi['skipped']} of {wi['asked']} windows skipped: "
                     + "; ".join(f"at pixel {b['origin_px']}: {b['skipped']}" for b in bad[:3])
                     + (" ..." if len(bad) > 3 else ""))
    if wi["overlap"]:
        lines.append("windows overlap (the scan holds fewer than that many windows of that "
                     "size): they are not independent samples")
    return "\n".join(lines)


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
