"""The contact room against independent references (issue 19, SPEC.md 7).

* ContactMechanics (PyPI, MIT; its constrained conjugate gradient of Polonsky & Keer on
  ``PeriodicFFTElasticHalfSpace`` / ``FreeFFTElasticHalfSpace``) called in asperity's
  conventions by ``benchmarks/contact_peers.py`` (the conventions are listed there);
* a plain NumPy Polonsky-Keer written from the paper, ``benchmarks/plain_contact.py``,
  itself checked here against Westergaard, Love's integral by quadrature and
  ContactMechanics;
* closed forms and invariants: full contact of a periodic map (p = p_mean + E*|q| h_q / 2),
  a periodic map shifted by whole pixels, a mirrored map, a transposed map with its pixel
  sides exchanged.

Maps: random self-affine (Hurst 0.8, rms slope 0.1; one with non-square pixels and
undefined pixels), and two measured ones read by SurfaceTopography (matrix-3, the ski
scan's corner with its undefined border), each on both boundaries.  asperity's solver runs
at its default tolerance (1e-8); the references at 1e-12.
"""
from __future__ import annotations

import sys
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

from asperity.contact import effective_modulus, solve_contact

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from contact_peers import cm_available, cm_solve, self_affine  # noqa: E402
from plain_contact import love_coefficients, make_operator, polonsky_keer  # noqa: E402

DATA = ROOT.parent / "shared" / "data" / "surfaces"
NO_CM = cm_available()
needs_cm = pytest.mark.skipif(NO_CM is not None, reason=str(NO_CM))
E = 2.0e11                                   # E*, Pa
BOUNDARIES = ("periodic", "free")
REF_TOL = 1e-12


def _plane_removed(h):
    """h minus its least-squares plane over the defined pixels."""
    i, j = np.indices(h.shape)
    ok = np.isfinite(h)
    A = np.column_stack([np.ones(ok.sum()), i[ok], j[ok]])
    c = np.linalg.lstsq(A, h[ok], rcond=None)[0]
    return h - (c[0] + c[1] * i + c[2] * j)


@lru_cache(maxsize=None)
def case(name):
    """(heights m, (dx, dy) m, nominal pressure Pa, hardness Pa or None)."""
    if name == "self-affine":
        dx = 0.5e-6
        return self_affine(128, dx=dx, seed=1), (dx, dx), 0.0025 * E, None
    if name == "holes":                     # non-square pixels, scattered and a block of NaN
        dx, dy = 0.4e-6, 0.6e-6
        h = self_affine(96, 80, dx=dx, dy=dy, seed=2)
        rng = np.random.default_rng(3)
        h[rng.random(h.shape) < 0.04] = np.nan
        h[10:22, 30:51] = np.nan
        return h, (dx, dy), 0.01 * E, None
    if name in ("hard", "hard-holes"):
        h, px, _, _ = case("self-affine" if name == "hard" else "holes")
        h = h[:96, :80] if name == "hard" else h
        return h, px, 0.01 * E, (0.05 if name == "hard" else 0.02) * E
    if not DATA.is_dir():
        pytest.skip(f"measured surfaces not found: {DATA} is absent")
    from SurfaceTopography import read_topography
    if name == "matrix-3":                  # isotropic AFM roughness, 256 x 256, 10 um
        t = read_topography(str(DATA / "matrix-3.txt"))
        h = _plane_removed(np.asarray(t.heights(), float))
        return h, tuple(s / n for s, n in zip(t.physical_sizes, h.shape)), 0.01 * E, None
    if name == "ski":                       # the ski scan's corner: undefined first row/column
        t = read_topography(str(DATA / "SkiInfiniteFocus.x3p"))
        h = np.ma.filled(np.ma.asarray(t.heights(), float), np.nan)[:128, :112]
        px = tuple(s / n for s, n in zip(t.physical_sizes, t.nb_grid_pts))
        assert np.isnan(h[0]).all() and np.isnan(h[:, 0]).all(), "the undefined border moved"
        return _plane_removed(h), px, 0.02 * E, None
    raise KeyError(name)


