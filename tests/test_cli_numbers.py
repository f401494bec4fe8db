"""Every numeric flag of every command takes a number in any form, a minus sign and an
exponent included (``--force -1e-1 0``, ``--elastic -1e9``: argparse alone took them for
unknown options), then checks its range in one line; and one exit-status rule for every
command: 1 for a bad value (argparse's type and choice errors included), 2 for a command
line that cannot be parsed (README, "Errors").

The flags are enumerated from the parsers, so a new flag is covered (and a new text flag
must be named in :data:`TEXT_FLAGS`)."""
from __future__ import annotations

import argparse
import math
import re
from pathlib import Path

import pytest
from cli_run import run
from hostile import assert_refused, cli

from asperity.cli.main import COMMANDS, EPILOG, build_parser
from asperity.cli.parsing import value_options
from asperity.errors import InputError

SURF = Path(__file__).resolve().parents[1] / "surfaces"
WEDGE = SURF / "wedge-asymmetric.toml"
#: flags that take text (paths, names, addresses), not numbers
TEXT_FLAGS = {"--friction-map", "--unit", "--plot", "--output", "--csv", "--abaqus", "--out",
              "--scan-dir", "--body", "--scheduler", "--map", "--export", "--host",
              "--data-dir", "--save-pressure", "--gait", "--optimise", "--bounds",
              "--fric", "--vfric", "--vfriction", "--abaqus-user", "--gwfl", "--fe"}
#: flags typed as text whose value is a number (checked by the command: whole_flag)
NUMERIC_METAVARS = {"N", "K", "W", "S", "STEPS"}
PARSER = build_parser()
OPTIONS = [(cmd, p, a) for cmd, p, a in value_options(PARSER)]


def flag(action) -> str:
    return max(action.option_strings, key=len)


def n_values(action) -> int:
    return action.nargs if isinstance(action.nargs, int) else 1


def numeric(action) -> bool:
    return action.choices is None and flag(action) not in TEXT_FLAGS


def test_every_flag_is_numeric_text_or_a_choice():
    """A new flag must be classified: typed float/int, a number typed as text (a numeric
    metavar), a choice, or named in TEXT_FLAGS."""
    for cmd, _, a in OPTIONS:
        if a.choices is not None or flag(a) in TEXT_FLAGS:
            continue
        assert a.type in (float, int) or a.metavar in NUMERIC_METAVARS, (cmd, flag(a))


def _required_argv(p: argparse.ArgumentParser, skip) -> list[str]:
    """The least argv the parser accepts besides ``skip``: its required positionals and
    flags (one of each required exclusive group)."""
    argv = []
    for a in p._actions:
        if a is skip or a.nargs == 0:
            continue
        if not a.option_strings and a.required and a.nargs not in ("?", "*"):
            argv.append("x")
    taken = set()
    for g in p._mutually_exclusive_groups:
        if g.required:
            if any(a is skip for a in g._group_actions):
                taken |= set(g._group_actions)
                continue
            a = g._group_actions[0]
            taken |= set(g._group_actions)
            argv += [a.option_strings[0], *["1"] * n_values(a)]
    for a in p._actions:
        if a.option_strings and a.required and a is not skip and a not in taken:
            argv += [a.option_strings[0], *["1"] * n_values(a)]
    return argv


@pytest.mark.parametrize("text", ["-1e-1", "-1E9", "-.5", "-5.", "-1e+308", "-inf", "-nan"])
def test_every_option_takes_a_negative_number_as_its_value(text):
    """Parsed, not refused as an unknown option (the command checks the range later)."""
    for cmd, p, a in OPTIONS:
        if a.choices is not None:
            continue
        argv = [cmd, *_required_argv(p, a), a.option_strings[0], *[text] * n_values(a)]
        try:
            ns = PARSER.parse_args(argv)
        except InputError as exc:                  # taken, and not a whole number
            assert a.type is int and f"{flag(a)} must be a whole number" in str(exc), exc
            continue
        got = getattr(ns, a.dest)
        values = got if isinstance(got, list) else [got]
        assert len(values) == n_values(a), (cmd, flag(a), got)
        for v in values:
            if isinstance(v, str):
                assert v == text, (cmd, flag(a), v)
            elif a.type is float:
                assert v == float(text) or (math.isnan(v) and "nan" in text), (cmd, flag(a), v)


def test_a_negative_number_after_a_positional_is_still_a_value():
    ns = PARSER.parse_args(["slide", "--mu1", "0.3", "--u0", "1", "--angle", "-1e1", "--body",
                            "disc", "--force", "-1e-1", "0", "--t-end", "1"])
    assert ns.angle == -10.0 and ns.force == [-0.1, 0.0]


