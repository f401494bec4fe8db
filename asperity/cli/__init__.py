"""Subcommands of the ``asperity`` command (see :mod:`asperity.cli.main`)."""
from __future__ import annotations


def emit(args, obj: dict, text: str, written: tuple[tuple[str, str], ...] = ()) -> None:
    """Print a command's result: one JSON object with --json, else ``text`` and a line
    for each file written (``written``: (what, path) pairs; the --plot file is added)."""
    import json
    if getattr(args, "json", False):
        print(json.dumps(obj, indent=2, allow_nan=False))
        return
    print(text)
    for what, path in (*written, ("plot", getattr(args, "plot", None))):
        if path:
            print(f"{what} written to {path}")
