"""Texture -> directional friction: the computation behind ``asperity derive``.

:func:`derive` evaluates the reservoir p(psi) of a texture over ``n_directions`` equally
spaced sliding directions by the closed form or the spring simulation, with the axis
coefficients and all diagnostics, and :func:`to_json` turns the result into the
documented JSON object (self-locking values are ``null``, never NaN or Infinity).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import __version__
from ..errors import InputError, check_choice, check_instance, check_int
from .diagnostics import (
    DERIVATIVE_STEP,
    SURFACE_DERIVATIVE_STEP,
    Admissibility,
    Associativity,
    check_admissibility,
    check_associativity,
    dT_dpsi_from,
    find_self_locking,
    locking_share,
)
from .faces import compute_faces_reservoir, faces_source
from .reservoir import Reservoir, check_contact, check_progress, directions, locked_runs

METHODS = ("closed-form", "springs")


@dataclass(frozen=True)
class Derivation:
    """The directional friction of a texture or surface (what :func:`asperity.derive`
    returns; ``asperity derive --json`` prints it).

    Attributes
    ----------
    texture : object
        The texture or surface derived.
    contact, method : str
        The contact regime (``"all-faces"``, ``"windward"``) and the method
        (``"closed-form"``, ``"springs"``).
    reservoir : asperity.friction.reservoir.Reservoir
        The reservoir points p(psi) at every sliding direction.
    axes : dict
        ``mu_a_plus``, ``mu_a_minus``, ``mu_b_plus``, ``mu_b_minus`` (None where
        self-locking).
    self_locking : list
        The self-locking directions and faces.
    admissibility, associativity : object
        The diagnostics: ``p.s >= 0`` for every direction (and its minimum); the largest
        ``|L - dT/dpsi|`` and ``|L|``.
    springs : dict or None
        The spring model and its agreement with the closed form (``method="springs"``).
    closed_form : asperity.friction.reservoir.Reservoir or None
        The closed form's reservoir beside the springs' one.
    principal_direction_deg : float
        t_a in the x-y frame, deg (surfaces: found from the friction).
    anisotropy : float
        (max T - min T) / mean T over the directions.
    locking_share : float
        Largest load share on faces that cannot be climbed.
    """

    texture: object
    contact: str
    method: str
    reservoir: Reservoir
    axes: dict                       # mu_a_plus, mu_a_minus, mu_b_plus, mu_b_minus
    self_locking: list
    admissibility: Admissibility
    associativity: Associativity
    springs: dict | None = None      # spring model and agreement with the closed form
    closed_form: Reservoir | None = field(default=None, repr=False)
    principal_direction_deg: float = 0.0   # t_a in the x-y frame (surfaces: found)
    anisotropy: float = 0.0          # (max T - min T) / mean T over the directions
    locking_share: float = 0.0       # largest load share on faces that cannot be climbed


def derive(texture, contact: str = "all-faces", method: str = "closed-form",
           n_directions: int = 72, model=None, progress=None, elastic=None) -> Derivation:
    """Directional friction of a texture or surface over equally spaced sliding directions.

    The computation behind ``asperity derive``: the reservoir p(psi) at ``n_directions``
    directions psi_k = 2 pi k / n by the closed form (or the spring simulation), the axis
    coefficients, and the diagnostics: admissibility, associativity, self-locking.

    Parameters
    ----------
    texture : WedgeTexture, GaussianWedgeTexture, FacetSurface, HeightMap or TriangleMesh
        A wedge texture (frame ``t_a``, ``t_b`` given: the principal direction is 0) or a
        surface (:func:`asperity.load_surface`; frame x, y of the file: the principal
        direction is found, and mu_a+/- are taken along and against it, mu_b+/- at +90 deg
        from it).  A HeightMap or TriangleMesh is taken as its facets (default friction
        0.1, mean slope removed).
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.
    method : {"closed-form", "springs"}, default "closed-form"
        "springs" (wedge textures only) runs the spring-on-wedge simulation for every
        direction and the four axis directions, and reports its largest relative deviation
        from the closed form.
    n_directions : int, default 72
        Number of sliding directions, in [8, 100000].
    model : SpringModel or None, default None
        The springs of ``method="springs"``; None: ``SpringModel()``.
    progress : callable or None, default None
        ``progress(fraction)``, called during long facet computations.
    elastic : ElasticContact or None, default None
        One pressure: each face (facet) of a HeightMap or wedge texture weighs the normal
        force it carries in that elastic contact (SPEC.md section 7); closed form only.
        Several pressures: :func:`asperity.derive_family`.

    Returns
    -------
    Derivation
        ``reservoir`` (a Reservoir over the directions); ``axes``, the dict of
        ``mu_a_plus``, ``mu_a_minus``, ``mu_b_plus``, ``mu_b_minus`` (``inf`` where
        self-locking); ``principal_direction_deg`` (``t_a`` from +x); ``anisotropy``,
        (max T - min T) / mean T; ``admissibility`` (``p . s >= 0`` everywhere: ``admissible``,
        ``min_dissipation``); ``associativity`` (``L = dT/dpsi``: ``associated``,
        ``max_deviation``, ``max_lateral``); ``self_locking``, a list of ``{"psi_deg",
        "face"}``; ``locking_share``; ``springs`` (method springs); ``texture``,
        ``contact``, ``method``.

    Raises
    ------
    asperity.InputError
        A texture of another kind, an option out of range, ``method="springs"`` on a
        surface or with ``elastic``, or several pressures in ``elastic``.

    See Also
    --------
    asperity.compute_reservoir, asperity.derive_scan, asperity.derive_family,
    asperity.fit_derivation

    Notes
    -----
    The principal direction of a surface is the axis of the second Fourier harmonic of
    T(psi) = p . s (a direction and its reverse count alike): the axis along which
    forwards and backwards together rub most.  A law of maximum dissipation has
    ``L = dT/dpsi`` (SPEC.md section 1); the wedge models break it.

    Examples
    --------
    SPEC.md: the symmetric 30 deg wedge with mu = 0.3 is admissible but not associated
    (max ``|L - dT/dpsi|`` = 0.012 while max ``|L|`` = 0.055):

    >>> d = asperity.derive(asperity.WedgeTexture(30.0, 30.0, 0.3, 0.3), n_directions=360)
    >>> a = d.associativity
    >>> print(d.admissibility.admissible, a.associated,
    ...       f"{a.max_deviation:.4f} {a.max_lateral:.4f}")
    True False 0.0116 0.0545

    A face too steep to climb self-locks in a range of directions:

    >>> d = asperity.derive(asperity.load_texture("surfaces/self-locking.toml"))
    >>> print(len(d.self_locking), d.self_locking[0], f"{d.axes['mu_a_minus']:.4f}")
    33 {'psi_deg': 0.0, 'face': 'alpha'} 0.3184
    """
    if elastic is not None:
        texture = _elastic_texture(texture, elastic, method)
    texture = faces_source(texture)
    check_progress(progress)
    check_contact(contact)
    check_choice("method", method, METHODS)
    n = check_int("directions", n_directions, 8, 100_000)
    if model is not None:
        from ..texture.spring_model import SpringModel
        check_instance("model", model, SpringModel)
    surface = getattr(texture, "kind", "") == "surface"
    if surface and method != "closed-form":
        raise InputError("method springs needs a wedge texture; surfaces use the facet closed form")
    psi = directions(n)
    faces = texture.faces()
    h = SURFACE_DERIVATIVE_STEP if surface else DERIVATIVE_STEP
    # the directions, their +-h neighbours for dT/dpsi: one pass over the facets
    both = compute_faces_reservoir(faces, np.concatenate([psi, psi + h, psi - h]), contact,
                                   progress)
    cf = both.take(slice(0, n))
    theta = principal_direction(cf) if surface else 0.0
    axis_psi = theta + np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])
    if method == "closed-form":
        res = cf
        t = compute_faces_reservoir(faces, axis_psi, contact).tangential
        assoc = check_associativity(res, *dT_dpsi_from(both.take(slice(n, 2 * n)),
                                                       both.take(slice(2 * n, 3 * n)), h))
        springs = None
    else:
        from ..texture.spring_model import SpringModel
        from ..texture.springs import simulate_reservoir
        model = SpringModel() if model is None else model
        res = simulate_reservoir(texture, psi, model, contact)
        t = simulate_reservoir(texture, axis_psi, model, contact).tangential
        assoc = check_associativity(res)
        springs = {"model": _model_dict(model), "max_relative_deviation_from_closed_form":
                   relative_deviation(res, cf)}
    axes = {"mu_a_plus": float(t[0]), "mu_a_minus": float(t[1]),
            "mu_b_plus": float(t[2]), "mu_b_minus": float(t[3])}
    return Derivation(texture, contact, method, res, axes, find_self_locking(res, faces.names),
                      check_admissibility(res), assoc, springs, cf,
                      principal_direction_deg=math.degrees(theta),
                      anisotropy=anisotropy(res),
                      locking_share=float(np.nanmax(locking_share(faces, res), initial=0.0)))


def _elastic_texture(texture, elastic, method):
    from ..surface.contact_facets import check_elastic
    from .elastic import elastic_textures
    if check_elastic(elastic).family:
        raise InputError("derive takes one pressure (a number); derive_family derives a law "
                         "for each of several")
    if method != "closed-form":
        raise InputError("method springs has its own load model; elastic contact weights "
                         "the closed form")
    return elastic_textures(texture, elastic)[0]


def principal_direction(res: Reservoir) -> float:
    """Principal direction (radians, in [0, pi)) of a reservoir over a uniform full turn of
    directions: the axis of the second Fourier harmonic of T(psi) = p . s, T ~ c0 + c2
    cos 2(psi - theta) (a sliding direction and its reverse count alike; self-locking
    directions count as the largest finite friction) -- the axis along which the friction
    of both ways together is largest, not the one direction of largest friction
    (:func:`largest_friction`: with asymmetric friction mu_b+ may exceed mu_a+ and mu_a-).
    Across the lay of a textured surface; 0 for the wedge textures' t_a when mu_a > mu_b."""
    T = res.tangential
    ok = np.isfinite(T)
    if not ok.any():
        return 0.0
    T = np.where(ok, T, T[ok].max())
    c2 = np.sum(T * np.exp(2j * res.psi))       # T ~ c0 + c cos 2(psi - theta)
    if abs(c2) <= 1e-14 * np.sum(np.abs(T)):
        return 0.0
    theta = float(np.mod(0.5 * np.angle(c2), np.pi))
    return 0.0 if np.pi - theta < 1e-12 else theta


