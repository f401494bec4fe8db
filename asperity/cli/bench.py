"""``asperity bench``: speed figures of the closed form and the spring simulation."""
from __future__ import annotations

import json


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="print speed figures",
                       description="Closed-form reservoir evaluations per second and "
                                   "spring-tip updates per second (compilation excluded).")
    p.add_argument("--seconds", type=float, default=1.0, help="time per measurement (s)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=main)


def main(args) -> int:
    from ..bench import run
    from ..errors import check_range
    out = run(check_range("--seconds", args.seconds, 0.05, 600))
    if args.json:
        print(json.dumps(out, indent=2))
        return 0
    for k, v in out["closed_form"].items():
        print(f"closed form, {k:9s}: {v['evaluations_per_second']:.3e} reservoir evaluations/s")
    for k, v in out["springs"].items():
        print(f"springs, {k:23s}: {v['updates_per_second']:.3e} spring-tip updates/s")
    return 0
