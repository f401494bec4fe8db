"""``asperity report``: regenerate the validation report (Markdown and PNG)."""
from __future__ import annotations


def add_parser(sub) -> None:
    p = sub.add_parser("report", help="regenerate reports/ (Markdown + PNG)",
                       description="Regenerate the validation report: SPEC.md check values, "
                                   "closed form against springs, polar diagrams, loading curve.")
    p.add_argument("--out", default="reports", help="output folder")
    p.set_defaults(func=main)


def main(args) -> int:
    from ..report import run
    print(f"report written to {run(args.out)}")
    return 0
