"""Law families: one fitted law per nominal pressure of an elastic contact (gauge files,
version 2).

``asperity fit --elastic E --pressure P1 P2 ...`` fits one law per pressure (the same kind
and options for each) to the friction weighted by the contact force
(:mod:`asperity.friction.elastic`); a :class:`GaugeFamily` holds them, each a
:class:`~asperity.laws.fitting.GaugeLaw` whose source carries its contact figures.
:meth:`GaugeFamily.at` gives the law at any pressure in [first, last]:

* at a member's pressure: that member, exactly;
* between members k and k+1: the weight ``w = ln(p / p_k) / ln(p_k+1 / p_k)`` (linear in
  ln p: the members are usually a geometric series of pressures, and friction varies with
  the contact fraction, roughly with ln p);

  - truncated ellipse: each semi-axis ``(1 - w) mu_k + w mu_k+1`` (positive, so a valid
    ellipse, associated as every ellipse law), ``t_a`` turned from the member k's by ``w``
    times the smaller angle to the member k+1's (an ellipse written with ``t_a`` reversed
    is the same set with its + and - semi-axes exchanged);
  - star: the reservoir point of each fitted sliding direction ``(1 - w) p_k(psi) + w
    p_k+1(psi)`` (the two one-sided limits of a set-valued direction apart), and the star
    law fitted through these points as ``asperity fit`` fits one (C through them, D from
    their sliding rule): a star law with its own fit report, or a one-line refusal if the
    interpolated points are not star-shaped or D is not convex;

* outside [first, last]: refused (no extrapolation).

The version-2 file (the shared fields once, each member's law as a version-1 file's fields,
checked as one) is :mod:`asperity.laws.gauge_file`'s.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .fitting import GaugeLaw, ReservoirData

#: what :meth:`GaugeFamily.at` does between members, in the file's family.interpolation
INTERPOLATION = ("linear in ln p between the two members around p; truncated ellipse: the "
                 "semi-axes and the direction t_a; star: each sliding direction's reservoir "
                 "point, the star law fitted through them; outside [first, last] refused")
#: relative agreement of a member's pressure with its contact's mean pressure (the solve's
#: tolerance is 1e-8 by default)
PRESSURE_MATCH = 1e-4
#: most members of a family (as ElasticContact.MAX_PRESSURES)
MAX_MEMBERS = 100


#: keys of a source's texture description that depend on the load (the facets that carry
#: some): kept with each member
PER_MEMBER = ("n_facets", "n_unloaded", "data_quality")


def _common(source: dict) -> dict:
    """A member's source without what depends on its pressure."""
    out = {k: v for k, v in source.items() if k != "elastic_contact"}
    if isinstance(out.get("texture"), dict):
        out["texture"] = {k: v for k, v in out["texture"].items() if k not in PER_MEMBER}
    return out


def own_keys(source: dict) -> dict:
    """The texture keys of a member's source that depend on its pressure."""
    tex = source.get("texture")
    return {k: tex[k] for k in PER_MEMBER if k in tex} if isinstance(tex, dict) else {}


def contact_mismatch(c: dict, pressure: float, ref: dict) -> str | None:
    """What of a member's contact figures ``c`` disagrees with its ``pressure`` or with the
    family's E*, boundary and hardness (``ref``), in words; None when nothing does."""
    if not abs(c.get("pressure_Pa", math.nan) - pressure) <= PRESSURE_MATCH * pressure:
        return (f"contact.pressure_Pa ({c.get('pressure_Pa')}) is not the member's pressure "
                f"({pressure:g} Pa)")
    for key in ("E_star_Pa", "boundary", "hardness_Pa"):
        if c.get(key) != ref.get(key):
            return f"contact.{key} ({c.get(key)}) is not the family's ({ref.get(key)})"
    return None


