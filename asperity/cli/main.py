"""The ``asperity`` command: one module per subcommand, user errors in one line."""
from __future__ import annotations

import argparse
import importlib
import sys

from .. import __version__

#: subcommand name -> module in asperity.cli (each has add_parser(subparsers) and main(args))
COMMANDS = {
    "derive": "derive",
    "fit": "fit",
    "law": "law",
    "report": "report",
    "bench": "bench",
    "slide": "slide",
    "risk": "risk",
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="asperity",
        description="Direction-dependent friction from surface textures: "
                    "texture -> friction -> law -> consequences.")
    parser.add_argument("--version", action="version", version=f"asperity {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name, mod in COMMANDS.items():
        importlib.import_module(f"asperity.cli.{mod}").add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    from ..errors import AsperityError
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except AsperityError as exc:
        print(f"asperity {args.command}: error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"asperity {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
