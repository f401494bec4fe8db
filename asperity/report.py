"""``asperity report``: regenerate reports/ (Markdown + PNG), the validation record.

Sections: SPEC.md check values, closed form against the spring simulation for a table
of textures (both contact regimes), polar diagrams of both regimes, a loading curve.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .io import write_text_atomic

TEXTURES = [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (30, 30, 0.3, 0.3), (60, 15, 0.3, 0.1)]
PSI_DEG = [0, 30, 60, 89, 90, 120, 180, 240, 300]


def _spec_section() -> list[str]:
    from .closed_form import compute_axis_coefficients, compute_reservoir
    from .texture import WedgeTexture
    rows = []
    a = compute_axis_coefficients(WedgeTexture(30, 10, 0.1, 0.2))
    rows += [("alpha=30, beta=10, mu=0.1/0.2: mu_a+", 0.185697, a["mu_a_plus"]),
             ("same: mu_a-", 0.193238, a["mu_a_minus"]),
             ("same: mu_b+- ", 0.182587, a["mu_b_plus"])]
    b = compute_axis_coefficients(WedgeTexture(5, 5, 0.1, 0.1))
    rows.append(("alpha=beta=5, mu=0.1: mu_a+ = mu_a-", 0.100773, b["mu_a_plus"]))
    r = compute_reservoir(WedgeTexture(30, 30, 0.3, 0.3), np.radians([0.0, 89.0]), "windward")
    rows += [("windward 30/30, mu=0.3: |p(0)|", 1.061, float(np.hypot(*r.p[0]))),
             ("same: p_a(89 deg)", 0.585, float(r.p[1, 0])),
             ("same: p_b(89 deg)", 0.348, float(r.p[1, 1]))]
    out = ["## 1. SPEC.md check values (closed form)", "",
           "| quantity | SPEC.md | asperity | difference |", "|---|---|---|---|"]
    out += [f"| {q} | {s:g} | {v:.6f} | {v - s:+.1e} |" for q, s, v in rows]
    return out + [""]


def _springs_section() -> list[str]:
    from .closed_form import compute_reservoir
    from .springs import SpringModel, simulate_reservoir
    from .texture import WedgeTexture
    psi = np.radians(PSI_DEG)
    models = {"k_f = inf": SpringModel(n_springs=64, steps_per_period=32000),
              "k_f/k_n = 1e5": SpringModel(k_f=1e8, n_springs=64, steps_per_period=32000)}
    out = ["## 2. Closed form against the spring-on-wedge simulation", "",
           "Largest relative deviation |p_springs - p_closed| / |p_closed| over psi = "
           + ", ".join(map(str, PSI_DEG)) + " deg (64 springs per pitch, 32000 samples per "
           "pitch; at psi = 90 deg, along the ridges, the body does not travel across the texture and 32000 springs per pitch sample it instead).", "",
           "| alpha, beta (deg) | mu_alpha, mu_beta | contact | springs | max rel. deviation |",
           "|---|---|---|---|---|"]
    for a, b, ma, mb in TEXTURES:
        t = WedgeTexture(a, b, ma, mb)
        for contact in ("all-faces", "windward"):
            cf = compute_reservoir(t, psi, contact)
            for name, m in models.items():
                sim = simulate_reservoir(t, psi, m, contact)
                ok = ~(cf.locked | cf.set_valued | sim.locked)
                dev = np.hypot(*(sim.p[ok] - cf.p[ok]).T) / np.hypot(*cf.p[ok].T)
                out.append(f"| {a}, {b} | {ma}, {mb} | {contact} | {name} | {dev.max():.2e} |")
    return out + [""]


def _figures(folder: Path) -> list[str]:
    from .closed_form import compute_reservoir
    from .derive import derive
    from .plotting import plot_derivation
    from .texture import WedgeTexture
    out = ["## 3. Polar reservoirs of both contact regimes", ""]
    for contact in ("all-faces", "windward"):
        t = WedgeTexture(30, 30, 0.3, 0.3)
        d = derive(t, contact, "closed-form", 360)
        other = "windward" if contact == "all-faces" else "all-faces"
        name = f"polar_{contact}.png"
        plot_derivation(d, folder / name, other=compute_reservoir(t, d.reservoir.psi, other))
        s = d.associativity
        out += [f"![{contact}]({name})", "",
                f"{contact}: admissible = {d.admissibility.admissible}, max |L - dT/dpsi| = "
                f"{s.max_deviation:.4f}, max |L| = {s.max_lateral:.4f}.", ""]
    return out


def _loading_section(folder: Path) -> list[str]:
    from .io import save_figure_atomic
    from .plotting import _plt
    from .springs import SpringModel, simulate_loading_curve
    from .texture import WedgeTexture
    t = WedgeTexture(5, 5, 0.1, 0.1, height=1e-6)
    m = SpringModel(k_n=1e3, k_f=1e7, preload=2e-3)
    c = simulate_loading_curve(t, 0.0, m)
    plt = _plt()
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
    return ["## 4. From stick to full sliding (finite k_f)", "",
            "![loading curve](loading_curve.png)", "",
            f"alpha = beta = 5 deg, mu = 0.1, k_f/k_n = 1e4: k_t = {c.k_t:.4e} Pa/m, "
            f"measured initial slope {c.k_t_measured:.4e} Pa/m, steady mu {c.mu_steady:.6f} "
            "(closed form 0.100773).", ""]


def run(folder: str | Path = "reports") -> Path:
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    lines = ["# asperity validation report", "",
             "Generated by `asperity report`; do not edit by hand.", ""]
    lines += _spec_section() + _springs_section() + _figures(folder) + _loading_section(folder)
    path = folder / "REPORT.md"
    write_text_atomic(path, "\n".join(lines))
    return path
