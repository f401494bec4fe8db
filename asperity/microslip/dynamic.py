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
from .quasi_static import MicroslipResult, check_capacity, load_scale


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
    number of fixed-point iterations used and the status."""
    from ._chain_kernels import STATUS_OK, moreau_chain
    cycles = check_int("cycles", cycles, 1, 1_000_000)
    steps_per_segment = check_int("steps_per_segment", steps_per_segment, 10, 100_000_000)
    check_capacity(chain, loading)
    n = chain.n
    par = dynamic_parameters(chain, steps_per_segment)
    lead = not (loading.dT[0] == 0.0 and loading.F[0] == 0.0)
    dT_pts = [0.0] + ([loading.dT[0]] if lead else [])
    F_pts = [0.0] + ([loading.F[0]] if lead else [])
    start = len(dT_pts) - 1
    for _ in range(cycles):
        dT_pts += list(loading.dT[1:])
        F_pts += list(loading.F[1:])
    t_pts = np.arange(len(dT_pts), dtype=float)
    seg = loading.dT.size - 1
    rec = np.array([0, n - 1] if record_nodes is None else record_nodes, dtype=np.int64)
    u, v, s, w, xi = (np.zeros(n) for _ in range(5))
    mass = par["mass"] * chain.weight
    args = (chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw, float(chain.alpha_T))
    mean_u, u_end = [], []
    tr_t, tr_u = [], []
    max_it, sum_it, steps = 0, 0, 0
    t0 = 0.0
    every = max(1, int(seg * steps_per_segment // max(1, record_points)))
    # march to the start of the first cycle, then one cycle at a time
    bounds = [float(start)] + [float(start + seg * (c + 1)) for c in range(cycles)]
    for t_end in bounds:
        span = t_end - t0
        if span > 0:
            nrec = int(span * steps_per_segment // every) + 1
            ru, rt = np.zeros((nrec, rec.size)), np.zeros(nrec)
            code, st, mi, si = moreau_chain(*args, t_pts - t0, np.array(dT_pts), np.array(F_pts),
                                            span, par["dt"], mass, mass, par["damping"],
                                            tol.prox_r_factor, tol.prox_tol, tol.prox_max_iter,
                                            u, v, s, w, xi, every, rec, ru, rt)
            steps += st
            max_it = max(max_it, mi)
            sum_it += si
            if code != STATUS_OK:
                raise SolverError(f"Moreau: the proximal fixed point did not converge in "
                                  f"{tol.prox_max_iter} iterations (step {steps})")
            k = min(nrec, int(span * steps_per_segment) // every)
            tr_t += list(rt[:k] + t0)
            tr_u += list(ru[:k])
        t0 = t_end                       # the kernel restarts at t = 0 on a shifted axis
        mean_u.append(float(chain.weight @ u))
        u_end.append(u.copy())
    mean_u = np.array(mean_u)
    d = float(mean_u[-1] - mean_u[-2]) if cycles >= 1 else 0.0
    if abs(d) <= 1e-6 * load_scale(chain, loading):
        d = 0.0
    tt = np.array(tr_t)
    trace = {"t": (tt - start) / seg, "dT": np.interp(tt, t_pts, dT_pts), "u": np.array(tr_u),
             "nodes": rec}
    solver = {"method": "Moreau midpoint, friction impulses by the proximal fixed point",
              "r": f"{tol.prox_r_factor:g} / G (G = 1 / (m_slider (1 + c dt/2)), "
                   f"the slider's Delassus term)",
              "tolerance": tol.prox_tol, "iteration_limit": tol.prox_max_iter,
              "max_iterations_used": int(max_it),
              "mean_iterations": sum_it / max(1, steps * n), "steps": int(steps),
              "status": "converged", **{k: v for k, v in par.items()}}
    return MicroslipResult(chain, loading, "dynamic", cycles, mean_u, np.array(u_end),
                           chain.kt * (u - s), d, None, True, trace, solver)
