"""The measured surfaces of ../shared/data/surfaces give the expected character."""
import json
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


def test_ski_is_anisotropic_across_its_grinding_lay(ski):
    assert ski.n_undefined == 4272                  # ~0.4 % undefined pixels, counted
    # the grooves run along the axis of smallest mean squared slope (the lay)
    g = np.stack([ski.gx, ski.gy])
    m = (g * ski.weight) @ g.T
    evals, evecs = np.linalg.eigh(m)
    lay = np.degrees(np.arctan2(evecs[1, 0], evecs[0, 0])) % 180.0
    for contact, min_aniso in (("all-faces", 0.03), ("windward", 0.3)):
        d = derive(ski, contact, n_directions=72)
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