def _sides(data: ReservoirData):
    """(distinct psi, left point, right point): an ordinary direction's point twice, a
    set-valued direction's two one-sided limits."""
    first = np.ones(data.psi.size, bool)
    first[1:] = data.psi[1:] != data.psi[:-1]
    idx = np.cumsum(first) - 1
    u = data.psi[first]
    left = np.empty((u.size, 2))
    right = np.empty((u.size, 2))
    for i, k, lim in zip(idx, range(data.psi.size), data.limit):
        if lim <= 0:
            left[i] = data.p[k]
        if lim >= 0:
            right[i] = data.p[k]
    return u, left, right


@dataclass(frozen=True)
class GaugeFamily:
    """A law family: one fitted law per nominal pressure of an elastic contact.

    What ``asperity fit --elastic E --pressure P1 P2 ...`` fits and a version-2 gauge file
    holds.  ``at(p)`` gives the law at any pressure in [first, last]: a member's own law at
    its pressure; in between, linear in ``ln p`` (the weight
    ``w = ln(p / p_k) / ln(p_k+1 / p_k)``) -- a truncated ellipse's semi-axes and
    direction t_a, or a star law refitted through the interpolated reservoir points;
    outside, refused (no extrapolation).

    Parameters
    ----------
    pressures : sequence of float
        Nominal pressures (Pa, > 0, strictly increasing), one per member.
    members : tuple of GaugeLaw
        1 to 100 fitted laws (:func:`~asperity.fit_derivation`), one a pressure: one kind,
        one source but for each member's ``source["elastic_contact"]`` (whose pressure is
        the member's), fitted at the same sliding directions.

    Raises
    ------
    InputError
        If the pressures are not positive and strictly increasing, or the members do not
        match them or one another (kind, source, contact, sliding directions).

    See Also
    --------
    asperity.derive_family : the derivations at each pressure.
    asperity.write_gauge, asperity.read_gauge : the version-2 gauge file.
    asperity.ElasticContact : the contact options.

    Examples
    --------
    The SPEC.md wedge pressed onto E* = 1 GPa at 10 and 100 MPa:

    >>> tex = asperity.load_texture("surfaces/wedge-asymmetric.toml")
    >>> fam = asperity.derive_family(tex, asperity.ElasticContact(1e9, [1e7, 1e8]))
    >>> laws = tuple(asperity.fit_derivation(d, "truncated-ellipse") for d in fam.members)
    >>> gf = asperity.GaugeFamily(fam.pressures, laws)
    >>> [round(m.law.C.mu_a_plus, 5) for m in gf.members]
    [0.1855, 0.18527]
    >>> gl = gf.at(3e7)
    >>> print(f"{gl.law.C.mu_a_plus:.5f}", round(gl.source["elastic_contact"]["weight"], 4))
    0.18539 0.4771
    >>> gf.at(2e8)
    Traceback (most recent call last):
    ...
    asperity.errors.InputError: pressure 2e+08 Pa is outside the law family's pressures
    [1e+07, 1e+08] Pa: no extrapolation; refit the family with a wider --pressure range
    """

    pressures: tuple
    members: tuple

    def __post_init__(self):
        from ..errors import check_array, check_range
        raw = check_array("pressures", self.pressures, ndim=1, finite=False)
        ps = tuple(check_range("pressures", float(p), 0.0, None, low_open=True, unit="Pa")
                   for p in raw)
        if not isinstance(self.members, (list, tuple)):
            raise InputError(f"members must be a tuple of GaugeLaw, got "
                             f"{type(self.members).__name__}")
        ms = tuple(self.members)
        if not 1 <= len(ms) <= MAX_MEMBERS or len(ms) != len(ps):
            raise InputError(f"a family needs 1 to {MAX_MEMBERS} members, one a pressure, got "
                             f"{len(ms)} members for {len(ps)} pressures")
        for k in range(1, len(ps)):
            if not ps[k] > ps[k - 1]:
                raise InputError(f"pressures must be strictly increasing, got {ps[k]:g} Pa after "
                                 f"{ps[k - 1]:g} Pa")
        for k, m in enumerate(ms):
            if not isinstance(m, GaugeLaw):
                raise InputError(f"member {k} must be a GaugeLaw, got {type(m).__name__}")
            if not isinstance(m.source.get("elastic_contact"), dict):
                raise InputError(f"member {k} has no elastic contact figures (fit it with "
                                 "--elastic and --pressure)")
            why = contact_mismatch(m.source["elastic_contact"], ps[k],
                                   ms[0].source["elastic_contact"])
            if why:
                raise InputError(f"member {k}: {why}")
            if m.kind != ms[0].kind:
                raise InputError(f"member {k} is a {m.kind} law, member 0 a {ms[0].kind}: one "
                                 "kind a family")
            if _common(m.source) != _common(ms[0].source):
                raise InputError(f"member {k} was fitted to another source than member 0")
            u, u0 = _sides(m.data)[0], _sides(ms[0].data)[0]
            if u.shape != u0.shape or not np.allclose(u, u0, rtol=0.0, atol=1e-12):
                raise InputError(f"member {k} was fitted at other sliding directions than "
                                 "member 0")
        object.__setattr__(self, "pressures", ps)
        object.__setattr__(self, "members", ms)

    @property
    def kind(self) -> str:
        return self.members[0].kind

    @property
    def source(self) -> dict:
        """The members' common source (without their contact figures)."""
        return _common(self.members[0].source)

    def contact(self, k: int) -> dict:
        """Member k's elastic contact figures."""
        return self.members[k].source["elastic_contact"]

    @property
    def elastic(self) -> dict:
        """E*, boundary and hardness shared by the members."""
        c = self.contact(0)
        return {"E_star_Pa": c["E_star_Pa"], "boundary": c["boundary"],
                "hardness_Pa": c.get("hardness_Pa")}

    def bracket(self, pressure: float, name: str = "pressure") -> tuple[int, float]:
        """(k, w): the law at ``pressure`` lies between members k and k+1 at weight w in
        [0, 1) (w = 0: member k itself); InputError outside [first, last]."""
        from ..errors import check_range
        p = check_range(name, pressure, 0.0, None, low_open=True, unit="Pa")
        ps = self.pressures
        if not ps[0] <= p <= ps[-1]:
            rng = f"{ps[0]:g}" if len(ps) == 1 else f"[{ps[0]:g}, {ps[-1]:g}]"
            shown = f"{p:g}" if f"{p:g}" not in (f"{ps[0]:g}", f"{ps[-1]:g}") else repr(p)
            raise InputError(f"{name} {shown} Pa is outside the law family's pressures {rng} "
                             "Pa: no extrapolation; refit the family with a wider --pressure "
                             "range")
        if p in ps:
            return ps.index(p), 0.0
        k = int(np.searchsorted(ps, p, side="right")) - 1
        return k, math.log(p / ps[k]) / math.log(ps[k + 1] / ps[k])

    def at(self, pressure: float, name: str = "pressure") -> GaugeLaw:
        """The law at ``pressure`` (Pa), interpolated between the members around it (module
        docstring); ``name`` names the pressure in messages."""
        k, w = self.bracket(pressure, name)
        if w == 0.0:
            return self.members[k]
        try:
            return _interpolate(self.members[k], self.members[k + 1], w, pressure,
                                (self.pressures[k], self.pressures[k + 1]))
        except InputError as exc:
            raise InputError(f"{name} {pressure:g} Pa: the law interpolated between the members "
                             f"at {self.pressures[k]:g} and {self.pressures[k + 1]:g} Pa is not "
                             f"valid ({exc}); use a member's pressure or refit with more "
                             "pressures") from None


