"""The body solver finishes on every law (issue 25, item 1), and every step it takes is a
solution of its step: the optimality conditions checked in NumPy (tests/body_kkt.py), not
the kernel's own residual.

The sweep is a covering array (every pair of levels of body x law x spin x direction in
some row) of the footprints (disc, ring, rectangle, L-shaped polygon, a body file), the
laws (Coulomb; ellipses of ratio 3 and 10; the truncated ellipse and the star law fitted to
the asymmetric wedge texture; the windward star law; a collinear, non-associated law; a
law family between its members), with and without spin, at launch directions off the
law's axes and spinning from rest.  Each row must come to rest with at most
MEAN_ITERATIONS Newton iterations a step on average and MAX_ITERATIONS in any step.

Measured when written (the sweep of /tmp-style runs at the CLI's 1024 points, 6 bodies x
11 laws x 2 spins x 4 directions): mean 1.0-2.3 iterations a step, at most 23 in a step
except the final stick of a ring (up to 170: the stick test's least-margin search at a
pivot).  Before the fix, the no-spin disc on an ellipse at 40 deg took 65 a step on
average and did not finish.
"""
from __future__ import annotations

import json
import math
from dataclasses import replace
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from body_kkt import check_run
from cli_run import run
from pairwise import covering_array, ids

from asperity.bodies import footprint as F
from asperity.dynamics.body import simulate_body
from asperity.dynamics.body_horizon import slip_ratio
from asperity.dynamics.body_api import slide_body
from asperity.dynamics.moreau import slide
from asperity.errors import InputError
from asperity.laws import planar as P

ROOT = Path(__file__).resolve().parents[1]
SURFACES = ROOT / "surfaces"
#: bounds stated in the issue's sense: the mean over a run, and the worst single step
MEAN_ITERATIONS = 3.0
MAX_ITERATIONS = 400


@cache
def fitted(kind: str, contact: str = "all-faces"):
    from asperity import derive, fit_derivation, load_texture
    return fit_derivation(derive(load_texture(SURFACES / "wedge-asymmetric.toml"),
                                 contact=contact), kind)


def family_member(gl, p):
    return replace(gl, source={**gl.source, "elastic_contact": {
        "area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
        "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "free", "hardness_Pa": None,
        "iterations": 10, "residual": 1e-9, "converged": True}})


@cache
def law(name: str):
    if name == "coulomb":
        return P.coulomb_law(0.3)
    if name == "ellipse-3":
        return P.ellipse_law(0.3, 0.1)
    if name == "ellipse-10":
        return P.ellipse_law(0.05, 0.5)
    if name == "collinear":
        return P.collinear_law(mu1=0.3, mu2=0.1)
    if name == "windward-star":
        return P.windward_star_law(30.0, 15.0, 0.3, 0.2)
    if name == "truncated":
        return P.from_gauge(fitted("truncated-ellipse"))
    if name == "star-texture":
        return P.from_gauge(fitted("star"))
    if name == "family":
        # the star laws of the asymmetric wedge with compliant (all faces) and rigid
        # (windward) asperities as the members at 1 and 10 MPa, taken at 3 MPa between them
        from asperity.laws.family import GaugeFamily, law_at
        a = fitted("star")
        b = replace(fitted("star", "windward"), source=a.source)
        fam = GaugeFamily((1e6, 1e7), (family_member(a, 1e6), family_member(b, 1e7)))
        gl, how = law_at(fam, 3e6)
        assert how["interpolated"]
        return P.from_gauge(gl)
    raise KeyError(name)


@cache
def body(name: str):
    """(points, weights, mass, inertia) of a footprint of about 96 points."""
    from asperity.dynamics.body_api import make_body
    if name == "polygon":
        fp = F.polygon([(0, 0), (0.1, 0), (0.1, 0.02), (0.03, 0.02), (0.03, 0.07), (0, 0.07)],
                       contact_points=96)
        return fp.points, fp.weights, 1.0, fp.inertia_per_mass
    kw = {"radius": 0.05} if name in ("disc", "ring") else \
        {"size": (0.1, 0.04)} if name == "rectangle" else {}
    kind = str(SURFACES / "body-bracket.toml") if name == "body-file" else name
    b = make_body(kind, contact_points=64 if name == "ring" else 96, **kw)
    return b.footprint.points, b.footprint.weights, b.mass, b.inertia


