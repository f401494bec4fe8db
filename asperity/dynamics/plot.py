"""Figures of the Moreau solver's results: the path of a sliding body."""
from __future__ import annotations

import math


def plot_path(path, res, law, angle_deg: float) -> None:
    """The path from the origin to the rest point, with the launch direction."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    ax.plot(res.q[:, 0], res.q[:, 1], color="tab:blue", lw=2, label=f"path ({law.name})")
    d = max(float(abs(res.q).max()), 1e-12)
    a = math.radians(angle_deg)
    ax.plot([0, d * math.cos(a)], [0, d * math.sin(a)], color="0.5", ls="--", lw=1,
            label="initial velocity direction")
    ax.plot(0, 0, "ko", ms=4)
    ax.plot(res.q_final[0], res.q_final[1], "s", color="tab:red", ms=6,
            label="rest" if res.stop_step is not None else "end (still moving)")
    ax.set_xlabel("x along t_a (m)")
    ax.set_ylabel("y along t_b (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(law.description, fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)


#: outlines of the body drawn along its path (the start and the end among them)
OUTLINES = 9


def plot_body_path(path, res, outline, law, angle_deg: float, title: str = "") -> None:
    """The path of a body's centre of mass with the body's outline (``outline`` (k, 2), body
    frame, m; NaN rows separate loops) turned by theta at :data:`OUTLINES` times spread over
    the motion, and an orientation mark (a line from the centre along the body's x axis to
    its outline); the launch direction dashed."""
    import numpy as np

    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    q = res.q
    outline = np.asarray(outline, dtype=float)
    reach = float(np.nanmax(np.hypot(outline[:, 0], outline[:, 1]))) if outline.size else 0.0
    mark = max(reach, 1e-12)
    t = res.t
    k = len(t)
    if k > 1 and t[-1] > t[0]:
        times = np.linspace(t[0], t[-1], OUTLINES)
        idx = sorted({int(min(np.searchsorted(t, s), k - 1)) for s in times})
    else:
        idx = [k - 1]
    cmap = plt.get_cmap("viridis")
    for j, i in enumerate(idx):
        c, s = math.cos(q[i, 2]), math.sin(q[i, 2])
        ox = q[i, 0] + c * outline[:, 0] - s * outline[:, 1]
        oy = q[i, 1] + s * outline[:, 0] + c * outline[:, 1]
        col = cmap(j / max(len(idx) - 1, 1))
        ax.plot(ox, oy, color=col, lw=1.2,
                label=f"body at t = {t[i]:.3g} s" if j in (0, len(idx) - 1) else None)
        ax.plot([q[i, 0], q[i, 0] + c * mark], [q[i, 1], q[i, 1] + s * mark], color=col,
                lw=1.0)
        ax.plot(q[i, 0], q[i, 1], "o", color=col, ms=2.5)
    ax.plot(q[:, 0], q[:, 1], color="tab:blue", lw=2, label=f"path of the centre ({law.name})")
    d = max(float(np.abs(q[:, :2]).max()), reach, 1e-12)
    a = math.radians(angle_deg)
    ax.plot([0, d * math.cos(a)], [0, d * math.sin(a)], color="0.5", ls="--", lw=1,
            label="initial velocity direction")
    ax.plot(res.q_final[0], res.q_final[1], "s", color="tab:red", ms=6,
            label="rest" if res.stop_time is not None else "end (still moving)")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    import textwrap
    lines = (title or law.description).splitlines()
    ax.set_title("\n".join(w for line in lines for w in textwrap.wrap(line, 95)), fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=120)
    plt.close(fig)
