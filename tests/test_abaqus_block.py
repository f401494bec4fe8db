"""The Abaqus block of ``asperity law --abaqus`` (issue 18, sections 8 and 10): each law's
block is the best symmetric orthotropic ellipse of *its own* law (the ellipse and star laws
of one texture differ, and say which law and source they approximate), and the numbers of
its LOSES line -- the law's friction along each axis, the asymmetry lost along each, the
angle and radial errors -- are those computed here independently: radial functions of the
truncated ellipse and of the star polygon written out, the least-squares ellipse found by
another optimiser (Powell's method on the README's objective), for laws asymmetric along t_b."""
from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest
from cli_run import run
from scipy.optimize import minimize

from asperity import derive, fit_derivation, write_gauge
from asperity.laws.export import abaqus_block
from asperity.laws.sets import TruncatedEllipse
from asperity.laws.walker_leine import associated
from asperity.texture.wedges import WedgeTexture

#: the README's objective: relative radial error at 720 polar angles from t_a
N_POLAR = 720
ALPHA, BETA, MU_ALPHA, MU_BETA = 30.0, 10.0, 0.1, 0.2


@pytest.fixture(scope="module")
def laws():
    d = derive(WedgeTexture(ALPHA, BETA, MU_ALPHA, MU_BETA), n_directions=360)
    return {"star": fit_derivation(d, "star"), "ellipse": fit_derivation(d, "truncated-ellipse")}


# ----------------------------------------------------------------------------- references

def wedge_axes() -> dict:
    """SPEC.md's closed forms of the all-faces wedge: mu_a+, mu_a-, mu_b (H written out)."""
    a, b = math.radians(ALPHA), math.radians(BETA)
    ta, tb = math.tan(a), math.tan(b)

    def H(x, y):
        return (x + math.tan(y)) / (1.0 - x * math.tan(y))
    return {"a+": (H(MU_ALPHA, a) * tb + H(MU_BETA, -b) * ta) / (ta + tb),
            "a-": (H(MU_BETA, b) * ta + H(MU_ALPHA, -a) * tb) / (ta + tb),
            "b": (MU_ALPHA * tb / math.cos(a) + MU_BETA * ta / math.cos(b)) / (ta + tb)}


def rho_ellipse(phi, ap, am, bp, bm, theta=0.0):
    """Radial function of the truncated ellipse: each quadrant its semi-axes."""
    u = phi - theta
    c, s = np.cos(u), np.sin(u)
    A, B = np.where(c >= 0, ap, am), np.where(s >= 0, bp, bm)
    return 1.0 / np.sqrt((c / A) ** 2 + (s / B) ** 2)


