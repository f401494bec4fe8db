"""The sampling of a disc's and a ring's footprint against the closed forms of their
Coulomb force and torque (SPEC.md 8): the errors against the number of contact points N
that chose ``asperity.bodies.footprint.DEFAULT_CONTACT_POINTS`` (issue 20: a disc's force
and torque within 0.5 % of the closed forms for every eps at the default N).

    python benchmarks/footprint_quadrature.py [N ...] [--directions D] [--dense K] [--json]

For each N: the worst relative error over D velocity directions (the body turned under
the velocity) of the force (as a vector, |F + f e_v| / f) and of the torque, at eps = 0,
0.1, 0.653, 1, 3, 100, and the worst over K values of eps spread over (0, 1.2] (where the
instantaneous centre lies in the footprint, or near it: the hard part).  No timing: the
figures do not depend on the machine's load.
"""
from __future__ import annotations

import argparse
import json

import numpy as np

from asperity.bodies import accuracy as fpa
from asperity.bodies import footprint as fpm


def measure(kind: str, n: int, directions: int, dense: int) -> dict:
    fp = fpm.disc(1.0, contact_points=n) if kind == "disc" else fpm.ring(1.0, contact_points=n)
    table = fpa.sampling_errors(fp, fpa.TABLE_EPS, directions)
    sweep = fpa.sampling_errors(fp, np.linspace(1.2 / dense, 1.2, dense), directions)
    worst = max(sweep + table, key=lambda r: max(r["force"], r["torque"]))
    return {"kind": kind, "n": fp.n, "table": table, "worst": worst,
            "default": n == fpm.DEFAULT_CONTACT_POINTS[kind]}


def format_rows(rows: list[dict]) -> str:
    head = "| kind | N | " + " | ".join(f"eps={e:g} F / T %" for e in fpa.TABLE_EPS) + \
        " | worst over eps in (0, 1.2]: F / T % (at eps) |"
    lines = [head, "|" + "---|" * (3 + len(fpa.TABLE_EPS))]
    for r in rows:
        cells = [f"{c['force'] * 100:.3f} / {c['torque'] * 100:.3f}" for c in r["table"]]
        w = r["worst"]
        lines.append(f"| {r['kind']} | {r['n']}{' (default)' if r['default'] else ''} | "
                     + " | ".join(cells) + f" | {w['force'] * 100:.3f} / "
                     f"{w['torque'] * 100:.3f} ({w['eps']:.3f}) |")
    return "\n".join(lines)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("sizes", type=int, nargs="*", default=[64, 128, 256, 512, 1024, 2048])
    p.add_argument("--kinds", nargs="*", default=["disc", "ring"], choices=["disc", "ring"])
    p.add_argument("--directions", type=int, default=48)
    p.add_argument("--dense", type=int, default=300)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    rows = [measure(k, n, a.directions, a.dense) for k in a.kinds for n in a.sizes]
    print(json.dumps(rows, indent=1) if a.json else format_rows(rows))
