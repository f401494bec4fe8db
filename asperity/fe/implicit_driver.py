"""An Abaqus/Standard-like implicit driver for FRIC (tests and benchmarks).

How Abaqus/Standard uses FRIC within one increment, mimicked here: every Newton iteration
calls the routine at every closed contact point with COPIES of the start-of-increment TAU
and STATEV, the relative slip DGAM of the whole increment so far (not of the iteration),
the LM the routine returned at the previous iteration (the previous increment's at the
first one), and the current pressure; only the outputs of the iteration at which the
global residual has converged are kept (committed) as the next increment's start values.
The routine's DDTDDG enters the global tangent, so a consistent tangent gives a quadratic
Newton.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class ContactState:
    """Committed (start-of-increment) values of ``m`` contact points."""

    tau: np.ndarray          # (m, nfdir)
    statev: np.ndarray       # (m, nstatv)
    lm: np.ndarray           # (m,) int

    @classmethod
    def fresh(cls, m: int, nfdir: int, nstatv: int) -> ContactState:
        return cls(np.zeros((m, nfdir)), np.zeros((m, nstatv)), np.zeros(m, dtype=int))

    def copy(self) -> ContactState:
        return ContactState(self.tau.copy(), self.statev.copy(), self.lm.copy())


@dataclass
class IncrementResult:
    u: np.ndarray
    state: ContactState
    residuals: list = field(default_factory=list)    # |R| at each iteration
    lm_seen: list = field(default_factory=list)      # LM passed in at each iteration


class NotConverged(RuntimeError):
    """The Newton loop of an increment did not converge (the increment is not kept)."""


def newton_increment(fric, state: ContactState, u_start, B, press, residual, *,
                     area=1.0, tol: float = 1e-9, max_iter: int = 30,
                     u_guess=None) -> IncrementResult:
    """Solve one increment ``R(u) = r(u) + sum_k area_k B_k^T TAU_k(u) = 0``.

    fric     : callable(lm=, tau=, statev=, dgam=, press=, kinc=) -> FricOut (see
               :func:`asperity.fe.fortran_harness.call_fric` with lib, props, nfdir bound)
    state    : committed values at the start of the increment (never modified)
    u_start  : (n,) degrees of freedom at the start of the increment
    B        : (m, nfdir, n) slip of contact point k = B[k] @ u (secondary relative to main)
    press    : (m,) contact pressures (held during the increment)
    residual : callable(u) -> (r, K), the rest of the model (internal minus external forces)
    tol      : absolute tolerance on |R|

    TAU is the frictional stress with the sign of the slip: the force on the secondary
    point is -area TAU, hence the + sign in R. Returns the converged u and the committed
    state; raises :class:`NotConverged` otherwise."""
    B = np.asarray(B, dtype=float)
    m = B.shape[0]
    areas = np.broadcast_to(np.asarray(area, dtype=float), (m,))
    press = np.broadcast_to(np.asarray(press, dtype=float), (m,))
    u_start = np.asarray(u_start, dtype=float)
    u = u_start.copy() if u_guess is None else np.array(u_guess, dtype=float)
    lm_iter = state.lm.copy()
    out = IncrementResult(u, state)
    for _ in range(max_iter):
        r, K = residual(u)
        R, J = np.array(r, dtype=float), np.array(K, dtype=float)
        new = state.copy()
        out.lm_seen.append(lm_iter.copy())
        for k in range(m):
            res = fric(lm=int(lm_iter[k]), tau=state.tau[k].copy(),
                       statev=state.statev[k].copy(), dgam=B[k] @ (u - u_start),
                       press=float(press[k]))
            lm_iter[k] = res.lm
            new.lm[k] = res.lm
            if res.lm == 1:
                raise NotConverged("FRIC asked for Lagrange-multiplier stick (LM = 1), "
                                   "which this driver does not model")
            if res.lm == 2:                            # frictionless for this iteration
                new.tau[k] = 0.0
                continue
            new.tau[k], new.statev[k] = res.tau, res.statev[:state.statev.shape[1]]
            R += areas[k] * B[k].T @ res.tau
            J += areas[k] * B[k].T @ res.ddtddg @ B[k]
        norm = float(np.linalg.norm(R))
        out.residuals.append(norm)
        if norm <= tol:
            out.u, out.state = u, new
            return out
        u = u - np.linalg.solve(J, R)
    raise NotConverged(f"no convergence in {max_iter} iterations: |R| = {out.residuals}")
