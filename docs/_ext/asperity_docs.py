"""The documentation's own Sphinx directives, so that what the site shows cannot drift from
what the package does.

``.. asperity-command:: NAME``
    The reference of ``asperity NAME``, generated from its argparse parser: the description,
    the usage, every argument of every group (flags, value, help, default, choices), the exit
    statuses. A command of the package not documented this way anywhere fails the build.
``.. asperity-run::``
    Runs the command line of its content at build time and shows it with what it printed.
    ``asperity ...`` runs this checkout's package (``python -m asperity``); the commands of a
    page run in order in one scratch folder (``docs/_run/<page>/``, where ``surfaces/`` is the
    shipped folder), so a later command reads what an earlier one wrote. Options:
    ``:name:`` keeps the output for :rst:role:`asperity-value`; ``:returncode:`` the exit
    status expected (default 0; any other status fails the build); ``:stderr:`` shows the
    standard error too; ``:hide:`` runs without showing (for values only); ``:image:`` a
    file the command wrote, shown below it.
``:asperity-value:`NAME:KEY[:FORMAT]```
    A number of a run above in the same page: ``KEY`` a dotted path into its JSON output
    (``verdict.drift_per_cycle_m``, list items by index), formatted with ``FORMAT`` (Python's
    format spec, e.g. ``.4f``); or ``/REGEX/`` searched in its text output (group 1). So the
    numbers a tutorial's prose quotes are the numbers the command printed.

At the end of reading, every name of ``asperity.__all__`` must be documented (an API page
documents it) and every command must have its reference: each one missing is a warning,
which the build (``-W``) turns into a failure.
"""
from __future__ import annotations

import argparse
import functools
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path
from typing import ClassVar

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective, SphinxRole

ROOT = Path(__file__).resolve().parents[2]
RUN_DIR = "_run"
#: numpydoc's checks every public name passes (docs/conf.py's numpydoc_validation_checks;
#: tests/test_api_docs.py runs them too): a docstring, a summary line, every parameter
#: documented and none that does not exist, a Returns section where something is returned,
#: an Examples section
NUMPYDOC_CHECKS = ("GL08", "SS01", "PR01", "PR02", "RT01", "EX01")
logger = logging.getLogger(__name__)


@functools.cache
def _subparsers():
    """The commands' parsers (built once a build: every command's reference reads them)."""
    from asperity.cli.main import build_parser
    parser = build_parser()
    return next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))


def _text(action: argparse.Action, formatter) -> str:
    """An argument's help with its default and choices (when its help does not give them)."""
    text = formatter._expand_help(action) if action.help else ""
    extra = []
    if action.choices is not None and not isinstance(action.choices, dict):
        listed = ", ".join(str(c) for c in action.choices)
        if listed not in text:
            extra.append(f"choices: {listed}")
    default = action.default
    if (action.option_strings and default not in (None, False, argparse.SUPPRESS)
            and not isinstance(action, (argparse._HelpAction, argparse._VersionAction))
            and "default" not in text.lower()):
        extra.append(f"default: {default}")
    return text + ("" if not extra else (" (" + "; ".join(extra) + ")"))


class CommandReference(SphinxDirective):
    """``.. asperity-command:: NAME``: the generated reference of ``asperity NAME``."""

    required_arguments = 1

    def run(self):
        from asperity.cli.parsing import flag_of
        name = self.arguments[0]
        sub = _subparsers()
        if name not in sub.choices:
            raise self.error(f"asperity-command: no command {name!r} "
                             f"(commands: {', '.join(sub.choices)})")
        _commands(self.env).setdefault(self.env.docname, set()).add(name)
        parser = sub.choices[name]
        formatter = parser._get_formatter()
        out: list[nodes.Node] = []
        if parser.description:
            out.append(nodes.paragraph(text=parser.description))
        # argparse indents the usage's continuation lines under "usage: ": drop that prefix
        usage = "\n".join(line.removeprefix("usage: ").removeprefix(" " * len("usage: "))
                          for line in parser.format_usage().strip().splitlines())
        out.append(nodes.literal_block(usage, usage, language="text"))
        for group in parser._action_groups:
            actions = [a for a in group._group_actions if a.help != argparse.SUPPRESS]
            if not actions:
                continue
            out.append(nodes.rubric(text=group.title))
            if group.description:
                out.append(nodes.paragraph(text=group.description))
            dl = nodes.definition_list()
            for action in actions:
                invocation = formatter._format_action_invocation(action)
                flag = flag_of(action)
                item = nodes.definition_list_item()
                # the anchor (commands.md#asperity-derive-json) on the term: HTML keeps it there
                term = nodes.term(ids=[nodes.make_id(f"asperity-{name}-{flag.lstrip('-')}")])
                term += nodes.literal(invocation, invocation)
                item += term
                definition = nodes.definition()
                definition += nodes.paragraph(text=_text(action, formatter))
                item += definition
                dl += item
            out.append(dl)
        if parser.epilog:
            out.append(nodes.paragraph(text=parser.epilog))
        return out


