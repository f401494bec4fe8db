"""The report's section on planar rigid bodies (asperity/report/bodies.py): its numbers
against the closed forms of SPEC.md 8, the footprint's own sums and the point mass."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from asperity.report import bodies as B

G = 9.81
SURF = Path(__file__).resolve().parents[1] / "surfaces"


def test_the_section_follows_moreau():
    from asperity.report import SECTIONS
    assert SECTIONS.index("bodies") == SECTIONS.index("moreau") + 1


def test_range_maxima_take_each_range_with_both_ends():
    eps = np.array([0.0, 0.05, 0.1, 0.5, 1.0, 5.0, 10.0, 50.0, 100.0, 200.0])
    err = np.array([9.0, 1.0, 2.0, 1.0, 3.0, 1.0, 4.0, 1.0, 5.0, 99.0])
    assert B.range_maxima(eps, err) == [9.0, 3.0, 4.0, 5.0]


def test_default_disc_within_half_a_percent_of_the_closed_forms():
    """The table's largest errors of the default footprint below 0.5 % over eps in [0, 100],
    and far below beyond eps = 1 (Gauss's rule exact on a smooth integrand); fewer points
    are worse."""
    from asperity.bodies.footprint import DEFAULT_CONTACT_POINTS
    eps, errors = B.sampling_table(points=(None, 64))
    assert eps[0] == 0.0 and eps.max() == pytest.approx(100.0)
    ef, em = errors[DEFAULT_CONTACT_POINTS["disc"]]
    assert ef.max() < 5e-3 and em.max() < 5e-3
    assert ef.max() > 1e-5                                  # the sampling error is measured
    assert B.range_maxima(eps, ef)[3] < 1e-8 and B.range_maxima(eps, em)[3] < 1e-8
    assert ef[eps > 1.5].max() < 1e-8 and em[eps > 1.5].max() < 1e-8
    assert errors[64][0].max() > ef.max()


def test_own_fixed_point_of_a_footprint():
    """The sampled footprint's terminal ratio: the ring's is 1 at every orientation, the
    default disc's within 0.5 % of 0.653002 (its spread over orientations below 1 %), a
    coarse disc's spread wider."""
    from asperity.bodies.closed_forms import TERMINAL_RATIO
    from asperity.bodies.footprint import disc, ring
    lo, hi = B.own_fixed_range(ring(B.R, contact_points=64), directions=12)
    assert lo == pytest.approx(1.0, abs=1e-9) and hi == pytest.approx(1.0, abs=1e-9)
    lo, hi = B.own_fixed_range(disc(B.R), directions=36)
    e0 = TERMINAL_RATIO["disc"]
    assert abs(lo / e0 - 1) < 5e-3 and abs(hi / e0 - 1) < 5e-3
    lo64, hi64 = B.own_fixed_range(disc(B.R, contact_points=64), directions=36)
    assert hi64 - lo64 > 2 * (hi - lo)


def test_staged_disc_reaches_its_terminal_ratio_and_stops_together():
    """A slowly spinning disc (eps0 = 10, 64 points) followed in stages down to 1e-8 of its
    speed: v / (R omega) there lies in the range of the sampled footprint's own terminal
    ratio over orientations (0.6216 to 0.6572 for 64 points; the closed form 0.653002 is
    the limit of many points); the reference ODE there is within 0.1 % of 0.653002; slide
    and spin stop together at the reference's stop time."""
    from asperity.bodies.closed_forms import TERMINAL_RATIO, disc_reference
    from asperity.bodies.footprint import disc
    from asperity.laws.planar import coulomb_law
    fp = disc(B.R, contact_points=64)
    omega0 = B.V0 / (B.R * 10.0)
    st = B.staged_run(fp, coulomb_law(B.MU), (B.V0, 0.0, omega0), steps_per_stage=600)
    assert 1e-10 < st.depth < 1e-9                     # nine stages, each below 1/10
    assert np.all(np.diff(st.t) > 0) and st.t_stop > st.t[-1]
    lo, hi = B.own_fixed_range(fp, directions=36)
    assert lo * 0.999 < st.eps_end < hi * 1.001, (lo, st.eps_end, hi)
    ref = disc_reference(B.V0, omega0, B.MU, G, B.R, "disc")
    assert abs(B.reference_eps_at(ref, st.w_end) / TERMINAL_RATIO["disc"] - 1) < 1e-3
    # at the launch the reference interpolates to eps0 itself
    assert B.reference_eps_at(ref, 1.0) == pytest.approx(10.0, rel=1e-9)
    f = st.first
    assert abs(f.slide_stop_time - f.spin_stop_time) <= 2 * f.dt
    assert f.stop_time == pytest.approx(ref.stop_time, rel=2e-3)
    assert st.t_stop == pytest.approx(ref.stop_time, rel=2e-3)


def test_staged_ring_ends_at_one():
    from asperity.bodies.footprint import ring
    from asperity.laws.planar import coulomb_law
    fp = ring(B.R, contact_points=32)
    st = B.staged_run(fp, coulomb_law(B.MU), (B.V0, 0.0, B.V0 / (B.R * 0.1)), stages=5,
                      steps_per_stage=400)
    assert 1e-6 < st.depth < 1e-5                      # each stage ends below 1/10
    assert st.eps_end == pytest.approx(1.0, abs=1e-4)


def test_spin_drift_first_step_against_the_integral_of_p():
    """A disc spun from rest: the first step's acceleration against -g/(2 pi) int p dpsi
    (spin_drift_force) and the footprint's own sum; none on the ellipse law."""
    rows = {r["law"].split(",")[1].split()[0] if "wedge" in r["law"] else "ellipse": r
            for r in B.drift_rows(B.QUICK, to_rest=False, surfaces=SURF)}
    af, ww, el = rows["all-faces"], rows["windward"], rows["ellipse"]
    assert af["a_ref"][0] > 0.01 and abs(af["a_ref"][1]) < 1e-12
    assert af["error"] < 1e-3 and af["error_own"] < 1e-3
    assert ww["a_ref"][0] < -1.0                       # windward: strongly asymmetric
    assert ww["error_own"] < 0.02 and ww["error"] < 0.05
    assert np.hypot(*el["a_ref"]) < 1e-12
    assert np.hypot(*el["a_sim"]) < 1e-3 * G * 0.15


def test_own_drift_is_the_sum_over_the_points():
    """own_drift: zero on a centrally symmetric law with an even ring, the integral on a
    fine disc, and the sign of the law's asymmetry (mu_a+ > mu_a-: pushed towards -t_a)."""
    from asperity.bodies.closed_forms import spin_drift_force
    from asperity.bodies.footprint import disc, ring
    from asperity.laws.planar import ellipse_law, truncated_ellipse_law
    assert np.abs(B.own_drift(ring(B.R, contact_points=16), ellipse_law(0.4, 0.2))).max() \
        < 1e-15
    law = truncated_ellipse_law(0.3, 0.15, 0.2, 0.2)
    own = B.own_drift(disc(B.R), law)
    ref = spin_drift_force(law)
    assert own[0] < -0.01
    assert np.hypot(*(own - ref)) < 2e-3 * np.hypot(*ref)
    fp = ring(B.R, contact_points=4)                  # points at 0, 90, 180, 270 deg
    got = B.own_drift(fp, law)
    p = law.force(np.array([0.5, 1.0, 1.5, 0.0]) * math.pi)   # psi of omega x r_i
    assert got == pytest.approx(-p.mean(axis=0), abs=1e-15)


def test_rectangle_follows_the_point_mass_without_spin_and_turns_with_it():
    rows = B.rectangle_rows(B.QUICK)
    plain, spin, ecc = rows
    assert plain["point_mass_gap"] < 1e-9 and abs(plain["angle_deg"]) < 1e-9
    assert plain["stop_time"] is not None
    assert abs(spin["angle_deg"]) > 30.0
    assert abs(ecc["angle_deg"]) > 5.0 and ecc["point_mass_gap"] > 1e-4


def test_crossing_times_are_the_benchmarks_criteria():
    """First v < stop_speed, first R omega < stop_speed, and v / (R omega) where v + R omega
    first falls below end_fraction of its start (here x + x^2/2 < 0.03225 at x = 1 - t =
    0.031: the ratio 2 / x)."""
    t = np.linspace(0.0, 1.0, 1001)
    v, w = 1.0 - t, 0.5 * (1.0 - t) ** 2
    s, sp, ratio = B.crossing_times(t, v, w, stop_speed=0.1052, end_fraction=0.0215)
    assert s == pytest.approx(0.895) and sp == pytest.approx(0.542)
    assert ratio == pytest.approx(2.0 / (1.0 - 0.969))
    s, sp, ratio = B.crossing_times(t, v + 1.0, w, stop_speed=0.1, end_fraction=0.02)
    assert s is None and ratio is None


def _fake_bench(folder, **disc):
    mj = {"version": "9.9", "contacts": 4, "dt": 1e-4, "radius": 0.05, "mu": 0.3,
          "torsional": 0.01, "v0": 1.0, "omega0": 20.0, "slide_stop_time": 0.4712,
          "spin_stop_time": 0.4512, "spin_stops_before_slide_by": 0.02,
          "terminal_ratio": 6.2, "stop_speed": 1e-3, "end_fraction": 0.02}
    mj.update(disc)
    (folder / B.BENCH_JSON).write_text(json.dumps({"body": {"mujoco_disc": mj,
                                                             "load_average": [1.5, 1, 1]}}))


def test_mujoco_part_reads_the_committed_json_or_says_how(tmp_path):
    """MuJoCo's row from body-bench.json in the report folder; our disc and the closed
    forms beside it, stopping together; without a usable file, the command to make one."""
    from asperity.bodies.closed_forms import disc_reference
    _fake_bench(tmp_path, path=[[0.0, 1.0, 1.0], [0.1, 0.7, 0.5], [0.2, 0.4, 0.1]])
    body, where = B.bench_json(tmp_path)
    assert where == tmp_path / B.BENCH_JSON and body["mujoco_disc"]["version"] == "9.9"
    lines = B.bench_section(tmp_path, B.QUICK)
    text = "\n".join(lines)
    mj = next(x for x in lines if x.startswith("| MuJoCo 9.9"))
    assert "| 0.4712 | 0.4512 | +0.0200 | 6.2 |" in mj
    assert "load average 1.50" in text
    ref = disc_reference(1.0, 20.0, 0.3, G, 0.05)
    for name in ("closed forms", "asperity body solver"):
        row = [c.strip() for c in next(x for x in lines if x.startswith(f"| {name}"))
               .strip("|").split("|")]
        slide, spin, gap = float(row[1]), float(row[2]), float(row[3])
        assert abs(gap) <= 2e-4 and abs(slide - spin) <= 2e-4, row     # they stop together
        assert slide == pytest.approx(ref.stop_time, abs=2e-3)
        assert 0.6 < float(row[4]) < 0.72, row            # near 0.653, not 6.2
    assert (tmp_path / "bodies_mujoco.png").stat().st_size > 20_000
    (tmp_path / B.BENCH_JSON).write_text("{not json")
    body, where = B.bench_json(tmp_path)
    assert where != tmp_path / B.BENCH_JSON
    if body is None:
        text = "\n".join(B.bench_section(tmp_path, B.QUICK))
        assert B.BENCH_COMMAND in text and "| MuJoCo" not in text


@pytest.mark.slow
def test_quick_section_tables_and_figures(tmp_path):
    """The whole section (quick): its tables against the closed forms, every figure."""
    lines = B.section(tmp_path, quick=True, surfaces=SURF)
    text = "\n".join(lines)
    assert lines[0].startswith("## Bodies")
    default = next(x for x in lines if "(default)" in x)
    cells = [c.strip() for c in default.strip("|").split("|")]
    assert float(cells[1]) < 5e-3 and float(cells[2]) < 5e-3
    rows = [[c.strip() for c in x.strip("|").split("|")] for x in lines
            if x.startswith(("| disc |", "| ring |"))]
    assert len(rows) == 4
    for r in rows:
        eps_end, ref = float(r[9]), float(r[10])
        lo, hi = (float(v) for v in r[11].split(" to "))
        assert lo * 0.999 < eps_end < hi * 1.001, r
        assert abs(ref / float(r[12]) - 1) < 3e-3, r
        assert abs(float(r[5]) - float(r[6])) <= 2e-4, r           # together, within 2 dt
        assert float(r[4]) == pytest.approx(float(r[7]), rel=2e-3), r
    for png in ("bodies_sampling.png", "bodies_terminal.png", "bodies_drift.png",
                "bodies_rectangle.png", "bodies_mujoco.png"):
        assert f"]({png})" in text and (tmp_path / png).stat().st_size > 20_000


@pytest.mark.slow
def test_default_disc_terminal_ratio_within_one_percent_from_both_spins():
    """The report's own runs (the default 1024-point disc): v / (R omega) at the end within
    1 % of 0.653002 from the fast and the slow spin, inside the footprint's own range."""
    from asperity.bodies.closed_forms import TERMINAL_RATIO
    rows = B.terminal_rows(B.FULL, kinds=("disc",))
    assert [r["eps0"] for r in rows] == [0.1, 10.0]
    for r in rows:
        lo, hi = r["own_range"]
        assert abs(r["eps_end"] / TERMINAL_RATIO["disc"] - 1) < 0.01, r["eps_end"]
        assert lo * 0.999 < r["eps_end"] < hi * 1.001, (lo, r["eps_end"], hi)
        assert r["depth"] < 1e-8
        assert abs(r["slide_stop_time"] - r["spin_stop_time"]) <= 2e-4
