"""VFRIC and VFRICTION (Abaqus/Explicit) called through ctypes exactly as Abaqus calls
them, against a reference written here in global vectors (not in the routine's local
angles): the law's frame e_x = props(1:3) projected on the tangent plane, e_y = n x e_x;
the slider's sliding direction is t1 (texture on the main surface, props(4) = +1) or -t1
(texture on the secondary surface); the force on the secondary node is -fN p or +fN p;
the law holds the node when fStickForce <= fN R(sliding direction).

The law-frame core here is the hand-written associated truncated ellipse of
:mod:`fe_standin` (closed form; :class:`TruncatedEllipse` is its Python twin), so these
tests check the wrappers and the harness; the generated cores are checked against
``asperity law --psi`` in the routine tests."""
from __future__ import annotations

import math

import numpy as np
import pytest
from fe_builds import library, needs_gfortran
from fe_standin import ellipse_core

from asperity.fe.abaqus_explicit import source
from asperity.fe.fortran_harness import call_vfric, call_vfriction
from asperity.laws.sets import TruncatedEllipse

pytestmark = needs_gfortran
AXES = {"mu_a_plus": 0.2, "mu_a_minus": 0.08, "mu_b_plus": 0.12, "mu_b_minus": 0.15,
        "theta": 0.3}
ELL = TruncatedEllipse(**AXES)
P_LO, P_HI = 1e5, 1e7                # pressures outside are counted as clamped
CORE = ellipse_core(*AXES.values(), p_lo=P_LO, p_hi=P_HI)


def lib(routine, precision="double"):
    return library(source(routine) + CORE, precision)


def reference(props, t1, n, fn, fs):
    """(f1, f2, stick) of the force on the secondary node in (t1, t2), global vectors."""
    t1, n, a = np.asarray(t1, float), np.asarray(n, float), np.asarray(props[:3], float)
    ex = a - a.dot(n) * n
    ex /= np.linalg.norm(ex)
    ey = np.cross(n, ex)
    t2 = np.cross(n, t1)
    side = props[3]
    s = t1 if side > 0 else -t1                            # the slider's sliding direction
    phi = math.atan2(s.dot(ey), s.dot(ex))
    if fs <= fn * ELL.radial([phi])[0]:
        return -fs, 0.0, True
    p = ELL.normal_point([phi])[0][0]
    f = (-fn if side > 0 else fn) * (p[0] * ex + p[1] * ey)
    return min(0.0, max(-fs, f.dot(t1))), f.dot(t2), False


def random_points(rng, m):
    """m contact points: orthonormal (t1, n), the law's axis, the side, fN, stick force."""
    out = []
    for _ in range(m):
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        t1 = np.cross(n, rng.normal(size=3))
        t1 /= np.linalg.norm(t1)
        props = np.r_[rng.normal(size=3), rng.choice([-1.0, 1.0])]
        fn = rng.uniform(1.0, 100.0)
        fs = fn * rng.uniform(0.0, 0.3)                     # stick and slip both occur
        out.append((props, t1, n, fn, fs))
    return out


def run_vfric(points, *, jcon, nslv, area, precision="double", nsv=2, statev=None):
    props = points[0][0]
    m = len(points)
    sv = np.zeros((nsv, nslv)) if statev is None else statev
    return call_vfric(lib("vfric", precision), fnormal=[p[3] for p in points],
                      fstick=[p[4] for p in points],
                      dircos_sl=np.column_stack([p[1] for p in points]),
                      dircos_n=np.column_stack([p[2] for p in points]), props=props,
                      statev=sv, jconslvid=jcon, area=area,
                      dtype=np.float64 if precision == "double" else np.float32,
                      sentinel=np.nan if m else 0.0)


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_vfric_stick_and_slip_against_global_reference(side):
    rng = np.random.default_rng(7 if side > 0 else 8)
    pts = random_points(rng, 400)
    sticks = 0
    for props, t1, n, fn, fs in pts:
        props = props.copy()
        props[3] = side
        got = run_vfric([(props, t1, n, fn, fs)], jcon=[1], nslv=1, area=[fn / 1e6])
        f1, f2, stick = reference(props, t1, n, fn, fs)
        sticks += stick
        ft = got["fTangential"][:, 0]
        assert ft[0] == pytest.approx(f1, abs=1e-12 * fn), (props, t1, n, fn, fs)
        assert ft[1] == pytest.approx(f2, abs=1e-12 * fn), (props, t1, n, fn, fs)
        assert -fs <= ft[0] <= 0.0
        assert got["statev"][1, 0] == (1.0 if stick else 0.0)
    assert 50 < sticks < 350, "both stick and slip must be exercised"


