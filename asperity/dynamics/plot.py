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