def largest_friction(res: Reservoir) -> tuple[float, float] | None:
    """(psi in degrees, T) of the sliding direction of largest finite friction T = p . s
    among the reservoir's directions; None when every direction self-locks."""
    T = res.tangential
    ok = np.isfinite(T)
    if not ok.any():
        return None
    k = int(np.argmax(np.where(ok, T, -np.inf)))
    return float(np.degrees(res.psi[k]) % 360.0), float(T[k])


#: what t_a is, in the words of the printed summaries
T_A_WORDS = "the axis of the cos 2psi term of T: forwards and backwards together rub most along it"


def anisotropy(res: Reservoir) -> float:
    """(max T - min T) / mean T over the directions that do not self-lock (0 if none)."""
    T = res.tangential
    T = T[np.isfinite(T)]
    if T.size == 0 or T.mean() <= 0:
        return 0.0
    return float((T.max() - T.min()) / T.mean())


def relative_deviation(a: Reservoir, b: Reservoir) -> float | None:
    """max over directions of |p_a - p_b| / |p_b| where neither self-locks (None if none)."""
    ok = ~(a.locked | b.locked | a.set_valued | b.set_valued)
    if not ok.any():
        return None
    d = np.hypot(*(a.p[ok] - b.p[ok]).T) / np.maximum(np.hypot(*b.p[ok].T), 1e-300)
    return float(d.max())


