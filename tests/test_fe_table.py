"""The tables the FE routines carry (asperity.fe.table): within 1e-4 of the law's own force
for every sliding direction, the law's own force at a set-valued direction, the nodes'
polygon within 1e-4 of C along every ray, and a one-line refusal naming the directions
when a bound cannot be met."""
from __future__ import annotations

import math

import numpy as np
import pytest
from fe_laws import law

from asperity.fe.table import ARC_HALF, TableError, law_table
from asperity.laws.geometry import TWO_PI

LAWS = ("ellipse", "star", "windward", "componentwise")


@pytest.mark.parametrize("name", LAWS)
def test_table_holds_the_force_of_every_direction(name):
    gl = law(name)
    tab = law_table(gl)
    assert np.all(np.diff(tab.psi) > 0) and tab.psi[-1] - tab.psi[0] < TWO_PI
    psi = np.random.default_rng(1).uniform(-10.0, 10.0, 50_000)
    edges = np.asarray(getattr(gl.law.D, "edges", np.empty(0)))
    if edges.size:                      # set-valued: any force of the arc slides that way
        d = np.abs(np.remainder(psi[:, None] - edges + math.pi, TWO_PI) - math.pi)
        psi = psi[np.all(d > 2 * ARC_HALF, axis=1)]
    err = np.hypot(*(tab.force(psi) - gl.force(psi).p).T)
    assert err.max() < 1e-4
    assert tab.max_error < 1e-4 and tab.max_radial_error < 1e-4
    phi = np.linspace(-math.pi, math.pi, 20_001)
    assert np.abs(tab.radial(phi) - gl.law.C.radial(phi)).max() < 1e-4


def test_flat_edges_become_the_arc_of_c_with_the_laws_force_in_the_middle():
    gl = law("windward")
    tab = law_table(gl)
    edges = gl.law.D.edges
    assert edges.size == 2
    for e in edges:
        f = gl.force(np.array([e]))
        assert f.set_valued[0]
        assert np.abs(tab.force([e])[0] - f.p[0]).max() < 1e-12
        assert np.abs(tab.force([e - 1.01 * ARC_HALF])[0] - f.p_minus[0]).max() < 1e-9
        assert np.abs(tab.force([e + 1.01 * ARC_HALF])[0] - f.p_plus[0]).max() < 1e-9
        inside = (tab.psi > e - ARC_HALF) & (tab.psi < e + ARC_HALF)
        pts = tab.p[inside]
        r = np.hypot(pts[:, 0], pts[:, 1])
        assert inside.sum() > 20
        assert np.abs(r - gl.law.C.radial(np.arctan2(pts[:, 1], pts[:, 0]))).max() < 1e-12


def test_a_bound_that_cannot_be_met_is_refused_naming_the_directions(monkeypatch):
    from asperity.fe import table
    monkeypatch.setattr(table, "MAX_NODES", 600)         # too few nodes for 1e-6
    with pytest.raises(TableError) as err:
        law_table(law("windward"), tol=1e-6)
    msg = str(err.value)
    assert "\n" not in msg and "directions, from" in msg and "deg" in msg


def test_the_table_of_a_turned_law_is_the_turned_table():
    from asperity.laws.componentwise import componentwise_gauge
    a = law_table(componentwise_gauge(mu_f=0.1, mu_b=0.15, mu_t=0.2))
    b = law_table(componentwise_gauge(mu_f=0.2, mu_b=0.3, mu_t=0.4))
    psi = np.linspace(0, TWO_PI, 997)
    assert np.abs(b.force(psi) - 2 * a.force(psi)).max() < 2e-4
