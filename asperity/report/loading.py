"""Report section: the loading curve of the spring model from stick to full sliding
(finite flexural stiffness k_f)."""
from __future__ import annotations

from pathlib import Path


def section(folder: Path) -> list[str]:
    from ..io import pyplot, save_figure_atomic
    from ..texture.spring_model import SpringModel
    from ..texture.springs import simulate_loading_curve
    from ..texture.wedges import WedgeTexture
    t = WedgeTexture(5, 5, 0.1, 0.1, height=1e-6)
    m = SpringModel(k_n=1e3, k_f=1e7, preload=2e-3)
    c = simulate_loading_curve(t, 0.0, m)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(c.displacement * 1e6, c.tangential_stress / c.normal_stress[-1], label="springs")
    x = c.displacement[c.displacement < 1.5 * c.mu_steady * c.normal_stress[-1] / c.k_t]
    ax.plot(x * 1e6, c.k_t * x / c.normal_stress[-1], "--", label="k_t u (stick)")
    ax.axhline(c.mu_steady, color="0.5", lw=0.8)
    ax.set_xlabel("displacement along t_a (um)")
    ax.set_ylabel("tangential / normal stress")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure_atomic(fig, folder / "loading_curve.png", dpi=110)
    plt.close(fig)
    return ["## From stick to full sliding (finite k_f)", "",
            "![loading curve](loading_curve.png)", "",
            f"alpha = beta = 5 deg, mu = 0.1, k_f/k_n = 1e4: k_t = {c.k_t:.4e} Pa/m, "
            f"measured initial slope {c.k_t_measured:.4e} Pa/m, steady mu {c.mu_steady:.6f} "
            "(closed form 0.100773).", ""]
