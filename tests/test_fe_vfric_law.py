"""The generated VFRIC and VFRICTION (issue 27) against the gauge file's own law, the force
that ``asperity law --psi`` prints: sliding contact points in random 3D frames give
-fN p (texture on the main surface) or +fN p(180 deg + ...) (on the secondary surface)
within 1e-4 fN, the law holds the node below fN R, and a law family's member, blend and
clamping follow the pressure fNormal / area of each node.  The reference works in global
vectors (the law's axes e_x, e_y built from props), not in the routine's local angles."""
from __future__ import annotations

import math

import numpy as np
import pytest
from fe_builds import library, needs_gfortran
from law_families import PRESSURES, four_members

from asperity import derive, fit_derivation
from asperity.fe.abaqus_fric import routine_source
from asperity.fe.fortran_harness import call_vfric, call_vfriction
from asperity.texture.wedges import WedgeTexture

pytestmark = needs_gfortran
TOL = 1e-4


def texture_laws():
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360)
    w = derive(WedgeTexture(30.0, 30.0, 0.3, 0.3), "windward", n_directions=360)
    return {"ellipse": fit_derivation(d, "truncated-ellipse"), "star": fit_derivation(d, "star"),
            "windward-star": fit_derivation(w, "star")}


LAWS = texture_laws()


def edges_of(gl) -> np.ndarray:
    return np.asarray(getattr(gl.law.D, "edges", ()) if gl.kind == "star" else (), float)


def frames(rng, m, side=None):
    """m contact points: orthonormal t1, n; the law's axis and side in props."""
    out = []
    for _ in range(m):
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        t1 = np.cross(n, rng.normal(size=3))
        t1 /= np.linalg.norm(t1)
        s = rng.choice([-1.0, 1.0]) if side is None else side
        out.append((np.r_[rng.normal(size=3), s], t1, n))
    return out


def law_frame(props, t1, n):
    """(phi, e_x, e_y, t2): the slider's sliding direction in the law frame and the axes."""
    a = np.asarray(props[:3], float)
    ex = a - a.dot(n) * n
    ex /= np.linalg.norm(ex)
    ey = np.cross(n, ex)
    s = t1 if props[3] > 0 else -t1
    return math.atan2(s.dot(ey), s.dot(ex)), ex, ey, np.cross(n, t1)


def sliding_force(gl, props, t1, n, fn):
    """The force on the secondary node in (t1, t2) while sliding (no clipping)."""
    phi, ex, ey, t2 = law_frame(props, t1, n)
    p = gl.force(np.array([phi])).p[0]
    f = (-fn if props[3] > 0 else fn) * (p[0] * ex + p[1] * ey)
    return np.array([f.dot(t1), f.dot(t2)]), phi


def one_call(routine, lib, pts, fn, fs, area, state=None):
    common = {"fnormal": fn, "fstick": fs, "dircos_sl": np.column_stack([p[1] for p in pts]),
              "dircos_n": np.column_stack([p[2] for p in pts]), "props": pts[0][0]}
    m = len(pts)
    if routine == "vfric":
        out = call_vfric(lib, statev=np.zeros((2, m)) if state is None else state,
                         jconslvid=np.arange(m, 0, -1), area=area[::-1], **common)
        return out["fTangential"], out["statev"][:, ::-1]
    out = call_vfriction(lib, state=np.zeros((2, 1, m)) if state is None else state,
                         area=area, **common)
    return out["fTangential"], out["state"][:, 0, :]


@pytest.mark.parametrize("routine", ["vfric", "vfriction"])
@pytest.mark.parametrize("law", sorted(LAWS))
def test_sliding_force_is_the_laws_within_1e4(routine, law):
    """Sliding (a stick force far above what the law holds): the force is -fN p along
    (t1, t2), p the law's force for the slider's direction, within 1e-4 fN; points on
    both sides, one call per props (props is one per call)."""
    gl = LAWS[law]
    lib = library(routine_source(gl, routine))
    rng = np.random.default_rng(11)
    checked = 0
    for side in (1.0, -1.0):
        for _ in range(12):
            pts = frames(rng, 15, side)
            pts = [(pts[0][0], t1, n) for _, t1, n in pts]
            fn = rng.uniform(1.0, 50.0, size=15)
            ft, sv = one_call(routine, lib, pts, fn, 1e3 * fn, fn / 1e6)
            for k, (props, t1, n) in enumerate(pts):
                ref, phi = sliding_force(gl, props, t1, n, fn[k])
                if np.any(np.abs(np.remainder(phi - edges_of(gl) + math.pi, 2 * math.pi)
                                 - math.pi) < 0.02):
                    continue                     # beside a set-valued direction
                assert ft[:, k] == pytest.approx(ref, abs=TOL * fn[k]), (law, side, phi)
                assert sv[1, k] == 0.0                              # it slid
                checked += 1
    assert checked > 300


