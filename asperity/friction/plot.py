"""Figures of a directional-friction result: the polar reservoir, T and L against psi,
and a height-map preview of a surface.  matplotlib is imported only when a figure is drawn.
"""
from __future__ import annotations

import math

import numpy as np

from ..io import pyplot

REGIME_STYLE = {
    "all-faces": {"color": "tab:blue", "label": "all faces (compliant springs)"},
    "windward": {"color": "tab:red", "label": "windward only (rigid asperities)"},
}


def _branches(res):
    """Split the reservoir curve where it self-locks or jumps (set-valued directions)."""
    ok = ~(res.locked | res.set_valued)
    pts, cur = [], []
    for k in range(res.psi.size):
        if ok[k]:
            cur.append(res.p[k])
        elif cur:
            pts.append(np.array(cur))
            cur = []
    if cur:
        if pts and ok[0]:
            pts[0] = np.vstack([np.array(cur), pts[0]])   # wrap around psi = 0
        else:
            pts.append(np.array(cur))
    if ok.all() and pts:
        pts[0] = np.vstack([pts[0], pts[0][:1]])          # close the curve
    return pts


def draw_reservoir(ax, res, *, style=None, arrows: int = 12, faint: bool = False):
    """Draw the reservoir curve p(psi) of ``res`` into the (p_a, p_b) plane ``ax``."""
    st = style or REGIME_STYLE.get(res.contact, {"color": "k", "label": res.contact})
    kw = dict(color=st["color"], lw=1.0 if faint else 2.0, alpha=0.35 if faint else 1.0)
    for i, b in enumerate(_branches(res)):
        ax.plot(b[:, 0], b[:, 1], ls="--" if faint else "-",
                label=None if i else st["label"] + (" (for comparison)" if faint else ""), **kw)
    # set-valued directions: the segment between the limits on either side
    for k in np.flatnonzero(res.set_valued & ~res.locked):
        n = res.psi.size
        a, b = res.p[(k - 1) % n], res.p[(k + 1) % n]
        if np.all(np.isfinite(a)) and np.all(np.isfinite(b)):
            ax.plot([a[0], b[0]], [a[1], b[1]], color=st["color"], lw=kw["lw"], ls=":",
                    alpha=kw["alpha"])
    if faint or arrows <= 0:
        return
    n = res.psi.size
    step = max(1, n // arrows)
    scale = np.nanmax(np.hypot(*res.p[~res.locked].T)) if (~res.locked).any() else 1.0
    for k in range(0, n, step):
        s = np.array([math.cos(res.psi[k]), math.sin(res.psi[k])])
        if res.locked[k]:
            ax.plot([0, 1.15 * scale * s[0]], [0, 1.15 * scale * s[1]], color="crimson",
                    lw=2.5, alpha=0.8)
            continue
        p = res.p[k]
        ax.plot([0, 1.1 * scale * s[0]], [0, 1.1 * scale * s[1]], color="0.6", lw=0.6, ls=":")
        ax.annotate("", xy=(p[0], p[1]), xytext=(0, 0),
                    arrowprops=dict(arrowstyle="->", color=st["color"], lw=1.0, alpha=0.8))


def plot_derivation(d, path, *, other=None) -> None:
    """Polar reservoir (with sliding directions and force arrows) and T/L against psi.

    ``other``: a Reservoir of the other contact regime, drawn faint for comparison.
    """
    from ..io import save_figure_atomic
    plt = pyplot()
    res = d.reservoir
    tex = d.texture
    surface = getattr(tex, "kind", "") == "surface"
    if surface and tex.preview is not None:
        fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(16.5, 5.2),
                                           gridspec_kw={"width_ratios": [1.05, 1, 0.9]})
        draw_height_preview(ax3, tex, d.principal_direction_deg)
    else:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.2),
                                      gridspec_kw={"width_ratios": [1.05, 1]})
    if other is not None:
        draw_reservoir(ax, other, faint=True)
    draw_reservoir(ax, res)
    ax.axhline(0, color="0.8", lw=0.5)
    ax.axvline(0, color="0.8", lw=0.5)
    ax.set_aspect("equal", adjustable="datalim")
    if surface:
        ax.set_xlabel(r"$p_x$")
        ax.set_ylabel(r"$p_y$")
        info = tex.info
        mu = info.get("mu")
        ax.set_title(f"reservoir p(psi), {d.contact}\n{info.get('source')}, {tex.n_facets} facets, "
                     + (f"mu={mu:g}" if mu is not None else "friction map"), fontsize=10)
    else:
        ax.set_xlabel(r"$p_a$ (along $t_a$, across the ridges)")
        ax.set_ylabel(r"$p_b$ (along $t_b$, along the ridges)")
        ax.set_title(f"reservoir p(psi), {d.contact}\n"
                     f"alpha={tex.alpha_deg:g}, beta={tex.beta_deg:g} deg, "
                     f"mu_alpha={tex.mu_alpha:g}, mu_beta={tex.mu_beta:g}", fontsize=10)
    ax.plot([], [], color="0.6", lw=0.6, ls=":", label="sliding direction s")
    if res.locked.any():
        ax.plot([], [], color="crimson", lw=2.5, label="self-locking directions")
    ax.legend(loc="lower left", fontsize=8, framealpha=0.9)
    ax.grid(alpha=0.2)

    deg = np.degrees(res.psi)
    ok = ~(res.locked | res.set_valued)   # break the curves at jumps and locks
    T = np.where(ok, res.tangential, np.nan)
    L = np.where(ok, res.lateral, np.nan)
    ax2.plot(deg, T, color="k", label="tangential T = p.s")
    ax2.plot(deg, L, color="tab:green", label="lateral L = p.s_perp")
    if res.locked.any():
        for x in deg[res.locked]:
            ax2.axvline(x, color="crimson", alpha=0.25, lw=3)
    ax2.axhline(0, color="0.7", lw=0.5)
    ax2.set_xlabel("sliding direction psi (deg from " + ("+x)" if surface else "t_a)"))
    ax2.set_ylabel("force / normal load")
    ax2.set_xlim(0, 360)
    ax2.set_xticks(range(0, 361, 45))
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    a = d.axes
    def fmt(x):
        return "inf" if not math.isfinite(x) else f"{x:.4f}"
    if surface:
        th = d.principal_direction_deg
        for x in (th, th + 180.0):
            ax2.axvline(x % 360.0, color="tab:orange", lw=1.0, ls="--")
    ax2.set_title(f"mu_a+={fmt(a['mu_a_plus'])}  mu_a-={fmt(a['mu_a_minus'])}  "
                  f"mu_b+={fmt(a['mu_b_plus'])}  mu_b-={fmt(a['mu_b_minus'])}", fontsize=10)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def draw_height_preview(ax, surface, principal_deg: float) -> None:
    """Height map (or binned mesh heights) in um, with the principal direction t_a
    (across the lay, the principal axis) drawn through the centre."""
    z = surface.preview
    lx, ly = surface.extent
    im = ax.imshow((z - np.nanmean(z)).T * 1e6, origin="lower", cmap="viridis",
                   extent=(0, lx * 1e3, 0, ly * 1e3), interpolation="nearest")
    ax.figure.colorbar(im, ax=ax, fraction=0.046, pad=0.04, label="height (um)")
    cx, cy = 0.5 * lx * 1e3, 0.5 * ly * 1e3
    r = 0.4 * min(lx, ly) * 1e3
    t = math.radians(principal_deg)
    ax.annotate("", xy=(cx + r * math.cos(t), cy + r * math.sin(t)),
                xytext=(cx - r * math.cos(t), cy - r * math.sin(t)),
                arrowprops=dict(arrowstyle="->", color="tab:orange", lw=2.0))
    ax.text(cx + r * math.cos(t), cy + r * math.sin(t), f"  t_a {principal_deg:.1f} deg",
            color="tab:orange", fontsize=9, fontweight="bold")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("height map, principal direction t_a", fontsize=10)
