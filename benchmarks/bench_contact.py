"""Contact solver benchmark (issue 19): asperity's ``solve_contact`` against
ContactMechanics and a plain NumPy / scipy.fft Polonsky-Keer, in the same run.

    python benchmarks/bench_contact.py [--n 1024] [--free-n 1024] [--big] [--repeats R]
                                       [--no-curve] [--json]

Same figures as ``asperity bench --only contact`` (the problem, the memory measurement and
the targets are described in :mod:`asperity.contact.bench`).  Each solver runs in a child
process; the peers' children run this script with ``--worker contactmechanics|plain``
(asperity's with ``python -m asperity.contact.bench``), so the package never imports
ContactMechanics.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))        # contact_peers, plain_contact
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))    # this checkout's asperity


def contactmechanics_solver(h, dx, E, p, boundary, tol, initial):
    """(pressure, iterations) of ContactMechanics' constrained conjugate gradient; a warm
    start passes the previous pressure as its initial pixel forces."""
    from contact_peers import cm_solve
    p_out, _, it, ok = cm_solve(h, dx, dx, E, p, boundary, tol=tol, initial=initial)
    if not ok:
        raise RuntimeError(f"ContactMechanics did not converge in {it} iterations")
    return p_out, it


def plain_solver(h, dx, E, p, boundary, tol, initial):
    from plain_contact import polonsky_keer
    p_out, _, it, err = polonsky_keer(h, dx, dx, E, p, boundary, tol=tol, initial=initial)
    if not err < tol:
        raise RuntimeError(f"the plain solver did not converge in {it} iterations")
    return p_out, it


if __name__ == "__main__":
    if "--worker" in sys.argv:
        from asperity.contact.bench import worker_main
        sys.exit(worker_main(sys.argv[1:], {"contactmechanics": contactmechanics_solver,
                                            "plain": plain_solver}))
    from asperity.contact.bench import bench_contact, format_contact
    a = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    a.add_argument("--n", type=int, default=1024, help="periodic map n x n (and the curve)")
    a.add_argument("--free-n", type=int, default=1024, help="free map n x n")
    a.add_argument("--big", action="store_true", help="also a free 4096 x 4096 (asperity)")
    a.add_argument("--repeats", type=int, default=1)
    a.add_argument("--no-curve", action="store_true", help="leave out the load curve")
    a.add_argument("--json", action="store_true")
    args = a.parse_args()
    out = bench_contact(args.n, args.free_n, args.big, repeats=args.repeats,
                        curve=not args.no_curve)
    print(json.dumps(out, indent=2) if args.json else format_contact(out))
