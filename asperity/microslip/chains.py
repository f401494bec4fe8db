"""Cumulative microslip (ratcheting) of assemblies under thermal cycles (SPEC.md section 5).

An assembly is a chain of contact nodes on a rigid support along one slip axis ``x``: node
``i`` carries an elastic tangential spring ``k_t,i`` in series with a slider that moves
towards ``+x`` when the spring force ``q_i = k_t,i (u_i - s_i)`` reaches ``mu+ N_i`` and
towards ``-x`` when it reaches ``-mu- N_i`` (the regularised asymmetric Coulomb law);
consecutive nodes are joined by elastic elements of stiffness ``k_e`` and length ``l_e``
that expand freely by ``alpha_T l_e dT``.  An external tangential force ``F`` may act,
shared by the nodes in fixed proportions.

Sign convention: ``x`` is the assembly's slip axis; ``u > 0`` is a displacement towards
``+x``; ``mu+`` resists sliding towards ``+x``, ``mu-`` towards ``-x``.  With ``mu+ > mu-``
the assembly creeps towards ``-x`` (the side of the smaller coefficient): a negative drift.

* :func:`two_node_chain`, :func:`strip_chain` build the two models of Antoni et al.;
* :func:`two_node_dT_c`, :func:`two_node_drift_per_cycle`, :func:`strip_dT_c` are the closed
  forms (SPEC.md 5) beside the numerics;
* :func:`simulate` marches cycles quasi-statically (exact solution of the rate-independent
  chain, event by event: every slider's start and stop located along each linear load
  segment) and detects the stabilised cycle, from which the drift after any number of cycles
  is extrapolated exactly;
* :func:`simulate_dynamic` solves the same chain with small masses and slow loading by
  Moreau's midpoint time-stepping, friction impulses from the proximal equation onto
  ``[-mu- N dt, mu+ N dt]``.

Units: SI (m, N, K, Pa).  The strip is per unit width (p in Pa, k_t in Pa/m, F in N/m).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import AsperityError, InputError, check_array, check_instance, check_range, check_text
from .limits import (
    ASYMMETRY,
    STIFFNESS_RATIO,
    STRIP,
    TWO_NODE,
    check_alpha_T,
    check_mu,
    check_nodes,
    check_param,
    same_friction,
)

MODES = ("quasi-static", "dynamic")


class SlideOffError(AsperityError):
    """A physical outcome: the external load exceeds what the sliders can hold."""


class SolverError(AsperityError):
    """The active-set or the proximal iteration did not converge (a numerical failure)."""


@dataclass(frozen=True)
class MicroslipTolerances:
    """The tolerances of this module, in one place."""

    #: the cycle is stabilised when the contact forces at the end of two consecutive cycles
    #: differ by at most this, relative to the largest slider threshold
    stabilised: float = 1e-9
    #: a drift per cycle below this, relative to the thermal displacement scale
    #: |alpha_T| * length * dT range, counts as no drift (the rounding of a chain 1e9 times
    #: stiffer than its contacts reaches ~1e-9)
    no_drift: float = 1e-8
    #: slip events per node and load segment before the march gives up (a chain's sliders
    #: start and stop a few times per segment)
    max_events_per_node: int = 50
    #: march every load segment event by event (else in one increment where that is
    #: certain to be exact: the same result, faster; for checks and benchmarks)
    events_only: bool = False
    #: Moreau: fixed-point tolerance (relative to the impulse bound), iteration limit, r/G
    prox_tol: float = 1e-12
    prox_max_iter: int = 100
    prox_r_factor: float = 1.0

    def __post_init__(self):
        from ..errors import check_int
        checked = {name: check_range(f"tol.{name}", getattr(self, name), 1e-15, 1e-2)
                   for name in ("stabilised", "no_drift", "prox_tol")}
        for name in ("max_events_per_node", "prox_max_iter"):
            checked[name] = check_int(f"tol.{name}", getattr(self, name), 1, 100_000)
        checked["prox_r_factor"] = check_range("tol.prox_r_factor", self.prox_r_factor, 0.0,
                                               2.0, low_open=True, high_open=True)
        from ..errors import check_flag
        checked["events_only"] = check_flag("tol.events_only", self.events_only)
        for name, value in checked.items():
            object.__setattr__(self, name, value)


TOL = MicroslipTolerances()


@dataclass(frozen=True)
class Chain:
    """A slider chain (the equations: ``asperity.microslip._chain_kernels``).

    Attributes
    ----------
    kind : str
        ``"two-node"`` or ``"strip"``.
    x : ndarray, shape (n,)
        Node positions along the slip axis, m.
    kb, le : ndarray, shape (n-1,)
        Element stiffness (N/m) and length (m).
    kt : ndarray, shape (n,)
        Contact stiffness, N/m.
    cp, cm : ndarray, shape (n,)
        Thresholds ``mu+ N_i``, ``mu- N_i``, N.
    fw : ndarray, shape (n,)
        Share of the external force on each node (sums to 1).
    weight : ndarray, shape (n,)
        Contact-area share of each node (sums to 1): the assembly's displacement is
        the weighted mean of the node displacements.
    """

    kind: str
    x: np.ndarray
    kb: np.ndarray
    le: np.ndarray
    kt: np.ndarray
    cp: np.ndarray
    cm: np.ndarray
    fw: np.ndarray
    weight: np.ndarray
    alpha_T: float
    mu_plus: float
    mu_minus: float
    params: dict = field(default_factory=dict)

    def __post_init__(self):
        _check_chain(self)

    @property
    def n(self) -> int:
        return int(self.x.size)

    @property
    def length(self) -> float:
        return float(self.le.sum())

    def with_friction(self, mu_plus: float, mu_minus: float) -> Chain:
        """The same chain with other coefficients (thresholds scaled from the normal loads)."""
        Nn = self.normal_loads
        from dataclasses import replace
        return replace(self, cp=mu_plus * Nn, cm=mu_minus * Nn, mu_plus=float(mu_plus),
                       mu_minus=float(mu_minus))

    @property
    def normal_loads(self) -> np.ndarray:
        return np.asarray(self.params["normal_loads"])


def _check_chain(c: Chain) -> None:
    """Every array of a chain coerced to contiguous float64 of the right length and checked,
    so that the kernels only ever see consistent, admissible arrays (one-line InputError)."""
    check_text("chain.kind", c.kind, 40)
    x = check_array("chain.x", c.x, shape=(None,))
    n = check_nodes("chain node count", x.size)
    arrays = {"x": x}
    # name, length, sign (">0", ">=0" or "" for any), +inf allowed
    for name, size, sign, inf in (("kb", n - 1, ">0", False), ("le", n - 1, ">0", False),
                                  ("kt", n, ">0", False), ("cp", n, ">0", True),
                                  ("cm", n, ">0", True), ("fw", n, "", False),
                                  ("weight", n, ">0", False)):
        a = check_array(f"chain.{name}", getattr(c, name), shape=(size,), finite=False)
        if np.isnan(a).any() or (not inf and not np.isfinite(a).all()):
            raise InputError(f"chain.{name} must be finite{' or +inf' if inf else ''}")
        if (sign == ">0" and (a <= 0).any()) or (sign == ">=0" and (a < 0).any()):
            raise InputError(f"chain.{name} must be {sign[0]}{sign[1:-1]} 0 everywhere, got "
                             f"{a.min():g}")
        arrays[name] = np.ascontiguousarray(a)
    if abs(arrays["weight"].sum() - 1.0) > 1e-9 or abs(arrays["fw"].sum() - 1.0) > 1e-9:
        raise InputError("chain.weight and chain.fw must each sum to 1")
    for name, a in arrays.items():
        object.__setattr__(c, name, a)
    object.__setattr__(c, "alpha_T", check_alpha_T("chain.alpha_T", c.alpha_T))
    object.__setattr__(c, "mu_plus", check_mu("chain.mu_plus", c.mu_plus))
    object.__setattr__(c, "mu_minus", check_mu("chain.mu_minus", c.mu_minus))
    check_instance("chain.params", c.params, dict)
    _check_resolvable(c)


def _built(kind, x, kb, le, kt, mp, mm, N, w, alpha_T, params) -> Chain:
    """A chain built here from checked scalars (two_node_chain, strip_chain): its arrays
    are float64, contiguous, finite and positive by construction, so only what depends on
    their combination (resolvable stiffness ratios and asymmetry) is checked -- the array
    checks of a user's Chain cost more than a two-node case's solution."""
    if same_friction(mp, mm):
        mm = mp            # the same coefficient but for rounding: exactly symmetric sliders
    c = object.__new__(Chain)
    for name, v in (("kind", kind), ("x", x), ("kb", kb), ("le", le), ("kt", kt),
                    ("cp", mp * N), ("cm", mm * N), ("fw", w), ("weight", w.copy()),
                    ("alpha_T", alpha_T), ("mu_plus", mp), ("mu_minus", mm),
                    ("params", params)):
        object.__setattr__(c, name, v)
    c.__dict__["_uniform"] = True          # both models are uniform by construction
    _check_resolvable(c)
    return c


def _check_resolvable(c: Chain) -> None:
    """Stiffness ratios and the ratio of the coefficients within what double precision
    resolves (nearly equal coefficients are resolved whatever their difference)."""
    kb, kt = c.kb, c.kt
    for ratio, what, fix in ((kb.max() / kt.min(), "elements are", "fewer nodes"),
                             (kt.max() / kb.min(), "contacts are", "more nodes")):
        if ratio > STIFFNESS_RATIO:
            raise InputError(f"the chain's {what} {ratio:.3g} times stiffer than its "
                             f"{'contacts' if what[0] == 'e' else 'elements'} (at most "
                             f"{STIFFNESS_RATIO:g}: beyond what double precision resolves); "
                             f"a strip: use {fix} (assembly.n) or change E h / k_t, two nodes: "
                             "k / k_t")
    mus = [m for m in (c.mu_plus, c.mu_minus) if math.isfinite(m)]
    if len(mus) == 2 and max(mus) > ASYMMETRY * min(mus):
        raise InputError(f"mu_plus / mu_minus = {c.mu_plus / c.mu_minus:.3g} is beyond what the "
                         f"chain solvers resolve (at most {ASYMMETRY:g} either way)")


def stiffness_ratio(c: Chain) -> float:
    """The largest element/contact stiffness ratio of a chain, either way."""
    return float(max(c.kb.max() / c.kt.min(), c.kt.max() / c.kb.min()))


def two_node_chain(k, l0, alpha_T, k_t, N, mu_plus, mu_minus) -> Chain:
    """Antoni et al.'s two-node model: a bar on a rigid support through two sliders.

    A bar (stiffness ``k``, length ``l0``, expansion ``alpha_T`` relative to the support)
    whose two ends rest on the support under the normal force ``N`` each, through an
    elastic tangential spring ``k_t`` in series with a slider: it moves towards +x when
    the spring force reaches ``mu+ N``, towards -x at ``mu- N`` (SPEC.md 5).

    Parameters
    ----------
    k : float
        Bar stiffness, N/m, in [1e-3, 1e15].
    l0 : float
        Bar length, m, in [1e-6, 1e3].
    alpha_T : float
        Expansion coefficient relative to the support, 1/K, signed (< 0 when the bar
        expands less than its support): ``|alpha_T|`` in [1e-9, 1e-3].
    k_t : float
        Tangential contact stiffness of each node, N/m, in [1e-3, 1e15].
    N : float
        Normal force on each node, N, in [1e-6, 1e9].
    mu_plus : float
        Coefficient resisting sliding towards +x, in [1e-6, 1e4], or inf (self-locking).
    mu_minus : float
        Coefficient resisting sliding towards -x, in [1e-6, 1e4], or inf.

    Returns
    -------
    Chain
        The two-node chain (``kind`` ``"two-node"``, ``n`` = 2; ``cp``, ``cm``: the slider
        thresholds ``mu+ N``, ``mu- N``).

    Raises
    ------
    InputError
        If a value is out of its range, or the stiffness ratios or ``mu+ / mu-`` (at most
        1e3 either way) are beyond what double precision resolves.

    See Also
    --------
    asperity.strip_chain : the continuous strip.
    asperity.assess : the ratchet verdict under load cycles.

    Notes
    -----
    With ``mu+ > mu-`` the elastic limit is
    :math:`\\Delta T_c = \\mu^- N (1/k + 2/k_t) / (\\alpha_T l_0)`; the bar ratchets iff
    ``dT_max - dT_min > 2 dT_c``, by ``-alpha_T l0 (dT_max - dT_min - 2 dT_c)`` per cycle
    once stabilised.

    Examples
    --------
    SPEC.md's check values, ``dT_c = 0.1 * 100 * (1e-6 + 4e-6) / 1.2e-6 = 41.67`` K:

    >>> ch = asperity.two_node_chain(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0,
    ...                              mu_plus=0.2, mu_minus=0.1)
    >>> ch.kind, ch.n, ch.cp, ch.cm
    ('two-node', 2, array([20., 20.]), array([10., 10.]))
    >>> v = asperity.assess(ch, asperity.Loading.cycles_between(0.0, 125.0))
    >>> print(f"{v['dT_c_K']:.2f} K")
    41.67 K
    """
    k, l0, k_t, N = (check_param(name, v, TWO_NODE[name])
                     for name, v in (("k", k), ("l0", l0), ("k_t", k_t), ("N", N)))
    alpha_T = check_alpha_T("alpha_T", alpha_T)
    mp, mm = check_mu("mu_plus", mu_plus), check_mu("mu_minus", mu_minus)
    Nn = np.array([N, N])
    return _built("two-node", np.array([0.0, l0]), np.array([k]), np.array([l0]),
                  np.array([k_t, k_t]), mp, mm, Nn, np.array([0.5, 0.5]), alpha_T,
                  {"k": k, "l0": l0, "alpha_T": alpha_T, "k_t": k_t, "N": N,
                   "normal_loads": Nn})


def strip_chain(h, E, p, l, k_t, alpha_T, n, mu_plus, mu_minus) -> Chain:
    """The continuous strip of Antoni et al. on an elastic bed, discretised into nodes.

    A strip (per unit width) of thickness ``h`` and modulus ``E`` on a tangential bed of
    stiffness ``k_t`` per unit area under the pressure ``p``, free ends, cut into ``n``
    equally spaced nodes: linear elements of stiffness ``E h / dx``; node ``i`` carries the
    bed over its tributary length (``dx``, ``dx/2`` at the free ends): stiffness
    ``k_t dx``, normal load ``p dx`` (lumped).

    Parameters
    ----------
    h : float
        Thickness, m, in [1e-7, 10].
    E : float
        Young's modulus, Pa, in [1e4, 1e13].
    p : float
        Contact pressure, Pa, in [1e-3, 1e10].
    l : float
        Length along the slip axis, m, in [1e-6, 1e3].
    k_t : float
        Tangential bed stiffness per unit area, Pa/m, in [1e3, 1e20].
    alpha_T : float
        Expansion coefficient relative to the support, 1/K, signed: ``|alpha_T|`` in
        [1e-9, 1e-3].
    n : int
        Nodes, in [2, 1e6].
    mu_plus : float
        Coefficient resisting sliding towards +x, in [1e-6, 1e4], or inf (self-locking).
    mu_minus : float
        Coefficient resisting sliding towards -x, in [1e-6, 1e4], or inf.

    Returns
    -------
    Chain
        The strip (``kind`` ``"strip"``); forces per unit width (N/m).

    Raises
    ------
    InputError
        If a value is out of its range, or the element/contact stiffness ratio (``(lam
        dx)^-2`` and ``(lam dx)^2``, at most 1e9) or ``mu+ / mu-`` (at most 1e3) is beyond
        what double precision resolves.

    See Also
    --------
    asperity.two_node_chain : the two-node model.
    asperity.assess : the ratchet verdict under load cycles.

    Notes
    -----
    Shear lag with :math:`\\lambda = \\sqrt{k_t / (E h)}`: the end whose slip the smaller
    coefficient resists (``x = 0`` on heating when ``mu- < mu+`` and ``alpha_T > 0``)
    starts slipping at
    :math:`\\Delta T_c = \\mu p \\lambda \\coth(\\lambda l / 2) / (|\\alpha_T| k_t)`,
    ``mu = min(mu+, mu-)`` (SPEC.md 5); the nodes converge to it.
    ``dT_max - dT_min > 2 dT_c`` is necessary but not sufficient for a strip to ratchet.

    Examples
    --------
    The bushing of ``surfaces/bushing-strip.toml`` (illustrative values), 201 nodes:
    ``dT_c`` = 2.9538 K in closed form, 2.9543 K with the nodes; 0 -> 120 K cycles walk
    about 0.27 um per cycle:

    >>> s = asperity.strip_chain(h=2.5e-3, E=1.1e11, p=5e6, l=0.04, k_t=1e13,
    ...                          alpha_T=6e-6, n=201, mu_plus=0.185697, mu_minus=0.193238)
    >>> v = asperity.assess(s, asperity.Loading.cycles_between(0.0, 120.0), 1e6,
    ...                     tolerance=1e-4)
    >>> v["verdict"], round(v["dT_c_K"], 4), v["cycles_to_tolerance"]
    ('ratchet', 2.9543, 364)
    >>> print(f"{v['drift_per_cycle_m']:.2e} m per cycle")
    2.75e-07 m per cycle
    """
    h, E, p, l, k_t = (check_param(name, v, STRIP[name]) for name, v in
                       (("h", h), ("E", E), ("p", p), ("l", l), ("k_t", k_t)))
    alpha_T = check_alpha_T("alpha_T", alpha_T)
    n = check_nodes("n", n)
    mp, mm = check_mu("mu_plus", mu_plus), check_mu("mu_minus", mu_minus)
    dx = l / (n - 1)
    trib = np.full(n, dx)
    trib[0] = trib[-1] = 0.5 * dx
    Nn = p * trib
    return _built("strip", np.linspace(0.0, l, n), np.full(n - 1, E * h / dx),
                  np.full(n - 1, dx), k_t * trib, mp, mm, Nn, trib / l, alpha_T,
                  {"h": h, "E": E, "p": p, "l": l, "k_t": k_t, "alpha_T": alpha_T, "n": n,
                   "normal_loads": Nn})


def is_uniform(chain: Chain) -> bool:
    """The chain is uniform: every element has the same kb le (so the same thermal force),
    and each node's contact stiffness and thresholds are in one proportion to its tributary
    length (the half-lengths of its elements), as in the two-node model and the strip.
    Along a load segment whose external force does not change, no slider of such a chain
    stops sliding inside the segment, so the march takes the segment in one increment
    (:mod:`._march_kernels`); other chains are marched event by event."""
    memo = chain.__dict__.get("_uniform")
    if memo is not None:
        return memo
    kl = chain.kb * chain.le
    trib = np.zeros(chain.n)
    trib[:-1] += 0.5 * chain.le
    trib[1:] += 0.5 * chain.le

    def even(a):
        a = a[np.isfinite(a)] if np.isinf(a).any() else a
        return a.size == 0 or bool(np.ptp(a) <= 1e-9 * np.abs(a).max())
    ok = bool(even(kl) and all(even(a / trib) for a in (chain.kt, chain.cp, chain.cm))
              and all(np.isinf(a).all() or np.isfinite(a).all() for a in (chain.cp, chain.cm)))
    chain.__dict__["_uniform"] = ok
    return ok


def elastic_limit(chain: Chain, sign: float = 1.0) -> float:
    """dT_c of the chain: the size of the temperature change (heating if ``sign`` = +1,
    cooling if -1), from the stress-free state without external force, at which the first
    slider slips (K, > 0 whatever the sign of alpha_T; inf if none ever does)."""
    from ._chain_kernels import solve_chain
    check_instance("chain", chain, Chain)
    if isinstance(sign, bool) or sign not in (1, -1, 1.0, -1.0):
        raise InputError(f"sign must be 1 (heating) or -1 (cooling), got {sign!r}")
    memo = chain.__dict__.setdefault("_elastic_limit", {})   # a chain is immutable
    if float(sign) in memo:
        return memo[float(sign)]
    n = chain.n
    u = np.empty(n)
    solve_chain(chain.kb, chain.kt, chain.alpha_T * chain.le * sign, np.zeros(n),
                np.zeros(n, np.int64), np.empty(n), np.empty(n), u)
    q = chain.kt * u                                     # contact forces per K
    with np.errstate(divide="ignore", over="ignore"):
        lim = np.where(q > 0, chain.cp / np.where(q > 0, q, 1.0),
                       np.where(q < 0, chain.cm / np.where(q < 0, -q, 1.0), np.inf))
    memo[float(sign)] = float(lim.min())
    return memo[float(sign)]
