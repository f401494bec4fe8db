"""The figure of the Abaqus routines' sign and side conventions
(``reports/fe_abaqus_conventions.png``): which body carries the texture, the slip of the
secondary surface, the force on it, and the law's frame in the tangent plane.

Regenerate:  python -c "from asperity.fe.conventions_figure import draw; draw()"
"""
from __future__ import annotations

import math

import numpy as np

DEFAULT = "reports/fe_abaqus_conventions.png"
#: an asymmetric truncated ellipse for the plan view (mu_a+, mu_a-, mu_b+, mu_b-)
AXES = (0.2, 0.08, 0.12, 0.15)
THETA = math.radians(35.0)                    # the law's +x from local direction 1


def _saw(x0, x1, y, h, n, up=True):
    xs = np.linspace(x0, x1, 2 * n + 1)
    ys = y + np.where(np.arange(xs.size) % 2 == 1, h if up else -h, 0.0)
    return xs, ys


def _side(ax, textured_main: bool) -> None:
    """Side view: main body below, secondary above, slip of the secondary to the right."""
    ax.set_xlim(-0.2, 4.2)
    ax.set_ylim(-1.3, 2.3)
    ax.set_aspect("equal")
    ax.axis("off")
    if textured_main:
        xs, ys = _saw(0, 4, 0.0, 0.18, 8)
        ax.fill_between(xs, -1.0, ys, color="#c9c9c9", lw=0)
        ax.plot(xs, ys, color="k", lw=1)
        ax.add_patch(_rect(0.8, 0.18, 2.4, 0.9, "#9ecae1"))
        title = "texture on the MAIN surface\nFRIC PROPS(3) = +1, VFRIC props(4) = +1"
        force = "force on the secondary:\n$-f_N\\,R(\\theta)\\,p(\\varphi-\\theta)$"
    else:
        ax.fill_between([0, 4], -1.0, 0.0, color="#c9c9c9", lw=0)
        ax.plot([0, 4], [0, 0], color="k", lw=1)
        xs, ys = _saw(0.8, 3.2, 0.18, 0.18, 5, up=False)
        ax.fill_between(xs, ys, 1.08, color="#9ecae1", lw=0)
        ax.plot(xs, ys, color="k", lw=1)
        title = "texture on the SECONDARY surface\nFRIC PROPS(3) = -1, VFRIC props(4) = -1"
        force = ("force on the secondary:\n$+f_N\\,R(\\theta)\\,p(\\varphi+180^\\circ-\\theta)$"
                 "\n(the main surface slides\nover the texture along $-t_1$)")
    ax.text(2.0, 0.63, "secondary (slave)", ha="center", va="center", fontsize=9)
    ax.text(2.0, -0.55, "main (master)", ha="center", va="center", fontsize=9)
    ax.annotate("", xy=(3.9, 1.45), xytext=(2.9, 1.45),
                arrowprops={"arrowstyle": "-|>", "color": "tab:blue", "lw": 2})
    ax.text(3.4, 1.6, "slip DGAM, $t_1$\n(secondary over main)", ha="center", va="bottom",
            fontsize=8, color="tab:blue")
    ax.annotate("", xy=(1.0, 0.32), xytext=(2.0, 0.32),
                arrowprops={"arrowstyle": "-|>", "color": "tab:red", "lw": 2})
    ax.text(0.1, 1.25, force, fontsize=8, color="tab:red", va="bottom")
    ax.text(2.0, -1.25, "TAU = minus that force per area: it has the sign of the slip",
            ha="center", fontsize=8)
    ax.set_title(title, fontsize=9)


def _rect(x, y, w, h, color):
    from matplotlib.patches import Rectangle
    return Rectangle((x, y), w, h, color=color, lw=1, ec="k")


def plan_law():
    """The law of the plan view in the local frame (t1, t2): the associated law of the
    truncated ellipse AXES turned by THETA, so its force for sliding along t1 is
    R(THETA) p(-THETA) of the unturned law (what FRIC returns per unit pressure)."""
    from ..laws.sets import TruncatedEllipse
    from ..laws.walker_leine import associated
    return associated(TruncatedEllipse(*AXES, theta=THETA))


