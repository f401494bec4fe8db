"""The ``asperity`` command: one module per subcommand, user errors in one line.

Every subcommand runs the same way: the arguments are parsed (:mod:`.parsing`: a bad
value is one line, exit status 1; a command line that cannot be parsed is one line, status
2), the output paths it declares are checked before any work, the work runs inside an
output transaction (its files are committed together at the end, or not at all), and
whatever goes wrong is reported in one line: a user error exits with 1, Ctrl-C with 130,
SIGTERM with 143 (:mod:`.interrupts`), an output pipe closed early (``| head``) quietly.
An unexpected internal error is one line too (status 70), with the full traceback when
``ASPERITY_DEBUG=1``.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys

from .. import __version__
from .interrupts import EXIT_INTERRUPTED, EXIT_TERMINATED, Terminated, terminate_as_interrupt
from .parsing import EXIT_USAGE, Parser  # noqa: F401  (EXIT_USAGE: for callers)

#: subcommand name -> module in asperity.cli (each has add_parser(subparsers) and main(args))
COMMANDS = {
    "derive": "derive",
    "fit": "fit",
    "law": "law",
    "report": "report",
    "bench": "bench",
    "slide": "slide",
    "crawl": "crawl",
    "risk": "risk",
    "study": "study",
    "serve": "serve",
    "contact": "contact",
}
EXIT_INTERNAL = 70
#: the exit statuses, in every command's --help
EPILOG = ("exit status: 0 done; 1 a bad value or file (one line names it); 2 a command line "
          "that cannot be parsed (unknown flag, a flag without its value); 3 a computation "
          "that did not converge (slide, contact); 70 an internal error; 130 Ctrl-C; 143 "
          "SIGTERM (nothing written)")


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(
        prog="asperity", epilog=EPILOG,
        description="Direction-dependent friction from surface textures: "
                    "texture -> friction -> law -> consequences.")
    parser.add_argument("--version", action="version", version=f"asperity {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    for mod in COMMANDS.values():
        importlib.import_module(f"asperity.cli.{mod}").add_parser(sub)
    for p in sub.choices.values():                   # what every command has
        p.epilog = EPILOG
        p.add_argument("-q", "--quiet", action="store_true",
                       help="no progress on stderr (a bar on a terminal, else a line every "
                            "few seconds); errors still show")
    return parser


def check_declared_outputs(args) -> None:
    """The outputs a subcommand declares (``set_defaults(outputs=[(flag, dest, figure)],
    inputs=[dest, ...])``): each usable, none twice, none an input."""
    from ..io import check_outputs
    outputs = [(flag, getattr(args, dest, None), figure)
               for flag, dest, figure in getattr(args, "outputs", ())]
    inputs = [getattr(args, dest, None) for dest in getattr(args, "inputs", ())]
    check_outputs(outputs, [x for x in inputs if isinstance(x, str)])


def main(argv: list[str] | None = None) -> int:
    from ..errors import AsperityError, one_line
    from ..io import output_transaction
    from ..progress import progress_bar
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except AsperityError as exc:                     # a bad value (type, choice): status 1
        _say(f"{_name_of(argv)}: error: {one_line(exc)}")
        return 1
    name = f"asperity {args.command}"
    from ..resources import PROGRAM
    PROGRAM.set(name)                                # the name in front of notes
    stop = terminate_as_interrupt()
    try:
        with stop:
            check_declared_outputs(args)
            with output_transaction(), progress_bar(name, quiet=args.quiet):
                code = int(args.func(args) or 0)
        sys.stdout.flush()
        return code
    except AsperityError as exc:
        _say(f"{name}: error: {one_line(exc)}")
        return 1
    except KeyboardInterrupt as exc:
        detail = "" if isinstance(exc, Terminated) else one_line(exc)
        if stop.received:
            _say(f"{name}: terminated by SIGTERM ({detail or 'no output written'})")
            return EXIT_TERMINATED
        _say(f"{name}: interrupted ({detail or 'no output written'})")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        _quiet_stdout()
        return 0
    except MemoryError:
        _say(f"{name}: error: out of memory; ask for less (fewer directions, a smaller scan, "
             "fewer steps) or use a machine with more memory")
        return 1
    except RecursionError:
        _say(f"{name}: error: input nested too deeply to be processed")
        return 1
    except OSError as exc:
        where = f" {exc.filename!r}" if getattr(exc, "filename", None) else ""
        _say(f"{name}: error:{where} {exc.strerror or type(exc).__name__}")
        return 1
    except Exception as exc:                         # a bug: still one line, never a traceback
        if os.environ.get("ASPERITY_DEBUG"):
            raise
        _say(f"{name}: internal error: {type(exc).__name__}: {one_line(exc)} (please report "
             "it; ASPERITY_DEBUG=1 shows the traceback)")
        return EXIT_INTERNAL


def _name_of(argv) -> str:
    """``asperity COMMAND`` from the command line (before it is parsed)."""
    words = [w for w in (sys.argv[1:] if argv is None else argv) if not str(w).startswith("-")]
    return f"asperity {words[0]}" if words and words[0] in COMMANDS else "asperity"


def _say(line: str) -> None:
    try:
        print(line, file=sys.stderr)
    except (BrokenPipeError, OSError):
        pass


def _quiet_stdout() -> None:
    """stdout's reader has gone: point stdout at /dev/null so the interpreter's final
    flush does not raise again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
