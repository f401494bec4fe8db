"""Figures of a friction law: C, D, the data it was fitted to and the sliding rule."""
from __future__ import annotations

import numpy as np

from .fitting import GaugeLaw
from .geometry import unit


def _closed(curve: np.ndarray) -> np.ndarray:
    return np.vstack([curve, curve[:1]])


def draw_law(ax, gl: GaugeLaw, *, arrows: int = 24, color: str = "tab:blue") -> None:
    """C (solid), D (dashed, scaled like C's hull), the data (dots) and the sliding rule
    (arrows from |p| s to p: how far the force turns away from the sliding direction)."""
    law = gl.law
    step = max(1, gl.data.psi.size // 120)
    ax.plot(gl.data.p[::step, 0], gl.data.p[::step, 1], "o", color="k", ms=3, mfc="none",
            mew=0.6, label="data p(psi)", zorder=3)
    phi = np.linspace(0.0, 2.0 * np.pi, 1441)
    C = law.C.radial(phi)[:, None] * unit(phi)
    if gl.kind == "star":
        C = _closed(law.C.points)
    ax.plot(C[:, 0], C[:, 1], color=color, lw=2.0, label="C (reservoir)")
    if gl.kind == "star":
        Db = _closed(law.D.boundary.points)
        ax.plot(Db[:, 0], Db[:, 1], color="tab:orange", lw=1.2, ls="--",
                label="D (sliding set, scale arbitrary)")
    elif law.D != law.C:
        rD = law.D.radial(phi)
        Dc = (rD * np.min(law.C.radial(phi) / rD))[:, None] * unit(phi)
        ax.plot(Dc[:, 0], Dc[:, 1], color="tab:orange", lw=1.2, ls="--",
                label="D (sliding set, scaled inside C)")
    else:
        ax.plot([], [], color="tab:orange", lw=1.2, ls="--", label="D = C (associated)")
    psi = np.radians(gl.principal_direction_deg) + 2 * np.pi * np.arange(arrows) / arrows
    f = law.force(psi)
    r = np.hypot(f.p[:, 0], f.p[:, 1])
    s = f.s
    for k in range(arrows):
        start = r[k] * s[k]
        ax.plot([0, start[0]], [0, start[1]], color="0.65", lw=0.6, ls=":")
        ax.annotate("", xy=(f.p[k, 0], f.p[k, 1]), xytext=(start[0], start[1]),
                    arrowprops=dict(arrowstyle="->", color="tab:green", lw=1.0))
    ax.plot([], [], color="tab:green", lw=1.0, label="sliding rule: |p| s -> p")
    for k in np.flatnonzero(f.set_valued):
        ax.plot(*np.array([f.p_minus[k], f.p_plus[k]]).T, color="crimson", lw=2.5, alpha=0.6)
    ax.axhline(0, color="0.8", lw=0.5)
    ax.axvline(0, color="0.8", lw=0.5)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.2)


def _law_title(gl: GaugeLaw) -> str:
    tex = gl.source.get("texture", {})
    if tex.get("kind") in ("wedge", "gaussian-wedge"):
        what = (f"alpha={tex.get('alpha_deg'):g}, beta={tex.get('beta_deg'):g} deg, "
                f"mu_alpha={tex.get('mu_alpha'):g}, mu_beta={tex.get('mu_beta'):g}")
    else:
        what = str(tex.get("source", tex.get("kind", "surface")))
    if tex.get("rule"):
        what = (f"rule {tex['rule']}: mu_f = {tex.get('mu_f'):g}, mu_b = {tex.get('mu_b'):g}, "
                f"mu_t = {tex.get('mu_t'):g}")
    return f"{gl.kind} law, {gl.source.get('contact')}\n{what}"


def plot_law(gl: GaugeLaw, path, title: str | None = None) -> None:
    """The law in the force plane and T, L against psi (law: lines, data: dots)."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.2), gridspec_kw={"width_ratios": [1.05, 1]})
    draw_law(ax, gl)
    ax.set_xlabel("p_a" if gl.principal_direction_deg == 0 else "p_x")
    ax.set_ylabel("p_b" if gl.principal_direction_deg == 0 else "p_y")
    ax.set_title(title or _law_title(gl), fontsize=10)
    ax.legend(loc="lower left", fontsize=7, framealpha=0.9)
    psi = np.linspace(0, 2 * np.pi, 1441)
    f = gl.force(psi)
    deg = np.degrees(psi)
    T = np.where(f.set_valued, np.nan, f.tangential)
    L = np.where(f.set_valued, np.nan, f.lateral)
    ax2.plot(deg, T, color="k", lw=1.2, label="law: T = p.s")
    ax2.plot(deg, L, color="tab:green", lw=1.2, label="law: L = p.s_perp")
    d = gl.data
    ok = d.limit == 0
    s = unit(d.psi[ok])
    sp = unit(d.psi[ok] + 0.5 * np.pi)
    step = max(1, ok.sum() // 90)
    dd = np.degrees(d.psi[ok])[::step]
    ax2.plot(dd, np.einsum("ij,ij->i", d.p[ok], s)[::step], "o", ms=2.5, color="k", mfc="none",
             label="data T")
    ax2.plot(dd, np.einsum("ij,ij->i", d.p[ok], sp)[::step], "o", ms=2.5, color="tab:green",
             mfc="none", label="data L")
    ax2.axhline(0, color="0.7", lw=0.5)
    ax2.set_xlim(0, 360)
    ax2.set_xticks(range(0, 361, 45))
    ax2.set_xlabel("sliding direction psi (deg)")
    ax2.set_ylabel("force / normal load")
    r = gl.fit
    ax2.set_title(f"max radial error {r.max_radial_error:.2e}, max angle "
                  f"{r.max_angle_error_deg:.3g} deg", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
