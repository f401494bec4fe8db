"""Report section: the SPEC.md check values against the closed forms."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def section(folder: Path) -> list[str]:
    from ..friction.faces import compute_axis_coefficients, compute_reservoir
    from ..texture.wedges import WedgeTexture
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
    out = ["## SPEC.md check values (closed form)", "",
           "| quantity | SPEC.md | asperity | difference |", "|---|---|---|---|"]
    out += [f"| {q} | {s:g} | {v:.6f} | {v - s:+.1e} |" for q, s, v in rows]
    return out + [""]
