"""The documentation site's own directives (docs/_ext/asperity_docs.py), in small Sphinx
projects built here: a command shown on a page is the command's real output and the numbers
quoted from it are its numbers; a command that fails, a number that is not in the output, a
command without its reference or a public name without its API page fails a build with -W;
the generated reference gives every flag of every command."""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx", reason="the docs extra")

ROOT = Path(__file__).resolve().parents[1]
EXT = ROOT / "docs" / "_ext"

CONF = f"""
import sys
sys.path.insert(0, {str(EXT)!r})
extensions = ["asperity_docs"]
exclude_patterns = ["_build", "_run"]
"""


def build(tmp_path: Path, index: str, *, complete: bool = False,
          builder: str = "text") -> tuple[int, str, Path]:
    """Build a one-page project with -W; (status, warnings, output folder).
    ``complete``: check that every public name and command is documented."""
    src = tmp_path / "src"
    src.mkdir(exist_ok=True)
    (src / "conf.py").write_text(CONF + f"asperity_check_complete = {complete}\n")
    (src / "index.rst").write_text(index)
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q",
                           "-b", builder, str(src), str(out)], capture_output=True, text=True,
                          timeout=600, check=False)
    return proc.returncode, proc.stderr, out


def all_commands_page(skip: str | None = None) -> str:
    from asperity.cli.main import COMMANDS
    parts = ["Commands\n========\n"]
    for name in COMMANDS:
        if name != skip:
            parts.append(f"{name}\n{'-' * len(name)}\n\n.. asperity-command:: {name}\n")
    return "\n".join(parts)


