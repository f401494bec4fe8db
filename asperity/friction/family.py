"""A law family mu(psi; p): one derivation per nominal pressure of an elastic contact.

:func:`derive_family` derives the directional friction of a texture or height map at each
pressure of an :class:`~asperity.surface.contact_facets.ElasticContact` (the faces weighted
by the contact force, :mod:`asperity.friction.elastic`; each contact solve starts from the
previous pressure's), :func:`family_json` is the JSON object ``asperity derive --pressure
P1 P2 ... --json`` prints and :func:`family_text` its summary.  Each member is derived on
its own: its principal direction is found again (it may turn with the load); side by side
(the summary's rows, text and plot) their axis coefficients are turned to one reference
direction, the axial mean of the members' t_a (:func:`asperity.friction.axes.align_rows`),
while each member keeps its own t_a and its full derivation as found.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .. import __version__
from ..errors import InputError, check_int
from .axes import AXES, REFERENCE_WORDS, align_rows


@dataclass(frozen=True)
class LawFamily:
    """A law family's derivations: one a nominal pressure.

    Attributes
    ----------
    pressures : tuple of float
        The nominal pressures, Pa, as given.
    members : tuple of asperity.friction.derive.Derivation
        The derivation at each pressure.
    elastic : asperity.ElasticContact
        The elastic contact settings.
    """

    pressures: tuple
    members: tuple
    elastic: object


def derive_family(texture, elastic, contact: str = "all-faces", n_directions: int = 72,
                  progress=None) -> LawFamily:
    """A law family mu(psi; p): the derivation of a texture at every pressure of an elastic contact.

    At each nominal pressure the faces (facets) are weighted by the normal force they carry
    in the elastic contact (SPEC.md section 7; each contact solve starts from the previous
    pressure's solution), and derived by :func:`asperity.derive`.  Each member finds its
    principal direction again (it may turn with the load).

    Parameters
    ----------
    texture : HeightMap, WedgeTexture, GaussianWedgeTexture or list of FacetSurface
        A height map (:func:`asperity.read_surface`) or a wedge texture, or the
        contact-weighted surfaces, one a pressure, that :func:`asperity.load_elastic`
        returns for ``elastic``.
    elastic : ElasticContact
        The contact; its pressures (Pa) are the family's.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.
    n_directions : int, default 72
        Number of sliding directions of each member, in [8, 100000].
    progress : callable or None, default None
        ``progress(fraction)``, called during long facet computations.

    Returns
    -------
    LawFamily
        ``pressures`` (Pa, as given), ``members`` (the :func:`asperity.derive` result at
        each; ``member.texture.elastic`` holds the contact's figures) and ``elastic``.

    Raises
    ------
    asperity.InputError
        An option out of range, or a list that is not one contact-weighted surface a
        pressure.

    See Also
    --------
    asperity.derive, asperity.ElasticContact, asperity.load_elastic, asperity.GaugeFamily

    Examples
    --------
    The sawtooth of flank slopes 0.1 and 0.5 (mu = 0.15) pressed onto E* = 1 GPa: the
    contact spreads with the load, the friction stays near the area-weighted 0.15724:

    >>> saw = asperity.WedgeTexture(5.71059, 26.5651, 0.15, 0.15)
    >>> fam = asperity.derive_family(saw, asperity.ElasticContact(1e9, [1e7, 5e7]),
    ...                              n_directions=8)
    >>> for p, d in zip(fam.pressures, fam.members):
    ...     print(f"{p:g} Pa: contact {d.texture.elastic['area_fraction']:.4f}, "
    ...           f"mu_a+ {d.axes['mu_a_plus']:.5f}")
    1e+07 Pa: contact 0.1318, mu_a+ 0.15737
    5e+07 Pa: contact 0.5293, mu_a+ 0.15727
    """
    from ..surface.contact_facets import check_elastic
    from .derive import derive
    from .elastic import elastic_textures
    from .reservoir import check_contact, check_progress
    elastic = check_elastic(elastic)
    check_contact(contact)
    check_progress(progress)
    check_int("directions", n_directions, 8, 100_000)
    if isinstance(texture, (list, tuple)):
        textures = list(texture)
        if len(textures) != len(elastic.pressures) or any(
                getattr(t, "elastic", None) is None for t in textures):
            raise InputError(f"texture must be one contact-weighted surface a pressure "
                             f"({len(elastic.pressures)}), as load_elastic returns them")
    else:
        textures = elastic_textures(texture, elastic)
    members = tuple(derive(t, contact, "closed-form", n_directions, progress=progress)
                    for t in textures)
    return LawFamily(tuple(elastic.pressures), members, elastic)


def _num(x):
    return float(x) if math.isfinite(x) else None


def summary_rows(fam: LawFamily) -> tuple[list[dict], float]:
    """One row a pressure: the contact's area fraction, the axis coefficients along the
    common reference direction (``axes_reversed``: the member's own t_a points the other
    way, its + and - exchanged) and the member's own principal direction; and the
    reference direction (deg)."""
    rows = []
    for p, d in zip(fam.pressures, fam.members):
        c = d.texture.elastic
        rows.append({"pressure_Pa": p, "p_over_E_star": p / fam.elastic.E_star,
                     "area_fraction": c["area_fraction"], **dict(d.axes),
                     "principal_direction_deg": d.principal_direction_deg,
                     "self_locking": bool(d.self_locking)})
    ref = align_rows(rows)
    for r in rows:
        r.update({k: _num(r[k]) for k in AXES})
    return rows, ref


def family_json(fam: LawFamily) -> dict:
    """The JSON object of ``asperity derive --pressure P1 P2 ... --json`` (formats: outputs)."""
    from .derive import to_json
    e = fam.elastic
    c = fam.members[0].texture.elastic
    rows, ref = summary_rows(fam)
    return {"asperity_version": __version__, "family": "pressure",
            "pressures_Pa": list(fam.pressures), "E_star_Pa": e.E_star,
            "boundary": c["boundary"], "hardness_Pa": e.hardness,
            "reference_direction_deg": ref, "summary": rows,
            "members": [to_json(d) for d in fam.members]}


def family_text(fam: LawFamily) -> str:
    """The summary of a family: the contact's assumptions once, a row a pressure."""
    from ..surface.contact_facets import ASSUMPTIONS
    first = fam.members[0]
    tex = first.texture
    head = tex.describe() if hasattr(tex, "describe") else \
        f"texture: {tex.kind}  alpha={tex.alpha_deg:g} deg  beta={tex.beta_deg:g} deg  " \
        f"mu_alpha={tex.mu_alpha:g}  mu_beta={tex.mu_beta:g}"
    e = fam.elastic
    c = tex.elastic
    lines = [head, f"contact: {first.contact}   directions: {first.reservoir.psi.size}",
             f"law family over {len(fam.pressures)} pressures: E* = {e.E_star:.4g} Pa, "
             f"boundary {c['boundary']}, hardness "
             + ("none" if e.hardness is None else f"{e.hardness:.4g} Pa")]
    lines += ["  " + a for a in ASSUMPTIONS]
    lines += ["", "  p (Pa)      p/E*       contact    mu_a+      mu_a-      mu_b+      mu_b-"
                  "      t_a (deg)"]
    rows, ref = summary_rows(fam)
    for r in rows:
        mus = "".join(f"{'locked':<11}" if r[k] is None else f"{r[k]:<11.6f}" for k in AXES)
        lines.append(f"  {r['pressure_Pa']:<11.4g} {r['p_over_E_star']:<10.3g} "
                     f"{r['area_fraction']:<10.4f} {mus}{r['principal_direction_deg']:.2f}"
                     + ("  (turned)" if r["axes_reversed"] else ""))
    full = [p for p, d in zip(fam.pressures, fam.members)
            if d.texture.elastic["area_fraction"] >= 1.0]
    if full:
        lines.append("full contact at p = " + ", ".join(f"{p:g}" for p in full) + " Pa: the "
                     "whole surface carries load")
    locked = [p for p, d in zip(fam.pressures, fam.members) if d.self_locking]
    if locked:
        lines.append("SELF-LOCKING at p = " + ", ".join(f"{p:g}" for p in locked) + " Pa "
                     "in some directions: friction is unbounded there (see --json)")
    lines.append("(" + REFERENCE_WORDS.format(ref=ref) + "; t_a: each pressure's own)")
    return "\n".join(lines)


def plot_family(fam: LawFamily, path) -> None:
    """mu_a+/-, mu_b+/- (along the common reference direction) and the contact area
    fraction against p / E*."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    rows, ref = summary_rows(fam)
    x = [r["p_over_E_star"] for r in rows]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    for k, style in zip(AXES, ("-o", "--o", "-s", "--s")):
        ax.plot(x, [math.nan if r[k] is None else r[k] for r in rows], style, label=k)
    bx.plot(x, [r["area_fraction"] for r in rows], "-o", color="k")
    for a, label in ((ax, "friction coefficient"), (bx, "contact area fraction")):
        a.set_xscale("log")
        a.set_xlabel("p / E*")
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title(f"along t_a = {ref:.1f} deg (the members' axial mean)", fontsize=9)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
