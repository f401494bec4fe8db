"""The law family's report: the figure draws each member's reservoir, coloured along the
colour map by ln p from the first member (its start) to the last (its end) and labelled
with its pressure; the table marks "(turned)" exactly the members read along the common
axis the other way round."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from law_families import PRESSURES, four_members

from asperity import io
from asperity.laws.family import GaugeFamily
from asperity.laws.family_report import common_axes, format_family, plot_family


@pytest.mark.parametrize("n", [2, 4])
def test_members_coloured_by_log_pressure_first_to_last(monkeypatch, tmp_path, n):
    import matplotlib
    figs = []
    monkeypatch.setattr(io, "save_figure_atomic", lambda fig, path, **kw: figs.append(fig))
    family = four_members()
    fam = GaugeFamily(family.pressures[:n], family.members[:n])
    plot_family(fam, tmp_path / "f.png")
    (fig,) = figs
    lines = [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("p = ")]
    assert [ln.get_label() for ln in lines] == [f"p = {p:.3g} Pa" for p in PRESSURES[:n]]
    cmap = matplotlib.colormaps["viridis"]
    lp = np.log(PRESSURES[:n])
    for ln, x, gl in zip(lines, lp, fam.members):
        want = cmap((x - lp[0]) / (lp[-1] - lp[0]))
        np.testing.assert_allclose(matplotlib.colors.to_rgba(ln.get_color()), want, atol=1e-12)
        C = gl.law.C.points
        np.testing.assert_allclose(ln.get_xydata(), np.vstack([C, C[:1]]), rtol=1e-12)


@pytest.mark.parametrize("directions", [(10, 170, 100, 20), (5, 178, 90, 350)])
def test_turned_marks_exactly_the_members_read_the_other_way(directions):
    f = four_members()
    fam = GaugeFamily(f.pressures, tuple(replace(gl, principal_direction_deg=d)
                                         for gl, d in zip(f.members, directions)))
    axes, _ = common_axes(fam)
    reversed_ = [a["axes_reversed"] for a in axes]
    assert any(reversed_) and not all(reversed_)
    rows = [ln for ln in format_family(fam).splitlines() if ln.startswith("  ")
            and ln.split()[0][0].isdigit()]
    assert len(rows) == 4
    assert [row.endswith("(turned)") for row in rows] == reversed_
