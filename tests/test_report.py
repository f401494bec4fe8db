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


def test_every_section_is_a_module_with_a_section_function():
    import importlib

    from asperity.report import SECTIONS
    for name in SECTIONS:
        module = importlib.import_module(f"asperity.report.{name}")
        assert callable(module.section), name
        assert module.__doc__, name


def test_spec_section_states_the_check_values_and_run_numbers_sections(tmp_path, monkeypatch):
    import asperity.report as report
    from asperity.report import spec
    lines = spec.section(tmp_path)
    rows = [r for r in lines if r.startswith("| ") and "SPEC.md" not in r]
    assert len(rows) == 7
    for r in rows[:4]:                                  # the closed forms to 1e-6 (SPEC.md)
        quoted, got, diff = (float(x) for x in r.split("|")[2:5])
        assert abs(got - quoted) < 1e-6, r
        assert abs(diff) < 5e-7, r                      # SPEC's 6 decimals, unrounded: 4.3e-7
    monkeypatch.setattr(report, "SECTIONS", ("spec", "polar"))
    text = report.run(tmp_path).read_text()
    assert "## 1. SPEC.md check values" in text and "## 2. Polar reservoirs" in text
    assert (tmp_path / "polar_windward.png").stat().st_size > 10_000