def _model_dict(model) -> dict:
    from dataclasses import asdict
    return {k: (None if isinstance(v, float) and math.isinf(v) else v)
            for k, v in asdict(model).items()}


def _num(x: float) -> float | None:
    """JSON number, or null for an infinite value (self-locking)."""
    return float(x) if math.isfinite(x) else None


def to_json(d: Derivation) -> dict:
    """The JSON object printed by ``asperity derive --json`` (keys in the file formats' outputs)."""
    r = d.reservoir
    T, L = r.tangential, r.lateral
    dirs = []
    for k in range(r.psi.size):
        locked = bool(r.locked[k])
        dirs.append({
            "psi_deg": round(float(np.degrees(r.psi[k])), 10),
            "p": None if locked else [float(r.p[k, 0]), float(r.p[k, 1])],
            "tangential": None if locked else float(T[k]),
            "lateral": None if locked else float(L[k]),
            "self_locking": locked,
            "set_valued": bool(r.set_valued[k]),
        })
    out = {
        "asperity_version": __version__,
        "texture": d.texture.to_dict(),
        "contact": d.contact,
        "method": d.method,
        **{k: _num(v) for k, v in d.axes.items()},
        "principal_direction_deg": d.principal_direction_deg,
        "anisotropy": d.anisotropy,
        "admissible": d.admissibility.admissible,
        "min_dissipation": _num(d.admissibility.min_dissipation),
        "self_locking": d.self_locking,
        "self_locking_load_share": d.locking_share,
        "associativity": {
            "associated": d.associativity.associated if d.associativity.defined.any() else None,
            "max_abs_L_minus_dT_dpsi": d.associativity.max_deviation,
            "max_abs_lateral": d.associativity.max_lateral,
            "psi_deg_of_max": d.associativity.psi_max_deg
            if math.isfinite(d.associativity.psi_max_deg) else None,
        },
        "directions": dirs,
    }
    if getattr(d.texture, "elastic", None) is not None:
        out["elastic_contact"] = dict(d.texture.elastic)
    if getattr(d.texture, "kind", "") == "surface":
        from .quality import data_quality
        out["n_facets"] = d.texture.n_facets
        out["n_undefined"] = d.texture.n_undefined
        out["data_quality"] = data_quality(d)
        if getattr(d.texture, "tiling", None):
            out["tiling"] = d.texture.tiling
    if d.springs is not None:
        out["springs"] = d.springs
    return out


