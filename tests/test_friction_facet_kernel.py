"""Streamed facet reservoir (numba kernel and streamed NumPy) against the NumPy reference."""
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import asperity.friction.facet_reservoir as fr
from asperity.errors import InputError
from asperity.friction.faces import compute_face_reservoir
from asperity.friction.facet_reservoir import compute_facet_reservoir, numpy_facet_reservoir

RTOL = 1e-12
IMPLS = [compute_facet_reservoir, numpy_facet_reservoir]


def reference(gx, gy, mu, w, psi, contact):
    mu_arr = np.broadcast_to(np.asarray(mu, dtype=float), gx.shape)
    return compute_face_reservoir(np.column_stack([gx, gy]), mu_arr, w, psi, contact)


def assert_same(r, ref):
    assert r.contact == ref.contact
    np.testing.assert_array_equal(r.psi, ref.psi)
    np.testing.assert_array_equal(r.locked, ref.locked)
    np.testing.assert_array_equal(r.locked_face, ref.locked_face)
    np.testing.assert_array_equal(r.set_valued, ref.set_valued)
    assert r.locked_face.dtype == np.int64
    assert np.all(np.isinf(r.p[r.locked]))
    ok = ~ref.locked
    if ok.any():
        scale = np.abs(ref.p[ok]).max()
        np.testing.assert_allclose(r.p[ok], ref.p[ok], rtol=RTOL, atol=RTOL * scale)


def random_facets(n, seed, *, per_facet_mu=True, zero_weights=False):
    rng = np.random.default_rng(seed)
    gx, gy = rng.normal(0.0, 0.3, n), rng.normal(0.0, 0.3, n)
    mu = rng.uniform(0.0, 0.4, n) if per_facet_mu else 0.25
    w = rng.uniform(0.1, 1.0, n)
    if zero_weights:
        w[rng.random(n) < 0.3] = 0.0
    return gx, gy, mu, w


@pytest.fixture
def small_chunks(monkeypatch):
    """Many chunks and a facet split across threads even for a few thousand facets."""
    monkeypatch.setattr(fr, "CHUNK", 64)
    monkeypatch.setattr(fr, "MIN_FACETS_PER_WORKER", 16)


PSI = np.linspace(0.0, 2 * np.pi, 73)


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
@pytest.mark.parametrize("per_facet_mu", [False, True])
@pytest.mark.parametrize("zero_weights", [False, True])
@pytest.mark.parametrize("chunks", ["default", "small"])
def test_random_facets_match_reference(contact, per_facet_mu, zero_weights, chunks, request):
    if chunks == "small":
        request.getfixturevalue("small_chunks")
    gx, gy, mu, w = random_facets(3001, 1, per_facet_mu=per_facet_mu, zero_weights=zero_weights)
    ref = reference(gx, gy, mu, w, PSI, contact)
    assert not ref.locked.any()
    for impl in IMPLS:
        assert_same(impl(gx, gy, mu, w, PSI, contact), ref)


def test_many_facets_split_over_threads_match_reference():
    gx, gy, mu, w = random_facets(40_000, 2, zero_weights=True)
    psi = np.linspace(0.0, 2 * np.pi, 7)
    for contact in ("all-faces", "windward"):
        ref = reference(gx, gy, mu, w, psi, contact)
        assert_same(compute_facet_reservoir(gx, gy, mu, w, psi, contact), ref)


@pytest.mark.parametrize("contact", ["all-faces", "windward"])
def test_self_locking_first_face_in_facet_order(contact, small_chunks):
    gx, gy, mu, w = random_facets(2000, 3, zero_weights=False)
    # steep faces with large friction lock when climbed; the zero-weight one never loads
    for i, (g, m, wt) in {300: ((-3.0, 0.0), 0.6, 0.0), 700: ((3.0, 0.0), 0.6, 1.0),
                          1500: ((0.0, 4.0), 0.5, 1.0), 1900: ((2.5, 2.5), 0.7, 1.0)}.items():
        gx[i], gy[i] = g
        mu[i], w[i] = m, wt
    psi = np.radians(np.arange(0.0, 360.0, 5.0))
    ref = reference(gx, gy, mu, w, psi, contact)
    assert ref.locked.any() and not ref.locked.all()
    assert set(ref.locked_face[ref.locked]) >= {700, 1500}
    assert 300 not in set(ref.locked_face)
    for impl in IMPLS:
        assert_same(impl(gx, gy, mu, w, psi, contact), ref)


@pytest.mark.parametrize("copies", [1, 50])
def test_windward_level_faces_set_valued_along_ridges(copies):
    # symmetric wedge faces plus a flat facet: along the ridges (90 deg) no face is climbed
    t = math.tan(math.radians(30.0))
    gx = np.tile([t, -t, 0.0], copies)
    gy = np.zeros_like(gx)
    w = np.tile([1.0, 1.0, 0.5], copies)
    psi = np.radians([0.0, 45.0, 89.0, 90.0, 91.0, 180.0, 270.0])
    for mu in (0.3, np.tile([0.3, 0.2, 0.1], copies)):
        ref = reference(gx, gy, mu, w, psi, "windward")
        np.testing.assert_array_equal(ref.set_valued, [False, False, False, True, False, False,
                                                       True])
        for impl in IMPLS:
            assert_same(impl(gx, gy, mu, w, psi, "windward"), ref)


def test_windward_flat_only_is_level_not_set_valued():
    gx = gy = np.zeros(100)
    r = compute_facet_reservoir(gx, gy, 0.4, np.ones(100), PSI, "windward")
    assert_same(r, reference(gx, gy, 0.4, np.ones(100), PSI, "windward"))
    assert not r.set_valued.any()
    np.testing.assert_allclose(r.tangential, 0.4, rtol=1e-14)


