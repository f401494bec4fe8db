"""The windows' library functions default to what their commands default to: a call of
``derive_windows`` / ``contact_windows`` without a keyword gives what ``asperity derive
--window`` / ``asperity contact --window`` gives without the flag."""
from __future__ import annotations

import inspect

import pytest

from asperity.cli.main import build_parser
from asperity.friction import elastic_windows as ew


@pytest.mark.parametrize("command,function", [("derive", ew.derive_windows),
                                              ("contact", ew.contact_windows)])
def test_library_defaults_are_the_commands_defaults(command, function):
    args = build_parser().parse_args([command, "scan.x3p", "--window", "64", "--elastic",
                                      "1e9", "--pressure", "1e6"])
    shared = {name: p.default for name, p in inspect.signature(function).parameters.items()
              if p.default is not inspect.Parameter.empty and hasattr(args, name)
              and getattr(args, name) is not None}       # None: the command decides later
    assert {"height_scale", "detrend"} <= set(shared)
    for name, default in shared.items():
        assert default == getattr(args, name), name
