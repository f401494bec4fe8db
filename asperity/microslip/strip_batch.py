"""The strip's closed forms for a block of cases: the elastic limit dT_c of the discrete
strip (``strip_chain``'s n nodes) and the shakedown test (a load cycle that never reaches
it), so that the exact block solver (:func:`asperity.microslip.batch.assess_batch`) marches
only the cases that slip.

The discrete strip under a uniform temperature change dT from the stress-free state, no
force: with element stiffness kb = E h / dx and contact stiffness kt = k_t dx (half at the
two ends), the node displacements are u_i = A sinh((i - c) theta), c = (n - 1) / 2,
cosh theta = 1 + kt / (2 kb), and the end conditions give the end contact force per K,
|q_0| / dT = (kt / 2) |alpha_T| dx tanh(c theta) / sinh theta.  The ends carry the largest
force per threshold (half a node's contact, half its normal load), so the first slider
slips there, at

    dT_c = min(mu+, mu-) p sinh(theta) / (k_t |alpha_T| dx tanh(c theta))

(both ends at once, heating or cooling alike; the continuum's mu p lam coth(lam l / 2) /
(|alpha_T| k_t) as dx -> 0, :func:`asperity.microslip.closed_forms.strip_dT_c`).  theta is
taken as 2 asinh(sqrt(kt / (4 kb))), exact where arccosh(1 + x) would cancel.

Shakedown: with no force and |dT| below dT_c at every breakpoint (and 0, the stress-free
start) no slider ever slips: the verdict is shakedown, the drift 0, the cycle stabilised at
the first (its end state is its start state), the assembly's displacement at every cycle end
0 (the strip's elastic displacement is odd about its middle).  Cases within 1e-9 of the
limit, refused chains (stiffness ratio, asymmetry) and strips of more than
:data:`MAX_NODES` nodes (whose per-case march may be refused for its size) are left to the
exact solver.
"""
from __future__ import annotations

import numpy as np

from .limits import ASYMMETRY, SAME_FRICTION, STIFFNESS_RATIO

#: strips longer than this are left to the exact path (it checks their march's resources)
MAX_NODES = 100_000
#: a maximum |dT| within this relative distance of dT_c is left to the exact path
BAND = 1e-9


def _elements(params: dict):
    """(n, dx, kb, kt) of m strips as strip_chain builds them: element spacing and
    stiffness E h / dx, an interior node's contact stiffness k_t dx."""
    n = int(params.get("n", 201))
    dx = np.asarray(params["l"], dtype=float) / (n - 1)
    kb = np.asarray(params["E"], dtype=float) * np.asarray(params["h"], dtype=float) / dx
    return n, dx, kb, np.asarray(params["k_t"], dtype=float) * dx


def strip_dT_c_block(params: dict, mu_plus, mu_minus) -> np.ndarray:
    """dT_c (K) of m discrete strips: params h, E, p, l, k_t, alpha_T (m,) and n (one int);
    inf where both sides self-lock."""
    p, k_t, aT = (np.asarray(params[k], dtype=float) for k in ("p", "k_t", "alpha_T"))
    n, dx, kb, kt = _elements(params)
    s = np.sqrt(kt / (4.0 * kb))                       # sinh(theta / 2)
    theta = 2.0 * np.arcsinh(s)
    sinh_t = 2.0 * s * np.sqrt(1.0 + s * s)
    mu = np.minimum(np.asarray(mu_plus, dtype=float), np.asarray(mu_minus, dtype=float))
    with np.errstate(invalid="ignore", over="ignore"):
        return mu * p * sinh_t / (k_t * np.abs(aT) * dx * np.tanh(0.5 * (n - 1) * theta))


def strip_shakedown(params: dict, mu_plus, mu_minus, dT, F, *, cycles, max_marched=200):
    """The exact block solver's answer (:func:`asperity.microslip.batch.assess_batch`'s
    keys) for the cases that shake down from the start, ``code`` 2 for the others."""
    m = np.asarray(mu_plus).size
    mp = np.array(mu_plus, dtype=float)               # copies: the answer's own arrays
    mm = np.array(mu_minus, dtype=float)
    same = (mp == mm) | (np.isfinite(mp) & np.isfinite(mm)
                         & (np.abs(mp - mm) <= SAME_FRICTION * np.maximum(np.abs(mp), np.abs(mm))))
    mm = np.where(same, mp, mm)                        # chains._built
    dT_c = strip_dT_c_block(params, mp, mm)
    dT = np.asarray(dT, dtype=float).reshape(m, -1)
    F = np.asarray(F, dtype=float).reshape(m, -1)
    reach = np.abs(dT).max(axis=1)
    n, _, kb, kt = _elements(params)
    ratio = np.maximum(kb / (0.5 * kt), kt / kb)
    fin = np.isfinite(mp) & np.isfinite(mm)
    asym = np.where(fin, np.maximum(mp, mm) / np.where(fin, np.minimum(mp, mm), 1.0), 1.0)
    ok = ((np.abs(F) == 0.0).all(axis=1) & (reach < dT_c * (1.0 - BAND))
          & (ratio <= STIFFNESS_RATIO * (1.0 - BAND)) & (asym <= ASYMMETRY * (1.0 - BAND))
          & (n <= MAX_NODES))
    rng = dT.max(axis=1) - dT.min(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        margin = np.where(np.isfinite(dT_c) & (dT_c > 0), rng / (2.0 * dT_c), 0.0)
    cyc = np.asarray(cycles, dtype=float)
    marched = np.minimum(max_marched, np.ceil(cyc)).clip(max=2)
    return {"code": np.where(ok, 0, 2).astype(np.int64), "mu_plus": mp, "mu_minus": mm,
            "dT_c": dT_c, "margin": margin, "drift_per_cycle": np.where(ok, 0.0, np.nan),
            "drift_after_cycles": np.where(ok, 0.0, np.nan),
            "cycles_to_tolerance": np.full(m, np.nan),
            "stabilised_at": np.where(ok, 1, -1).astype(np.int64),
            "extrapolated": np.where(ok, cyc > marched, -1).astype(np.int64),
            "verdict": np.zeros(m, np.int64), "cycles_marched": marched.astype(np.int64)}