FACTORS = {
    "body": ["disc", "ring", "rectangle", "polygon", "body-file"],
    "law": ["coulomb", "ellipse-3", "ellipse-10", "truncated", "star-texture",
            "windward-star", "collinear", "family"],
    "spin": [0.0, 20.0],
    "angle": [40.0, 137.0, 250.0, "from-rest"],
}
ROWS = covering_array(FACTORS, lambda r: not (r["angle"] == "from-rest" and r["spin"] == 0.0))


def launch(row):
    pts, w, m, inertia = body(row["body"])
    if row["angle"] == "from-rest":
        u0 = (0.0, 0.0, row["spin"])
    else:
        a = math.radians(row["angle"])
        u0 = (math.cos(a), math.sin(a), row["spin"])
    return pts, w, m, inertia, u0


@pytest.mark.parametrize("row", ROWS, ids=ids(ROWS))
def test_every_body_comes_to_rest_on_every_law_with_a_bounded_iteration_count(row):
    pts, w, m, inertia, u0 = launch(row)
    res, rep = check_run(pts, w, law(row["law"]), mass=m, inertia=inertia, u0=u0, dt=2e-4)
    what = f"{row}: {res.message}, mean {res.mean_iterations:.2f}, max {res.max_iterations_used}"
    assert res.ok and res.rest, what
    assert res.mean_iterations <= MEAN_ITERATIONS, what
    assert res.max_iterations_used <= MAX_ITERATIONS, what
    # every step solves its own equations: sliding steps' residual, pivots' reactions in C,
    # the final stick's margin
    assert rep["worst_residual"] < 1e-8, (what, rep)
    assert rep["worst_gauge"] <= 1.0 + 1e-9, (what, rep)
    assert rep["min_margin"] >= -1e-9, (what, rep)
    e = res.energy
    assert np.all(np.diff(e) <= 1e-12 * e[0]), f"{what}: the kinetic energy rose"


def test_the_covering_array_holds_every_pair_and_is_far_smaller_than_the_product():
    n = len(FACTORS["body"]) * len(FACTORS["law"]) * len(FACTORS["spin"]) * \
        len(FACTORS["angle"])
    assert len(ROWS) < n / 4
    seen = {(k1, r[k1], k2, r[k2]) for r in ROWS for k1 in r for k2 in r if k1 < k2}
    for b in FACTORS["body"]:
        for lw in FACTORS["law"]:
            assert ("body", b, "law", lw) in seen


# ----------------------------------------------------------------------------- the case

def test_the_no_spin_disc_on_an_ellipse_at_40_deg_finishes_as_the_point_mass(capsys):
    """asperity slide --law ellipse --mu1 0.3 --mu2 0.1 --u0 1 --angle 40 --body disc
    --radius 0.05 --omega0 0: did not finish (65 iterations a step, not converged at step
    5703).  Without spin every point slips alike: the disc is the point mass."""
    code, out, err = run(capsys, "slide", "--law", "ellipse", "--mu1", "0.3", "--mu2", "0.1",
                         "--u0", "1", "--angle", "40", "--body", "disc", "--radius", "0.05",
                         "--omega0", "0", "--json")
    assert code == 0, err
    d = json.loads(out)
    pm = slide(P.ellipse_law(0.3, 0.1), 1.0, 40.0)
    rest = np.asarray(pm.q[-1])
    got = np.asarray(d["rest"])
    assert np.allclose(got, rest, rtol=0, atol=1e-9 * np.hypot(*rest)), (got, rest)
    assert d["status"] == "ok" and d["stop_time"] is not None
    assert d["mean_iterations"] <= 2.5 and d["max_iterations_used"] <= 10, d