@pytest.fixture(scope="module")
def gauge(tmp_path_factory):
    g = tmp_path_factory.mktemp("g") / "star.json"
    code, _, err = cli("fit", WEDGE, "--directions", "72", "-o", g)
    assert code == 0, err
    return g


def _base(cmd: str, action, gauge: Path, tmp: Path) -> list:
    """A cheap argv of ``cmd`` that runs without the flag under test."""
    f = flag(action)
    if cmd in ("derive", "fit"):
        if f in ("--mu", "--pixel-size", "--height-scale", "--max-slope", "--despike",
                 "--despike-window", "--rest-level", "--bearing-fraction", "--grid-step",
                 "--tile-rows", "--window", "--windows", "--window-seed", "--workers"):
            return [SURF / "scan-ridges.txt", "--unit", "um", "--pixel-size", "1",
                    "--directions", "16"]
        return ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2",
                "--directions", "16"]
    if cmd == "contact":
        if f == "--materials":
            return [SURF / "scan-ridges.txt", "--unit", "um", "--pixel-size", "1",
                    "--pressure", "1e6"]
        if f in ("--alpha", "--beta", "--mu-alpha", "--mu-beta", "--height"):
            return ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2",
                    "--elastic", "1e9", "--pressure", "1e6"]
        return [SURF / "scan-ridges.txt", "--unit", "um", "--pixel-size", "1", "--elastic",
                "1e9", "--pressure", "1e6"]
    if cmd == "law":
        return [gauge]
    if cmd == "slide":
        point = ["--mu1", "0.3", "--u0", "0.05", "--angle", "30", "--dt", "1e-3"]
        if f in ("--pressure",):
            return [gauge, "--u0", "0.05", "--angle", "30"]
        body = {"--" + d.replace("_", "-") for d, _ in __import__(
            "asperity.cli.slide", fromlist=["BODY_OPTIONS"]).BODY_OPTIONS}
        if f in body | {"--t-end"}:
            return [*point, "--body", "disc", "--radius", "0.05", "--contact-points", "8"]
        return point
    if cmd == "risk":
        return [WEDGE, SURF / "two-node-spec.toml"]
    if cmd == "study":
        return [tmp / "none.toml"]
    if cmd == "crawl":
        run = ["--quasi-static", "--points", "8", "--dt", "0.05"]
        if f == "--pressure":
            return [gauge, *run]
        if f in ("--alpha", "--beta", "--mu-alpha", "--mu-beta", "--height"):
            return ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2",
                    *run]
        if f in ("--mu", "--pixel-size", "--height-scale", "--max-slope", "--despike",
                 "--despike-window", "--rest-level", "--bearing-fraction"):
            return [SURF / "scan-ridges.txt", "--unit", "um", "--pixel-size", "1", *run]
        mus = [x for m, v in (("--mu-f", "0.1"), ("--mu-b", "0.15"), ("--mu-t", "0.2"))
               if m != f for x in (m, v)]
        mode = ["--periods", "1"] if f == "--gravity" else ["--quasi-static"]
        return [*mus, *mode, "--points", "8", *([] if f == "--dt" else ["--dt", "0.05"])]
    return []


@pytest.mark.parametrize("cmd", sorted(COMMANDS))
def test_every_numeric_flag_checks_a_negative_value_in_one_line(cmd, gauge, tmp_path,
                                                                 capsys, monkeypatch):
    """``FLAG -1e-1`` (and ``-1e308``) reaches the command: a result (0) where a negative
    value is allowed, else one line naming the flag (1) -- never 'expected one argument'
    (2), never a traceback."""
    monkeypatch.chdir(tmp_path)
    seen = 0
    for c, _, a in OPTIONS:
        if c != cmd or not numeric(a):
            continue
        for text in ("-1e-1", "-1e308"):
            argv = [cmd, *_base(cmd, a, gauge, tmp_path), a.option_strings[0],
                    *[text] * n_values(a)]
            code, out, err = run(capsys, *argv)
            assert code in (0, 1), (argv, code, err)
            if code == 1:
                assert err.count("\n") == 1 and flag(a) in err, (argv, err)
            else:
                assert "nan" not in out.lower(), (argv, out)
            seen += 1
    assert seen or cmd == "report"