@lru_cache(maxsize=None)
def reference(name, boundary, solver):
    h, (dx, dy), p, H = case(name)
    if solver == "cm":
        out = cm_solve(h, dx, dy, E, p, boundary, hardness=H, tol=REF_TOL)
        assert out[3], f"ContactMechanics did not converge on {name}, {boundary}"
    else:
        out = polonsky_keer(h, dx, dy, E, p, boundary, hardness=H, tol=REF_TOL)
        assert out[3] < REF_TOL, f"the plain reference did not converge on {name}, {boundary}"
    return out[0], out[1]


@lru_cache(maxsize=None)
def solved(name, boundary):
    h, px, p, H = case(name)
    return solve_contact(h, px, E, p, boundary=boundary, hardness=H)


def rel_l2(a, b):
    ok = np.isfinite(b)
    assert np.array_equal(np.isfinite(a), ok), "undefined pixels differ"
    return float(np.linalg.norm(a[ok] - b[ok]) / np.linalg.norm(b[ok]))


# ---- the references themselves ---------------------------------------------------------

def test_love_coefficients_are_the_integral_of_1_over_r():
    """Displacement of a pixel under a unit pressure on another: (1 / (pi E*)) int dA / r,
    by quadrature (the pixel's own by the polar integral from its centre)."""
    from scipy import integrate
    dx, dy, Es = 1.0, 0.6, 2.0
    L = love_coefficients(8, 8, dx, dy, Es)
    for i, j in [(1, 0), (0, 2), (3, 5), (-2, 3), (-8, -8), (7, -1)]:
        v = integrate.dblquad(lambda y, x: 1 / np.hypot(i * dx - x, j * dy - y),
                              -dx / 2, dx / 2, -dy / 2, dy / 2, epsabs=1e-13)[0]
        assert L[i, j] == pytest.approx(v / (np.pi * Es), rel=1e-9)
    c = np.arctan2(dy, dx)
    own = 4 * (integrate.quad(lambda t: dx / 2 / np.cos(t), 0, c)[0]
               + integrate.quad(lambda t: dy / 2 / np.sin(t), c, np.pi / 2)[0])
    assert L[0, 0] == pytest.approx(own / (np.pi * Es), rel=1e-12)


@pytest.mark.parametrize("f", [0.1, 0.4, 0.8])
def test_plain_reference_against_westergaard(f):
    """h = D cos(2 pi x / lam) (SPEC 7): contact width from sin^2(pi a / lam) = p / p*,
    Westergaard's pressure p = 2 p_mean cos(pi x/lam) sqrt(s^2 - sin^2(pi x/lam)) / s^2."""
    n, lam, D = 1024, 1e-3, 1e-6
    x = np.arange(n) * lam / n
    h = np.tile(D * np.cos(2 * np.pi * x / lam)[:, None], (1, 2))
    p_star = np.pi * E * D / lam
    p, gap, _, err = polonsky_keer(h, lam / n, lam / n, E, f * p_star, tol=1e-11)
    assert err < 1e-11
    s2 = f
    half = lam / np.pi * np.arcsin(np.sqrt(s2))          # a, half the contact width
    assert abs((p[:, 0] > 0).sum() * lam / n - 2 * half) <= 2 * lam / n
    xs = np.where(x > lam / 2, x - lam, x)
    exact = 2 * f * p_star * np.cos(np.pi * xs / lam) / s2 * np.sqrt(
        np.clip(s2 - np.sin(np.pi * xs / lam) ** 2, 0, None))
    assert rel_l2(p[:, 0], exact) < 3e-3
    assert np.sum(p) == pytest.approx(f * p_star * h.size, rel=1e-13)
    assert gap[p > 0].max() == 0 and gap.min() >= 0


def test_plain_reference_full_contact_of_the_sinusoid():
    n, lam, D = 256, 1e-3, 1e-6
    x = np.arange(n) * lam / n
    h = np.tile(D * np.cos(2 * np.pi * x / lam)[:, None], (1, 2))
    p_star = np.pi * E * D / lam
    p, _, _, _ = polonsky_keer(h, lam / n, lam / n, E, 1.2 * p_star, tol=1e-12)
    assert rel_l2(p[:, 0], p_star * (1.2 + np.cos(2 * np.pi * x / lam))) < 1e-10


