"""Does the body solver finish on every law?  The whole product of footprints x laws x spin x
launch directions at the command line's defaults (1024 contact points, 512 for a ring,
dt = 1e-4 s), each run until rest, with its Newton iterations (issue 25, item 1).

    python benchmarks/body_sweep.py                    # the table (about 10 min, quiet machine)
    python benchmarks/body_sweep.py --json out.json    # also the rows as JSON
    python benchmarks/body_sweep.py --bodies disc --laws ellipse-3 ellipse-10 --spins 0

A case that does not finish within --timeout seconds (SIGALRM, checked between kernel pieces)
is reported as "timeout".  The test suite runs a covering array of the same factors at 96
points (tests/test_body_convergence.py) with every step checked against its optimality
conditions; this script gives the figures at full size.
"""
from __future__ import annotations

import argparse
import itertools
import json
import math
import signal
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
SURFACES = REPO / "surfaces"

BODIES = ("disc", "ring", "rectangle", "polygon", "body-bracket", "body-plate")
LAWS = ("coulomb", "ellipse-3", "ellipse-10", "ellipse-10-turned", "truncated", "collinear",
        "star-builtin", "star-texture", "star-windward", "family")
SPINS = (0.0, 20.0)
ANGLES = (0.0, 40.0, 90.0, 137.0, 250.0)


def make_law(name: str, cache={}):
    from asperity import derive, fit_derivation, load_texture
    from asperity.laws import planar as P
    from asperity.laws.family import GaugeFamily, law_at
    if name in cache:
        return cache[name]

    def fit(kind, contact="all-faces"):
        return fit_derivation(derive(load_texture(SURFACES / "wedge-asymmetric.toml"),
                                     contact=contact), kind)

    def member(gl, p, source):
        return replace(gl, source={**source, "elastic_contact": {
            "area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 10 * p,
            "mean_gap_m": 1e-7, "E_star_Pa": 1e9, "boundary": "free", "hardness_Pa": None,
            "iterations": 10, "residual": 1e-9, "converged": True}})

    if name == "coulomb":
        law = P.coulomb_law(0.3)
    elif name == "ellipse-3":
        law = P.ellipse_law(0.3, 0.1)
    elif name == "ellipse-10":
        law = P.ellipse_law(0.5, 0.05)
    elif name == "ellipse-10-turned":
        law = P.ellipse_law(0.05, 0.5)
    elif name == "truncated":
        law = P.from_gauge(fit("truncated-ellipse"))
    elif name == "collinear":
        law = P.collinear_law(mu1=0.3, mu2=0.1)
    elif name == "star-builtin":
        law = P.star_law(0.3, 0.1)
    elif name == "star-texture":
        law = P.from_gauge(fit("star"))
    elif name == "star-windward":
        law = P.from_gauge(fit("star", "windward"))
    elif name == "family":
        a = fit("star")
        b = fit("star", "windward")
        fam = GaugeFamily((1e6, 1e7), (member(a, 1e6, a.source), member(b, 1e7, a.source)))
        law = P.from_gauge(law_at(fam, 3e6)[0])
    else:
        raise SystemExit(f"unknown law {name!r}; known: {', '.join(LAWS)}")
    cache[name] = law
    return law


def make_body(name: str):
    from asperity.dynamics.body_api import _as_body
    from asperity.dynamics.body_api import make_body as mk
    from asperity.bodies import footprint as F
    if name == "polygon":
        return _as_body(F.polygon([(0, 0), (0.1, 0), (0.1, 0.02), (0.03, 0.02), (0.03, 0.07),
                                   (0, 0.07)]), None, None)
    if name in ("disc", "ring"):
        return mk(name, radius=0.05)
    if name == "rectangle":
        return mk(name, size=(0.1, 0.04))
    if name.startswith("body-"):
        return mk(str(SURFACES / f"{name}.toml"))
    raise SystemExit(f"unknown body {name!r}; known: {', '.join(BODIES)}")


class Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise Timeout


def run_case(body, law, spin, angle, timeout):
    from asperity.dynamics.body_api import slide_body
    u0 = 0.0 if angle is None else 1.0
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(int(timeout))
    t = time.perf_counter()
    try:
        r = slide_body(make_law(law), make_body(body), u0, angle or 0.0, spin).result
        row = {"status": r.status, "rest": r.rest, "steps": r.steps,
               "mean_iterations": r.mean_iterations, "max_iterations": r.max_iterations_used}
    except Timeout:
        row = {"status": "timeout", "rest": False}
    finally:
        signal.alarm(0)
    row.update(body=body, law=law, omega0=spin, angle=angle, seconds=time.perf_counter() - t)
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bodies", nargs="+", default=list(BODIES), metavar="BODY")
    ap.add_argument("--laws", nargs="+", default=list(LAWS), metavar="LAW")
    ap.add_argument("--spins", nargs="+", type=float, default=list(SPINS), metavar="RAD_S")
    ap.add_argument("--angles", nargs="+", type=float, default=list(ANGLES), metavar="DEG")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds a case (default 120)")
    ap.add_argument("--json", metavar="FILE", help="write the rows as JSON")
    a = ap.parse_args(argv)
    cases = [(b, lw, s, ang) for b, lw, s, ang in
             itertools.product(a.bodies, a.laws, a.spins, a.angles)]
    # spinning from rest (u0 = 0) once per body, law and non-zero spin
    cases += [(b, lw, s, None) for b, lw, s in itertools.product(a.bodies, a.laws, a.spins)
              if s != 0.0]
    make_law(a.laws[0])
    run_case(a.bodies[0], a.laws[0], 0.0, 0.0, a.timeout)      # compile outside the timings
    rows = []
    print(f"{'body':13s} {'law':18s} {'omega0':>6s} {'angle':>6s} {'status':14s} "
          f"{'mean it':>7s} {'max it':>6s} {'steps':>6s} {'s':>6s}")
    for b, lw, s, ang in cases:
        r = run_case(b, lw, s, ang, a.timeout)
        rows.append(r)
        flag = "" if r["status"] == "ok" and r["rest"] else "  <-- "
        print(f"{b:13s} {lw:18s} {s:6g} {'rest' if ang is None else f'{ang:g}':>6s} "
              f"{r['status']:14s} {r.get('mean_iterations', math.nan):7.2f} "
              f"{r.get('max_iterations', -1):6d} {r.get('steps', -1):6d} "
              f"{r['seconds']:6.2f}{flag}", flush=True)
    ok = [r for r in rows if r["status"] == "ok" and r["rest"]]
    means = np.array([r["mean_iterations"] for r in ok]) if ok else np.array([math.nan])
    print(f"\n{len(ok)} of {len(rows)} cases at rest with status ok; mean iterations a step: "
          f"median {np.median(means):.2f}, largest {means.max():.2f}; most in one step: "
          f"{max((r['max_iterations'] for r in ok), default=-1)}; "
          f"total {sum(r['seconds'] for r in rows):.0f} s")
    if a.json:
        from asperity.io import write_text_atomic
        write_text_atomic(a.json, json.dumps(rows, indent=1) + "\n")
    return 0 if len(ok) == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