@pytest.mark.parametrize("cmd", sorted(COMMANDS))
def test_every_whole_number_flag_refuses_a_fraction_with_its_range(cmd, gauge, tmp_path,
                                                                     capsys, monkeypatch):
    """``FLAG 2.5`` of a whole-number flag: one line naming the flag and its range (the
    parser said 'must be a whole number' without it: '--max-iterations 2.5')."""
    monkeypatch.chdir(tmp_path)
    for c, _, a in OPTIONS:
        if c != cmd or a.type is not int:
            continue
        for text in ("2.5", "1e400", "nan"):
            argv = [cmd, *_base(cmd, a, gauge, tmp_path), a.option_strings[0],
                    *[text] * n_values(a)]
            if flag(a) == "--despike-window":
                argv += ["--despike", "6"]
                if cmd == "risk":
                    argv[1:3] = [SURF / "scan-ridges.txt", SURF / "two-node-spec.toml"]
            if flag(a) in ("--n-springs", "--steps-per-period"):
                argv += ["--method", "springs"]
            code, out, err = run(capsys, *argv)
            assert code == 1 and out == "" and err.count("\n") == 1, (argv, code, err)
            assert re.search(re.escape(flag(a)) + r" must be an? (odd )?whole number in \[",
                             err), (argv, err)


@pytest.mark.parametrize("argv,msg", [
    (["slide", "--mu1", "0.3", "--u0", "1", "--angle", "40", "--body", "disc", "--radius",
      "0.05", "--force", "-1e-1", "0"], "--force, --torque and --force-amplitude need --t-end"),
    (["contact", SURF / "scan-ridges.txt", "--unit", "um", "--pixel-size", "1", "--elastic",
      "-1e9", "--pressure", "1e6"], "--elastic must be in [1, 1e+13] Pa, got -1e+09"),
    (["derive", WEDGE, "--elastic", "-1e9", "--pressure", "1e6"], "--elastic must be"),
    (["slide", "--mu1", "0.3", "--u0", "-1e-3", "--angle", "0"],
     "--u0 must be in [0, 10000] m/s, got -0.001"),
    (["slide", "--mu1", "0.3", "--u0", "1", "--angle", "0", "--dt", "-1e-4"], "--dt must be"),
    (["derive", WEDGE, "--directions", "-1e3"], "--directions must be"),
])
def test_the_issues_cases_reach_the_range_check(argv, msg):
    assert_refused(cli(*argv), code=1, contains=msg)


# --------------------------------------------------------------------------- exit status

@pytest.mark.parametrize("cmd", sorted(COMMANDS))
def test_one_exit_status_rule_for_every_command(cmd, capsys):
    """1: a value argparse cannot convert or that is not a choice (one line naming the
    flag); 2: an unknown flag, a flag without its value (one line); the rule is in --help."""
    p = PARSER._subparsers._group_actions[0].choices[cmd]
    opts = [a for c, _, a in OPTIONS if c == cmd]
    with pytest.raises(SystemExit) as e:
        run(capsys, cmd, *_required_argv(p, None), "--no-such-flag")
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1 and "--no-such-flag" in err, err
    if opts:
        with pytest.raises(SystemExit) as e:
            run(capsys, cmd, opts[-1].option_strings[0])      # without its value
        err = capsys.readouterr().err
        assert e.value.code == 2 and err.count("\n") == 1 and "expected" in err, err
    for a in opts:
        if a.type in (float, int):
            code, out, err = run(capsys, cmd, a.option_strings[0], *["abc"] * n_values(a))
            assert code == 1 and out == "" and err.count("\n") == 1, (cmd, flag(a), err)
            assert f"asperity {cmd}: error: {flag(a)} must be a" in err and "'abc'" in err
        if a.choices is not None:
            code, _, err = run(capsys, cmd, a.option_strings[0], *["no-such"] * n_values(a))
            assert code == 1 and err.count("\n") == 1, (cmd, flag(a), err)
            assert f"{flag(a)} must be one of {', '.join(a.choices)}, got 'no-such'" in err
    with pytest.raises(SystemExit) as e:
        run(capsys, cmd, "--help")
    assert e.value.code == 0
    assert " ".join(EPILOG.split()) in " ".join(capsys.readouterr().out.split())
    assert p.epilog == EPILOG


def test_the_real_command_follows_the_rule():
    assert_refused(cli("slide", "--mu1", "x", "--u0", "1", "--angle", "0"), code=1,
                   contains="asperity slide: error: --mu1 must be a number, got 'x'")
    assert_refused(cli("slide", "--law", "spline"), code=1,
                   contains="--law must be one of coulomb, ellipse, collinear, componentwise, star")
    assert_refused(cli("slide", "--mu1"), code=2, contains="expected one argument")
    assert_refused(cli("frobnicate"), code=2, contains="invalid choice")
    assert_refused(cli("contact", "--pressure", "1e6", "--elastic", "1e9", "--materials", "1",
                       "0.3"), code=2, contains="not allowed with argument")