@pytest.mark.parametrize("name", ["ellipse-3", "ellipse-10", "truncated", "family"])
@pytest.mark.parametrize("angle", [0.0, 40.0, 137.0, 250.0, 300.0])
def test_without_spin_a_disc_follows_the_point_mass_on_anisotropic_laws(name, angle):
    """The class of the issue's case: every direction, every anisotropic law, no spin."""
    pts, w, m, inertia = body("disc")
    a = math.radians(angle)
    res = simulate_body(pts, w, law(name), mass=m, inertia=inertia,
                        u0=(math.cos(a), math.sin(a), 0.0), dt=2e-4)
    assert res.ok and res.rest, res.message
    assert res.mean_iterations <= 2.5, res.mean_iterations
    pm = slide(law(name), 1.0, angle, dt=2e-4)
    # closed-form laws agree to rounding; a star law (the family) is tabulated for the body
    # (8192 directions: the table smears D's flat-edge jumps) and exact for the point mass
    tol = 1e-9 if name.startswith("ellipse") or name == "truncated" else 3e-4
    assert abs(res.stop_time - pm.stop_time) <= 2e-4 * (1 + tol * 1e4)
    d = float(np.hypot(*pm.q[-1]))
    assert np.allclose(res.q_final[:2], pm.q[-1], rtol=0, atol=tol * d), (res.q_final, pm.q[-1])
    assert abs(res.q_final[2]) < 1e-9


# ----------------------------------------------------------------------------- pivots

TRI = np.array([[0.0, 0.02], [0.02, -0.01], [-0.02, -0.01]])
CLUSTERS = {
    "triangle": (TRI, np.full(3, 1 / 3)),
    "two spots of three": (np.array([[-0.05, 0.0]] * 3 + [[0.05, 0.0]] * 3), np.full(6, 1 / 6)),
    "a spot of three and one": (np.array([[0.01, 0.0]] * 3 + [[-0.03, 0.0]]), np.full(4, 0.25)),
}


@pytest.mark.parametrize("shape", list(CLUSTERS))
@pytest.mark.parametrize("name", ["ellipse-3", "coulomb", "star-texture", "collinear"])
@pytest.mark.parametrize("u0", [(0.0, 0.0, 20.0), (1.0, 0.3, 20.0), (0.3, 0.0, -5.0)])
def test_few_point_bodies_pivot_and_slide_slowly_at_their_solutions(shape, name, u0):
    """Footprints of a few spots pivot about one of them (its points stick together) or let
    it slide slowly: the kink of the step's equations.  The pivot's reaction must lie in C
    and a slowly sliding spot must not be taken for a pivot (a reaction outside C)."""
    pts, w = CLUSTERS[shape]
    res, rep = check_run(pts, w, law(name), mass=1.0, inertia=1e-3, u0=u0, dt=1e-4)
    what = f"{shape}, {name}, {u0}: {res.message}, {rep}"
    assert res.ok and res.rest, what
    assert res.mean_iterations <= MEAN_ITERATIONS, what
    assert rep["worst_residual"] < 1e-8 and rep["worst_gauge"] <= 1 + 1e-9, what
    assert rep["min_margin"] >= -1e-9, what


def test_the_pivot_cases_reach_pivots_and_a_reaction_just_outside_c():
    """The sweep above is only worth something if it passes through pivots, including one
    whose needed reaction lies just outside C (a slowly sliding point): the triangle spun
    from rest on the 3:1 ellipse does (the reaction at 1.009 of C at one step)."""
    res, rep = check_run(TRI, np.full(3, 1 / 3), law("ellipse-3"), mass=1.0, inertia=1e-3,
                         u0=(0.0, 0.0, 20.0), dt=1e-4)
    assert rep["pivots"] >= 20, rep


# ----------------------------------------------------------------------------- degenerate bodies

