"""Law families over the nominal pressure (issue 19, gauge files version 2): the file
round-trips exactly, the law at a member's pressure is that member, the law between two
members against the interpolation computed here, every interpolated law a valid law, the
refusals outside the range and of edited files, and a map turned half a turn gives mu+ and
mu- exchanged member by member."""
import json
import math
from dataclasses import replace

import numpy as np
import pytest

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.friction.family import derive_family
from asperity.laws.family import GaugeFamily
from asperity.laws.fitting import fit_derivation
from asperity.laws.gauge_file import GaugeFileError, family_to_dict, read_gauge, write_gauge
from asperity.laws.gauge_schema import schema
from asperity.microslip.friction import friction_from_gauge
from asperity.surface.contact_facets import ElasticContact
from asperity.surface.topography import HeightMap
from asperity.texture.wedges import WedgeTexture

PRESSURES = (1e6, 5e6, 2e7)


def smooth_random(nx, ny, seed):
    rng = np.random.default_rng(seed)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(nx), np.fft.fftfreq(ny), indexing="ij"))
    z = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((nx, ny)))
                             * np.exp(-(q * 10) ** 2)))
    return z / np.abs(np.diff(z, axis=0)).mean() * 0.1e-6       # ~0.1 slope at 1 um pixels


def scan_family(z, kind, boundary="free", pressures=PRESSURES):
    e = ElasticContact(1e9, pressures, boundary=boundary, tol=1e-11)
    fam = derive_family(HeightMap(z, 1e-6, 1e-6), e, "all-faces", 72)
    return GaugeFamily(fam.pressures, tuple(fit_derivation(d, kind) for d in fam.members))


@pytest.fixture(scope="module")
def families():
    z = smooth_random(48, 40, 3)
    return {k: scan_family(z, k) for k in ("star", "truncated-ellipse")}


def contact(p):
    return {"area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "periodic", "hardness_Pa": None,
            "iterations": 10, "residual": 1e-9, "converged": True}


def wedge_law(alpha, beta, kind, contact_regime="all-faces", mu=(0.1, 0.1)):
    tex = WedgeTexture(alpha_deg=alpha, beta_deg=beta, mu_alpha=mu[0], mu_beta=mu[1])
    return fit_derivation(derive(tex, contact_regime, "closed-form", 72), kind)


def synthetic(laws, pressures):
    """Laws of different wedges as the members of one family (one source for all): members
    that differ strongly, for the interpolation and its consumers."""
    src = laws[0].source
    return GaugeFamily(tuple(pressures), tuple(
        replace(gl, source={**src, "elastic_contact": contact(p)})
        for gl, p in zip(laws, pressures)))


def same_law(a, b):
    assert a.kind == b.kind and a.source == b.source and a.fit == b.fit
    assert a.principal_direction_deg == b.principal_direction_deg
    for x, y in ((a.data.psi, b.data.psi), (a.data.p, b.data.p), (a.data.limit, b.data.limit)):
        np.testing.assert_array_equal(x, y)
    if a.kind == "star":
        np.testing.assert_array_equal(a.law.C.points, b.law.C.points)
        for f in ("psi", "h", "dh"):
            np.testing.assert_array_equal(getattr(a.law.D, f), getattr(b.law.D, f))
    else:
        assert a.law.C.axes == b.law.C.axes and a.law.C.theta == b.law.C.theta


# ----------------------------------------------------------------------------- the file

