"""The plane-strain solve of a wedge texture resolves every wedge: a period of a Gaussian
texture of n wedges gets at least WEDGE_NODES_PER_WEDGE nodes a wedge (a power of two, at
most WEDGE_MAX_NODES), and the node spacing times the nodes is the period."""
from __future__ import annotations

import pytest

from asperity import GaussianWedgeTexture, WedgeTexture
from asperity.friction import elastic as fe


@pytest.mark.parametrize("n_wedges", [1, 20, 60])
def test_every_wedge_gets_its_nodes(n_wedges):
    tex = GaussianWedgeTexture(20.0, 50.0, 0.2, 0.2, 5e-6, 1.5e-6, n_wedges=n_wedges, seed=3)
    hm, prof, dx = fe.wedge_heightmap(tex, 0.01)
    n = hm.heights.shape[0]
    assert n & (n - 1) == 0 and fe.WEDGE_MIN_NODES <= n <= fe.WEDGE_MAX_NODES
    assert n >= min(fe.WEDGE_MAX_NODES, fe.WEDGE_NODES_PER_WEDGE * n_wedges)
    assert n * dx == pytest.approx(prof.period, rel=1e-12)


def test_light_pressure_on_a_sharp_crest_refines_the_period():
    """At p / E* 100 times lighter the contact of the crest is 100 times narrower: more
    nodes, up to the cap."""
    tex = WedgeTexture(20.0, 50.0, 0.2, 0.2)
    sizes = [fe.wedge_heightmap(tex, p)[0].heights.shape[0] for p in (1e-2, 1e-4)]
    assert sizes[1] > sizes[0] or sizes[1] == fe.WEDGE_MAX_NODES