def test_a_run_shows_the_output_and_quotes_its_numbers(tmp_path):
    page = """Risk
====

.. asperity-run::
   :name: r

   asperity risk surfaces/two-node-spec.toml --json

Drift per cycle :asperity-value:`r:drift_per_cycle_m:.6e` m, dT_c
:asperity-value:`r:dT_c_K:.3f` K, pressure :asperity-value:`r:loading.history_K.1` K.

.. asperity-run::
   :name: t

   asperity risk surfaces/two-node-spec.toml

Verdict word :asperity-value:`t:/^verdict: *(\\S+)/`.

.. asperity-run::
   :name: h
   :hide:

   asperity risk surfaces/two-node-spec.toml --tolerance 0.2 --json

Cycles to 0.2 mm: :asperity-value:`h:cycles_to_tolerance`.
"""
    status, warnings, out = build(tmp_path, page)
    assert status == 0, warnings
    text = (out / "index.txt").read_text()
    direct = subprocess.run([sys.executable, "-m", "asperity", "risk",
                             "surfaces/two-node-spec.toml", "--json"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout
    result = json.loads(direct)
    flat = " ".join(text.split())
    assert f"Drift per cycle {result['drift_per_cycle_m']:.6e} m" in flat
    assert f"dT_c {result['dT_c_K']:.3f} K" in flat
    assert f"pressure {result['loading']['history_K'][1]} K" in flat
    assert "$ asperity risk surfaces/two-node-spec.toml --json" in text
    assert f"Verdict word {result['verdict'].upper()}" in flat
    hidden = json.loads(subprocess.run(
        [sys.executable, "-m", "asperity", "risk", "surfaces/two-node-spec.toml", "--tolerance",
         "0.2", "--json"], cwd=ROOT, capture_output=True, text=True, check=True).stdout)
    assert f"Cycles to 0.2 mm: {hidden['cycles_to_tolerance']}." in flat
    assert "--tolerance 0.2" not in text                 # a hidden run shows nothing
    # a later run reads what an earlier one wrote: the page's commands share one folder
    assert (tmp_path / "src" / "_run" / "index" / "surfaces").is_symlink()


@pytest.mark.parametrize("page, complaint", [
    ("X\n=\n\n.. asperity-run::\n\n   asperity risk surfaces/no-such.toml\n", "exited with 1"),
    ("X\n=\n\n.. asperity-run::\n   :returncode: 1\n\n   asperity risk surfaces/two-node-spec.toml\n",
     "exited with 0, expected 1"),
    (("X\n=\n\n.. asperity-run::\n   :name: r\n\n   asperity risk surfaces/two-node-spec.toml"
     " --json\n\n:asperity-value:`r:verdict.no_such_key`\n"), "no_such_key"),
    ("X\n=\n\n:asperity-value:`r:verdict`\n", "no run named 'r' above"),
    (("X\n=\n\n.. asperity-run::\n   :name: r\n\n   asperity risk surfaces/two-node-spec.toml"
     "\n\n:asperity-value:`r:/no such text (\\d)/`\n"), "not in the output"),
    (("X\n=\n\n.. asperity-run::\n   :image: none.png\n\n   asperity risk "
     "surfaces/two-node-spec.toml\n"), "wrote no none.png"),
    ("X\n=\n\n.. asperity-command:: no-such-command\n", "no command 'no-such-command'"),
])
def test_what_a_page_gets_wrong_fails_the_build(tmp_path, page, complaint):
    status, warnings, _ = build(tmp_path, page)
    assert status != 0 and complaint in warnings, warnings


def test_a_refusal_shown_with_its_status(tmp_path):
    page = ("X\n=\n\n.. asperity-run::\n   :returncode: 1\n   :stderr:\n\n"
            "   asperity risk surfaces/two-node-spec.toml --tolerance -5\n")
    status, warnings, out = build(tmp_path, page)
    assert status == 0, warnings
    assert "error: --tolerance must be in [1e-06, 1e+06] mm, got -5" in (out / "index.txt").read_text()


def test_every_flag_of_every_command_in_the_reference(tmp_path):
    from asperity.cli.main import build_parser
    status, warnings, out = build(tmp_path, all_commands_page())
    assert status == 0, warnings
    text = (out / "index.txt").read_text()
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction))
    missing = [f"{name} {flag}" for name, parser in sub.choices.items()
               for action in parser._actions for flag in action.option_strings
               if flag not in text]
    assert not missing
    flat = " ".join(text.split())
    for name, parser in sub.choices.items():
        formatter = parser._get_formatter()
        for action in parser._actions:
            shown = formatter._expand_help(action) if action.help else ""
            if action.choices and not isinstance(action.choices, dict) and \
                    ", ".join(map(str, action.choices)) not in shown:
                assert "choices: " + ", ".join(map(str, action.choices)) in flat, \
                    (name, action.dest)
            if (action.option_strings and action.default not in (None, False, argparse.SUPPRESS)
                    and action.help not in (None, argparse.SUPPRESS)
                    and "default" not in shown.lower() and "%(default)" not in shown):
                assert f"(default: {action.default})" in flat or \
                    f"; default: {action.default})" in flat, (name, action.dest)
            if action.help not in (None, argparse.SUPPRESS) and action.option_strings:
                # each help text is there (whitespace as the text builder wraps it)
                assert " ".join(action.help.split()[:4]) in " ".join(text.split()), \
                    (name, action.option_strings)


def test_a_command_without_reference_and_names_without_api_page_fail(tmp_path):
    status, warnings, _ = build(tmp_path, all_commands_page(skip="crawl"), complete=True)
    assert status != 0
    assert "`asperity crawl` has no reference" in warnings
    import asperity
    for name in asperity.__all__:          # no API page here: every public name is missing
        missing = f"asperity.{name} is public (asperity.__all__) but no API page documents it"
        assert (missing in warnings) == (name != "__version__"), name
    assert "asperity risk` has no reference" not in warnings


def test_every_flag_has_its_anchor_in_html(tmp_path):
    """``commands.md#asperity-derive-json`` leads to the flag: an id per flag in the HTML."""
    from asperity.cli.main import build_parser
    status, warnings, out = build(tmp_path, "X\n=\n\n.. asperity-command:: derive\n\n"
                                  ".. asperity-command:: risk\n", builder="html")
    assert status == 0, warnings
    page = (out / "index.html").read_text()
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction))
    for name in ("derive", "risk"):
        for action in sub.choices[name]._actions:
            if action.option_strings:
                flag = max(action.option_strings, key=len).lstrip("-")
                assert f'id="asperity-{name}-{flag}"' in page, (name, flag)
