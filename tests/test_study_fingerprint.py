"""A study never mixes results of two different inputs (issue 18, section 6): the store
records the SHA-256 of every file the study names, so that a gauge named by the assembly,
a texture (TOML or scan), the assembly itself or a scan of a file library rewritten since
-- even at the same size and time stamp -- is refused on resume, naming the file, by
``asperity study`` and by the Python API; ``--restart`` says what it discards, discards it
(in one transaction: an interrupted restart leaves the old store whole) and the rerun equals
a fresh run on the new inputs."""
from __future__ import annotations

import json
import os
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest
from cli_run import run
from x3p_files import x3p_bytes

from asperity import derive, fit_derivation, load_texture, write_gauge
from asperity.study import store as store_module
from asperity.study.run import run_study_file
from asperity.study.store import StoreError

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
GRID = '[parameters]\n"loading.dT_max" = { values = [60.0, 120.0] }\n'
OUT_COLS = "case_id, status, message, mu_plus, mu_minus, verdict, drift_per_cycle_m, " \
           "mu_a_plus, mu_a_minus, anisotropy"


def _assembly(friction: str, p: float = 5.0e6) -> str:
    text = (SURF / "bushing-strip.toml").read_text()
    before, after = text.split("[friction]")
    before = before.replace("p = 5.0e6", f"p = {p!r}")
    return before + f"[friction]\n{friction}\n" + after[after.index("[loading]"):]


def _scan(path: Path, bump: float = 0.0) -> None:
    """A 24 x 24 x3p scan of an asymmetric sawtooth (gentle rise, steep fall along x),
    stored uncompressed: ``bump`` changes one height, not the file's size."""
    saw = np.tile([0.0, 0.2, 0.4, 0.6, 0.8, 0.0], 4)[:, None] * 1e-6
    z = saw + 1e-10 * np.random.default_rng(3).normal(size=(24, 24))
    z[5, 7] += bump
    path.write_bytes(x3p_bytes(z, compress=False))


def _gauge(path: Path, texture: str) -> None:
    write_gauge(path, fit_derivation(derive(load_texture(SURF / texture))))


@pytest.fixture
def folder(tmp_path) -> Path:
    d = tmp_path / "in"
    d.mkdir()
    shutil.copyfile(SURF / "wedge-asymmetric.toml", d / "wedge.toml")
    _gauge(d / "g.json", "wedge-asymmetric.toml")
    _scan(d / "scan.x3p")
    (d / "asm-gauge.toml").write_text(_assembly('gauge = "g.json"'))
    (d / "asm-texture.toml").write_text(_assembly('texture = "wedge.toml"'))
    return d


def _rewrite_keeping_size_and_time(path: Path, write) -> None:
    st = path.stat()
    write()
    assert path.stat().st_size == st.st_size
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))


def _change(kind: str, d: Path) -> str:
    """Change the input of ``kind``; the file name the refusal must give."""
    if kind == "gauge named by the assembly":
        _gauge(d / "g.json", "wedge-symmetric-30.toml")
        return "g.json"
    if kind in ("texture named by the assembly", "study texture (TOML)"):
        t = d / "wedge.toml"
        t.write_text(t.read_text().replace("mu_alpha = 0.1", "mu_alpha = 0.12"))
        return "wedge.toml"
    if kind == "assembly":
        (d / "asm-texture.toml").write_text(_assembly('texture = "wedge.toml"', p=6.0e6))
        return "asm-texture.toml"
    _rewrite_keeping_size_and_time(d / "scan.x3p", lambda: _scan(d / "scan.x3p", 2e-7))
    return "scan.x3p"


STUDIES = {
    "gauge named by the assembly": '[study]\nkind = "grid"\nassembly = "asm-gauge.toml"\n' + GRID,
    "texture named by the assembly":
        '[study]\nkind = "grid"\nassembly = "asm-texture.toml"\n' + GRID,
    "study texture (TOML)":
        '[study]\nkind = "grid"\nassembly = "asm-gauge.toml"\ntexture = "wedge.toml"\n' + GRID,
    "study texture (scan, same size and time)":
        '[study]\nkind = "grid"\nassembly = "asm-gauge.toml"\ntexture = "scan.x3p"\n' + GRID,
    "assembly": '[study]\nkind = "grid"\nassembly = "asm-texture.toml"\n' + GRID,
    "scan of a file library (same size and time)":
        '[study]\nkind = "files"\nfiles = ["wedge.toml", "*.x3p"]\nstages = ["derive"]\n',
}


def _rows(out: Path) -> list[tuple]:
    con = sqlite3.connect(out / "study.sqlite")
    try:
        cols = {r[1] for r in con.execute("PRAGMA table_info(cases)")}
        fields = ", ".join(c for c in OUT_COLS.split(", ") if c in cols)
        return con.execute(f"SELECT {fields} FROM cases ORDER BY case_id").fetchall()
    finally:
        con.close()


def _study(d: Path, kind: str) -> Path:
    p = d / "s.toml"
    p.write_text(STUDIES[kind])
    return p


