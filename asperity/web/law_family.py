"""A law family on the Law page (a gauge file of version 2: one law per nominal pressure,
:mod:`asperity.laws.family`): fitted from a Surface result with several pressures
(:func:`fit_family`, what ``asperity fit ... --elastic E --pressure P1 P2 ...`` fits) or
opened from a file, and its outputs -- the gauge file, the CSV table with its pressure
column and the Abaqus blocks, one a member (the writers of ``asperity law``), the members'
reservoirs in one force plane coloured by pressure and the members' table."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .figures import _layout, _r
from .figures_contact import colour, pressure_label
from .results import rename
from .units import choose, show


def fit_family(members, pressures, law: str):
    """The GaugeFamily of the derivations ``members`` at ``pressures`` (any order: sorted
    by pressure here), one law of kind ``law`` each."""
    from ..errors import InputError
    from ..laws.family import GaugeFamily
    from ..laws.fitting import fit_derivation
    order = sorted(range(len(pressures)), key=lambda k: pressures[k])
    laws = []
    for k in order:
        try:
            laws.append(fit_derivation(members[k], law))
        except InputError as exc:
            raise InputError(f"the law at p = {pressures[k]:g} Pa: {exc}") from None
    return GaugeFamily(tuple(pressures[k] for k in order), tuple(laws))


def family_figure(fam) -> dict:
    """The reservoir C of every member in one force plane, coloured by pressure."""
    from ..laws.geometry import unit
    E = fam.elastic["E_star_Pa"]
    u = choose(list(fam.pressures), "Pa", smallest=True)
    phi = np.linspace(0.0, 2.0 * np.pi, 721)
    traces = []
    n = len(fam.members)
    for k, (p, gl) in enumerate(zip(fam.pressures, fam.members)):
        C = np.vstack([gl.law.C.points, gl.law.C.points[:1]]) if gl.kind == "star" else \
            gl.law.C.radial(phi)[:, None] * unit(phi)
        name = pressure_label(p, E, u)
        traces.append({"type": "scatter", "mode": "lines", "x": _r(C[:, 0]), "y": _r(C[:, 1]),
                       "name": name, "line": {"width": 2, "color": colour(k, n)},
                       "hovertemplate": f"{name}<br>p = (%{{x:.5f}}, %{{y:.5f}})"
                                        "<extra></extra>"})
    return {"data": traces, "layout": _layout(
        f"the reservoir C of each of the {n} {fam.kind} laws (hover a curve)", "p_x", "p_y",
        equal=True, legend={"orientation": "v", "x": 1.02, "y": 1.0})}


def family_rows(fam) -> list[dict]:
    """The members' table: pressure, contact fraction, mu_a+-, mu_b+-, t_a."""
    from ..laws.family_report import family_summary
    out = []
    for m in family_summary(fam)["members"]:
        out.append({"pressure_Pa": m["pressure_Pa"],
                    "p_over_E_star": m["pressure_Pa"] / m["contact"]["E_star_Pa"],
                    "area_fraction": m["contact"]["area_fraction"], **m["axes"],
                    "principal_direction_deg": m["principal_direction_deg"],
                    "max_radial_error": m["fit"]["max_radial_error"],
                    "admissible": m["fit"]["admissible"]})
    return out


def family_outputs(fam, ctx: dict, source: str, n_csv: int = 360) -> dict:
    """The gauge file (version 2), the CSV table (pressure_Pa column) and the Abaqus blocks
    of a family into the job folder (downloaded as ``<source>_family_<kind>``), and what the
    page shows of it."""
    from .. import write_gauge
    from ..io import write_text_atomic
    from ..laws.family import GaugeFamily
    from ..laws.family_report import family_abaqus, family_table, format_family
    from .labels import law_downloads
    folder = ctx["job_dir"]
    fam = GaugeFamily(fam.pressures, tuple(replace(m, source=rename(m.source, ctx["names"]))
                                           for m in fam.members))
    write_gauge(folder / "gauge.json", fam)
    write_text_atomic(folder / "law.csv", family_table(fam, n_csv))
    abaqus = family_abaqus(fam)
    write_text_atomic(folder / "law.inp", abaqus)
    return {"family": {"pressures_Pa": list(fam.pressures), "rows": family_rows(fam),
                       **fam.elastic},
            "kind": fam.kind, "report": format_family(fam), "abaqus": abaqus,
            "figures": {"family": family_figure(fam)},
            "files": ["gauge.json", "law.csv", "law.inp"],
            "downloads": law_downloads(f"{source}_family", fam.kind)}


def gauge_outputs(gauge, ctx: dict, source: str) -> dict | None:
    """:func:`family_outputs` of an opened gauge file when it holds a family, else None."""
    from ..laws.family import GaugeFamily
    if not isinstance(gauge, GaugeFamily):
        return None
    out = family_outputs(gauge, ctx, source)
    u = choose(list(gauge.pressures), "Pa", smallest=True)
    out["note"] = (f"a law family: {len(gauge.members)} {gauge.kind} laws, one a nominal "
                   f"pressure from {show(gauge.pressures[0], u)} to "
                   f"{show(gauge.pressures[-1], u)}; step 3 takes the law at the pressure "
                   "you give")
    return out
