"""Exports of a fitted law for other tools.

* :func:`polar_table` -- CSV ``psi_deg,p_a,p_b``: the law's force for equally spaced sliding
  directions, in the principal frame (``t_a`` at the gauge's principal direction, ``t_b`` at
  +90 deg; for wedge textures the texture's own frame).  At a set-valued direction the
  force is the point on the ray of the midpoint of D's flat edge (see
  :class:`~asperity.laws.walker_leine.LawForce`).
* :func:`abaqus_block` -- an Abaqus ``*FRICTION, ANISOTROPIC`` keyword block: the best
  symmetric orthotropic ellipse of the gauge's own law (``mu_1`` along ``t_a``, ``mu_2`` along
  ``t_b``): the law's own semi-axes when it is such an ellipse, else least squares on the
  relative radial error to the law's force polar -- so an ellipse law and a star law of one
  texture give different blocks, each its law's.  Comment lines name the law (kind, what it
  was fitted to) and the frame, and state what the approximation loses -- asymmetry
  (opposite directions with different friction), non-associated sliding (the law's force
  against the ellipse's associated force) and the radial error -- and by how much.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import __version__
from .fitting import GaugeLaw, ReservoirData, fit_truncated_ellipse
from .geometry import angle_between, unit
from .sets import TruncatedEllipse
from .walker_leine import associated


def _to_local(p: np.ndarray, theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.column_stack([c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1]])


def polar_table(gl: GaugeLaw, n: int = 360) -> str:
    """CSV text, header ``psi_deg,p_a,p_b``, n directions from t_a (psi_deg = 360 k / n)."""
    from ..errors import check_instance
    check_instance("gauge law", gl, GaugeLaw)
    from ..errors import check_int
    n = check_int("directions", n, 4, 1_000_000)
    theta = math.radians(gl.principal_direction_deg)
    k = np.arange(n)
    psi_local_deg = 360.0 * k / n
    f = gl.force(theta + 2.0 * np.pi * k / n)
    p = _to_local(f.p, theta)
    rows = ["psi_deg,p_a,p_b"]
    rows += [f"{a!r},{b!r},{c!r}" for a, b, c in zip(psi_local_deg.tolist(), p[:, 0].tolist(),
                                                      p[:, 1].tolist())]
    return "\n".join(rows) + "\n"


def write_csv(path, gl: GaugeLaw, n: int = 360) -> None:
    from ..io import write_text_atomic
    write_text_atomic(path, polar_table(gl, n))


#: polar angles, equally spaced from t_a, at which a law's force polar is sampled for the
#: orthotropic fit and its radial error (and sliding directions for the angle error)
POLAR_POINTS = 720
#: relative difference below which a truncated ellipse's opposite semi-axes count as equal
SYMMETRIC_TOL = 1e-12


@dataclass(frozen=True)
class OrthotropicApproximation:
    """The best symmetric orthotropic (Abaqus-style) ellipse of a law and what it loses.

    mu_1, mu_2 : semi-axes along t_a and t_b
    axes       : the law's friction along +-t_a, +-t_b (p.s): mu_a+, mu_a-, mu_b+, mu_b-
    asymmetry_a, asymmetry_b : |mu+ - mu-| / ((mu+ + mu-)/2) along each axis (lost)
    max_radial_error, rms_radial_error : ellipse against the law's force polar, relative
    max_angle_deg : largest angle between the law's force and the ellipse's associated
        force for the same sliding direction (non-associated sliding, lost)
    exact : the law is itself a symmetric ellipse orthotropic in the principal frame (its
        own mu_1, mu_2: nothing is lost)
    """

    mu_1: float
    mu_2: float
    axes: dict
    asymmetry_a: float
    asymmetry_b: float
    max_radial_error: float
    rms_radial_error: float
    max_angle_deg: float
    exact: bool = False


def _own_ellipse(gl: GaugeLaw, theta: float) -> TruncatedEllipse | None:
    """The law's C when it is a symmetric ellipse with its axes along t_a and t_b."""
    C = gl.law.C
    if not isinstance(C, TruncatedEllipse):
        return None
    same = (math.isclose(C.mu_a_plus, C.mu_a_minus, rel_tol=SYMMETRIC_TOL)
            and math.isclose(C.mu_b_plus, C.mu_b_minus, rel_tol=SYMMETRIC_TOL))
    turn = math.remainder(C.theta - theta, math.pi)      # a symmetric ellipse: modulo pi
    if not (same and abs(turn) <= SYMMETRIC_TOL):
        return None
    return TruncatedEllipse(C.mu_a_plus, C.mu_a_plus, C.mu_b_plus, C.mu_b_plus, theta=theta)


