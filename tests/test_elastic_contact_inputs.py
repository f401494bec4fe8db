"""ElasticContact takes every positive pressure, however small (a soft contact at 0.5 Pa),
and refuses zero and negative ones in one line naming the range."""
from __future__ import annotations

import pytest

from asperity.errors import InputError
from asperity.surface.contact_facets import ElasticContact


@pytest.mark.parametrize("pressure", [0.5, 1e-3, (0.2, 0.7, 3.0)])
def test_any_positive_pressure_is_taken(pressure):
    e = ElasticContact(E_star=1e6, pressure=pressure)
    assert e.pressure == pressure


@pytest.mark.parametrize("pressure", [0.0, -0.5, (0.5, 0.0)])
def test_zero_or_negative_pressure_is_refused(pressure):
    with pytest.raises(InputError, match=r"pressure must be in \(0, inf\) Pa") as e:
        ElasticContact(E_star=1e6, pressure=pressure)
    assert "\n" not in str(e.value)
