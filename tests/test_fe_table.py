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


def test_family_table_holds_the_family_at_every_pressure_clamped_outside():
    """FamilyTable.level(p) is ``law --pressure p``'s law within 1e-4 in every direction
    (away from flat edges): at the members, between them (blended in ln p), and clamped
    to the end members below and above the family's pressures (flagged as clamped)."""
    from law_families import four_members

    from asperity.fe.table import _near_edges, family_table
    fam = four_members()
    ft = family_table(fam)
    lo, hi = fam.pressures[0], fam.pressures[-1]
    psi = np.linspace(0.0, TWO_PI, 1441)
    for p in np.concatenate([np.geomspace(0.2 * lo, 5.0 * hi, 23), fam.pressures]):
        ref = fam.at(min(max(p, lo), hi))
        err = np.hypot(*(ft.level(p).force(psi) - ref.force(psi).p).T)
        err[_near_edges(psi, ref)] = 0.0
        assert err.max() < 1e-4, p
        assert ft.weights(p)[2] == (p < lo or p > hi)
    assert np.array_equal(ft.level(0.5 * lo).p, ft.level(lo).p)
    assert np.array_equal(ft.level(2.0 * hi).p, ft.level(hi).p)


@pytest.fixture(scope="module")
def ellipse_members():
    """Two truncated ellipses of different asymmetry: the family's laws between them
    (semi-axes interpolated) are not the blend of their forces."""
    from asperity.friction.derive import derive
    from asperity.laws.fitting import fit_derivation
    from asperity.texture.wedges import WedgeTexture
    return [fit_derivation(derive(WedgeTexture(a, b, 0.3, 0.05), "windward", "closed-form",
                                  72), "truncated-ellipse") for a, b in ((10, 40), (35, 15))]


def _family(members, pressures):
    from dataclasses import replace

    from law_families import contact

    from asperity.laws.family import GaugeFamily
    src = members[0].source
    return GaugeFamily(pressures, tuple(replace(g, source={**src, "elastic_contact": contact(p)})
                                        for g, p in zip(members, pressures)))


def test_a_family_that_jumps_between_close_pressures_is_refused(ellipse_members):
    """Laws that change by 0.07 between pressures 1e-7 apart cannot be blended within 1e-4
    by adding levels: refused at once in one line naming the pressures (not bisected down
    to the level limit)."""
    from asperity.fe.table import TableError, family_table
    fam = _family(ellipse_members, (1e6, 1e6 * (1.0 + 1e-7)))
    with pytest.raises(TableError) as err:
        family_table(fam)
    msg = str(err.value)
    assert "\n" not in msg and "between 1e+06 and 1e+06 Pa" in msg and "2 pressure levels" in msg


def test_a_family_needing_more_levels_than_allowed_is_refused(ellipse_members, monkeypatch):
    """With the level limit at the members' count, a family that needs levels between its
    members is refused in one line (the limit holds, whatever the pressure ratio)."""
    from asperity.fe import table
    monkeypatch.setattr(table, "MAX_LEVELS", 2)
    with pytest.raises(table.TableError) as err:
        table.family_table(_family(ellipse_members, (1e6, 1e8)))
    msg = str(err.value)
    assert "\n" not in msg and "between 1e+06 and 1e+08 Pa" in msg
