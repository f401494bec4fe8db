"""Report sections built from the library APIs."""
from pathlib import Path

import pytest

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


def _row(lines, first: str) -> list[str]:
    return [c.strip() for c in next(x for x in lines if x.startswith(f"| {first} |"))
            .strip("|").split("|")]


@pytest.mark.slow
def test_elastic_contact_section_meets_its_closed_forms(tmp_path):
    """The section's numbers against tolerances: Hertz (free, 256^2) contact radius and
    peak pressure within 1 %, the load to 1e-10; Westergaard widths within 2 pixels and
    full contact at p > p*; ContactMechanics to 1e-5 when it is importable; the rounded
    ridge at light load at its crest's mu, the sawtooth's heavy load at the area's
    values; the contact fraction of every measured surface growing with the load."""
    import re

    from asperity.report import contact
    lines = contact.section(tmp_path)
    text = "\n".join(lines)
    assert lines[0] == "## Elastic contact"
    hz = next(x for x in lines if x.startswith("Hertz"))
    a_err, p_err = (float(v) for v in re.findall(r"error ([+-][0-9.]+) %", hz))
    assert abs(a_err) < 1.0 and abs(p_err) < 1.0, hz
    assert abs(float(re.search(r"load error ([-0-9.e+]+)", hz).group(1))) < 1e-10
    wg = [x for x in lines if re.match(r"\| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [+-]", x)]
    assert len(wg) == 8
    for r in wg:
        f, width, exact, err = (float(v) for v in r.strip("|").split("|"))
        assert abs(err) <= 2.0 and abs(width - exact) * 1024 == pytest.approx(abs(err),
                                                                               abs=0.2)
        assert (width == 1.0) == (f >= 1.0), r
    if "ContactMechanics comparison not run" not in text:
        for b in ("periodic", "free"):
            row = _row(lines, b)
            assert float(row[1]) < 1e-5 and abs(float(row[2])) < 1e-10, row
    else:                   # only where the package has no benchmarks/ or no ContactMechanics
        from importlib.util import find_spec
        peers = Path(contact.__file__).resolve().parents[2] / "benchmarks" / "contact_peers.py"
        assert not (peers.is_file() and find_spec("ContactMechanics")), text
    ridge = [x for x in lines if x.startswith("| rounded ridge |")]
    light, heavy, area = (_row([x], "rounded ridge") for x in (ridge[0], ridge[-2], ridge[-1]))
    assert light[1] == "0.0001" and area[1] == "area weighted"
    assert abs(float(light[3]) - 0.15) < 2e-4 and abs(float(light[4]) - 0.15) < 2e-4
    assert 0.15 < float(heavy[3]) < float(area[3]) and 0.15 < float(heavy[4]) < float(area[4])
    saw = [x for x in lines if x.startswith("| sawtooth |")]
    heavy, area = (_row([x], "sawtooth") for x in saw[-2:])
    assert abs(float(heavy[3]) - float(area[3])) < 1e-4
    assert abs(float(heavy[4]) - float(area[4])) < 1e-4
    for png in ("contact_validation.png", "contact_load_cases.png"):
        assert f"]({png})" in text and (tmp_path / png).stat().st_size > 20_000
    from asperity.report.measured import shared_surfaces
    if shared_surfaces().is_dir():
        for name, _ in contact.MEASURED:
            rows = [_row([x], name) for x in lines if x.startswith(f"| {name} |")]
            assert len(rows) == len(contact.MEASURED_RATIOS), name
            frac = [float(r[3]) for r in rows]
            assert all(0 < a < b <= 1 for a, b in zip(frac, frac[1:])), (name, frac)
        assert (tmp_path / "contact_measured.png").stat().st_size > 20_000
