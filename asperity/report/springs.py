"""Report section: the spring-on-wedge simulation against the closed form, for a table of
textures in both contact regimes."""
from __future__ import annotations

from pathlib import Path

import numpy as np

TEXTURES = [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (30, 30, 0.3, 0.3), (60, 15, 0.3, 0.1)]
PSI_DEG = [0, 30, 60, 89, 90, 120, 180, 240, 300]


def section(folder: Path) -> list[str]:
    from ..friction.faces import compute_reservoir
    from ..texture.spring_model import SpringModel
    from ..texture.springs import simulate_reservoir
    from ..texture.wedges import WedgeTexture
    psi = np.radians(PSI_DEG)
    models = {"k_f = inf": SpringModel(n_springs=64, steps_per_period=32000),
              "k_f/k_n = 1e5": SpringModel(k_f=1e8, n_springs=64, steps_per_period=32000)}
    out = ["## Closed form against the spring-on-wedge simulation", "",
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