def _mix(a, b, w):
    return (1.0 - w) * a + w * b


def _interpolate(g0: GaugeLaw, g1: GaugeLaw, w: float, p: float, between) -> GaugeLaw:
    from .fitting import _quality, fit_star
    from .sets import TruncatedEllipse
    from .walker_leine import associated
    u, L0, R0 = _sides(g0.data)
    _, L1, R1 = _sides(g1.data)
    left, right = _mix(L0, L1, w), _mix(R0, R1, w)
    psi, pts, lim = [], [], []
    for j in range(u.size):
        if np.array_equal(left[j], right[j]):
            psi.append(u[j]); pts.append(left[j]); lim.append(0)
        else:
            psi += [u[j], u[j]]; pts += [left[j], right[j]]; lim += [-1, 1]
    data = ReservoirData(np.array(psi), np.array(pts), np.array(lim, dtype=np.int64))
    if g0.kind == "truncated-ellipse":
        e0, e1 = g0.law.C, g1.law.C
        a0 = [e0.mu_a_plus, e0.mu_a_minus, e0.mu_b_plus, e0.mu_b_minus]
        a1 = [e1.mu_a_plus, e1.mu_a_minus, e1.mu_b_plus, e1.mu_b_minus]
        turn = math.remainder(e1.theta - e0.theta, 2 * math.pi)
        if abs(turn) > 0.5 * math.pi:            # the same ellipse, t_a reversed
            a1 = [a1[1], a1[0], a1[3], a1[2]]
            turn = math.remainder(turn + math.pi, 2 * math.pi)
        theta = e0.theta + w * turn
        law = associated(TruncatedEllipse(*(_mix(x, y, w) for x, y in zip(a0, a1)),
                                          theta=theta))
        rep = _quality(law, data, {})
        direction = math.degrees(theta) % 360.0
    else:
        law, rep = fit_star(data)
        if not (rep.admissible and rep.D_convex):
            raise InputError("its D is not convex" if not rep.D_convex else
                             "it is not admissible (negative dissipation)")
        turn = math.remainder(g1.principal_direction_deg - g0.principal_direction_deg, 180.0)
        direction = (g0.principal_direction_deg + w * turn) % 180.0
    c0 = g0.source["elastic_contact"]
    contact = {"interpolated_at_Pa": float(p), "between_Pa": [float(x) for x in between],
               "weight": float(w), "E_star_Pa": c0["E_star_Pa"], "boundary": c0["boundary"],
               "hardness_Pa": c0.get("hardness_Pa")}
    return GaugeLaw(g0.kind, law, data, rep, {**_common(g0.source), "elastic_contact": contact},
                    float(direction))