def test_vfric_holds_exactly_up_to_the_law_and_slides_beyond():
    """Sliding along t1 = the law's +x on the main side: the law holds fS <= fN R(0)."""
    t1, n, props, fn = np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), [1, 0, 0, 1], 50.0
    r0 = float(ELL.radial([0.0])[0])
    p0 = ELL.normal_point([0.0])[0][0]
    for fs, stick in ((fn * r0 * (1 - 1e-9), True), (fn * r0 * (1 + 1e-6), False),
                      (3 * fn * r0, False)):
        ft = run_vfric([(props, t1, n, fn, fs)], jcon=[1], nslv=1, area=[1e-5])["fTangential"]
        if stick:
            assert ft[:, 0].tolist() == [-fs, 0.0]
        else:
            assert ft[0, 0] == pytest.approx(max(-fs, -fn * p0[0]), rel=1e-12)
            assert ft[1, 0] == pytest.approx(-fn * p0[1], rel=1e-12)
            assert ft[0, 0] < -fn * r0 * (1 - 1e-6)   # the associated force exceeds R(0)


def test_vfric_indexes_state_and_area_by_surface_node():
    """nContact = 5 contact points on 8 surface nodes, jConSlvid permuted: each point's
    state and area are those of its surface node; other nodes untouched."""
    rng = np.random.default_rng(3)
    pts = random_points(rng, 5)
    props = pts[0][0]
    pts = [(props, *p[1:]) for p in pts]
    jcon = np.array([7, 2, 5, 1, 8])
    fn = np.array([p[3] for p in pts])
    area = np.full(8, 1.0)
    inside = np.array([True, False, True, False, True])       # pressure in [P_LO, P_HI]?
    area[jcon - 1] = np.where(inside, fn / 1e6, fn / 1e8)
    statev = np.full((2, 8), 5.0)
    got = run_vfric(pts, jcon=jcon, nslv=8, area=area, statev=statev)
    for k, (p, t1, n, f, fs) in enumerate(pts):
        f1, f2, stick = reference(p, t1, n, f, fs)
        j = jcon[k] - 1
        assert got["fTangential"][:, k] == pytest.approx([f1, f2], abs=1e-12 * f)
        assert got["statev"][0, j] == 5.0 + (0 if inside[k] else 1)
        assert got["statev"][1, j] == (1.0 if stick else 0.0)
    untouched = np.setdiff1d(np.arange(8), jcon - 1)
    assert (got["statev"][:, untouched] == 5.0).all()


def test_vfric_writes_only_the_state_variables_that_exist():
    """nStateVar = 1: the clamp count only (writing a second one would overwrite the
    next surface node's)."""
    rng = np.random.default_rng(4)
    pts = random_points(rng, 3)
    pts = [(pts[0][0], *p[1:]) for p in pts]
    statev = np.full((1, 3), 9.0)
    got = run_vfric(pts, jcon=[3, 1, 2], nslv=3, area=[1e9] * 3, nsv=1, statev=statev)
    assert got["statev"].tolist() == [[10.0, 10.0, 10.0]]         # every point clamped


