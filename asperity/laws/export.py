"""Exports of a fitted law for other tools.

* :func:`polar_table` -- CSV ``psi_deg,p_a,p_b``: the law's force for equally spaced sliding
  directions, in the principal frame (``t_a`` at the gauge's principal direction, ``t_b`` at
  +90 deg; for wedge textures the texture's own frame).  At a set-valued direction the
  force is the point on the ray of the midpoint of D's flat edge (see
  :class:`~asperity.laws.walker_leine.LawForce`).
* :func:`abaqus_block` -- an Abaqus ``*FRICTION, ANISOTROPIC`` keyword block: the best
  symmetric orthotropic ellipse (``mu_1`` along ``t_a``, ``mu_2`` along ``t_b``, least squares on
  the relative radial error to the data), with comment lines that state the frame and what
  the approximation loses -- asymmetry (opposite directions with different friction) and
  non-associated sliding (force not along the ellipse's normal) -- and by how much.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import __version__
from .fitting import GaugeLaw, ReservoirData, fit_truncated_ellipse
from .geometry import angle_between, polar_angle
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


@dataclass(frozen=True)
class OrthotropicApproximation:
    """The best symmetric orthotropic (Abaqus-style) ellipse and what it loses.

    mu_1, mu_2 : semi-axes along t_a and t_b
    axes       : the law's friction along +-t_a, +-t_b (p.s): mu_a+, mu_a-, mu_b+, mu_b-
    asymmetry_a, asymmetry_b : |mu+ - mu-| / ((mu+ + mu-)/2) along each axis (lost)
    max_radial_error, rms_radial_error : ellipse against the data, relative
    max_angle_deg : largest angle between the data's force and the ellipse's associated
        force for the same sliding direction (non-associated sliding, lost)
    """

    mu_1: float
    mu_2: float
    axes: dict
    asymmetry_a: float
    asymmetry_b: float
    max_radial_error: float
    rms_radial_error: float
    max_angle_deg: float


def orthotropic_approximation(gl: GaugeLaw) -> OrthotropicApproximation:
    from ..errors import check_instance
    check_instance("gauge law", gl, GaugeLaw)
    theta = math.radians(gl.principal_direction_deg)
    data: ReservoirData = gl.data
    e = fit_truncated_ellipse(data, theta, symmetric=True)
    phi = polar_angle(data.p)
    r = np.hypot(data.p[:, 0], data.p[:, 1])
    rad = (e.radial(phi) - r) / r
    ok = data.limit == 0
    ang = angle_between(associated(e).force(data.psi[ok]).p, data.p[ok])
    t = gl.force(theta + np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])).tangential
    axes = dict(zip(("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"), map(float, t)))
    return OrthotropicApproximation(
        mu_1=e.mu_a_plus, mu_2=e.mu_b_plus, axes=axes,
        asymmetry_a=abs(t[0] - t[1]) / (0.5 * (t[0] + t[1])),
        asymmetry_b=abs(t[2] - t[3]) / (0.5 * (t[2] + t[3])),
        max_radial_error=float(np.abs(rad).max()),
        rms_radial_error=float(np.sqrt(np.mean(rad * rad))),
        max_angle_deg=float(np.degrees(ang.max())) if ang.size else 0.0)


def _pct(x: float) -> str:
    return "0" if abs(x) < 5e-9 else f"{100 * x:.3g}"


def abaqus_block(gl: GaugeLaw) -> str:
    """``*FRICTION, ANISOTROPIC`` with mu_1 (along t_a) and mu_2 (along t_b) on the data
    line, preceded by ``**`` comment lines."""
    a = orthotropic_approximation(gl)
    src = gl.source.get("texture", {})
    what = src.get("kind", "texture")
    ax = a.axes
    lines = [
        f"** asperity {__version__}: best symmetric orthotropic approximation of the "
        f"{gl.kind} law of a {what} texture, {gl.source.get('contact')} contact",
        f"** direction 1 = t_a (principal direction, {gl.principal_direction_deg:.6g} deg from "
        "the x axis of the source), direction 2 = t_b (+90 deg); orient the contact's local "
        "tangent directions accordingly",
        f"** LOSES: asymmetry (mu_a+ = {ax['mu_a_plus']:.6g}, mu_a- = {ax['mu_a_minus']:.6g}: "
        f"{_pct(a.asymmetry_a)} % apart; mu_b+ = {ax['mu_b_plus']:.6g}, "
        f"mu_b- = {ax['mu_b_minus']:.6g}: {_pct(a.asymmetry_b)} % apart) and "
        f"non-associated sliding (force up to {a.max_angle_deg:.3g} deg from the texture's "
        f"force for the same sliding direction); radial error up to "
        f"{_pct(a.max_radial_error)} % (rms {_pct(a.rms_radial_error)} %)",
        "*FRICTION, ANISOTROPIC",
        f"{a.mu_1:.6g}, {a.mu_2:.6g}",
    ]
    return "\n".join(lines) + "\n"


def write_abaqus(path, gl: GaugeLaw) -> None:
    from ..io import write_text_atomic
    write_text_atomic(path, abaqus_block(gl))
