"""Does the warm load curve leave room for deflation / Krylov recycling?  (issue 19)

    python benchmarks/deflation_probe.py [--n 256] [--plain] [--json]

Deflation and subspace recycling speed up CG on a FIXED linear system.  The constrained
(Polonsky-Keer) CG solves a linear system only once its contact set has stopped changing;
before that each iteration moves pixels in or out of contact.  For every warm step of the
benchmark's curve (:mod:`asperity.contact.bench`) this prints:

* ``its``: iterations of the warm solve (what :func:`iter_load_curve` does);
* ``set_frozen_at``: the last iteration that clipped a pixel out of contact or moved one
  in (``_pk_kernels.update``'s counts); the iterations after it are the only ones that a
  CG acceleration on a fixed set could remove;
* ``eps_when_frozen``: the residual at that iteration;
* ``known_set_its``: iterations from a start that already has the exact final contact set
  (uniform pressure on it): the linear part alone, i.e. the most a perfect predictor of
  the set would leave; ``known_set_frozen_at`` the same count as above for that start.

``--plain``: the same without the preconditioner (:data:`.solver.PRECONDITION` off), to
see whether the set-changing phase shortens when the linear convergence is faster.

Measured (load 0.3-0.9; 8 pressures, tol 1e-8, preconditioned): the set stops changing
at iteration 9-14 of each warm solve at 256^2 (residual then 2e-5 .. 3e-4), 15-26 at
512^2 (4e-7 .. 4e-5), 24-32 at 1024^2 (9e-7 .. 1e-5); the curve costs 6.9 / 7.1 / 7.1
single solves and would still cost 4.0 / 4.7 / 5.3 if every iteration after the freeze
were free.  Without the preconditioner the set phase is about twice as long (18-30 at
256^2) and the bound 3.9: a faster linear iteration shortens both phases alike, so it
helps cold and warm solves alike and leaves the ratio.  A deflation space restricted to
the contact set needs its k products with the influence matrix again whenever the set
changes, i.e. k extra FFT pairs an iteration throughout the set phase.

Nothing asserted; iterations do not depend on the machine.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from asperity.contact import _pk_kernels as K
from asperity.contact import elastic
from asperity.contact.bench import CURVE, E_STAR, LOAD, PIXEL, TOL, self_affine
from asperity.contact.solver import solve_on

_update = K.update
_rescale = K.rescale
LOG: list = []
EPS: list = []


def _logged_update(u, h, p, t, r, H, gbar, tau, z):
    out = _update(u, h, p, t, r, H, gbar, tau, z)
    LOG.append(out[1] + out[2])
    return out


def _logged_rescale(p, u, old, s, H, scale_u, fixed):
    out = _rescale(p, u, old, s, H, scale_u, fixed)
    EPS.append(out[0])
    return out


def _run(space, h, pbar, p0):
    LOG.clear()
    EPS.clear()
    res = solve_on(space, h, pbar, None, h.size, TOL, 10_000, p0, None)
    changed = [i + 1 for i, m in enumerate(LOG) if m > 0]
    frozen = changed[-1] if changed else 0
    # EPS[0] is the start's scaling; EPS[i] the change of iteration i
    eps = EPS[frozen] / (pbar * h.size) if frozen else float("nan")
    return res, frozen, eps


def measure(n: int, plain: bool = False) -> dict:
    from asperity.contact import solver
    solver.PRECONDITION = not plain
    K.update, K.rescale = _logged_update, _logged_rescale
    h = self_affine(n, dx=PIXEL, seed=1)
    space = elastic.HalfSpace(h.shape, PIXEL, PIXEL, E_STAR, "periodic")
    single = _run(space, h, LOAD * E_STAR, None)[0].iterations
    rows, prev = [], None
    for k, f in enumerate(CURVE):
        res, frozen, eps = _run(space, h, f * E_STAR, prev)
        row = {"p_over_E_star": f, "its": res.iterations, "set_frozen_at": frozen,
               "eps_when_frozen": eps}
        known, kfrozen, _ = _run(space, h, f * E_STAR, (res.pressure > 0).astype(float))
        row["known_set_its"] = known.iterations
        row["known_set_frozen_at"] = kfrozen
        rows.append(row)
        prev = res.pressure
    K.update, K.rescale = _update, _rescale
    its = sum(r["its"] for r in rows)
    floor = rows[0]["its"] + sum(r["set_frozen_at"] for r in rows[1:])
    return {"n": n, "tol": TOL, "preconditioned": not plain, "single_iterations": single, "curve": rows,
            "curve_iterations": its, "curve_in_single_solves": its / single,
            "bound_iterations_if_free_after_freeze": floor,
            "bound_in_single_solves": floor / single}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--plain", action="store_true")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    out = measure(a.n, a.plain)
    if a.json:
        print(json.dumps(out, indent=1))
        return 0
    print(f"n={a.n} tol={TOL:g} preconditioned={out['preconditioned']}")
    print(f"single cold solve at the benchmark's load: {out['single_iterations']} its")
    print("p/E*       its  set_frozen_at  eps_when_frozen  known_set_its  known_frozen_at")
    for r in out["curve"]:
        print(f"{r['p_over_E_star']:.5f}  {r['its']:4d}  {r['set_frozen_at']:13d}  "
              f"{r['eps_when_frozen']:15.2e}  {r['known_set_its']:13d}  "
              f"{r['known_set_frozen_at']:15d}")
    print(f"curve: {out['curve_iterations']} its = "
          f"{out['curve_in_single_solves']:.2f} single solves; even if every iteration "
          f"after the set froze were free (first solve cold, whole): "
          f"{out['bound_iterations_if_free_after_freeze']} its = "
          f"{out['bound_in_single_solves']:.2f} single solves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