def test_windward_no_loaded_face_is_an_input_error():
    with pytest.raises(InputError, match="every face descends"):
        reference(np.array([1.0]), np.array([0.0]), 0.1, np.array([1.0]), [math.pi], "windward")
    for impl in IMPLS:
        with pytest.raises(InputError, match="every face descends"):
            impl([1.0], [0.0], 0.1, [1.0], [0.0, math.pi], "windward")


def test_progress_batches_and_empty_psi_refused():
    gx, gy, mu, w = random_facets(500, 4)
    seen = []
    r = compute_facet_reservoir(gx, gy, mu, w, PSI, progress=seen.append, batch=10)
    assert seen == sorted(seen) and seen[-1] == 1.0 and len(seen) == 8
    assert_same(r, reference(gx, gy, mu, w, PSI, "all-faces"))
    seen.clear()
    numpy_facet_reservoir(gx, gy, mu, w, PSI, progress=seen.append, batch=73)
    assert seen == [1.0]
    with pytest.raises(InputError, match="psi must hold at least 1 value, got 0"):
        compute_facet_reservoir(gx, gy, mu, w, [])    # as the spring model's reservoir


def test_scalar_psi_and_lists():
    r = compute_facet_reservoir([0.1, -0.2], [0.0, 0.3], [0.1, 0.2], [1, 2], 0.5)
    assert_same(r, reference(np.array([0.1, -0.2]), np.array([0.0, 0.3]), [0.1, 0.2],
                             np.array([1.0, 2.0]), 0.5, "all-faces"))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(1, 90), seed=st.integers(0, 2**32 - 1),
       contact=st.sampled_from(["all-faces", "windward"]), uniform=st.booleans(),
       m=st.integers(1, 40))
def test_hypothesis_random_facets(n, seed, contact, uniform, m):
    rng = np.random.default_rng(seed)
    gx, gy = rng.normal(0.0, 0.4, n), rng.normal(0.0, 0.4, n)
    # some exactly axis-aligned and flat facets (level along the axes)
    gy[rng.random(n) < 0.3] = 0.0
    gx[rng.random(n) < 0.1] = 0.0
    mu = 0.3 if uniform else rng.uniform(0.0, 0.4, n)
    w = rng.uniform(0.0, 1.0, n) * (rng.random(n) < 0.8)
    w[0] = 1.0
    psi = np.concatenate([rng.uniform(0, 2 * np.pi, m), [0.0, 0.5 * np.pi, np.pi]])
    try:
        ref = reference(gx, gy, mu, w, psi, contact)
    except InputError:
        for impl in IMPLS:
            with pytest.raises(InputError):
                impl(gx, gy, mu, w, psi, contact)
        return
    for impl in IMPLS:
        assert_same(impl(gx, gy, mu, w, psi, contact), ref)


@pytest.mark.parametrize("kwargs,match", [
    (dict(gx=[0.0, np.nan]), "gx and gy must be finite"),
    (dict(gy=[0.0, np.inf]), "gx and gy must be finite"),
    (dict(gy=[0.0]), "gy must have the shape"),
    (dict(gx=[[0.0, 1.0]]), r"gx must have 1 dimension\(s\)"),
    (dict(gx=["a", "b"]), "gx must be an array of numbers"),
    (dict(mu=-0.1), r"mu must be in \[0, 100\], got -0.1"),
    (dict(mu=[0.1, np.nan]), r"mu must be in \[0, 100\] \(1 facets"),
    (dict(mu=[0.1, 0.2, 0.3]), r"mu must be a number or an array of shape \(2,\)"),
    (dict(mu="x"), "mu must be a number"),
    (dict(weight=[1.0, -1.0]), "weight must be finite, >= 0"),
    (dict(weight=[0.0, 0.0]), "not all zero"),
    (dict(weight=[1.0]), r"weight must have shape \(2,\)"),
    (dict(psi=[0.0, np.nan]), "psi must be finite"),
    (dict(psi=[[0.0, 1.0]]), "psi must be a number or a 1-d array"),
    (dict(mu=[0.1, 1e300]), "mu must be in"),
    (dict(contact="leeward"), "contact must be one of"),
    (dict(batch=0), "batch must be a whole number in"),
    (dict(batch=1.5), "batch must be a whole number"),
    (dict(progress=3), "progress must be a callable"),
])
@pytest.mark.parametrize("impl", IMPLS)
def test_bad_input_one_line_errors(impl, kwargs, match):
    args = dict(gx=[0.1, 0.2], gy=[0.0, 0.1], mu=0.2, weight=[1.0, 1.0], psi=[0.0, 1.0],
                contact="all-faces")
    args.update(kwargs)
    extra = {k: args.pop(k) for k in ("batch", "progress") if k in args}
    with pytest.raises(InputError, match=match) as exc:
        impl(args["gx"], args["gy"], args["mu"], args["weight"], args["psi"], args["contact"],
             **extra)
    assert "\n" not in str(exc.value)


def test_import_asperity_does_not_import_numba():
    import subprocess
    import sys
    code = "import sys, asperity, asperity.friction.facet_reservoir; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_bench_facets_cli_json(capsys):
    import json

    from asperity.cli.main import main
    assert main(["bench", "--only", "facets", "--facets", "32", "--directions", "12",
                 "--numpy-directions", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)["facets"]
    assert out["facets"] == 2 * 32 * 32 and out["numpy_directions"] == 3
    for v in out["regimes"].values():
        assert v["same_flags"] and v["max_rel_diff"] < 1e-12
        assert v["numba"]["facet_directions_per_second"] > 0
