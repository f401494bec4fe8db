"""What a law family is, in numbers, words and pictures, and its exports: the JSON and text
of ``asperity fit --pressure P1 P2 ...`` and ``asperity law FAMILY.json``, the members'
gauges in one polar plot coloured by pressure, the CSV table and the Abaqus blocks of each
member."""
from __future__ import annotations

import math

import numpy as np

from .family import INTERPOLATION, GaugeFamily

#: the axis coefficients of a member, in the order of the text's table
AXES = ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus")


def member_axes(gl) -> dict:
    """The law's tangential friction along +-t_a, +-t_b (its principal frame)."""
    theta = math.radians(gl.principal_direction_deg)
    t = gl.force(theta + np.array([0.0, math.pi, 0.5 * math.pi, 1.5 * math.pi])).tangential
    return dict(zip(AXES, map(float, t)))


def family_summary(fam: GaugeFamily) -> dict:
    """JSON summary of a family: the shared source and contact options, and per member its
    pressure, axis coefficients, fit figures and contact figures."""
    from .summary import summary
    members = []
    for k, (p, gl) in enumerate(zip(fam.pressures, fam.members)):
        s = summary(gl)
        s.pop("source")
        members.append({"pressure_Pa": p, **s, "axes": member_axes(gl),
                        "contact": fam.contact(k)})
    return {"law": fam.kind, "family": {"axis": "pressure_Pa", "pressures_Pa":
                                        list(fam.pressures), "interpolation": INTERPOLATION,
                                        **fam.elastic},
            "source": fam.source, "members": members}


def format_family(fam: GaugeFamily) -> str:
    """The family for the terminal: one row a member."""
    from .export import source_words
    e = fam.elastic
    H = e["hardness_Pa"]
    lines = [f"law family: {len(fam.members)} {fam.kind} laws fitted to "
             f"{source_words(fam.source)}",
             f"elastic contact: E* = {e['E_star_Pa']:.4g} Pa, boundary {e['boundary']}, "
             "hardness " + ("none" if H is None else f"{H:.4g} Pa"),
             "",
             "  p (Pa)      p/E*       contact    mu_a+      mu_a-      mu_b+      mu_b-"
             "      t_a (deg)  max radial err  admissible"]
    for k, (p, gl) in enumerate(zip(fam.pressures, fam.members)):
        c = fam.contact(k)
        ax = member_axes(gl)
        lines.append(f"  {p:<11.4g} {p / e['E_star_Pa']:<10.3g} {c['area_fraction']:<10.4f} "
                     + "".join(f"{ax[a]:<11.6f}" for a in AXES)
                     + f"{gl.principal_direction_deg:<10.2f} {gl.fit.max_radial_error:<15.3e} "
                     + ("yes" if gl.fit.admissible else "NO"))
    lines += ["(mu_a+/-: the law's friction along and against its t_a; mu_b+/-: at +/-90 deg)",
              "between members: " + INTERPOLATION,
              "load shares: the normal force of a frictionless elastic contact at each "
              "pressure (the facet law unchanged); not right where the pressure reaches the "
              "hardness nor where sliding redistributes the load"]
    return "\n".join(lines)


def plot_family(fam: GaugeFamily, path) -> None:
    """The members' reservoirs C in one polar plot (force plane), coloured by ln p."""
    from ..io import pyplot, save_figure_atomic
    from .geometry import unit
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.8, 6))
    cmap = plt.get_cmap("viridis")
    lp = np.log(np.asarray(fam.pressures))
    span = float(lp[-1] - lp[0]) or 1.0
    phi = np.linspace(0.0, 2.0 * np.pi, 1441)
    for p, gl, x in zip(fam.pressures, fam.members, lp):
        C = np.vstack([gl.law.C.points, gl.law.C.points[:1]]) if gl.kind == "star" else \
            gl.law.C.radial(phi)[:, None] * unit(phi)
        ax.plot(C[:, 0], C[:, 1], color=cmap((x - lp[0]) / span), lw=1.6,
                label=f"p = {p:.3g} Pa")
    ax.axhline(0, color="0.8", lw=0.5)
    ax.axvline(0, color="0.8", lw=0.5)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("p_x (force / normal load)")
    ax.set_ylabel("p_y")
    ax.set_title(f"{fam.kind} law family, E* = {fam.elastic['E_star_Pa']:.3g} Pa: the "
                 "reservoir C at each pressure", fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.2)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def family_table(fam: GaugeFamily, n: int = 360) -> str:
    """CSV ``pressure_Pa,psi_deg,p_a,p_b``: each member's polar table (as
    :func:`~asperity.laws.export.polar_table`, its own principal frame), member after
    member."""
    from .export import polar_table
    rows = ["pressure_Pa,psi_deg,p_a,p_b"]
    for p, gl in zip(fam.pressures, fam.members):
        rows += [f"{p!r},{line}" for line in polar_table(gl, n).splitlines()[1:]]
    return "\n".join(rows) + "\n"


def family_abaqus(fam: GaugeFamily) -> str:
    """One ``*FRICTION, ANISOTROPIC`` block a member, each preceded by a comment line with
    its pressure: Abaqus takes one block a contact property, so pick the member at the
    contact pressure (or export the law at a pressure: ``asperity law --pressure P``)."""
    from .. import __version__
    from .export import abaqus_block
    out = [f"** asperity {__version__}: a law family over {len(fam.members)} nominal contact "
           f"pressures; ONE BLOCK A MEMBER: use the block of the member at your contact "
           f"pressure in its own *SURFACE INTERACTION, or export the law interpolated at a "
           f"pressure with `asperity law FAMILY.json --pressure P --abaqus FILE.inp`"]
    for k, (p, gl) in enumerate(zip(fam.pressures, fam.members)):
        out.append(f"** member {k}: nominal contact pressure {p:.6g} Pa (contact area "
                   f"fraction {fam.contact(k)['area_fraction']:.4g})")
        out.append(abaqus_block(gl).rstrip("\n"))
    return "\n".join(out) + "\n"