@pytest.mark.parametrize("kind", list(STUDIES))
def test_a_changed_input_is_refused_by_the_command_naming_it_and_restart_reruns(
        folder, tmp_path, capsys, kind):
    s, out = _study(folder, kind), tmp_path / "out"
    code, o, err = run(capsys, "study", s, "-o", out, "--workers", "0", "--json")
    assert code == 0, err
    n = json.loads(o)["stored"]
    old = _rows(out)
    assert n == len(old) and all(r[1] == "ok" for r in old), old
    name = _change(kind, folder)
    before = (out / "study.sqlite").read_bytes()
    code, o, err = run(capsys, "study", s, "-o", out, "--workers", "0")
    assert code == 1 and o == "" and err.count("\n") == 1, err
    assert f"{folder / name} changed since the study in {out} was started" in err, err
    assert f"--restart to discard the {n} stored cases" in err, err
    assert (out / "study.sqlite").read_bytes() == before
    # --restart says what it discards, runs every case again: a fresh run's results
    code, o, err = run(capsys, "study", s, "-o", out, "--workers", "0", "--restart")
    assert code == 0, err
    assert f"--restart: discarded the {n} cases stored in {out}" in o, o
    assert f"ran {n} cases" in o, o
    run_study_file(s, tmp_path / "fresh", workers=0)
    assert _rows(out) == _rows(tmp_path / "fresh") != old


@pytest.mark.parametrize("kind", list(STUDIES))
def test_a_changed_input_is_refused_by_the_python_api(folder, tmp_path, kind):
    s, out = _study(folder, kind), tmp_path / "out"
    run_study_file(s, out, workers=0)
    assert run_study_file(s, out, workers=0)["run"]["ran"] == 0       # unchanged: resumes
    name = _change(kind, folder)
    with pytest.raises(StoreError) as e:
        run_study_file(s, out, workers=0)
    assert f"{folder / name} changed since the study in {out} was started" in str(e.value)
    again = run_study_file(s, out, workers=0, restart=True)
    assert again["run"]["discarded"] == again["run"]["ran"] == again["stored"] > 0


def test_the_same_content_resumes_and_a_new_or_gone_scan_is_named(folder, tmp_path):
    s, out = _study(folder, "scan of a file library (same size and time)"), tmp_path / "out"
    run_study_file(s, out, workers=0)
    scan = folder / "scan.x3p"
    scan.write_bytes(scan.read_bytes())             # rewritten with the same bytes
    os.utime(scan, (1e9, 1e9))
    assert run_study_file(s, out, workers=0)["run"]["ran"] == 0
    shutil.copyfile(scan, folder / "more.x3p")
    with pytest.raises(StoreError, match="more.x3p is new since the study in"):
        run_study_file(s, out, workers=0)
    (folder / "more.x3p").unlink()
    (folder / "zz.x3p").write_bytes(scan.read_bytes())
    run_study_file(s, out, workers=0, restart=True)
    (folder / "zz.x3p").unlink()
    with pytest.raises(StoreError, match="zz.x3p is gone since the study in"):
        run_study_file(s, out, workers=0)


def test_a_changed_study_file_and_an_earlier_store_are_named_as_such(folder, tmp_path):
    s, out = _study(folder, "assembly"), tmp_path / "out"
    run_study_file(s, out, workers=0)
    s.write_text(s.read_text().replace("120.0", "110.0"))
    with pytest.raises(StoreError, match="holds a different study .the study file changed"):
        run_study_file(s, out, workers=0)
    run_study_file(s, out, workers=0, restart=True)
    con = sqlite3.connect(out / "study.sqlite")         # a store written before issue 18
    with con:
        con.execute("DELETE FROM meta WHERE key = 'input_digests'")
    con.close()
    with pytest.raises(StoreError, match="earlier asperity, which did not record"):
        run_study_file(s, out, workers=0)


class _Interrupted:
    """A connection that is interrupted (Ctrl-C) while the restart writes the new meta."""

    def __init__(self, con):
        self._con = con

    def __getattr__(self, name):
        return getattr(self._con, name)

    def executemany(self, sql, rows):
        if sql.startswith("INSERT INTO meta"):
            raise KeyboardInterrupt
        return self._con.executemany(sql, rows)


def test_an_interrupted_restart_leaves_the_old_store_whole(folder, tmp_path, monkeypatch):
    s, out = _study(folder, "gauge named by the assembly"), tmp_path / "out"
    run_study_file(s, out, workers=0)
    old = _rows(out)
    _change("gauge named by the assembly", folder)
    connect = store_module._connect
    monkeypatch.setattr(store_module, "_connect", lambda db: _Interrupted(connect(db)))
    with pytest.raises(KeyboardInterrupt):
        run_study_file(s, out, workers=0, restart=True)
    monkeypatch.undo()
    assert _rows(out) == old                           # not dropped, not mixed
    with pytest.raises(StoreError, match="g.json changed since"):
        run_study_file(s, out, workers=0)              # and still refused as before
    assert run_study_file(s, out, workers=0, restart=True)["run"]["ran"] == len(old)