def test_vfric_2d_gives_mu_plus_and_mu_minus():
    """2D (nDir = 2, nFricDir = 1), the law's +x along global x, texture on the main
    surface: sliding towards +x meets |p(0).x|, towards -x |p(180).x|."""
    fn, fs = 10.0, 100.0
    for t1, psi in (([1.0, 0.0], 0.0), ([-1.0, 0.0], math.pi)):
        got = call_vfric(lib("vfric"), fnormal=[fn], fstick=[fs],
                         dircos_sl=np.array([t1]).T, dircos_n=np.array([[0.0, 1.0]]).T,
                         props=[1.0, 0.0, 0.0, 1.0], statev=np.zeros((2, 1)),
                         jconslvid=[1], area=[1e-5])
        p = ELL.normal_point([psi])[0][0]
        assert got["fTangential"].shape == (1, 1)
        assert got["fTangential"][0, 0] == pytest.approx(-fn * abs(p[0]), rel=1e-12)


def test_vfriction_matches_vfric_point_by_point():
    """VFRICTION (nBlock = 6) gives each point what VFRIC gives it; its state is
    state(:, 1, k) and its pressure fNormal / areaCont(k)."""
    rng = np.random.default_rng(5)
    pts = random_points(rng, 6)
    props = pts[0][0]
    pts = [(props, *p[1:]) for p in pts]
    fn = np.array([p[3] for p in pts])
    area = np.where(np.arange(6) % 2 == 0, fn / 1e6, fn / 1e4)
    state = np.full((2, 1, 6), 1.0)
    got = call_vfriction(lib("vfriction"), fnormal=fn, fstick=[p[4] for p in pts],
                         dircos_sl=np.column_stack([p[1] for p in pts]),
                         dircos_n=np.column_stack([p[2] for p in pts]), props=props,
                         state=state, area=area, sentinel=np.nan)
    for k, (p, t1, n, f, fs) in enumerate(pts):
        f1, f2, stick = reference(p, t1, n, f, fs)
        assert got["fTangential"][:, k] == pytest.approx([f1, f2], abs=1e-12 * f)
        assert got["state"][0, 0, k] == 1.0 + (k % 2)
        assert got["state"][1, 0, k] == (1.0 if stick else 0.0)


@pytest.mark.parametrize("routine", ["vfric", "vfriction"])
def test_single_precision_build_agrees(routine):
    """The same source compiled against the single-precision vaba_param.inc agrees with
    the double-precision build to 1e-5 (relative to fN)."""
    rng = np.random.default_rng(6)
    pts = random_points(rng, 50)
    props = pts[0][0]
    pts = [(props, *p[1:]) for p in pts]
    out = {}
    for prec, dt in (("double", np.float64), ("single", np.float32)):
        kw = {"fnormal": [p[3] for p in pts], "fstick": [p[4] for p in pts],
              "dircos_sl": np.column_stack([p[1] for p in pts]),
              "dircos_n": np.column_stack([p[2] for p in pts]), "props": props, "dtype": dt}
        if routine == "vfric":
            r = call_vfric(lib(routine, prec), statev=np.zeros((2, 50)),
                           jconslvid=np.arange(1, 51), area=np.full(50, 1e-5), **kw)
        else:
            r = call_vfriction(lib(routine, prec), state=np.zeros((2, 1, 50)),
                               area=np.full(50, 1e-5), **kw)
        out[prec] = r["fTangential"].astype(float)
        assert out[prec].dtype == float and np.isfinite(out[prec]).all()
    fn = np.array([p[3] for p in pts])
    assert np.abs(out["single"] - out["double"]).max(axis=0) == pytest.approx(
        0.0, abs=1e-5 * fn.max())
    assert np.all(np.abs(out["single"] - out["double"]) <= 1e-5 * fn)


@pytest.mark.parametrize("name", ["fric", "VFRICTION", "vfric ", "vfrictio", ""])
def test_a_name_other_than_the_two_routines_is_refused(name):
    """No wrapper comes out under a name that is not its routine's (a FRIC file holding
    VFRICTION would compile and be called by no solver): the library's writer refuses
    the name in one line, and so does the explicit wrapper itself."""
    from asperity.errors import InputError
    from asperity.fe.abaqus_fric import routine_source
    with pytest.raises(ValueError, match="vfric or vfriction"):
        source(name)
    if name != "fric":
        with pytest.raises(InputError) as err:
            routine_source(ELL, name)
        assert "routine" in str(err.value) and "\n" not in str(err.value)
