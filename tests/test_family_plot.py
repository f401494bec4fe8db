"""The law family's figure: one reservoir per member, coloured along the colour map by
ln p from the first member (its start) to the last (its end), each labelled with its
pressure."""
from __future__ import annotations

import numpy as np
import pytest
from law_families import PRESSURES, four_members

from asperity import io
from asperity.laws.family import GaugeFamily
from asperity.laws.family_report import plot_family


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
    for ln, x in zip(lines, lp):
        want = cmap((x - lp[0]) / (lp[-1] - lp[0]))
        np.testing.assert_allclose(matplotlib.colors.to_rgba(ln.get_color()), want, atol=1e-12)
