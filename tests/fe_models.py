"""Small implicit models that use a compiled FRIC as their friction (shared by the FE
tests and the benchmark): a contact point driven through a spring, and the seed's two-node
assembly (SPEC.md section 5) under thermal cycles."""
from __future__ import annotations

from functools import partial

import numpy as np

from asperity.fe.fortran_harness import call_fric
from asperity.fe.implicit_driver import ContactState, newton_increment, two_node_cycles  # noqa: F401


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
