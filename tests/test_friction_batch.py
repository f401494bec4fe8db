"""mu+ and mu- of a block of wedge textures (asperity.microslip.friction_batch) against the
per-case path it stands in for, friction_from_texture(texture_from_dict(table_i)): equal
(to 1e-12 relative; on x86-64 bit for bit) wherever the block says ok, and ok False exactly
where the per-case path refuses the case."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from asperity.errors import InputError
from asperity.microslip.friction import friction_from_texture
from asperity.microslip.friction_batch import KINDS, resolve_slip_rules, texture_friction_batch
from asperity.texture.wedges import texture_from_dict

SURFACES = Path(__file__).resolve().parents[1] / "surfaces"


def table_of(name: str) -> dict:
    return tomllib.loads((SURFACES / name).read_text())["texture"]


def per_case(table, varied, i, contact="all-faces", axis=None, face="support"):
    """(mu+, mu-) of case i by the per-case path (the study puts float(v) in the table), or
    the InputError it raises."""
    t = dict(table)
    t.update({k: float(v[i]) for k, v in varied.items()})
    a = axis if axis is None or np.ndim(axis) == 0 else float(axis[i])
    try:
        f = friction_from_texture(texture_from_dict(t), contact, a, face)
    except InputError as exc:
        return exc
    return f.mu_plus, f.mu_minus


def check_block(table, varied, contact="all-faces", axis=None, face="support", cases=None):
    """Compare the block with the per-case path on ``cases`` (default: all); returns the
    number of cases ok and of self-locking directions among them."""
    mp, mm, ok = texture_friction_batch(table, varied, contact=contact, slip_axis_deg=axis,
                                        textured=face)
    m = ok.size
    assert mp.shape == mm.shape == (m,) and ok.dtype == bool
    n_ok = n_inf = 0
    for i in range(m) if cases is None else cases:
        ref = per_case(table, varied, i, contact, axis, face)
        where = f"case {i} ({contact}, axis {axis}, {face}): " + \
            ", ".join(f"{k} = {v[i]!r}" for k, v in varied.items())
        if isinstance(ref, InputError):
            assert not ok[i], f"{where}: the per-case path refuses it ({ref}) but ok is True"
            assert np.isnan(mp[i]) and np.isnan(mm[i])
            continue
        assert ok[i], f"{where}: the per-case path gives {ref} but ok is False"
        for got, want in zip((mp[i], mm[i]), ref):
            if math.isinf(want):
                assert got == want, f"{where}: self-locking {want} -> {got}"
            else:
                assert abs(got - want) <= 1e-12 * abs(want), f"{where}: {got!r} != {want!r}"
        n_ok += 1
        n_inf += math.isinf(ref[0]) + math.isinf(ref[1])
    return n_ok, n_inf


def random_values(rng, m, fields, wide=True):
    """Values around and beyond the ranges (wide) or inside them."""
    lo_hi = {"alpha_deg": (-5.0, 95.0) if wide else (1.0, 85.0),
             "beta_deg": (-5.0, 95.0) if wide else (1.0, 85.0),
             "mu_alpha": (-0.05, 1.2) if wide else (0.0, 0.8),
             "mu_beta": (-0.05, 1.2) if wide else (0.0, 0.8),
             "height": (-1e-6, 1e-5), "height_mean": (-1e-6, 1e-5),
             "height_std": (-1e-6, 2e-5), "mean_gap": (-1e-6, 2e-4)}
    return {f: rng.uniform(*lo_hi[f], m) for f in fields}


WEDGE_FIELDS = [("alpha_deg",), ("mu_beta",), ("height",), ("alpha_deg", "beta_deg"),
                ("alpha_deg", "beta_deg", "mu_alpha", "mu_beta")]


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
@pytest.mark.parametrize("name", ["wedge-asymmetric.toml", "self-locking.toml",
                                  "wedge-symmetric-30.toml"])
def test_random_wedge_blocks_equal_the_per_case_path(name, contact):
    rng = np.random.default_rng(len(name) + len(contact))
    table = table_of(name)
    seen_ok = seen_bad = seen_inf = 0
    for j, fields in enumerate(WEDGE_FIELDS):
        axis, face = [(None, "support"), (25.0, "part"), (-90.0, "support"),
                      (180.0, "part"), (None, "part")][j]
        varied = random_values(rng, 150, fields)
        n_ok, n_inf = check_block(table, varied, contact, axis, face)
        seen_ok += n_ok
        seen_bad += 150 - n_ok
        seen_inf += n_inf
    assert seen_ok > 300 and seen_bad > 50, "the blocks must mix good and refused cases"
    assert seen_inf > 0, "some cases must self-lock"


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_random_gaussian_wedge_blocks_equal_the_per_case_path(contact):
    rng = np.random.default_rng(7)
    table = table_of("gaussian-wedges.toml")
    assert table["kind"] == "gaussian-wedge"
    for fields, axis, face in [(("alpha_deg", "mu_alpha"), None, "support"),
                               (("height_mean", "height_std"), 10.0, "part"),
                               (("mean_gap", "alpha_deg", "beta_deg"), None, "part"),
                               (("height_mean", "mean_gap"), -45.0, "support")]:
        varied = random_values(rng, 150, fields)
        n_ok, _ = check_block(table, varied, contact, axis, face)
        assert 10 < n_ok < 150, f"{fields}: the block must mix good and refused cases"


def test_a_study_varying_the_slip_axis_per_case():
    rng = np.random.default_rng(11)
    table = table_of("wedge-asymmetric.toml")
    varied = random_values(rng, 200, ("alpha_deg", "mu_alpha"), wide=False)
    axis = rng.uniform(-400.0, 400.0, 200)
    axis[:4] = [-360.0, 360.0, np.nextafter(360.0, 400.0), np.nan]
    _, _, ok = texture_friction_batch(table, varied, slip_axis_deg=axis)
    assert ok[:2].all() and not ok[2:4].any() and not ok[np.abs(axis) > 360].any()
    # the per-case path takes any axis; the assembly refuses |axis| > 360 (risk), so do we
    check_block(table, varied, "windward", axis, "part", cases=np.flatnonzero(ok))


def boundary_values(field, table):
    """(values at and beyond the range of ``field``, the expected ok of each)."""
    up, down = (lambda x: np.nextafter(x, np.inf)), (lambda x: np.nextafter(x, -np.inf))
    nan, inf = np.nan, np.inf
    cases = {
        "alpha_deg": [(1e-6, 1), (down(1e-6), 0), (down(90.0), 1), (90.0, 0), (0.0, 0),
                      (-30.0, 0), (nan, 0), (inf, 0)],
        "mu_alpha": [(0.0, 1), (-0.0, 1), (100.0, 1), (up(100.0), 0), (-1e-300, 0), (nan, 0),
                     (inf, 0)],
        "height": [(1e-10, 1), (down(1e-10), 0), (100.0, 1), (up(100.0), 0), (nan, 0)],
        "height_std": [(0.0, 1), (-1e-300, 0), (3.0 * table.get("height_mean", 1.0), 1),
                       (up(3.0 * table.get("height_mean", 1.0)), 0), (inf, 0)],
        "n_wedges": [(1.0, 1), (0.0, 0), (1.5, 0), (1e7, 1), (1e7 + 1, 0), (nan, 0)],
        "seed": [(0.0, 1), (-1.0, 0), (2.5, 0), (2.0**62, 1), (down(2.0**63), 1),
                 (2.0**63, 0), (inf, 0)],
    }
    if field == "mean_gap":
        a, b = math.radians(table["alpha_deg"]), math.radians(table["beta_deg"])
        most = 100.0 * (table["height_mean"] * (1 / math.tan(a) + 1 / math.tan(b)))  # as the class
        cases["mean_gap"] = [(0.0, 1), (most, 1), (up(most), 0), (-1e-300, 0), (inf, 0)]
    v, ok = zip(*cases[field])
    return np.array(v), np.array(ok, dtype=bool)


@pytest.mark.parametrize("name,field", [
    ("wedge-asymmetric.toml", "alpha_deg"), ("wedge-asymmetric.toml", "mu_alpha"),
    ("wedge-asymmetric.toml", "height"), ("gaussian-wedges.toml", "alpha_deg"),
    ("gaussian-wedges.toml", "height_std"), ("gaussian-wedges.toml", "n_wedges"),
    ("gaussian-wedges.toml", "seed"), ("gaussian-wedges.toml", "mean_gap")])
def test_values_at_and_beyond_the_ranges(name, field):
    table = table_of(name)
    values, expected = boundary_values(field, table)
    _, _, ok = texture_friction_batch(table, {field: values})
    np.testing.assert_array_equal(ok, expected, err_msg=f"{field} = {values}")
    check_block(table, {field: values})
    for v in values[~expected]:          # the per-case path refuses these, naming the field
        t = dict(table, **{field: float(v)})
        with pytest.raises(InputError, match=f"texture.{field} "):
            friction_from_texture(texture_from_dict(t))


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_self_locking_at_the_lock_threshold(contact):
    """mu tan(alpha) around 1: the alpha face self-locks (mu+ = inf) where its vertical
    force share F_z = (1 - mu tan alpha)/sqrt(1 + tan^2 alpha) (psi = 0) reaches the lock
    tolerance; swept across it in steps of 1e-5 of it, where rounding decides, the same
    cases lock in the block as per case."""
    from asperity.friction.reservoir import LOCK_TOL
    alpha = np.array([20.0, 45.0, 60.0, 80.0, 89.0])
    ta = np.tan(np.radians(alpha))[:, None]
    fz = LOCK_TOL * (1.0 + 1e-5 * np.arange(-40, 41))[None, :]
    mu = (1.0 - fz * np.sqrt(1.0 + ta * ta)) / ta
    varied = {"alpha_deg": np.repeat(alpha, fz.size), "mu_alpha": mu.ravel()}
    table = table_of("wedge-asymmetric.toml")
    mp, mm, ok = texture_friction_batch(table, varied, contact=contact)
    locked = np.isinf(mp)
    assert locked.any() and (ok & ~locked).any(), "the sweep must cross the lock"
    assert np.isfinite(mm[ok]).all()
    check_block(table, varied, contact)
    mp2, mm2, ok2 = texture_friction_batch(table, varied, contact=contact, textured="part")
    np.testing.assert_array_equal(ok2, ok)
    np.testing.assert_array_equal(mm2[ok], mp[ok])
    np.testing.assert_array_equal(mp2[ok], mm[ok])


def test_a_texture_with_no_friction_is_left_to_the_per_case_path():
    table = table_of("wedge-symmetric-30.toml")
    varied = {"mu_alpha": np.array([0.0, 0.0, 1e-3]), "mu_beta": np.array([0.0, 1e-3, 0.0])}
    mp, mm, ok = texture_friction_batch(table, varied)
    assert not ok[0] and np.isnan(mp[0]) and np.isnan(mm[0])
    with pytest.raises(InputError, match="no friction along the slip axis"):
        friction_from_texture(texture_from_dict(dict(table, mu_alpha=0.0, mu_beta=0.0)))
    check_block(table, varied)


@pytest.mark.parametrize("change", [
    {"kind": "sinusoid"}, {"kind": 3}, {"wavelength": 1.0}, {"alpha_deg": 95.0},
    {"alpha_deg": "30"}, {"mu_beta": True}, {"height_std": 1e-6}, {"_profile": None}])
def test_a_table_no_case_can_be_built_from_is_left_to_the_per_case_path(change):
    table = dict(table_of("wedge-asymmetric.toml"), **change)
    varied = {"beta_deg": np.array([10.0, 20.0])}
    mp, mm, ok = texture_friction_batch(table, varied)
    assert not ok.any() and np.isnan(mp).all() and np.isnan(mm).all()
    with pytest.raises(InputError):
        texture_from_dict(dict(table, beta_deg=10.0))


def test_missing_keys_unknown_varied_fields_and_options():
    table = table_of("wedge-asymmetric.toml")
    beta = {"beta_deg": np.array([10.0, 20.0])}
    no_alpha = {k: v for k, v in table.items() if k != "alpha_deg"}
    assert not texture_friction_batch(no_alpha, beta)[2].any()
    assert texture_friction_batch(no_alpha, {**beta, "alpha_deg": np.array([30.0, 40.0])})[2].all()
    assert not texture_friction_batch(table, {**beta, "kind": np.array([1.0, 2.0])})[2].any()
    assert not texture_friction_batch(table, {**beta, "n_wedges": np.array([1.0, 2.0])})[2].any()
    for opts in ({"contact": "rigid"}, {"textured": "both"}, {"slip_axis_deg": 400.0},
                 {"slip_axis_deg": math.nan}, {"slip_axis_deg": "0"}):
        assert not texture_friction_batch(table, beta, **opts)[2].any(), opts
    mp, mm, ok = texture_friction_batch(table, {})
    assert ok.shape == (1,) and ok[0]
    f = friction_from_texture(texture_from_dict(table))
    assert (mp[0], mm[0]) == (f.mu_plus, f.mu_minus)
    with pytest.raises(InputError, match="1-d arrays of one length"):
        texture_friction_batch(table, {"alpha_deg": np.ones(3), "beta_deg": np.ones(4)})


def test_the_shipped_wedge_textures_are_kinds_the_block_covers():
    kinds = {tomllib.loads(p.read_text()).get("texture", {}).get("kind", "wedge")
             for p in SURFACES.glob("*.toml") if "texture" in tomllib.loads(p.read_text())}
    assert kinds and kinds <= set(KINDS), kinds


def test_the_study_path_the_block_stands_in_for():
    """The bushing tolerance study: its texture table, its varied texture fields and the
    assembly's slip axis and textured face, against assembly_friction case by case."""
    from asperity.microslip.risk import assembly_friction
    from asperity.study.cases import build_inputs
    from asperity.study.spec import load_study
    study = load_study(SURFACES / "bushing-tolerance.toml")
    spec, X = study.spec, study.matrix()[:150]
    names = study.parameter_names
    varied = {n.split(".", 1)[1]: X[:, j] for j, n in enumerate(names)
              if n.startswith("texture.")}
    _, asm = build_inputs(spec, {}, None)
    axis, face = resolve_slip_rules(asm.friction_table, spec.get("slip_axis_deg"),
                                    spec.get("textured"))
    assert (axis, face) == (0.0, "support")
    mp, mm, ok = texture_friction_batch(spec["texture"], varied, contact=spec["contact"],
                                        slip_axis_deg=axis, textured=face)
    assert ok.all()
    for i in range(len(X)):
        tex, asm = build_inputs(spec, dict(zip(names, map(float, X[i]))), None)
        f = assembly_friction(asm, tex, contact=spec["contact"],
                              slip_axis_deg=spec.get("slip_axis_deg"),
                              textured=spec.get("textured"))
        assert abs(mp[i] - f.mu_plus) <= 1e-12 * f.mu_plus
        assert abs(mm[i] - f.mu_minus) <= 1e-12 * f.mu_minus
    assert resolve_slip_rules(asm.friction_table, -30.0, "part") == (-30.0, "part")
    assert resolve_slip_rules({}, None, None) == (None, "support")


@pytest.mark.parametrize("face", ["support", "part"])
def test_windward_along_the_ridges(face):
    """Sliding along the ridges (psi = 90 deg) in the windward regime: a face is climbed
    only through cos(90 deg) = 6e-17 times its steep gradient (alpha, beta near 90 deg),
    else the level faces carry the load (set-valued); the same branch and number as per
    case on both sides of the level tolerance."""
    from asperity.friction.faces import compute_face_reservoir
    steep = 90.0 - np.geomspace(1e-1, 1e-6, 40)
    varied = {"alpha_deg": np.tile(steep, 3), "beta_deg": np.repeat([30.0, 89.9999, 89.99999], 40)}
    table = table_of("wedge-symmetric-30.toml")
    check_block(table, varied, "windward", 90.0, face)
    ta = np.tan(np.radians(steep))
    slope = ta * np.cos(np.radians(90.0))
    assert (slope > 1e-12).any() and (slope <= 1e-12).any(), "the sweep must cross the tolerance"
    res = compute_face_reservoir([[ta[-1], 0.0], [-1.0, 0.0]], [0.3, 0.3], [0.5, 0.5],
                                 np.radians([90.0]), "windward")
    assert not res.set_valued[0], "a climbed face by rounding: not the set-valued branch"
