"""Report sections built from the library APIs."""
from pathlib import Path

SURF = Path(__file__).resolve().parents[1] / "surfaces"


def test_report_section_tables_fits_and_figure7(tmp_path):
    from asperity.report.gauges import section
    src = tmp_path / "surfaces"
    src.mkdir()
    for name in ("wedge-symmetric-30", "self-locking"):
        (src / f"{name}.toml").write_text((SURF / f"{name}.toml").read_text())
    lines = section(tmp_path, surfaces=src)
    text = "\n".join(lines)
    rows = [x for x in lines if x.startswith("| wedge-symmetric-30 |")]
    assert len(rows) == 4                                   # 2 regimes x 2 laws
    assert "self-locks" in text
    for png in ("gauge_wedge-symmetric-30.png", "gauge_antoni_fig7.png"):
        assert f"]({png})" in text and (tmp_path / png).stat().st_size > 20_000