def _plan(ax) -> None:
    """Plan view of the tangent plane: t1, t2 = n x t1, the law's +x at theta, C and the
    force p for sliding along t1 (law angle -theta)."""
    law = plan_law()
    u = np.linspace(0, 2 * math.pi, 721)
    r = law.C.radial(u)
    ax.fill(r * np.cos(u), r * np.sin(u), color="#fdd0a2", alpha=0.7, lw=1, ec="tab:orange")
    ct, st = math.cos(THETA), math.sin(THETA)
    gx, gy = law.force(np.array([0.0])).p[0]       # sliding along t1: psi = 0 here
    kw = {"arrowprops": {"arrowstyle": "-|>", "lw": 1.8}}
    ax.annotate("", xy=(0.27, 0), xytext=(0, 0), **{**kw, "arrowprops": {
        **kw["arrowprops"], "color": "tab:blue"}})
    ax.text(0.275, -0.02, "$t_1$ (slip)", color="tab:blue", fontsize=9, va="top")
    ax.annotate("", xy=(0, 0.22), xytext=(0, 0), **{**kw, "arrowprops": {
        **kw["arrowprops"], "color": "0.3"}})
    ax.text(0.005, 0.225, "$t_2 = n\\times t_1$", fontsize=9, color="0.3")
    ax.annotate("", xy=(0.25 * ct, 0.25 * st), xytext=(0, 0), **{**kw, "arrowprops": {
        **kw["arrowprops"], "color": "tab:green"}})
    ax.text(0.255 * ct, 0.255 * st, "law +x\n(props(1:3) projected;\nPROPS(2) = $\\theta$)",
            color="tab:green", fontsize=8)
    arc = np.linspace(0, THETA, 30)
    ax.plot(0.09 * np.cos(arc), 0.09 * np.sin(arc), color="tab:green", lw=1)
    ax.text(0.1 * math.cos(THETA / 2), 0.1 * math.sin(THETA / 2), "$\\theta$",
            color="tab:green", fontsize=9)
    ax.annotate("", xy=(gx, gy), xytext=(0, 0), **{**kw, "arrowprops": {
        **kw["arrowprops"], "color": "tab:purple"}})
    ax.text(0.02, -0.06, "$p(\\varphi-\\theta)$: the law's force for\nsliding along $t_1$ "
            "(points along\nthe slip; on the boundary of C)", fontsize=8, color="tab:purple",
            va="top")
    ax.text(-0.25, 0.2, "C: the forces per unit\nnormal load the law\ncan hold (stick)",
            fontsize=8, color="tab:orange")
    ax.set_xlim(-0.27, 0.4)
    ax.set_ylim(-0.2, 0.3)
    ax.set_aspect("equal")
    ax.axhline(0, color="0.85", lw=0.5, zorder=0)
    ax.axvline(0, color="0.85", lw=0.5, zorder=0)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title("tangent plane seen from the main surface's normal n\n"
                 "VFRIC: $t_1$ = dirCosSl, n = dirCosN; FRIC: local directions 1, 2",
                 fontsize=9)


def figure():
    """The figure (side views with the texture on either surface, the plan view)."""
    from ..io import pyplot
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.6), gridspec_kw={"width_ratios": [1, 1, 1.05]})
    _side(axes[0], True)
    _side(axes[1], False)
    _plan(axes[2])
    fig.suptitle("Abaqus FRIC / VFRIC / VFRICTION written by asperity: sides and signs",
                 fontsize=11)
    fig.tight_layout()
    return fig


def draw(path: str = DEFAULT) -> str:
    """Draw the figure into ``path`` (written atomically) and return the path."""
    from ..io import pyplot, save_figure_atomic
    fig = figure()
    save_figure_atomic(fig, path, dpi=110)
    pyplot().close(fig)
    return path
