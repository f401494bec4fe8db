"""The measured surfaces of ../shared/data/surfaces give the expected character.

Nothing here is a snapshot of an earlier output: counts are recounted from the raw file,
statistics recomputed by an independent NumPy version of SPEC.md's formulas, and the
frame is checked by turning and mirroring the real surfaces (what follows exactly from
the physics); the remaining bounds state the character documented in the data README."""
import dataclasses
import json
import math
import zipfile
from pathlib import Path

import numpy as np
import pytest

from asperity.cli.main import main
from asperity.friction.derive import derive
from asperity.friction.faces import compute_reservoir
from asperity.surface.facets import load_surface

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "surfaces"
pytestmark = pytest.mark.skipif(not DATA.is_dir(),
                                reason=f"measured surfaces not found: {DATA} is absent")


def _axis_diff(a, b):
    d = abs(a - b) % 180.0
    return min(d, 180.0 - d)


@pytest.fixture(scope="module")
def ski():
    return load_surface(DATA / "SkiInfiniteFocus.x3p")


@pytest.fixture(scope="module")
def ski_windward(ski):
    return derive(ski, "windward", n_directions=72)


@pytest.fixture(scope="module")
def mi1():
    return load_surface(DATA / "mi-1.mi", height_scale=20.0)


def test_ski_undefined_pixels_are_those_of_the_raw_file(ski):
    """The x3p holds float32 heights, x fastest (data README); undefined points are stored
    as non-finite values.  Counted here from the archive itself, not by the reader."""
    with zipfile.ZipFile(DATA / "SkiInfiniteFocus.x3p") as z:
        raw = np.frombuffer(z.read("bindata/data.bin"), "<f4")
    assert raw.size == 1197 * 940                    # SizeX x SizeY of main.xml
    bad = int(np.count_nonzero(~np.isfinite(raw)))
    assert ski.n_undefined == bad
    assert 0.003 < bad / raw.size < 0.005            # README: ~0.4 % undefined pixels


def turned(surface, quarter_turns=0, mirror=False):
    """The facets of ``surface`` turned by 90 deg (z(x, y) -> z(y, -x): gradient (gx, gy)
    -> (-gy, gx)) ``quarter_turns`` times, or mirrored about the diagonal (gx <-> gy).
    Fresh arrays: the facets' own gx, gy are views of one array."""
    gx, gy = np.array(surface.gx), np.array(surface.gy)
    if mirror:
        gx, gy = gy, gx
    for _ in range(quarter_turns):
        gx, gy = -gy, gx
    return dataclasses.replace(surface, gx=gx, gy=gy)


def test_turning_the_ski_turns_its_principal_direction(ski, ski_windward):
    """Exact consequences of turning or mirroring a real surface: the principal direction
    turns with it (theta + 90 deg; 90 deg - theta when mirrored about the diagonal), the
    anisotropy stays, and so do mu_a+-, mu_b+- as pairs (+t_a may come out reversed)."""
    d = ski_windward
    th = d.principal_direction_deg
    for q, mirror, want in ((1, False, th + 90.0), (0, True, 90.0 - th)):
        e = derive(turned(ski, q, mirror), "windward", n_directions=72)
        assert _axis_diff(e.principal_direction_deg, want) < 1e-9, (q, mirror, e.principal_direction_deg)
        assert e.anisotropy == pytest.approx(d.anisotropy, rel=1e-12)
        for k in ("a", "b"):
            assert sorted((e.axes[f"mu_{k}_plus"], e.axes[f"mu_{k}_minus"])) == pytest.approx(
                sorted((d.axes[f"mu_{k}_plus"], d.axes[f"mu_{k}_minus"])), rel=1e-12)


def test_ski_is_anisotropic_across_its_grinding_lay(ski, ski_windward):
    # the grooves run along the axis of smallest mean squared slope (the lay)
    g = np.stack([ski.gx, ski.gy])
    m = (g * ski.weight) @ g.T
    evals, evecs = np.linalg.eigh(m)
    lay = np.degrees(np.arctan2(evecs[1, 0], evecs[0, 0])) % 180.0
    for contact, min_aniso in (("all-faces", 0.03), ("windward", 0.3)):
        d = ski_windward if contact == "windward" else derive(ski, contact, n_directions=72)
        assert _axis_diff(d.principal_direction_deg, lay + 90.0) < 3.0, (d.principal_direction_deg, lay)
        assert d.anisotropy > min_aniso
        assert d.axes["mu_a_plus"] > d.axes["mu_b_plus"] and d.axes["mu_a_minus"] > d.axes["mu_b_minus"]
    assert _axis_diff(lay, 30.0) < 5.0               # the grooves seen in the height map


def test_matrix4_grooves_along_y_give_principal_direction_along_x():
    d = derive(load_surface(DATA / "matrix-4.txt.gz"), "windward", n_directions=72)
    assert _axis_diff(d.principal_direction_deg, 0.0) < 5.0
    assert d.anisotropy > 0.15


@pytest.mark.parametrize("contact,tol", [("all-faces", 0.06), ("windward", 0.10)])
def test_matrix3_is_isotropic_within_tolerance(contact, tol):
    """Isotropic AFM roughness: T varies by less than tol of its mean over all directions
    (the grooved files vary by 0.19 and 0.41 in the windward regime)."""
    d = derive(load_surface(DATA / "matrix-3.txt"), contact, n_directions=72)
    assert d.anisotropy < tol


