"""The READMEs as a user reads them: the Python API blocks run as written, in order, and
every command shown with shipped files runs through the real parser and exits with 0."""
from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from cli_run import run

from asperity.cli.main import COMMANDS

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
SURFACES_README = (ROOT / "surfaces" / "README.md").read_text(encoding="utf-8")


def blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", text, flags=re.S)


def commands() -> list[str]:
    """``asperity ...`` calls of both READMEs that name shipped files: each line of the bash
    blocks (its ``asperity`` parts, joined by ``&&``: a later one reads what an earlier one
    wrote; ``pip install -e . && asperity ...`` keeps the asperity part) and inline code."""
    found = []
    for block in blocks(README, "bash"):
        for line in block.splitlines():
            parts = [c.strip() for c in line.split("&&") if c.strip().startswith("asperity ")]
            if parts:
                found.append(" && ".join(parts))
    for text in (README, SURFACES_README):
        found += [c for c in re.findall(r"`(asperity [^`]+)`", text) if "surfaces/" in c]
    return list(dict.fromkeys(found))


@pytest.fixture
def in_project(tmp_path, monkeypatch):
    """A scratch working folder in which ``surfaces/`` is the shipped one."""
    (tmp_path / "surfaces").symlink_to(ROOT / "surfaces", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_python_api_blocks_run_as_written(in_project, capsys):
    code = blocks(README, "python")
    assert len(code) >= 5, "the Python API section shows one example per stage"
    namespace: dict = {}
    for block in code:
        exec(compile(block, "README.md", "exec"), namespace)   # noqa: S102
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "mu_a+ = 0.185697, mu_a- = 0.193238"           # SPEC.md check values
    assert out[1] == "t_a at 0.0 deg, mu_a+ = 0.185697"              # the mesh: same wedge
    assert out[2].startswith("max radial error") and (in_project / "wedge-star.json").is_file()
    assert re.match(r"rest at \(0\.\d+, 0\.\d+\) m after 0\.\d+ s, deflected [+-]\d", out[3])
    assert out[4].startswith("ratchet: 364 cycles to 0.1 mm") and "+0.27" in out[4]  # Set-up


def test_the_documented_commands_exist():
    cmds = commands()
    assert any(c.startswith("asperity risk") for c in cmds)
    assert any(c.startswith("asperity derive") for c in cmds)
    assert any(c.startswith("asperity fit") for c in cmds)


@pytest.mark.parametrize("line", commands())
def test_documented_command_runs(line, in_project, capsys):
    for command in line.split(" && "):
        argv = shlex.split(command)[1:]
        code, out, err = run(capsys, *argv)
        assert code == 0, f"{command}: {err}"
        assert out.strip(), command
        for flag in ("--plot", "-o", "--csv", "--abaqus"):
            if flag in argv and argv[argv.index(flag) + 1:][:1] != [] and \
                    not argv[argv.index(flag) + 1].startswith("-"):  # study --plot: no file
                assert (in_project / argv[argv.index(flag) + 1]).stat().st_size > 0, command


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_command_has_help(name, capsys):
    with pytest.raises(SystemExit) as exc:
        run(capsys, name, "--help")
    assert exc.value.code == 0
    assert "usage: asperity " + name in capsys.readouterr().out


def test_a_newcomer_reads_it_to_the_end():
    """Under 300 lines: the rest is in the documentation site (docs/)."""
    assert len(README.splitlines()) < 300


def test_ci_runs_the_tests_and_builds_the_site_as_the_readme_says():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    shown = [part.strip() for block in blocks(README, "bash") for line in block.splitlines()
             for part in line.split("&&")]
    tests = [c for c in shown if c.startswith("python -m pytest")]
    docs = [c for c in shown if c.startswith("python -m sphinx")]
    assert len(tests) == 1 and len(docs) == 1
    for command in tests + docs:
        assert any(line.strip() == command for line in ci.splitlines()), command
    assert "-W" in docs[0].split() and " docs " in f" {docs[0]} "