@needs_cm
@pytest.mark.parametrize("boundary", BOUNDARIES)
@pytest.mark.parametrize("name", ["self-affine", "holes", "hard", "hard-holes"])
def test_plain_reference_matches_contactmechanics(name, boundary):
    """Two independent implementations of the same discrete problem agree to their
    convergence: pressure and gap."""
    p_cm, g_cm = reference(name, boundary, "cm")
    p_pl, g_pl = reference(name, boundary, "plain")
    assert rel_l2(p_pl, p_cm) < 1e-8
    assert np.nanmean(g_pl) == pytest.approx(np.nanmean(g_cm), rel=1e-8)


# ---- solve_contact against ContactMechanics --------------------------------------------

def _check_against(res, p_ref, g_ref, name):
    h, (dx, dy), p_mean, H = case(name)
    ok = np.isfinite(h)
    err = rel_l2(res.pressure, p_ref)
    assert err < 1e-5, f"relative L2 of the pressure {err:.2e}"
    # force balance: the load is the nominal pressure over the whole map (pixels x dx dy)
    load = np.nansum(res.pressure) * dx * dy
    assert load == pytest.approx(p_mean * h.size * dx * dy, rel=1e-10)
    assert res.mean_pressure == pytest.approx(p_mean, rel=1e-10)
    n_ref, n = int((p_ref[ok] > 0).sum()), int(res.contact[ok].sum())
    assert abs(n - n_ref) <= max(2, 2e-3 * n_ref), (n, n_ref)
    assert res.area_fraction == pytest.approx(n / ok.sum(), rel=1e-12)
    assert res.mean_gap == pytest.approx(np.nanmean(g_ref), rel=1e-5)
    assert res.max_pressure == pytest.approx(np.nanmax(p_ref), rel=1e-4)
    if H is not None:
        assert np.nanmax(res.pressure) <= H * (1 + 1e-12)
        plastic_ref = int((p_ref[ok] >= H * (1 - 1e-9)).sum())
        plastic = int((res.pressure[ok] >= H * (1 - 1e-9)).sum())
        assert plastic_ref > 0 and abs(plastic - plastic_ref) <= max(2, 2e-3 * plastic_ref)
    return err


@needs_cm
@pytest.mark.parametrize("boundary", BOUNDARIES)
@pytest.mark.parametrize("name", ["self-affine", "holes", "matrix-3", "ski"])
def test_pressure_matches_contactmechanics(name, boundary):
    res = solved(name, boundary)
    assert res.converged and res.residual <= 1e-8
    _check_against(res, *reference(name, boundary, "cm"), name)


@needs_cm
@pytest.mark.parametrize("boundary", BOUNDARIES)
@pytest.mark.parametrize("name", ["hard", "hard-holes"])
def test_plastic_cap_matches_contactmechanics(name, boundary):
    """Hardness H: pressures capped at H, the load carried by more contact (ContactMechanics'
    plastic cap takes a force per pixel: H x pixel area)."""
    res = solved(name, boundary)
    assert res.converged and res.hardness == case(name)[3]
    _check_against(res, *reference(name, boundary, "cm"), name)


# ---- invariants and closed forms -------------------------------------------------------

def test_periodic_map_shifted_by_whole_pixels_gives_the_shifted_pressure():
    h, px, p, _ = case("holes")
    base = solve_contact(h, px, E, p, boundary="periodic", tol=1e-10)
    for shift in ((37, -11), (0, 1), (-1, 0)):
        res = solve_contact(np.roll(h, shift, (0, 1)), px, E, p, boundary="periodic",
                            tol=1e-10)
        assert rel_l2(res.pressure, np.roll(base.pressure, shift, (0, 1))) < 1e-8
        assert np.array_equal(res.contact, np.roll(base.contact, shift, (0, 1)))
        assert res.mean_gap == pytest.approx(base.mean_gap, rel=1e-8)


@pytest.mark.parametrize("boundary", BOUNDARIES)
def test_mirrored_and_transposed_maps(boundary):
    """A map mirrored in x (or y) gives the mirrored pressure; the transposed map with its
    pixel sides exchanged gives the transposed pressure (catches dx / dy mixed up); the
    memory order of the array (a transposed view, a Fortran-ordered copy) changes nothing."""
    h, (dx, dy), p, _ = case("holes")
    base = solve_contact(h, (dx, dy), E, p, boundary=boundary, tol=1e-10)
    same = solve_contact(np.asfortranarray(h), (dx, dy), E, p, boundary=boundary, tol=1e-10)
    assert rel_l2(same.pressure, base.pressure) < 1e-12, "the memory order of the map matters"
    for flip in (np.s_[::-1, :], np.s_[:, ::-1]):
        res = solve_contact(h[flip], (dx, dy), E, p, boundary=boundary, tol=1e-10)
        assert rel_l2(res.pressure, base.pressure[flip]) < 1e-8
    res = solve_contact(h.T, (dy, dx), E, p, boundary=boundary, tol=1e-10)
    assert rel_l2(res.pressure, base.pressure.T) < 1e-8
    assert res.mean_gap == pytest.approx(base.mean_gap, rel=1e-8)


