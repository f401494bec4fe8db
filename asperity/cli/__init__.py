"""Subcommands of the ``asperity`` command (see :mod:`asperity.cli.main`): one module per
subcommand; :mod:`.parsing` the parser every command shares (numbers in any form, the
exit statuses), :mod:`.interrupts` SIGTERM handled as Ctrl-C is."""
from __future__ import annotations

import math


def json_text(obj) -> str:
    """``obj`` as indented JSON; a NaN or infinity anywhere is refused in one line naming
    its place (a result that is not a number must never reach a file or a pipe)."""
    import json
    where = _non_finite(obj, "")
    if where is not None:
        from ..errors import AsperityError
        raise AsperityError(f"the result is not a finite number at {where or 'the top'}; "
                            "the inputs are outside what the model can compute")
    return json.dumps(obj, indent=2, allow_nan=False)


def _non_finite(x, path: str):
    if isinstance(x, float) and not math.isfinite(x):
        return path
    if isinstance(x, dict):
        for k, v in x.items():
            found = _non_finite(v, f"{path}.{k}" if path else str(k))
            if found is not None:
                return found
    elif isinstance(x, (list, tuple)):
        for i, v in enumerate(x):
            found = _non_finite(v, f"{path}[{i}]")
            if found is not None:
                return found
    return None


def emit(args, obj: dict, text: str, written: tuple[tuple[str, str], ...] = ()) -> None:
    """Print a command's result: one JSON object with --json, else ``text`` and a line
    for each file written (``written``: (what, path) pairs; the --plot file is added).
    When an output file goes to standard output (``-``) the text goes to stderr."""
    import sys
    outputs = [(what, path) for what, path in (*written, ("plot", getattr(args, "plot", None)))
               if path]
    stream = sys.stderr if any(str(p) == "-" for _, p in outputs) else sys.stdout
    if getattr(args, "json", False):
        print(json_text(obj), file=stream)
        return
    print(text, file=stream)
    written_lines(outputs, stream)


def written_lines(outputs, stream=None) -> None:
    """Print "WHAT written to PATH" for each (what, path) once the files are committed."""
    import sys

    from ..io import on_commit
    stream = stream or sys.stdout
    for what, path in outputs:
        where = "standard output" if str(path) == "-" else path
        on_commit(lambda what=what, where=where: print(f"{what} written to {where}",
                                                       file=stream))


def add_cluster_arguments(parser, workers: str, scheduler: str) -> None:
    """``--workers N | --scheduler ADDRESS`` (mutually exclusive): where the Dask work of
    a command runs (see asperity.study.engine); the help texts say what runs there."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", metavar="N", default=None,
                       help=f"{workers}; local workers are at most one per core and what the "
                            f"free memory holds (a line says when fewer start)")
    where.add_argument("--scheduler", metavar="ADDRESS", default=None,
                       help=f"{scheduler} (scheduler address tcp://HOST:PORT or scheduler "
                            f"file)")


def whole_flag(flag: str, text, low: int, high: int) -> int | None:
    """A whole number typed on the command line ('200', '1e7') in [low, high]; None stays
    None (a flag not given)."""
    from ..errors import check_int, number_from_text
    from .parsing import _WHOLE
    if text is None:
        return None
    t = str(text).strip()        # digits alone: exactly (2**63 - 1 is no float)
    return check_int(flag, int(t) if _WHOLE.match(t) else number_from_text(flag, t), low, high)