@pytest.mark.parametrize("kind", ["star", "truncated-ellipse"])
def test_family_round_trips_through_the_file_exactly(families, kind, tmp_path):
    fam = families[kind]
    path = tmp_path / "fam.json"
    obj = write_gauge(path, fam)
    assert obj["version"] == 2 and [m["pressure_Pa"] for m in obj["members"]] == list(PRESSURES)
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.Draft202012Validator(schema(2)).validate(json.loads(path.read_text()))
    back = read_gauge(path)
    assert isinstance(back, GaugeFamily) and back.pressures == PRESSURES
    for a, b in zip(fam.members, back.members):
        same_law(a, b)
    again = tmp_path / "again.json"
    write_gauge(again, back)
    assert again.read_text() == path.read_text()
    # the contact figures of each member travel with it, and differ with the load
    fr = [back.contact(k)["area_fraction"] for k in range(3)]
    assert fr[0] < fr[1] < fr[2]


def test_a_single_law_is_still_version_1(families, tmp_path):
    fam = families["star"]
    one = GaugeFamily(fam.pressures[:1], fam.members[:1])
    assert one.at(PRESSURES[0]) is one.members[0]
    obj = write_gauge(tmp_path / "one.json", one)
    assert obj["version"] == 1 and "members" not in obj
    back = read_gauge(tmp_path / "one.json")
    same_law(back, fam.members[0])
    # a version-2 file of one member is its law
    two = family_to_dict(fam)
    two["members"] = two["members"][1:2]
    (tmp_path / "v2one.json").write_text(json.dumps(two))
    same_law(read_gauge(tmp_path / "v2one.json"), fam.members[1])


def test_version_1_files_still_read(tmp_path):
    gl = wedge_law(20, 6, "star")
    write_gauge(tmp_path / "v1.json", gl)
    obj = json.loads((tmp_path / "v1.json").read_text())
    assert obj["version"] == 1
    same_law(read_gauge(tmp_path / "v1.json"), gl)


def _edit(fam, tmp_path, edit):
    obj = family_to_dict(fam)
    edit(obj)
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(obj))
    with pytest.raises(GaugeFileError) as exc:
        read_gauge(f)
    msg = str(exc.value)
    assert "\n" not in msg and "Traceback" not in msg
    return msg


def test_edited_family_files_are_refused_naming_the_field(families, tmp_path):
    fam = families["star"]

    def swap(o):
        o["members"][0]["pressure_Pa"], o["members"][1]["pressure_Pa"] = 5e6, 1e6
        o["members"][0]["contact"]["pressure_Pa"], o["members"][1]["contact"]["pressure_Pa"] \
            = 5e6, 1e6
    assert "members[1].pressure_Pa must exceed" in _edit(fam, tmp_path, swap)

    def mismatch(o):
        o["members"][2]["pressure_Pa"] = 3e7
    assert "members[2].contact.pressure_Pa" in _edit(fam, tmp_path, mismatch)

    def modulus(o):
        o["members"][1]["contact"]["E_star_Pa"] = 2e9
    assert "members[1].contact.E_star_Pa" in _edit(fam, tmp_path, modulus)

    def data(o):
        o["members"][1]["data"]["p"][3][0] *= 1.01
    assert "field members[1].fit." in _edit(fam, tmp_path, data)

    def no_members(o):
        del o["members"]
    assert "missing field members" in _edit(fam, tmp_path, no_members)

    def as_version_1(o):
        o["version"] = 1
    assert "missing field frame" in _edit(fam, tmp_path, as_version_1)

    def empty(o):
        o["members"] = []
    assert "members must have at least 1 items" in _edit(fam, tmp_path, empty)

    def area(o):
        o["members"][0]["contact"]["area_fraction"] = 1.5
    assert "members[0].contact.area_fraction must be <= 1" in _edit(fam, tmp_path, area)