def _x_asymmetry(name, contact, **opts):
    T = compute_reservoir(load_surface(DATA / name, **opts), np.array([0.0, np.pi]), contact).tangential
    return (T[0] - T[1]) / T.mean()


def naive_T(surface, psi, contact):
    """T(psi) = p . s of SPEC.md section 2 over the facets, typed in with NumPy: a tip on a
    facet of gradient g moves with v = (s, g.s); the force on it is along m - mu v/|v|;
    p = -horizontal / vertical part, averaged with the facets' weights over the loaded
    facets (windward: those the motion climbs)."""
    gx, gy, w = surface.gx, surface.gy, surface.weight
    mu = surface.mu
    s = np.array([math.cos(psi), math.sin(psi)])
    nrm = np.sqrt(1 + gx * gx + gy * gy)
    slope = gx * s[0] + gy * s[1]
    v = np.sqrt(1 + slope * slope)
    m = np.stack([-gx / nrm, -gy / nrm, 1 / nrm])
    F = m - mu * np.stack([s[0] + 0 * gx, s[1] + 0 * gx, slope]) / v
    loaded = slope > 1e-12 if contact == "windward" else np.ones(gx.size, bool)
    p = -(F[:2] / F[2])[:, loaded] @ w[loaded] / w[loaded].sum()
    return float(p @ s)


@pytest.mark.parametrize("contact", ["windward", "all-faces"])
def test_mi1_friction_along_x_recomputed_and_mirrored(mi1, contact):
    """The asymmetry along x of the terraced AFM surface by an independent NumPy version of
    the homogenisation (to rounding, 2e-16 measured); mirroring the surface in x
    (gx -> -gx) swaps mu+ and mu-."""
    mi = mi1
    T = compute_reservoir(mi, np.array([0.0, np.pi]), contact).tangential
    np.testing.assert_allclose(T, [naive_T(mi, 0.0, contact), naive_T(mi, np.pi, contact)],
                               rtol=1e-12)
    flipped = dataclasses.replace(mi, gx=-np.array(mi.gx), gy=np.array(mi.gy))
    Tf = compute_reservoir(flipped, np.array([0.0, np.pi]), contact).tangential
    np.testing.assert_allclose(Tf, T[::-1], rtol=1e-12)


def test_mi1_terraces_are_asymmetric_along_x():
    """Steep rises, gentle falls along x: sliding towards +x climbs the steep rises, so
    mu+ > mu- along x; rigid asperities (windward) show it strongly (0.50), compliant
    springs (all faces) weakly (third order in the slopes; 0.005).  The isotropic
    control's asymmetry along x is 0.06 (windward)."""
    assert _x_asymmetry("mi-1.mi", "windward", height_scale=20.0) > 0.4
    assert _x_asymmetry("mi-1.mi", "all-faces", height_scale=20.0) > 0.002
    assert abs(_x_asymmetry("matrix-3.txt", "windward")) < 0.1


def test_every_shared_file_goes_through_the_cli(capsys):
    for name, extra in (("SkiInfiniteFocus.x3p", []), ("mi-1.mi", []), ("matrix-3.txt", []),
                        ("matrix-4.txt.gz", []), ("example_surface.stl.gz", ["--unit", "mm"])):
        code = main(["derive", str(DATA / name), "--json", "--directions", "36", *extra])
        out, err = capsys.readouterr()
        assert code == 0, err
        d = json.loads(out)
        assert d["n_facets"] > 10_000 and d["admissible"] and not d["self_locking"]
        assert 0.08 < d["mu_a_plus"] < 0.2 and 0.0 <= d["principal_direction_deg"] < 180.0


@pytest.mark.parametrize("name,law", [("matrix-4.txt.gz", "star"), ("mi-1.mi", "truncated-ellipse")])
def test_gauge_of_a_measured_surface_reloads_bit_for_bit(tmp_path, name, law):
    from asperity.laws.fitting import fit_derivation
    from asperity.laws.gauge_file import read_gauge, to_dict, write_gauge
    d = derive(load_surface(DATA / name, height_scale=20.0 if name == "mi-1.mi" else 1.0),
               "windward", n_directions=72)
    gl = fit_derivation(d, law)
    write_gauge(tmp_path / "g.json", gl)
    again = read_gauge(tmp_path / "g.json")
    assert to_dict(again) == to_dict(gl)
    psi = np.radians(np.arange(0.0, 360.0, 7.0))
    for a in psi:
        assert np.array_equal(again.law.force(a).p, gl.law.force(a).p)
    assert gl.fit.min_dissipation > 0


def test_an_instrument_file_read_in_another_unit_than_it_states():
    """unit reads the numbers of mi-1.mi (stated in micrometres) in nanometres: every
    length 1000 times smaller; pixel_size replaces the spacing."""
    pytest.importorskip("SurfaceTopography")
    from asperity.surface.readers import read_surface
    a = read_surface(DATA / "mi-1.mi")
    b = read_surface(DATA / "mi-1.mi", unit="nm")
    c = read_surface(DATA / "mi-1.mi", unit="nm", pixel_size=(2, 3))
    assert (b.dx, b.dy) == pytest.approx((a.dx * 1e-3, a.dy * 1e-3), rel=1e-12)
    np.testing.assert_allclose(b.heights, a.heights * 1e-3, rtol=1e-12, equal_nan=True)
    assert (c.dx, c.dy) == pytest.approx((2e-9, 3e-9), rel=1e-15)
    np.testing.assert_array_equal(np.isnan(c.heights), np.isnan(a.heights))