def rho_polygon(phi, pts):
    """Radial function of a star-shaped polygon: where the ray phi meets an edge."""
    u = np.column_stack([np.cos(phi), np.sin(phi)])[:, None, :]       # (m, 1, 2)
    v0, d = pts[None, :, :], (np.roll(pts, -1, axis=0) - pts)[None, :, :]
    den = u[..., 0] * d[..., 1] - u[..., 1] * d[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (v0[..., 0] * d[..., 1] - v0[..., 1] * d[..., 0]) / den      # along the ray
        s = (v0[..., 0] * u[..., 1] - v0[..., 1] * u[..., 0]) / den      # along the edge
    hit = (den != 0) & (s >= -1e-12) & (s <= 1 + 1e-12) & (t > 0)
    return np.where(hit, t, np.inf).min(axis=1)


def best_ellipse(rho, theta=0.0):
    """(mu_1, mu_2, max and rms relative radial error) of the symmetric orthotropic ellipse
    (axes along theta, theta + 90 deg) closest to ``rho`` at N_POLAR polar angles."""
    phi = theta + 2 * math.pi * np.arange(N_POLAR) / N_POLAR
    r = rho(phi)

    def errors(m):
        return (rho_ellipse(phi, m[0], m[0], m[1], m[1], theta) - r) / r
    x0 = [r[0], r[N_POLAR // 4]]
    sol = minimize(lambda m: float(np.sum(errors(m) ** 2)), x0, method="Powell",
                   options={"xtol": 1e-13, "ftol": 1e-30})
    e = errors(sol.x)
    return sol.x[0], sol.x[1], float(np.abs(e).max()), float(np.sqrt(np.mean(e * e)))


def ellipse_force(psi, ap, am, bp, bm):
    """Associated truncated ellipse (theta 0): the boundary point whose outward normal is
    the sliding direction, in the quadrant of that direction."""
    c, s = np.cos(psi), np.sin(psi)
    A, B = np.where(c >= 0, ap, am), np.where(s >= 0, bp, bm)
    h = np.sqrt((A * c) ** 2 + (B * s) ** 2)
    return np.column_stack([A * A * c / h, B * B * s / h])


# ----------------------------------------------------------------------------- the block

LOSES = re.compile(
    r"\*\* LOSES: asymmetry \(mu_a\+ = (?P<ap>\S+), mu_a- = (?P<am>\S+): (?P<asa>\S+) % apart; "
    r"mu_b\+ = (?P<bp>\S+), mu_b- = (?P<bm>\S+): (?P<asb>\S+) % apart\) and non-associated "
    r"sliding \(the ellipse's force up to (?P<ang>\S+) deg from the (?P<kind>\S+) law's force "
    r"for the same sliding direction\); radial error against the (?P=kind) law up to "
    r"(?P<rmax>\S+) % \(rms (?P<rrms>\S+) %\)$")


def block(gl, tmp_path=None, capsys=None, name="g"):
    """(comment lines, (mu_1, mu_2), LOSES fields) of `asperity law GAUGE --abaqus` (of
    abaqus_block, which it writes, for a law made here: a gauge file must hold the law
    fitted to its data)."""
    if tmp_path is None:
        lines = abaqus_block(gl).splitlines()
    else:
        g, inp = tmp_path / f"{name}.json", tmp_path / f"{name}.inp"
        write_gauge(g, gl)
        code, _, err = run(capsys, "law", g, "--abaqus", inp)
        assert code == 0, err
        lines = inp.read_text().splitlines()
    k = lines.index("*FRICTION, ANISOTROPIC")
    m = LOSES.match(lines[k - 1])
    assert m, lines[k - 1]
    return lines[:k], tuple(map(float, lines[k + 1].split(","))), m.groupdict()


def digits(printed: str, ref: float, n: int = 3):
    """``printed`` is ``ref`` shown with ``n`` significant digits (or 0 for ~0)."""
    x = float(printed)
    if abs(ref) < 5e-11:
        assert x == 0.0, (printed, ref)
        return
    half = 0.5 * 10.0 ** (math.floor(math.log10(abs(ref))) - n + 1)
    assert abs(x - ref) <= 1.001 * half + 1e-9 * abs(ref), (printed, ref)


def asymmetry(p, m):
    return 100 * abs(p - m) / (0.5 * (p + m))


def test_ellipse_and_star_blocks_are_each_their_own_law(laws, tmp_path, capsys):
    """One texture, two laws: the blocks name their law and source and differ; each data
    line is the best ellipse of that law's own radial function (not of the data, which
    both laws share, and not of the other law)."""
    got = {k: block(gl, tmp_path, capsys, k) for k, gl in laws.items()}
    for k, kind in (("star", "star"), ("ellipse", "truncated-ellipse")):
        head = got[k][0][0]
        assert f"approximation of the {kind} law of a gauge file fitted to a wedge texture " \
               f"(alpha 30 deg, beta 10 deg, mu 0.1 / 0.2), all-faces contact" in head, head
        assert got[k][2]["kind"] == kind
    C = laws["ellipse"].law.C
    a = C.axes
    own = {"ellipse": best_ellipse(lambda phi: rho_ellipse(
               phi, a["mu_a_plus"], a["mu_a_minus"], a["mu_b_plus"], a["mu_b_minus"], C.theta)),
           "star": best_ellipse(lambda phi: rho_polygon(phi, laws["star"].law.C.points))}
    for k in ("star", "ellipse"):
        mu = got[k][1]
        assert mu == pytest.approx(own[k][:2], rel=4e-6), (k, mu, own[k][:2])
        digits(got[k][2]["rmax"], 100 * own[k][2])
        digits(got[k][2]["rrms"], 100 * own[k][3])
    # the two laws' ellipses are far enough apart for the test above to tell them apart
    assert abs(own["star"][0] / own["ellipse"][0] - 1) > 5e-5
    assert got["star"][1] != got["ellipse"][1]


def test_an_orthotropic_symmetric_ellipse_law_gives_its_own_axes(laws):
    """An ellipse law that is already symmetric and orthotropic in the principal frame (at
    37 deg): its own mu1, mu2 on the data line, nothing lost."""
    th = math.radians(37.0)
    gl = replace(laws["ellipse"], law=associated(TruncatedEllipse(0.3, 0.3, 0.2, 0.2, theta=th)),
                 principal_direction_deg=37.0)
    head, mu, loses = block(gl)
    assert mu == (0.3, 0.2) and "its own semi-axes" in head[0]
    assert (loses["ap"], loses["am"], loses["bp"], loses["bm"]) == ("0.3", "0.3", "0.2", "0.2")
    assert loses["asa"] == loses["asb"] == loses["rmax"] == loses["rrms"] == "0"
    assert float(loses["ang"]) < 1e-9


def test_loses_numbers_of_a_star_law_asymmetric_along_t_b(laws, tmp_path, capsys):
    """The wedge's star law in a frame turned by 90 deg (t_a along the ridges): the
    asymmetry moves to t_b.  mu_b+ is the wedge's mu_a- (sliding along -t_a of the wedge),
    mu_b- its mu_a+ (SPEC.md closed forms), mu_a+- its mu_b; the ellipse and its radial
    error against the star polygon as computed here."""
    gl = replace(laws["star"], principal_direction_deg=90.0)
    _, mu, loses = block(gl, tmp_path, capsys)
    w = wedge_axes()
    for key, ref in (("ap", w["b"]), ("am", w["b"]), ("bp", w["a-"]), ("bm", w["a+"])):
        digits(loses[key], ref, 6)
    digits(loses["asa"], 0.0)
    digits(loses["asb"], asymmetry(w["a-"], w["a+"]))                 # 3.98 %
    m1, m2, rmax, rrms = best_ellipse(lambda phi: rho_polygon(phi, gl.law.C.points),
                                      theta=math.pi / 2)
    assert mu == pytest.approx((m1, m2), rel=4e-6)
    assert m2 > m1                       # the larger friction across the ridges: now t_b
    digits(loses["rmax"], 100 * rmax)
    digits(loses["rrms"], 100 * rrms)


def test_loses_numbers_of_an_ellipse_law_asymmetric_along_t_b(laws):
    """An associated truncated ellipse with mu_b+ = 0.3, mu_b- = 0.15 (symmetric along
    t_a): every number of the LOSES line against its closed form, and the angle between
    the law's force and the fitted ellipse's for the same sliding direction."""
    ax = (0.2, 0.2, 0.3, 0.15)
    gl = replace(laws["ellipse"], law=associated(TruncatedEllipse(*ax)))
    _, mu, loses = block(gl)
    for key, ref in zip(("ap", "am", "bp", "bm"), ax):
        digits(loses[key], ref, 6)
    digits(loses["asa"], 0.0)
    digits(loses["asb"], asymmetry(0.3, 0.15))                        # 66.7 %
    m1, m2, rmax, rrms = best_ellipse(lambda phi: rho_ellipse(phi, *ax))
    assert mu == pytest.approx((m1, m2), rel=4e-6)
    digits(loses["rmax"], 100 * rmax)
    digits(loses["rrms"], 100 * rrms)
    psi = 2 * math.pi * np.arange(N_POLAR) / N_POLAR
    p, q = ellipse_force(psi, *ax), ellipse_force(psi, m1, m1, m2, m2)
    ang = np.degrees(np.abs(np.arctan2(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0],
                                       np.einsum("ij,ij->i", p, q))))
    digits(loses["ang"], float(ang.max()))