def orthotropic_approximation(gl: GaugeLaw) -> OrthotropicApproximation:
    """The best symmetric orthotropic ellipse of the law of ``gl`` (in its principal frame):
    the law's own semi-axes when its C is such an ellipse, else the least-squares fit on the
    relative radial error to the law's own force polar (the boundary of its C at
    :data:`POLAR_POINTS` polar angles from t_a) -- each law its own ellipse, not the data's."""
    from ..errors import check_instance
    check_instance("gauge law", gl, GaugeLaw)
    theta = math.radians(gl.principal_direction_deg)
    phi = theta + 2.0 * math.pi * np.arange(POLAR_POINTS) / POLAR_POINTS
    r = gl.law.C.radial(phi)
    own = _own_ellipse(gl, theta)
    e = own
    if own is None:                      # the fit needs only the points (psi is not read)
        polar = ReservoirData(psi=phi, p=r[:, None] * unit(phi), limit=np.zeros(phi.size, int))
        e = fit_truncated_ellipse(polar, theta, symmetric=True)
    rad = (e.radial(phi) - r) / r
    f = gl.force(phi)                    # the same angles as sliding directions
    ok = ~f.set_valued
    ang = angle_between(associated(e).force(phi[ok]).p, f.p[ok])
    t = gl.force(theta + np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])).tangential
    axes = dict(zip(("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"), map(float, t)))
    return OrthotropicApproximation(
        mu_1=e.mu_a_plus, mu_2=e.mu_b_plus, axes=axes,
        asymmetry_a=abs(t[0] - t[1]) / (0.5 * (t[0] + t[1])),
        asymmetry_b=abs(t[2] - t[3]) / (0.5 * (t[2] + t[3])),
        max_radial_error=float(np.abs(rad).max()),
        rms_radial_error=float(np.sqrt(np.mean(rad * rad))),
        max_angle_deg=float(np.degrees(ang.max())) if ang.size else 0.0,
        exact=own is not None)


def _pct(x: float) -> str:
    return "0" if abs(x) < 5e-9 else f"{100 * x:.3g}"


def source_words(source: dict) -> str:
    """What a gauge's law was fitted to, in words: 'a wedge texture (alpha 30 deg, beta 10
    deg, mu 0.1 / 0.2)', 'the mesh wedge-30-10.stl', with the contact regime."""
    tex = source.get("texture", {}) if isinstance(source, dict) else {}
    tex = tex if isinstance(tex, dict) else {}
    kind = str(tex.get("kind", "texture"))
    if tex.get("rule"):
        return (f"the {tex['rule']} rule's coefficients (mu_f {tex.get('mu_f'):g}, mu_b "
                f"{tex.get('mu_b'):g}, mu_t {tex.get('mu_t'):g})")
    if "alpha_deg" in tex:
        what = (f"a {kind} texture (alpha {tex.get('alpha_deg'):g} deg, beta "
                f"{tex.get('beta_deg'):g} deg, mu {tex.get('mu_alpha'):g} / "
                f"{tex.get('mu_beta'):g})")
    else:
        name = tex.get("source") or tex.get("file")
        what = f"the {kind} {name}" if name else f"a {kind}"
    contact = source.get("contact") if isinstance(source, dict) else None
    return what + (f", {contact} contact" if contact else "")


def abaqus_block(gl: GaugeLaw) -> str:
    """``*FRICTION, ANISOTROPIC`` with mu_1 (along t_a) and mu_2 (along t_b) on the data
    line, preceded by ``**`` comment lines: which law (kind, what it was fitted to) the block
    approximates, the frame, and what the approximation loses."""
    a = orthotropic_approximation(gl)
    ax = a.axes
    how = ("its own semi-axes: the law is a symmetric orthotropic ellipse" if a.exact else
           f"least squares on the radial error to the law's force polar, {POLAR_POINTS} "
           f"directions")
    lines = [
        f"** asperity {__version__}: best symmetric orthotropic approximation of the "
        f"{gl.kind} law of a gauge file fitted to {source_words(gl.source)} ({how})",
        f"** direction 1 = t_a (principal direction, {gl.principal_direction_deg:.6g} deg from "
        "the x axis of the source), direction 2 = t_b (+90 deg); orient the contact's local "
        "tangent directions accordingly",
        f"** LOSES: asymmetry (mu_a+ = {ax['mu_a_plus']:.6g}, mu_a- = {ax['mu_a_minus']:.6g}: "
        f"{_pct(a.asymmetry_a)} % apart; mu_b+ = {ax['mu_b_plus']:.6g}, "
        f"mu_b- = {ax['mu_b_minus']:.6g}: {_pct(a.asymmetry_b)} % apart) and "
        f"non-associated sliding (the ellipse's force up to {a.max_angle_deg:.3g} deg from the "
        f"{gl.kind} law's force for the same sliding direction); radial error against the "
        f"{gl.kind} law up to {_pct(a.max_radial_error)} % (rms {_pct(a.rms_radial_error)} %)",
        "*FRICTION, ANISOTROPIC",
        f"{a.mu_1:.6g}, {a.mu_2:.6g}",
    ]
    return "\n".join(lines) + "\n"


def write_abaqus(path, gl: GaugeLaw) -> None:
    from ..io import write_text_atomic
    write_text_atomic(path, abaqus_block(gl))