def test_a_family_needs_one_source_and_increasing_pressures():
    a, b = wedge_law(20, 6, "star"), wedge_law(30, 6, "star")
    with pytest.raises(InputError, match="strictly increasing"):
        synthetic([a, b], (2e6, 1e6))
    with pytest.raises(InputError, match="another source"):
        GaugeFamily((1e6, 2e6), (replace(a, source={**a.source, "elastic_contact": contact(1e6)}),
                                 replace(b, source={**b.source, "elastic_contact": contact(2e6)})))
    with pytest.raises(InputError, match="kind"):
        synthetic([a, wedge_law(30, 6, "truncated-ellipse")], (1e6, 2e6))
    with pytest.raises(InputError, match="elastic contact figures"):
        GaugeFamily((1e6, 2e6), (a, b))
    fam = synthetic([a, b], (1e6, 2e6))
    with pytest.raises(InputError, match="contact.pressure_Pa"):   # contact at 2e6, said 3e6
        GaugeFamily((1e6, 3e6), fam.members)
    other = replace(b, source={**a.source, "elastic_contact": {**contact(2e6), "E_star_Pa": 2e9}})
    with pytest.raises(InputError, match="E_star_Pa"):
        GaugeFamily((1e6, 2e6), (fam.members[0], other))
    with pytest.raises(InputError, match="law family"):            # take it at a pressure
        friction_from_gauge(fam, 0.0)
    from asperity.laws.planar import from_gauge
    with pytest.raises(InputError, match="law family"):
        from_gauge(fam)


# ----------------------------------------------------------------------------- interpolation

def test_the_law_at_a_members_pressure_is_that_member(families):
    for fam in families.values():
        for p, m in zip(fam.pressures, fam.members):
            assert fam.at(p) is m


@pytest.mark.parametrize("p", [0.0, -1.0, 9.99e5, 2.0001e7, math.nan, math.inf])
def test_outside_the_range_is_refused_in_one_line(families, p):
    with pytest.raises(InputError) as exc:
        families["star"].at(p, "assembly.p")
    msg = str(exc.value)
    assert msg.startswith("assembly.p") and "\n" not in msg
    if 0 < p < math.inf:
        assert "[1e+06, 2e+07] Pa" in msg and "no extrapolation" in msg


def test_ellipse_between_members_against_the_hand_interpolation():
    a = wedge_law(10, 10, "truncated-ellipse", mu=(0.1, 0.1))
    b = wedge_law(30, 5, "truncated-ellipse", mu=(0.2, 0.3))
    fam = synthetic([a, b], (1e6, 1e8))
    for p, w in ((1e7, 0.5), (10 ** 6.5, 0.25), (10 ** 7.5, 0.75)):
        e = fam.at(p).law.C
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            hand = (1 - w) * a.law.C.axes[k] + w * b.law.C.axes[k]
            assert e.axes[k] == pytest.approx(hand, rel=1e-12)
    # three members: the law between the second and third is theirs, not the first's
    c = wedge_law(20, 15, "truncated-ellipse", mu=(0.25, 0.15))
    fam3 = synthetic([a, b, c], (1e6, 1e8, 1e10))
    e = fam3.at(1e9).law.C
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
        assert e.axes[k] == pytest.approx(0.5 * (b.law.C.axes[k] + c.law.C.axes[k]), rel=1e-12)
    # member b written with t_a reversed (the same set): the law between is the same set
    eb = b.law.C
    from asperity.laws.sets import TruncatedEllipse
    from asperity.laws.walker_leine import associated
    flipped = TruncatedEllipse(eb.mu_a_minus, eb.mu_a_plus, eb.mu_b_minus, eb.mu_b_plus,
                               theta=eb.theta + math.pi)
    b2 = replace(b, law=associated(flipped), principal_direction_deg=180.0)
    fam2 = synthetic([a, b2], (1e6, 1e8))
    phi = np.linspace(0, 2 * math.pi, 181)
    for p in (3e6, 1e7, 5e7):
        np.testing.assert_allclose(fam2.at(p).law.C.radial(phi), fam.at(p).law.C.radial(phi),
                                   rtol=1e-12)


