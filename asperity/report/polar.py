"""Report section: polar diagrams of the reservoir in both contact regimes."""
from __future__ import annotations

from pathlib import Path


def section(folder: Path) -> list[str]:
    from ..friction.derive import derive
    from ..friction.faces import compute_reservoir
    from ..friction.plot import plot_derivation
    from ..texture.wedges import WedgeTexture
    out = ["## Polar reservoirs of both contact regimes", ""]
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
