"""``asperity report``: regenerate the validation report (Markdown and PNG)."""
from __future__ import annotations


def add_parser(sub) -> None:
    p = sub.add_parser("report", help="regenerate reports/ (Markdown + PNG)",
                       description="Regenerate the validation report: SPEC.md check values, "
                                   "closed form against springs, polar diagrams, loading curve.")
    p.add_argument("--out", default="reports", help="output folder")
    p.set_defaults(func=main)


def check_folder(flag: str, folder: str) -> None:
    """An output folder that exists and is writable, or can be made where it is named."""
    import os
    from pathlib import Path

    from ..errors import InputError
    p = Path(folder)
    if p.exists() and not p.is_dir():
        raise InputError(f"{flag}: {folder!r} is a file, not a folder")
    probe = p
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise InputError(f"{flag}: {str(probe)!r} is a file, so {folder!r} cannot be made")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise InputError(f"{flag}: folder {str(probe)!r} is not writable (permission denied)")


def main(args) -> int:
    from ..report import run
    check_folder("--out", args.out)
    print(f"report written to {run(args.out)}")
    return 0