def test_a_footprint_at_one_spot_is_refused_in_one_line():
    for spot in ((0.0, 0.0), (0.01, -0.02)):
        with pytest.raises(InputError, match="one spot") as e:
            simulate_body(np.array([spot, spot]), [0.5, 0.5], P.coulomb_law(0.3), mass=1,
                          inertia=1e-3, u0=(1, 0, 10), dt=1e-4)
        assert "\n" not in str(e.value)


def test_a_run_until_rest_too_long_to_compute_is_refused_naming_why():
    """Two points 2 nm apart have almost no friction torque: the spin would take ~1e4 s to
    stop.  The old horizon missed the pure spin and ran 1.2e6 steps to stop 'moving'."""
    pts = np.array([[-1e-9, 0.0], [1e-9, 0.0]])
    with pytest.raises(InputError, match="span only 2e-09 m") as e:
        simulate_body(pts, [0.5, 0.5], P.coulomb_law(0.3), mass=1, inertia=1e-3,
                      u0=(0.0, 0.0, 20.0), dt=1e-4)
    assert "t_end must be given" in str(e.value) and "\n" not in str(e.value)
    # with t_end it runs: the spin barely slows (torque ~ m g mu 1e-9)
    r = simulate_body(pts, [0.5, 0.5], P.coulomb_law(0.3), mass=1, inertia=1e-3,
                      u0=(0.0, 0.0, 20.0), dt=1e-4, t_end=0.01)
    assert r.ok and abs(r.u_final[2] - 20.0) < 1e-6


def naive_slip_ratio(pts, w, rho, n=801):
    """min over instantaneous centres p of sum w |r - p| / sqrt(|p|^2 + rho^2) on a grid
    of p (out to 30 sizes) and the translation (1)."""
    size = np.hypot(pts[:, 0], pts[:, 1]).max() + rho
    best = 1.0
    for span in (size, 30 * size):
        g = np.linspace(-span, span, n)
        X, Y = np.meshgrid(g, g)
        px, py = X.ravel(), Y.ravel()
        num = np.zeros_like(px)
        for (x, y), wi in zip(pts, w):
            num += wi * np.hypot(x - px, y - py)
        best = min(best, float((num / np.hypot(np.hypot(px, py), rho)).min()))
    return best


@pytest.mark.parametrize("seed", range(4))
def test_slip_ratio_is_the_least_slip_per_unit_of_motion(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    pts = rng.normal(size=(n, 2)) * 0.02
    w = rng.uniform(0.2, 1.0, n)
    w /= w.sum()
    pts -= w @ pts
    rho = float(rng.uniform(0.005, 0.05))
    got = slip_ratio(pts, w, rho)
    ref = naive_slip_ratio(pts, w, rho)
    assert got <= ref * (1 + 1e-9), (got, ref)       # never above the grid's minimum
    assert got >= ref * (1 - 2e-3), (got, ref)       # and the grid is within 0.2 % of it
    # a ring of radius R about its centre: pure spin gives R / rho, translation 1
    th = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    ring = 0.05 * np.column_stack([np.cos(th), np.sin(th)])
    assert slip_ratio(ring, np.full(64, 1 / 64), 0.5) == pytest.approx(
        naive_slip_ratio(ring, np.full(64, 1 / 64), 0.5), rel=2e-3)


@pytest.mark.parametrize("t_end", ["0", "-1", "1e-5", "nan"])
def test_t_end_below_one_step_is_refused(t_end, capsys):
    code, out, err = run(capsys, "slide", "--mu1", "0.3", "--u0", "1", "--angle", "0",
                         "--body", "disc", "--radius", "0.05", "--t-end", t_end)
    assert code != 0 and err.count("\n") == 1 and "--t-end" in err, err
    code, out, err = run(capsys, "slide", "--mu1", "0.3", "--u0", "1", "--angle", "0",
                         "--t-end", t_end)
    assert code != 0 and err.count("\n") == 1 and "--t-end" in err, err
    with pytest.raises(InputError, match="t_end"):
        slide_body(law("coulomb"), F.disc(0.05, contact_points=16), 1.0, 0.0,
                   t_end=float(t_end), dt=1e-4)
