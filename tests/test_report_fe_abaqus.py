"""The report's FE section (asperity.report.fe_abaqus): its numbers meet the issue's bounds
(table and steady sliding within 1e-4 of the law, tangents to differences, the two-node
drift through FRIC to 1e-6 of alpha_T l0 dT) and its figure is written."""
from __future__ import annotations

import re

from fe_builds import needs_gfortran

pytestmark = needs_gfortran


def test_fe_abaqus_section(tmp_path):
    from asperity.report import fe_abaqus
    lines = fe_abaqus.section(tmp_path)
    rows = [ln for ln in lines if ln.startswith("| ") and "nodes" not in ln]
    assert len(rows) == 4
    for row in rows:
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert int(cells[1]) >= 360
        table, gen, steady, tangent = (float(c) for c in cells[2:6])
        assert table < 1e-4 and steady < 1e-4 and tangent < 1e-6 and gen < 1.0
    assert (tmp_path / "fe_fric_polar.png").stat().st_size > 10_000
    text = "\n".join(lines)
    m = re.search(r"drift per cycle (\S+) m, closed form (\S+) m, difference (\S+) of", text)
    drift, want, diff = (float(x) for x in m.groups())
    assert drift > 0 and abs(drift - want) <= 1e-6 * abs(want) * 3 and diff <= 1e-6