def test_full_contact_of_a_periodic_map_is_the_closed_form():
    """In full contact u = h - d, so p_q = E* |q| h_q / 2 (q != 0) and p_0 = p_mean: a
    result (area fraction 1, gap 0), not an error."""
    dx, dy = 0.5e-6, 0.7e-6
    h = self_affine(64, 48, dx=dx, dy=dy, seed=5)
    qx = 2 * np.pi * np.fft.fftfreq(64, dx)[:, None]
    qy = 2 * np.pi * np.fft.fftfreq(48, dy)[None, :]
    dp = np.fft.ifft2(np.fft.fft2(h) * E * np.hypot(qx, qy) / 2).real
    p_mean = -1.5 * dp.min()
    res = solve_contact(h, (dx, dy), E, p_mean, boundary="periodic", tol=1e-10)
    assert res.converged and res.area_fraction == 1.0 and res.contact.all()
    assert rel_l2(res.pressure, p_mean + dp) < 1e-8
    assert res.mean_gap == 0.0 and np.all(res.gap == 0.0)


@pytest.mark.parametrize("boundary", BOUNDARIES)
def test_result_follows_the_contract(boundary):
    """Pressure 0 out of contact and NaN on undefined pixels; gap 0 in contact, >= 0 out
    of it; gap = displacement - h + d with one d; the displacement is the half-space's
    response to the pressure (free: Love's coefficients exactly; periodic: up to the mean,
    which load control sets); the summary figures are those of the fields."""
    name = "holes"
    h, (dx, dy), p_mean, _ = case(name)
    res = solved(name, boundary)
    ok = np.isfinite(h)
    for field in (res.pressure, res.gap, res.displacement):
        assert field.shape == h.shape
    assert np.array_equal(np.isnan(res.pressure), ~ok) and np.array_equal(np.isnan(res.gap), ~ok)
    assert not res.contact[~ok].any()
    assert np.array_equal(res.contact[ok], res.pressure[ok] > 0)
    assert np.all(res.pressure[ok] >= 0) and np.all(res.gap[res.contact] == 0)
    scale = float(np.nanstd(h))
    assert res.gap[ok].min() >= -1e-6 * scale
    d = res.gap[ok] - res.displacement[ok] + h[ok]
    assert np.ptp(d) < 1e-6 * scale
    u = make_operator(h.shape, dx, dy, E, boundary)(np.where(ok, res.pressure, 0.0))
    du = res.displacement[ok] - u[ok]
    if boundary == "periodic":
        du -= du.mean()
    assert np.abs(du).max() < 1e-8 * np.abs(u[ok]).max()
    assert res.area_fraction == res.contact.sum() / ok.sum()
    assert res.max_pressure == np.nanmax(res.pressure)
    assert res.mean_gap == pytest.approx(np.nanmean(res.gap), rel=1e-12)
    assert (res.E_star, res.boundary, res.hardness) == (E, boundary, None)
    assert tuple(res.pixel_size) == (dx, dy) and res.pressure_asked == p_mean
    assert res.converged and 0 < res.iterations and res.residual <= 1e-8
    out = res.to_dict()
    keys = {"area_fraction", "pressure_Pa", "max_pressure_Pa", "mean_gap_m", "E_star_Pa",
            "boundary", "hardness_Pa", "iterations", "residual"}
    assert keys <= set(out)
    assert (out["area_fraction"], out["pressure_Pa"], out["boundary"]) == (
        res.area_fraction, res.mean_pressure, boundary)