@pytest.mark.parametrize("regime", ["all-faces", "windward"])
def test_star_between_members_goes_through_the_hand_interpolated_points(regime):
    a = wedge_law(10, 20, "star", regime, mu=(0.1, 0.2))
    b = wedge_law(35, 8, "star", regime, mu=(0.3, 0.1))
    fam = synthetic([a, b], (2e6, 3.2e7))
    p = 8e6
    w = math.log(4) / math.log(16)                    # = 0.5
    gl = fam.at(p)
    # the points, written out: each direction's point, one-sided limits apart
    hand = {}
    for g, wt in ((a, 1 - w), (b, w)):
        for psi, pt, lim in zip(g.data.psi, g.data.p, g.data.limit):
            for side in ((-1, 1) if lim == 0 else (lim,)):
                key = (round(float(psi), 12), side)
                hand[key] = hand.get(key, 0.0) + wt * pt
    got = {}
    for psi, pt, lim in zip(gl.data.psi, gl.data.p, gl.data.limit):
        for side in ((-1, 1) if lim == 0 else (lim,)):
            got[(round(float(psi), 12), side)] = pt
    assert got.keys() == hand.keys()
    for k in hand:
        np.testing.assert_allclose(got[k], hand[k], rtol=1e-12, atol=1e-15)
    if regime == "windward":
        assert (gl.data.limit != 0).any()           # set-valued directions kept
    # C passes through them; the law's force for each ordinary direction is that point
    pts = gl.data.p
    np.testing.assert_allclose(gl.law.C.radial(np.arctan2(pts[:, 1], pts[:, 0])),
                               np.hypot(pts[:, 0], pts[:, 1]), rtol=1e-9)
    ok = gl.data.limit == 0
    f = gl.force(gl.data.psi[ok])
    np.testing.assert_allclose(f.p, pts[ok], atol=2e-4 * np.abs(pts).max())
    # and the members differ: the interpolated law is neither
    T = [g.force(np.array([0.0])).tangential[0] for g in (a, gl, b)]
    assert abs(T[0] - T[2]) > 0.03 and min(T[0], T[2]) < T[1] < max(T[0], T[2])


@pytest.mark.parametrize("kind", ["star", "truncated-ellipse"])
def test_every_interpolated_law_is_a_valid_law(families, kind, tmp_path):
    from asperity.laws.gauge_checks import check_consistency
    fam = families[kind]
    for p in np.geomspace(PRESSURES[0], PRESSURES[-1], 11)[1:-1]:
        gl = fam.at(float(p))
        assert gl.kind == kind and gl.fit.admissible and gl.fit.min_dissipation > 0
        if kind == "star":
            assert gl.fit.D_convex and gl.law.D.min_turn_rate() >= 0
        dmin, _ = gl.law.min_dissipation(7200)
        assert dmin > 0
        check_consistency(gl)                  # what a file of it would have to satisfy
        write_gauge(tmp_path / "at.json", gl)   # a valid version-1 file
        same_law(read_gauge(tmp_path / "at.json"), gl)


def test_a_map_turned_half_a_turn_exchanges_mu_plus_and_minus_member_by_member():
    z = smooth_random(48, 40, 1)
    a = scan_family(z, "star", "periodic", (1e6, 2e7))
    b = scan_family(z[::-1, ::-1].copy(), "star", "periodic", (1e6, 2e7))
    for p in (1e6, 4e6, 2e7):                 # the members, and between them
        fa = friction_from_gauge(a.at(p), 0.0)
        fb = friction_from_gauge(b.at(p), 0.0)
        assert fb.mu_plus == pytest.approx(fa.mu_minus, rel=1e-7)
        assert fb.mu_minus == pytest.approx(fa.mu_plus, rel=1e-7)
    f0, f1 = (friction_from_gauge(a.at(p), 0.0) for p in (1e6, 2e7))
    assert abs(f0.mu_plus - f0.mu_minus) > 1e-3              # not trivially equal
    assert abs((f0.mu_plus - f0.mu_minus) - (f1.mu_plus - f1.mu_minus)) > 1e-3   # load matters