def _run_folder(env) -> Path:
    """This page's scratch folder: made anew at the page's first run."""
    folder = env.temp_data.get("asperity_run_folder")
    if folder is None:
        folder = Path(env.srcdir) / RUN_DIR / env.docname.replace("/", "--")
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        (folder / "surfaces").symlink_to(ROOT / "surfaces", target_is_directory=True)
        env.temp_data["asperity_run_folder"] = folder
    return folder


class Run(SphinxDirective):
    """``.. asperity-run::`` with the command line as content."""

    has_content = True
    option_spec: ClassVar[dict] = {
        "name": directives.unchanged_required, "returncode": int, "stderr": directives.flag,
        "hide": directives.flag, "image": directives.unchanged_required, "timeout": int}

    def run(self):
        line = " ".join(part.rstrip("\\").strip() for part in self.content).strip()
        if not line:
            raise self.error("asperity-run: no command line")
        argv = shlex.split(line)
        if argv[0] == "asperity":
            argv = [sys.executable, "-m", "asperity", *argv[1:]]
        elif argv[0] == "python":
            argv = [sys.executable, *argv[1:]]
        folder = _run_folder(self.env)
        env = dict(os.environ, MPLBACKEND="Agg", COLUMNS="100",
                   PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
        try:
            proc = subprocess.run(argv, check=False, cwd=folder, env=env, capture_output=True,
                                  text=True, timeout=self.options.get("timeout", 600))
        except subprocess.TimeoutExpired:
            raise self.error(f"asperity-run: `{line}` did not finish in time") from None
        expected = self.options.get("returncode", 0)
        if proc.returncode != expected:
            raise self.error(f"asperity-run: `{line}` exited with {proc.returncode}, expected "
                             f"{expected}:\n{proc.stdout[-1500:]}{proc.stderr[-1500:]}")
        if "name" in self.options:
            self.env.temp_data.setdefault("asperity_runs", {})[self.options["name"]] = \
                proc.stdout
        if "hide" in self.options:
            return []
        shown = f"$ {line}\n{proc.stdout}"
        if "stderr" in self.options and proc.stderr:
            shown += proc.stderr
        out: list[nodes.Node] = [nodes.literal_block(shown.rstrip(), shown.rstrip(),
                                                     language="text")]
        if "image" in self.options:
            path = folder / self.options["image"]
            if not path.is_file():
                raise self.error(f"asperity-run: `{line}` wrote no {self.options['image']}")
            uri = "/" + path.relative_to(self.env.srcdir).as_posix()
            out.append(nodes.image(uri=uri, alt=f"what `{line}` drew"))
        return out


def _lookup(data, key: str):
    for part in key.split("."):
        data = data[int(part)] if isinstance(data, list) else data[part]
    return data


class Value(SphinxRole):
    """``:asperity-value:`NAME:KEY[:FORMAT]``` or ``:asperity-value:`NAME:/REGEX/```."""

    def run(self):
        # the text as typed (rst would drop a regex's backslashes)
        typed = self.rawtext[self.rawtext.index("`") + 1:self.rawtext.rindex("`")]
        name, _, rest = typed.partition(":")
        output = self.env.temp_data.get("asperity_runs", {}).get(name)
        try:
            if output is None:
                raise LookupError(f"no run named {name!r} above in this page")
            if rest.startswith("/"):
                found = re.search(rest[1:rest.rindex("/")], output, flags=re.MULTILINE)
                if found is None:
                    raise LookupError(f"{rest} not in the output of {name!r}")
                value = found.group(1)
            else:
                key, _, spec = rest.partition(":")
                value = format(_lookup(json.loads(output), key), spec)
        except (LookupError, ValueError, TypeError) as exc:
            msg = self.inliner.reporter.error(f"asperity-value `{self.text}`: {exc}",
                                              line=self.lineno)
            return [self.inliner.problematic(self.rawtext, self.rawtext, msg)], [msg]
        return [nodes.Text(value)], []


def _commands(env) -> dict:
    """Page -> the commands whose reference it gives (kept with the environment)."""
    if not hasattr(env, "asperity_commands"):
        env.asperity_commands = {}
    return env.asperity_commands


def _purge(app, env, docname):
    _commands(env).pop(docname, None)


def _merge(app, env, docnames, other):
    _commands(env).update(_commands(other))


def _check_complete(app, env):
    """Every public name and every command documented (a warning each otherwise; config
    ``asperity_check_complete = False`` for a site that is not the package's)."""
    if not app.config.asperity_check_complete:
        return
    import asperity
    from asperity.cli.main import COMMANDS
    objects = env.get_domain("py").objects
    for name in asperity.__all__:
        if name != "__version__" and f"asperity.{name}" not in objects:
            logger.warning(f"asperity.{name} is public (asperity.__all__) but no API page "
                           f"documents it", type="asperity", subtype="undocumented")
    documented = set().union(*_commands(env).values())
    for name in COMMANDS:
        if name not in documented:
            logger.warning(f"`asperity {name}` has no reference (.. asperity-command:: {name})",
                           type="asperity", subtype="undocumented")


def setup(app):
    app.add_config_value("asperity_check_complete", True, "env")
    app.add_directive("asperity-command", CommandReference)
    app.add_directive("asperity-run", Run)
    app.add_role("asperity-value", Value())
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.connect("env-check-consistency", _check_complete)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True,
            "env_version": 1}
