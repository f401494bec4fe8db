"""A law family between and beyond its members: its refusals name the whole pressure
range, first to last member, whatever the number of members (a family used without a
pressure, a pressure outside it: no extrapolation); a pressure a hair outside an end is
shown apart from that end; the range's ends are members, taken as they are; between two star members t_a turns the short way, across 0/180 deg too."""
from __future__ import annotations

from dataclasses import replace

import pytest
from law_families import PRESSURES, four_members

from asperity.errors import InputError
from asperity.laws.family import GaugeFamily, law_at


@pytest.fixture
def family():
    return four_members()


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


@pytest.mark.parametrize("n", [2, 3, 4])
def test_a_pressure_a_hair_outside_an_end_is_shown_apart_from_it(family, n):
    """A pressure just outside the first or the last member's (1e-9 relative: the same in
    the %g the range is written in) is refused showing all its digits, never as the end
    itself ("2e+07 Pa is outside [.., 2e+07]")."""
    fam = GaugeFamily(family.pressures[:n], family.members[:n])
    for end, p in ((PRESSURES[0], PRESSURES[0] * (1 - 1e-9)),
                   (PRESSURES[n - 1], PRESSURES[n - 1] * (1 + 1e-9))):
        assert f"{p:g}" == f"{end:g}"
        with pytest.raises(InputError) as e:
            law_at(fam, p)
        assert f"pressure {p!r} Pa is outside" in str(e.value), str(e.value)


@pytest.mark.parametrize("d0,d1,mid", [(20.0, 40.0, 30.0), (170.0, 10.0, 0.0),
                                       (10.0, 170.0, 0.0), (100.0, 60.0, 80.0)])
def test_star_members_t_a_turns_the_short_way_in_proportion_to_log_pressure(family, d0, d1,
                                                                            mid):
    """Between two star members t_a turns from the first's to the second's by the shorter
    way (an axis: 170 and 10 deg are 20 deg apart, across 0/180), at the share w of the log
    pressure: at the geometric mean of the two pressures, half way."""
    a, b = (replace(gl, principal_direction_deg=d) for gl, d in
            zip(family.members[:2], (d0, d1)))
    fam = GaugeFamily(PRESSURES[:2], (a, b))
    p = (PRESSURES[0] * PRESSURES[1]) ** 0.5
    gl, how = law_at(fam, p)
    assert how["interpolated"] is True
    d = gl.principal_direction_deg
    assert 0.0 <= d < 180.0
    assert min(abs(d - mid), 180.0 - abs(d - mid)) < 1e-9