def format_text(d: Derivation) -> str:
    """Human-readable summary for the terminal."""
    def f(x):
        return "inf (self-locking)" if not math.isfinite(x) else f"{x:.6f}"
    tex = d.texture
    surface = getattr(tex, "kind", "") == "surface"
    locked_all = len(d.self_locking) == d.reservoir.psi.size
    if surface:
        th = d.principal_direction_deg
        head = [tex.describe(),
                f"contact: {d.contact}   directions: {d.reservoir.psi.size}",
                "principal direction t_a, anisotropy: none (no direction slides)" if locked_all
                else f"principal direction t_a ({T_A_WORDS}; across the lay): {th:.2f} deg "
                f"from +x; anisotropy (max T - min T)/mean T = {d.anisotropy:.4f}"]
        dirs = [f"towards {(th + k) % 360:.1f} deg" for k in (0, 180, 90, 270)]
    else:
        head = [f"texture: {tex.kind}  alpha={tex.alpha_deg:g} deg  beta={tex.beta_deg:g} deg  "
                f"mu_alpha={tex.mu_alpha:g}  mu_beta={tex.mu_beta:g}",
                f"contact: {d.contact}   method: {d.method}   directions: {d.reservoir.psi.size}"]
        dirs = ["along +t_a", "along -t_a", "along +t_b", "along -t_b"]
    if getattr(tex, "elastic", None) is not None:
        from ..surface.contact_facets import contact_lines
        head += contact_lines(tex.elastic)
    lines = head + ["",
             f"  mu_a+ (slide {dirs[0]}) = {f(d.axes['mu_a_plus'])}",
             f"  mu_a- (slide {dirs[1]}) = {f(d.axes['mu_a_minus'])}",
             f"  mu_b+ (slide {dirs[2]}) = {f(d.axes['mu_b_plus'])}",
             f"  mu_b- (slide {dirs[3]}) = {f(d.axes['mu_b_minus'])}"]
    top = largest_friction(d.reservoir)
    if top is not None and not locked_all:
        where = f"towards {top[0]:.1f} deg from +x" if surface else \
            f"at psi = {top[0]:.1f} deg from +t_a"
        lines.append(f"  largest friction{' of the directions that slide' if d.self_locking else ''}"
                     f": T = {top[1]:.6f}, sliding {where}")
    lines.append("")
    a = d.admissibility
    if locked_all:
        lines.append("admissible (p.s >= 0 for all directions): nothing to check (no "
                     "direction slides)")
    else:
        lines.append(f"admissible (p.s >= 0 for all directions): "
                     f"{'yes' if a.admissible else 'NO'}"
                     + (f"  (min p.s = {a.min_dissipation:.4g} at psi = {a.psi_min_deg:g} deg)"
                        if math.isfinite(a.min_dissipation) else ""))
    s = d.associativity
    if not s.defined.any():
        lines.append("associated (L = dT/dpsi): not defined (no direction with a finite, "
                     "single-valued force and defined neighbours)")
    else:
        lines.append(f"associated (L = dT/dpsi): {'yes' if s.associated else 'no'}; "
                     f"max |L - dT/dpsi| = {s.max_deviation:.4g}, max |L| = {s.max_lateral:.4g}")
    if d.self_locking:
        faces = sorted({e['face'] for e in d.self_locking})
        lines.append(f"SELF-LOCKING in {len(d.self_locking)} of {d.reservoir.psi.size} directions, "
                     f"psi in {locked_runs(d.reservoir)} ({'facet' if surface else 'face'} {', '.join(faces)}): "
                     "the tips cannot climb, friction is unbounded there")
        if surface:                  # one load share: the facets steeper than the limit
            from .quality import locking_advice
            lines += locking_advice(d)
        else:
            lines.append(f"  faces that cannot be climbed carry up to {100 * d.locking_share:.3g}"
                         " % of the load")
    else:
        lines.append("self-locking: none")
    if d.reservoir.set_valued.any():
        lines.append("set-valued (windward, sliding along the ridges) at psi = " + ", ".join(
            f"{x:g}" for x in np.degrees(d.reservoir.psi[d.reservoir.set_valued])) + " deg")
    if surface:
        from .quality import quality_lines
        lines += quality_lines(d)
    if d.springs is not None:
        dev = d.springs["max_relative_deviation_from_closed_form"]
        lines.append(f"spring simulation: max |p_springs - p_closed| / |p_closed| = "
                     f"{dev:.3g}" if dev is not None else "spring simulation: no comparable direction")
    return "\n".join(lines)
