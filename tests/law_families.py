"""A law family of four star members from wedge textures of different asymmetry (one
source; shared by the family tests): strongly different members, built in a second."""
from __future__ import annotations

from dataclasses import replace
from functools import cache

from asperity.friction.derive import derive
from asperity.laws.family import GaugeFamily
from asperity.laws.fitting import fit_derivation
from asperity.texture.wedges import WedgeTexture

PRESSURES = (1e6, 3e6, 2e7, 5e7)


def contact(p):
    return {"area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "periodic", "hardness_Pa": None,
            "iterations": 10, "residual": 1e-9, "converged": True}


@cache
def four_members() -> GaugeFamily:
    laws = [fit_derivation(derive(WedgeTexture(a, b, 0.1, 0.1), "all-faces", "closed-form",
                                  72), "star")
            for a, b in ((10, 30), (14, 26), (18, 22), (20, 20))]
    src = laws[0].source
    return GaugeFamily(PRESSURES, tuple(replace(gl, source={**src, "elastic_contact":
                                                            contact(p)})
                                        for gl, p in zip(laws, PRESSURES)))
