"""Metamorphic tests of texture -> friction -> law (issue 25, item 5).

* Isometries of a height map of oblong pixels (dx != dy): transposed (pixel sides
  exchanged), mirrored in x or y, turned a quarter or half a turn, the directional
  friction maps with the plane (p(Q s) = Q p(s)): a direction at psi goes to 90 deg - psi,
  180 deg - psi, psi + 90 deg ...; t_a, mu_a+- and mu_b+- follow, + and - exchanged where
  the mapped t_a wraps through 180 deg.  A transposition and a half turn keep each cell's
  triangulation: exact on any map; a mirror and a quarter turn exchange the cells'
  diagonals: exact on maps with planar cells (z = A(x) + B(y)), whose t_a lies at
  0.2 deg, so that its image crosses 0/180 deg.
* Oblong pixels against the square-pixel map resampled exactly (a planar-cell map with
  its x- or y-pixels linearly interpolated): the same law.
* Units: heights and pixel sides in m, um or mm: the same law.
* Law families between members against the stated rule (linear in ln p; ellipse t_a
  turned along the smaller angle, a member written with t_a reversed taken as the same
  set; star: the points interpolated), with members whose t_a decrease or cross 0/180
  deg; at members exactly; the ends of the range and one step past them; continuity.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from cli_run import run, run_json
from lays import ISOMETRIES, assert_mapped, isometry, lay, separable

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.laws.family import GaugeFamily
from asperity.laws.fitting import fit_derivation, fit_star
from asperity.laws.gauge_file import write_gauge
from asperity.laws.sets import TruncatedEllipse
from asperity.laws.walker_leine import associated
from asperity.surface.contact_facets import ElasticContact
from asperity.surface.topography import HeightMap

DX, DY = 1.0e-6, 0.6e-6
N_DIR = 72


def area_law(z, dx, dy, n=N_DIR):
    return derive(HeightMap(z, dx, dy), "all-faces", "closed-form", n)


# ---- isometries, resampling, units -------------------------------------------------------

CASES = [("lay", "transpose"), ("lay", "half-turn")] + [("planar", k) for k in ISOMETRIES]


@pytest.mark.parametrize("fixture, iso", CASES, ids=[f"{a}-{b}" for a, b in CASES])
def test_isometries_of_an_oblong_pixel_map_map_its_law(fixture, iso):
    z = lay(40, 28, DX, DY, angle_deg=95.0, seed=1) if fixture == "lay" else \
        separable(40, 28, DX, DY)
    a = area_law(z, DX, DY)
    z2, dx, dy, Q = isometry(iso, z, DX, DY)
    b = area_law(z2, dx, dy)
    assert_mapped(a, b, Q, iso, atol=1e-12)
    assert abs(a.axes["mu_a_plus"] - a.axes["mu_a_minus"]) > 2e-3     # asymmetric both ways
    assert abs(a.axes["mu_b_plus"] - a.axes["mu_b_minus"]) > 2e-4
    if fixture == "planar":                      # t_a next to 0 deg: images cross 0/180
        assert min(a.principal_direction_deg, 180 - a.principal_direction_deg) < 1.0


@pytest.mark.parametrize("axis", [0, 1])
def test_oblong_pixels_give_the_law_of_the_square_map_resampled_exactly(axis):
    """A planar-cell map of pixels 2h along ``axis`` and h across, and the same surface
    sampled every h (the new pixels interpolated linearly, exact on planar cells): every
    facet of the fine map is half of one of the coarse map, with its gradient."""
    h = 0.5e-6
    dx, dy = (2 * h, h) if axis == 0 else (h, 2 * h)
    z = separable(24, 20, dx, dy)
    fine = np.moveaxis(z, axis, 0)
    mid = 0.5 * (fine[:-1] + fine[1:])
    f = np.empty((2 * fine.shape[0] - 1,) + fine.shape[1:])
    f[0::2], f[1::2] = fine, mid
    f = np.moveaxis(f, 0, axis)
    twist = f[1:, 1:] - f[1:, :-1] - f[:-1, 1:] + f[:-1, :-1]
    assert np.abs(twist).max() < 1e-12 * np.ptp(z)             # still planar cells
    a, b = area_law(z, dx, dy), area_law(np.ascontiguousarray(f), h, h)
    np.testing.assert_allclose(b.reservoir.p, a.reservoir.p, rtol=0, atol=1e-12)
    assert b.principal_direction_deg == pytest.approx(a.principal_direction_deg, abs=1e-9)
    for k in a.axes:
        assert b.axes[k] == pytest.approx(a.axes[k], rel=1e-12), k


def test_units_of_the_lengths_do_not_change_the_law(tmp_path, capsys):
    """The same map in m, um and mm (heights and pixel sides): one law, in the API and on
    the command line (the file's numbers read in --unit, the pixel sides too)."""
    z = lay(32, 24, DX, DY, angle_deg=130.0, seed=3)
    a = area_law(z, DX, DY)
    for k in (1e6, 1e3):
        b = area_law(z * k, DX * k, DY * k)
        np.testing.assert_allclose(b.reservoir.p, a.reservoir.p, rtol=0, atol=1e-12)
    np.save(tmp_path / "m.npy", z)
    np.save(tmp_path / "um.npy", z * 1e6)
    common = ("--directions", N_DIR, "--detrend", "none")
    dm = run_json(capsys, "derive", tmp_path / "m.npy", "--unit", "m", "--pixel-size", DX, DY,
                  *common)
    du = run_json(capsys, "derive", tmp_path / "um.npy", "--unit", "um", "--pixel-size",
                  DX * 1e6, DY * 1e6, *common)
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus", "principal_direction_deg"):
        assert du[k] == pytest.approx(dm[k], rel=1e-10), k
    assert du["texture"]["pixel_size_m"] == pytest.approx([DX, DY], rel=1e-12)


# ---- law families ------------------------------------------------------------------------

def contact(p):
    return {"area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "free", "hardness_Pa": None,
            "iterations": 10, "residual": 1e-9, "converged": True}


def member_laws(kind, lays):
    """A law fitted to each (angle_deg, height) lay, all at the same 72 directions."""
    return [fit_derivation(area_law(lay(40, 28, DX, DY, angle_deg=a, seed=1, height=hh),
                                    DX, DY), kind) for a, hh in lays]


def family(laws, pressures):
    src = laws[0].source
    return GaugeFamily(tuple(pressures), tuple(
        replace(gl, source={**src, "elastic_contact": contact(p)})
        for gl, p in zip(laws, pressures)))


def reversed_ellipse(gl):
    """The same ellipse law written with t_a reversed (+ and - exchanged)."""
    e = gl.law.C
    flip = TruncatedEllipse(e.mu_a_minus, e.mu_a_plus, e.mu_b_minus, e.mu_b_plus,
                            theta=e.theta + math.pi)
    return replace(gl, law=associated(flip),
                   principal_direction_deg=(gl.principal_direction_deg + 180.0) % 360.0)


def hand_ellipse(e0, e1, w):
    """The README's rule: member 1 taken with its t_a on member 0's side (else the same set
    with + and - exchanged), each semi-axis (1 - w) mu_0 + w mu_1, t_a turned by w times
    the smaller angle from member 0's."""
    a0 = np.array([e0.mu_a_plus, e0.mu_a_minus, e0.mu_b_plus, e0.mu_b_minus])
    a1 = np.array([e1.mu_a_plus, e1.mu_a_minus, e1.mu_b_plus, e1.mu_b_minus])
    t0 = np.array([math.cos(e0.theta), math.sin(e0.theta)])
    t1 = np.array([math.cos(e1.theta), math.sin(e1.theta)])
    if t0 @ t1 < 0:
        a1, t1 = a1[[1, 0, 3, 2]], -t1
    turn = math.atan2(t0[0] * t1[1] - t0[1] * t1[0], t0 @ t1)     # in (-90, 90] deg
    return TruncatedEllipse(*((1 - w) * a0 + w * a1), theta=e0.theta + w * turn)


PHI = np.linspace(0.0, 2 * math.pi, 361)

ELLIPSE_CASES = {                       # (t_a of each member, deg; heights)
    "crossing 180": ((165.0, 2e-6), (20.0, 3.5e-6)),
    "decreasing": ((62.0, 3.5e-6), (24.0, 2e-6)),
}


@pytest.mark.parametrize("case", list(ELLIPSE_CASES))
@pytest.mark.parametrize("flip", [None, 0, 1])
def test_ellipse_family_between_members_follows_the_stated_rule(case, flip):
    """``flip``: that member written with its t_a reversed (a theta of 180 to 360 deg)."""
    laws = member_laws("truncated-ellipse", ELLIPSE_CASES[case])
    if flip is not None:
        laws[flip] = reversed_ellipse(laws[flip])
    ps = (2e6, 5e7)
    fam = family(laws, ps)
    e0, e1 = laws[0].law.C, laws[1].law.C
    d = math.remainder(math.degrees(e1.theta - e0.theta), 180.0)
    assert abs(d) > 30.0                                       # t_a turn a lot ...
    if case == "crossing 180":                                 # ... through 0/180 deg
        assert laws[0].principal_direction_deg % 180 > 150 and \
            laws[1].principal_direction_deg % 180 < 30
    for p in (2.0001e6, 7e6, 1e7, 3e7, 4.9999e7):
        w = math.log(p / ps[0]) / math.log(ps[1] / ps[0])
        gl = fam.at(p)
        hand = hand_ellipse(e0, e1, w)
        np.testing.assert_allclose(gl.law.C.radial(PHI), hand.radial(PHI), rtol=1e-12,
                                   err_msg=f"{case}, p = {p:g}: not the stated interpolation")
        np.testing.assert_allclose(gl.force(PHI).p, associated(hand).force(PHI).p, rtol=0,
                                   atol=1e-12)
        tilt = math.degrees(hand.theta) - gl.principal_direction_deg
        assert abs(math.remainder(tilt, 360.0)) < 1e-9
    # continuity at both ends: just inside the range is the member there, as a set
    for p, m in ((ps[0] * (1 + 1e-12), laws[0]), (ps[1] * (1 - 1e-12), laws[1])):
        np.testing.assert_allclose(fam.at(p).law.C.radial(PHI), m.law.C.radial(PHI),
                                   rtol=1e-9)


def test_star_family_between_members_goes_through_the_interpolated_points_across_180():
    """Star members with t_a at 176 and 8 deg: between them the law passes through the
    interpolated points (the star law fitted through them), its t_a turned along the
    smaller angle, through 0/180 deg; at each end it is the member there."""
    laws = member_laws("star", ((175.0, 2e-6), (8.0, 3.5e-6)))
    t0, t1 = (gl.principal_direction_deg for gl in laws)
    assert t0 > 170 and t1 < 10
    ps = (1e6, 1e8)
    fam = family(laws, ps)
    for p in (3e6, 1e7, 6e7):
        w = math.log(p / ps[0]) / math.log(ps[1] / ps[0])
        gl = fam.at(p)
        pts = (1 - w) * laws[0].data.p + w * laws[1].data.p     # no set-valued direction
        assert (laws[0].data.limit == 0).all() and np.array_equal(gl.data.psi,
                                                                  laws[0].data.psi)
        np.testing.assert_allclose(gl.data.p, pts, rtol=0, atol=1e-15)
        ref, _ = fit_star(gl.data)
        np.testing.assert_allclose(gl.force(PHI).p, ref.force(PHI).p, rtol=0, atol=1e-12)
        np.testing.assert_allclose(gl.law.C.radial(np.arctan2(pts[:, 1], pts[:, 0])),
                                   np.hypot(pts[:, 0], pts[:, 1]), rtol=1e-9)
        half = ((t1 - t0 + 90.0) % 180.0) - 90.0               # the smaller angle, signed
        assert abs(math.remainder(gl.principal_direction_deg - (t0 + w * half), 180.0)) < 1e-9
        assert 0.0 <= gl.principal_direction_deg < 180.0
    for p, m in ((ps[0] * (1 + 1e-12), laws[0]), (ps[1] * (1 - 1e-12), laws[1])):
        np.testing.assert_allclose(fam.at(p).force(PHI).p, m.force(PHI).p, rtol=0, atol=1e-6)


def test_the_ends_of_a_familys_range_and_one_step_past_them(tmp_path, capsys):
    """Three members: each member's pressure gives that member (the last one too), the law
    between two members is theirs (not a neighbour's), continuous at every member from
    both sides; one ulp outside the range is refused in one line; the command line's law
    at a pressure is the API's."""
    laws = member_laws("truncated-ellipse", ((172.0, 2e-6), (100.0, 2.8e-6), (14.0, 3.5e-6)))
    ps = (1e6, 1e7, 1e8)
    fam = family(laws, ps)
    for p, m in zip(ps, fam.members):
        assert fam.at(p) is m
    for k in range(2):
        e0, e1 = laws[k].law.C, laws[k + 1].law.C
        for w in (0.2, 0.7):
            p = ps[k] * (ps[k + 1] / ps[k]) ** w
            np.testing.assert_allclose(fam.at(p).law.C.radial(PHI),
                                       hand_ellipse(e0, e1, w).radial(PHI), rtol=1e-9,
                                       err_msg=f"between members {k} and {k + 1}")
    for k, m in enumerate(laws):
        for side in (-1, 1):
            p = ps[k] * (1 + side * 1e-12)
            if ps[0] <= p <= ps[-1]:
                np.testing.assert_allclose(fam.at(p).law.C.radial(PHI), m.law.C.radial(PHI),
                                           rtol=1e-9, err_msg=f"member {k}, side {side}")
    for p in (np.nextafter(ps[0], 0.0), np.nextafter(ps[-1], np.inf)):
        with pytest.raises(InputError) as exc:
            fam.at(float(p))
        assert "no extrapolation" in str(exc.value) and "\n" not in str(exc.value)
    path = tmp_path / "fam.json"
    write_gauge(path, fam)
    for p, psi in ((ps[-1], 135.0), (3e7, 250.0), (ps[0], 0.0), (3e6, 360.0)):
        d = run_json(capsys, "law", path, "--pressure", p, "--psi", psi)
        want = fam.at(p).force(np.array([math.radians(psi)]))
        assert d["p"] == pytest.approx(list(want.p[0]), rel=1e-12, abs=1e-15)
        assert d["family_pressure"]["interpolated"] == (p not in ps)
    code, out, err = run(capsys, "law", path, "--pressure", float(np.nextafter(1e8, 2e8)),
                         "--psi", 0)
    assert code == 1 and out == "" and len(err.strip().splitlines()) == 1


def test_a_hardness_between_the_familys_pressures_is_refused_in_one_line(tmp_path, capsys):
    """The cap must lie above every pressure of a family (the highest member would be all
    plastic): refused by the API and the command line, naming the hardness and its range."""
    with pytest.raises(InputError, match=r"hardness must be in \(1e\+08, inf\)"):
        ElasticContact(1e9, (1e6, 1e8), hardness=1e7)
    np.save(tmp_path / "z.npy", lay(32, 24, DX, DY))
    out = tmp_path / "fam.json"
    code, text, err = run(capsys, "fit", tmp_path / "z.npy", "--unit", "m", "--pixel-size",
                          DX, DY, "--elastic", 1e9, "--pressure", 1e6, 1e8, "--hardness", 1e7,
                          "-o", out)
    assert code == 1 and text == "" and not out.exists()
    assert err.strip().startswith("error") or "--hardness" in err
    assert "--hardness must be in (1e+08, inf)" in err and len(err.strip().splitlines()) == 1