@pytest.mark.parametrize("routine", ["vfric", "vfriction"])
def test_law_holds_below_fn_r(routine):
    """fStickForce below fN R(direction) (R of C along the slider's direction): the
    node is held, fTangential = (-fStickForce, 0); just above fN R it slides."""
    gl = LAWS["star"]
    lib = library(routine_source(gl, routine))
    rng = np.random.default_rng(12)
    pts = frames(rng, 40, 1.0)
    pts = [(pts[0][0], t1, n) for _, t1, n in pts]
    fn = rng.uniform(1.0, 50.0, size=40)
    r = np.array([gl.law.C.radial([law_frame(*p)[0]])[0] for p in pts])
    for factor, held in ((1.0 - 1e-3, True), (1.0 + 1e-3, False)):
        fs = factor * fn * r
        ft, sv = one_call(routine, lib, pts, fn, fs, fn / 1e6)
        assert (sv[1] == (1.0 if held else 0.0)).all()
        if held:
            assert ft[0] == pytest.approx(-fs, rel=1e-12) and (ft[1] == 0.0).all()
        assert ((ft[0] >= -fs * (1 + 1e-12)) & (ft[0] <= 0.0)).all()


def test_single_precision_generated_vfric_agrees():
    """The generated VFRIC compiled against the single-precision vaba_param.inc gives
    the double build's forces to 1e-5 fN."""
    src = routine_source(LAWS["ellipse"], "vfric")
    rng = np.random.default_rng(13)
    pts = frames(rng, 60, 1.0)
    pts = [(pts[0][0], t1, n) for _, t1, n in pts]
    fn = rng.uniform(1.0, 50.0, size=60)
    fs = rng.uniform(0.0, 0.3, size=60) * fn
    got = {}
    for prec, dt in (("double", np.float64), ("single", np.float32)):
        got[prec] = call_vfric(
            library(src, prec), fnormal=fn, fstick=fs, statev=np.zeros((2, 60)),
            dircos_sl=np.column_stack([p[1] for p in pts]),
            dircos_n=np.column_stack([p[2] for p in pts]), props=pts[0][0],
            jconslvid=np.arange(1, 61), area=np.full(60, 1e-5), dtype=dt)["fTangential"]
    assert got["single"].dtype == np.float32
    assert np.all(np.abs(got["single"] - got["double"]) <= 1e-5 * fn)


@pytest.mark.parametrize("routine", ["vfric", "vfriction"])
def test_family_member_blend_and_clamp_follow_each_nodes_pressure(routine):
    """A law family: each node's pressure fNormal / area picks its law -- a member at
    its pressure, fam.at(p) between members (1e-4), the nearest member outside the
    range with the clamp counted in state variable 1."""
    fam = four_members()
    lib = library(routine_source(fam, routine))
    rng = np.random.default_rng(14)
    pressures = [PRESSURES[1], PRESSURES[3], 8e6, 1e5, 2e8]
    refs = [fam.at(PRESSURES[1]), fam.at(PRESSURES[3]), fam.at(8e6), fam.members[0],
            fam.members[-1]]
    clamped = [0, 0, 0, 1, 1]
    for _ in range(6):
        pts = frames(rng, 5, 1.0)
        pts = [(pts[0][0], t1, n) for _, t1, n in pts]
        fn = rng.uniform(1.0, 50.0, size=5)
        area = fn / np.array(pressures)
        ft, sv = one_call(routine, lib, pts, fn, 1e3 * fn, area, None)
        for k, (props, t1, n) in enumerate(pts):
            ref, phi = sliding_force(refs[k], props, t1, n, fn[k])
            near = np.abs(np.remainder(phi - edges_of(refs[k]) + math.pi, 2 * math.pi)
                          - math.pi) < 0.05
            if not near.any():
                assert ft[:, k] == pytest.approx(ref, abs=TOL * fn[k]), (k, phi)
        assert sv[0].tolist() == clamped


@pytest.mark.parametrize("routine", ["vfric", "vfriction"])
def test_2d_sliding_meets_mu_plus_and_mu_minus(routine):
    """2D (nDir = 2, nFricDir = 1), the law's +x along global x: a secondary node
    sliding towards +x over the textured main surface meets mu+ = p(0).x, towards -x
    mu- = -p(180).x; with the texture on the secondary surface the two swap."""
    gl = LAWS["ellipse"]
    lib = library(routine_source(gl, routine))
    mu_p = gl.force(np.array([0.0])).p[0, 0]
    mu_m = -gl.force(np.array([math.pi])).p[0, 0]
    assert abs(mu_p - mu_m) > 0.005                          # an asymmetric law
    fn = np.array([10.0, 10.0])
    sl = np.array([[1.0, 0.0], [-1.0, 0.0]]).T
    nrm = np.array([[0.0, 1.0], [0.0, 1.0]]).T
    for side, expect in ((1.0, [mu_p, mu_m]), (-1.0, [mu_m, mu_p])):
        kw = {"fnormal": fn, "fstick": 1e3 * fn, "dircos_sl": sl, "dircos_n": nrm,
              "props": [1.0, 0.0, 0.0, side]}
        if routine == "vfric":
            ft = call_vfric(lib, statev=np.zeros((2, 2)), jconslvid=[2, 1],
                            area=[1e-5, 1e-5], **kw)["fTangential"]
        else:
            ft = call_vfriction(lib, state=np.zeros((2, 1, 2)), area=[1e-5, 1e-5],
                                **kw)["fTangential"]
        assert ft.shape == (1, 2)
        assert ft[0] == pytest.approx(-fn * np.array(expect), abs=TOL * 10.0)
