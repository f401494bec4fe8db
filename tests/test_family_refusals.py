"""A law family's refusals name its whole pressure range, first to last member, whatever
the number of members: a family used without a pressure, and a pressure outside it (no
extrapolation); the range's ends themselves are members, taken as they are."""
from __future__ import annotations

from dataclasses import replace

import pytest

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.laws.family import GaugeFamily, law_at
from asperity.laws.fitting import fit_derivation
from asperity.texture.wedges import WedgeTexture

PRESSURES = (1e6, 3e6, 2e7, 5e7)


def contact(p):
    return {"area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "periodic", "hardness_Pa": None,
            "iterations": 10, "residual": 1e-9, "converged": True}


@pytest.fixture(scope="module")
def family():
    laws = [fit_derivation(derive(WedgeTexture(a, b, 0.1, 0.1), "all-faces", "closed-form",
                                  72), "star")
            for a, b in ((10, 30), (14, 26), (18, 22), (20, 20))]
    src = laws[0].source
    return GaugeFamily(PRESSURES, tuple(replace(gl, source={**src, "elastic_contact":
                                                            contact(p)})
                                        for gl, p in zip(laws, PRESSURES)))


@pytest.mark.parametrize("n", [2, 3, 4])
def test_refusals_name_the_first_and_the_last_member(family, n):
    fam = GaugeFamily(family.pressures[:n], family.members[:n])
    first, last = f"{PRESSURES[0]:g}", f"{PRESSURES[n - 1]:g}"
    with pytest.raises(InputError) as e:
        law_at(fam, None)
    assert f"{first} to {last} Pa" in str(e.value) and "\n" not in str(e.value)
    for outside in (0.5 * PRESSURES[0], 2 * PRESSURES[n - 1]):
        with pytest.raises(InputError) as e:
            law_at(fam, outside)
        assert f"[{first}, {last}] Pa" in str(e.value)
    for k in (0, n - 1):
        gl, how = law_at(fam, PRESSURES[k])
        assert gl is fam.members[k] and how["interpolated"] is False
