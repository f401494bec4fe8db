"""The slider chain solved by Moreau's midpoint time-stepping with small masses and slow
loading: friction impulses from the proximal equation onto ``[-mu- N dt, mu+ N dt]``; the
check that the quasi-static verdict does not depend on neglecting inertia.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import check_int
from .chains import TOL, Chain, MicroslipTolerances, SolverError
from .loading import Loading
from .pacing import Pacer
from .quasi_static import (
    MicroslipResult,
    check_capacity,
    check_inputs,
    check_margin,
    load_scale,
    record_indices,
)

#: refuse a Moreau run of more node-steps than this (about 12 min at 1.4e8 node-steps/s)
MAX_NODE_STEPS = 1e11
#: first piece of a run, node-steps (later pieces aim at 0.1 s)
PIECE_NODE_STEPS = 2_000_000


def dynamic_parameters(chain: Chain, steps_per_segment: int) -> dict:
    """Masses, damping and time step of the dynamic mode: every segment of the loading
    lasts one time unit; node and slider masses m w_i (w: area shares) with m such that
    the highest frequency (Gershgorin bound) gives omega_max dt = 0.5; mass-proportional
    damping at the rate 2 omega_low (omega_low^2 = min k_t,i / (2 m w_i))."""
    n = chain.n
    kb = np.zeros(n)
    kb[:-1] += chain.kb
    kb[1:] += chain.kb
    dt = 1.0 / steps_per_segment
    om_max = 0.5 / dt
    m = float(np.max(2.0 * (kb + chain.kt) / chain.weight) / om_max**2)
    om_low = float(np.sqrt(np.min(chain.kt / (2.0 * m * chain.weight))))
    return {"dt": dt, "mass": m, "omega_max": om_max, "omega_low": om_low,
            "damping": 2.0 * om_low,
            "natural_periods_per_segment": om_low / (2.0 * math.pi)}


def simulate_dynamic(chain: Chain, loading: Loading, cycles: int = 3, *,
                     steps_per_segment: int = 20000, record_nodes=None, record_points: int = 400,
                     tol: MicroslipTolerances = TOL) -> MicroslipResult:
    """The same chain with small masses and slow loading, by Moreau's midpoint scheme.

    Loading breakpoints are reached at whole time units (one unit per segment, the lead-in
    included).  The drift per cycle is the change of the assembly displacement over the
    last cycle.  ``solver`` reports r, the tolerance, the iteration limit, the largest
    number of fixed-point iterations used and the status.  The work (steps x nodes) and
    memory are checked first; the kernel runs in pieces of about 0.1 s (Ctrl-C honoured,
    progress reported), with the same result as in one piece."""
    from ..progress import report
    from ..resources import check_memory, check_work
    from ._chain_kernels import STATUS_OK
    from ._dynamic_kernels import moreau_chain
    check_inputs(chain, loading, tol)
    cycles = check_int("cycles", cycles, 1, 1_000_000)
    steps_per_segment = check_int("steps_per_segment", steps_per_segment, 10, 100_000_000)
    record_points = check_int("record_points", record_points, 1, 1_000_000)
    rec = record_indices(chain, record_nodes)
    check_margin(chain, loading)
    check_capacity(chain, loading)
    n = chain.n
    lead = not (loading.dT[0] == 0.0 and loading.F[0] == 0.0)
    seg = loading.dT.size - 1
    start = 1 if lead else 0
    segments = start + seg * cycles
    total = segments * steps_per_segment
    every = max(1, int(seg * steps_per_segment // record_points))
    nrec = total // every + 1
    what = (f"the Moreau solution ({total:.3g} time steps x {n} nodes, --dynamic "
            f"{steps_per_segment} steps per load segment)")
    lower = "lower the steps per segment (--dynamic STEPS) or the nodes (assembly.n)"
    check_work(float(total) * n, MAX_NODE_STEPS, what, lower)
    check_memory(8.0 * (20 * n + 3 * segments + nrec * (rec.size + 1)), what, lower)
    par = dynamic_parameters(chain, steps_per_segment)
    dT_pts = np.concatenate([[0.0], [loading.dT[0]] if lead else [], *[loading.dT[1:]] * cycles])
    F_pts = np.concatenate([[0.0], [loading.F[0]] if lead else [], *[loading.F[1:]] * cycles])
    t_pts = np.arange(dT_pts.size, dtype=float)
    u, v, s, w, xi = (np.zeros(n) for _ in range(5))
    mass = par["mass"] * chain.weight
    args = (chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw, float(chain.alpha_T),
            t_pts, dT_pts, F_pts)
    ru, rt = np.zeros((nrec, rec.size)), np.zeros(nrec)
    istate = np.zeros(2, dtype=np.int64)
    mean_u, u_end = [], []
    max_it, sum_it, steps = 0, 0, 0
    pacer = Pacer(max(1, PIECE_NODE_STEPS // n))
    # march to the start of the first cycle, then one cycle at a time, each in pieces
    bounds = [start * steps_per_segment] + [(start + seg * (c + 1)) * steps_per_segment
                                             for c in range(cycles)]
    for b in bounds:
        while steps < b:
            k = pacer.size(b - steps)
            code, st, mi, si = moreau_chain(*args, steps, steps + k, par["dt"], mass, mass,
                                            par["damping"], tol.prox_r_factor, tol.prox_tol,
                                            tol.prox_max_iter, u, v, s, w, xi, every, rec, ru, rt,
                                            istate)
            pacer.done(k)
            steps += st
            max_it = max(max_it, mi)
            sum_it += si
            if code != STATUS_OK:
                raise SolverError(f"Moreau: the proximal fixed point did not converge in "
                                  f"{tol.prox_max_iter} iterations (step {steps})")
            report(steps / total, "Moreau time steps")
        mean_u.append(float(chain.weight @ u))
        u_end.append(u.copy())
    mean_u = np.array(mean_u)
    d = float(mean_u[-1] - mean_u[-2])
    if abs(d) <= 1e-6 * load_scale(chain, loading):
        d = 0.0
    k = int(istate[1])
    trace = {"t": (rt[:k] - start) / seg, "dT": np.interp(rt[:k], t_pts, dT_pts),
             "u": ru[:k], "nodes": rec}
    solver = {"method": "Moreau midpoint, friction impulses by the proximal fixed point",
              "r": f"{tol.prox_r_factor:g} / G (G = 1 / (m_slider (1 + c dt/2)), "
                   f"the slider's Delassus term)",
              "tolerance": tol.prox_tol, "iteration_limit": tol.prox_max_iter,
              "max_iterations_used": int(max_it),
              "mean_iterations": sum_it / max(1, steps * n), "steps": int(steps),
              "status": "converged", **{k: v for k, v in par.items()}}
    return MicroslipResult(chain, loading, "dynamic", cycles, mean_u, np.array(u_end),
                           chain.kt * (u - s), d, None, True, trace, solver)
