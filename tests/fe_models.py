"""Small implicit models that use a compiled FRIC as their friction (shared by the FE
tests and the benchmark): a contact point driven through a spring, and the seed's two-node
assembly (SPEC.md section 5) under thermal cycles."""
from __future__ import annotations

from functools import partial

import numpy as np

from asperity.fe.fortran_harness import call_fric
from asperity.fe.implicit_driver import ContactState, newton_increment


def fric_of(lib, props, nfdir, **kw):
    """FRIC with its properties and NFDIR bound: the driver's ``fric`` callable."""
    return partial(call_fric, lib, props=props, nfdir=nfdir, **kw)


def spring_driven_point(fric, w_path, ks, press: float, nfdir: int = 2, nstatv: int = 4,
                        guess=None, **newton):
    """A contact point pulled through a spring of stiffness ``ks`` (per unit area; a
    scalar or an (nfdir, nfdir) matrix) by a driver moved along ``w_path`` ((steps,
    nfdir)): one increment per step. Returns the increments' results."""
    Ks = ks * np.eye(nfdir) if np.ndim(ks) == 0 else np.asarray(ks, dtype=float)
    state = ContactState.fresh(1, nfdir, nstatv)
    u = np.zeros(nfdir)
    B = np.eye(nfdir)[None, :, :]
    out = []
    for w in np.atleast_2d(w_path):
        def residual(x, w=w):
            return Ks @ (x - w), Ks
        res = newton_increment(fric, state, u, B, [press], residual,
                               u_guess=None if guess is None else guess(u, w), **newton)
        state, u = res.state, res.u
        out.append(res)
    return out


def two_node_cycles(fric, *, k, l0, alpha_T, k_t, N, dT_min, dT_max, cycles: int = 4,
                    steps: int = 6, nstatv: int = 4):
    """The two-node bar (stiffness k, length l0, expansion alpha_T) on two contact points
    (area 1, pressure N, FRIC's PROPS(1) = k_t) through ``cycles`` thermal cycles
    dT_min -> dT_max -> dT_min, ``steps`` increments each way. Returns the mean node
    displacement at the end of each cycle (m) and the Newton iterations per increment."""
    state = ContactState.fresh(2, 1, nstatv)
    u = np.zeros(2)
    B = np.array([[[1.0, 0.0]], [[0.0, 1.0]]])
    K = k * np.array([[1.0, -1.0], [-1.0, 1.0]])
    ends, iterations = [], []
    ramp = np.linspace(dT_min, dT_max, steps + 1)[1:]
    path = np.r_[ramp, ramp[::-1][1:], dT_min]
    for _ in range(cycles):
        for dT in path:
            def residual(x, dT=dT):
                T = k * (x[1] - x[0] - alpha_T * l0 * dT)        # tension of the bar
                return np.array([-T, T]), K
            res = newton_increment(fric, state, u, B, [N, N], residual, tol=1e-10)
            state, u = res.state, res.u
            iterations.append(len(res.residuals))
        ends.append(float(u.mean()))
    return np.array(ends), iterations