@pytest.mark.parametrize("boundary", BOUNDARIES)
def test_a_load_curve_started_from_the_previous_solution(boundary):
    """``initial``: each pressure of a load curve started from the previous solution lands
    on the cold solve's answer; restarted from its own solution a solve has (almost)
    nothing left to do."""
    h, px, _, _ = case("self-affine")
    prev = None
    for f in (0.002, 0.003, 0.005):
        warm = solve_contact(h, px, E, f * E, boundary=boundary,
                             initial=None if prev is None else prev.pressure)
        cold = solve_contact(h, px, E, f * E, boundary=boundary, tol=1e-11)
        assert rel_l2(warm.pressure, cold.pressure) < 1e-6
        assert warm.mean_pressure == pytest.approx(f * E, rel=1e-10)
        prev = warm
    again = solve_contact(h, px, E, 0.005 * E, boundary=boundary, initial=cold.pressure)
    assert again.iterations < cold.iterations / 4
    assert rel_l2(again.pressure, cold.pressure) < 1e-8


def test_effective_modulus():
    """1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2; without E2 a rigid counterface."""
    assert effective_modulus(210e9, 0.3, 70e9, 0.33) == pytest.approx(
        1 / (0.91 / 210e9 + (1 - 0.33 ** 2) / 70e9), rel=1e-14)
    assert effective_modulus(210e9, 0.3) == pytest.approx(210e9 / 0.91, rel=1e-14)
    assert effective_modulus(1e9, 0.5, 1e9, 0.5) == pytest.approx(1e9 / 1.5, rel=1e-14)


# ---- the benchmark's plumbing (no timing asserted) -------------------------------------

@pytest.mark.parametrize("flags,msg", [
    (["--contact-size", "10"], "--contact-size must be a whole number in [64, 4096], got 10"),
    (["--repeats", "0"], "--repeats must be a whole number in [1, 20], got 0")])
def test_contact_benchmark_flags_refused(capsys, flags, msg):
    from cli_run import run
    code, out, err = run(capsys, "bench", "--only", "contact", *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err


def test_contact_benchmark_curve_is_the_library_load_curve(tmp_path):
    """asperity's child of the benchmark solves the load curve through iter_load_curve:
    the 8 pressures in turn, each warm solve cheaper than a cold one at its pressure, the
    last one's pressure that of a single solve at the highest pressure."""
    from asperity.contact import bench
    h = bench.self_affine(64, dx=bench.PIXEL, seed=1)
    np.save(tmp_path / "map.npy", h)
    spec = {"map": str(tmp_path / "map.npy"), "boundary": "periodic",
            "pressures": list(bench.CURVE), "tol": 1e-10, "out": str(tmp_path / "p.npy")}
    r = bench.run_case(bench.asperity_solver, spec, bench.asperity_curve)
    assert len(r["iterations_each"]) == len(r["seconds_each"]) == 8
    assert r["iterations"] == sum(r["iterations_each"])
    cold = [solve_contact(h, bench.PIXEL, bench.E_STAR, f * bench.E_STAR, tol=1e-10)
            for f in bench.CURVE]
    assert all(w < c.iterations for w, c in zip(r["iterations_each"][1:], cold[1:]))
    last = np.load(tmp_path / "p.npy")
    assert np.abs(last - cold[-1].pressure).max() < 1e-7 * cold[-1].max_pressure


@needs_cm
@pytest.mark.slow
def test_contact_benchmark_runs_every_solver_on_the_same_problem(capsys):
    """Each solver's child runs, reports its figures, and the three solve the same problem
    (their pressures agree to the tolerance); every target gets a verdict."""
    import json

    from cli_run import run
    code, out, err = run(capsys, "bench", "--only", "contact", "--contact-size", "64",
                         "--json")
    assert code == 0, err
    b = json.loads(out)["contact"]
    assert set(b["cases"]) == {"periodic", "free", "periodic curve"}
    for key, case_ in b["cases"].items():
        for solver in ("asperity", "contactmechanics", "plain"):
            r = case_[solver]
            assert "error" not in r, (key, solver, r)
            # the peak above the loaded map is a figure of big maps: at 64^2 it can be 0
            assert r["pixels"] == 64 * 64 and r["iterations"] > 0
            assert r["bytes_per_pixel"] == pytest.approx(r["peak_bytes"] / r["pixels"])
            assert len(r["iterations_each"]) == (8 if key == "periodic curve" else 1)
            if solver != "asperity":
                assert r["rel_l2_vs_asperity"] < 1e-6, (key, solver)
    assert all(v["value"] is not None for k, v in b["verdict"].items() if "4096" not in k)