def law_at(gauge, pressure, name: str = "--pressure", what: str = "the gauge file"):
    """(GaugeLaw, how) of a GaugeLaw or GaugeFamily at ``pressure`` (None for a single law):
    a family needs a pressure (one line refuses it without one); ``how`` is None for a
    single law, else {"pressure_Pa", "members_Pa", "interpolated"} for the text and JSON."""
    if not isinstance(gauge, GaugeFamily):
        return gauge, None
    if pressure is None:
        raise InputError(f"{what} holds a law family over the pressures "
                         f"{gauge.pressures[0]:g} to {gauge.pressures[-1]:g} Pa: give {name} "
                         "(the nominal contact pressure, Pa) to take the law at it")
    k, w = gauge.bracket(pressure, name)
    gl = gauge.at(pressure, name)
    return gl, {"pressure_Pa": float(pressure), "interpolated": w != 0.0,
                "members_Pa": [gauge.pressures[k]] if w == 0.0 else
                [gauge.pressures[k], gauge.pressures[k + 1]]}


def how_words(how: dict) -> str:
    """'the law family taken at p = ... Pa (interpolated between ... and ... Pa)'."""
    if how["interpolated"]:
        a, b = how["members_Pa"]
        return (f"law family taken at p = {how['pressure_Pa']:g} Pa (interpolated linearly "
                f"in ln p between its members at {a:g} and {b:g} Pa)")
    return f"law family taken at p = {how['pressure_Pa']:g} Pa (its member at that pressure)"
