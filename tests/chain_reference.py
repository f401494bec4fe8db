"""An independent, exact, event-driven quasi-static reference for the slider chains of SPEC.md
section 5 (tests only; written from the model, not from the package's solvers).

The model.  n nodes on the x axis; element e joins nodes e and e + 1 with the force
``N_e = kb_e (u_{e+1} - u_e - alpha_T le_e dT)``; node i carries a contact spring kt_i in
series with a slider at s_i, contact force ``q_i = kt_i (u_i - s_i)`` in ``[-cm_i, cp_i]``
(either bound may be +inf: that side never slides).  A slider moves towards +x only while
q_i = cp_i, towards -x only while q_i = -cm_i.  Equilibrium of node i:
``N_i - N_{i-1} - q_i + F fw_i = 0`` (no element beyond the ends).  Everything starts
stress-free at u = s = 0, (dT, F) = (0, 0).

The march.  In matrix form ``Kb u + q = T dT + fw F`` (Kb the elements' stiffness, T the
nodal force per kelvin), so the sliders' positions and the load fix the state.  Along a
linear load segment (lambda from 0 to 1) the sliders at a threshold (set A, sign sigma = +1
at cp, -1 at -cm) solve a rate problem: each either slides at constant force (q'_i = 0,
sigma_i s'_i >= 0) or sticks (s'_i = 0, sigma_i q'_i <= 0), the others stick, and
``Kb u' + q' = T dT' + fw F'``.  This linear complementarity problem (in z = sigma s'_A,
w = -sigma q'_A) has a positive definite matrix unless A holds every node (the condensed
contact stiffness is singular only for the rigid translation): it is solved by Murty's
least-index principal pivoting from the previous sliding set (every subset as a last
resort), each trial a tridiagonal solve, and every condition is verified exactly.  When
every slider is at a threshold, either the contact forces all stay (only without a change
of F; the rigid translation is then free within the sliding directions and the rate of
least motion, min sum kt u'^2, is taken: the limit of a small viscosity proportional to
kt), or some slider j sticks (pivoting on the others, each j in turn); else there is no
equilibrium (:class:`ReferenceSlideOff`).  The rates are constant until a slider reaches
a threshold (an event); the state is advanced exactly there and the rate problem solved
again.  All arithmetic is in ``fractions.Fraction`` built exactly from the floats given
(or taken as they are when given as Fractions); +inf thresholds are kept as None.

    res = exact_march(kb, le, kt, cp, cm, fw, alpha_T, [(0.0, 0.0), (30.0, 0.0)], 5, weight)
    res.drift, res.mean_u, res.u, res.s, res.q, res.events     # exact (Fractions)
    res.drift_f, res.mean_u_f, res.u_f, res.s_f, res.q_f       # the same as floats/NumPy

``march(chain, loading, cycles)`` does the same for an asperity Chain and Loading;
``asymmetric_thresholds(chain.cm, Fraction(1, 10**12))`` gives thresholds exactly
mu+ = mu- (1 + r) for the nearly symmetric cases.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

ZERO = Fraction(0)
MAX_STEPS_PER_SEGMENT = 100_000


class ReferenceSlideOff(Exception):
    """No equilibrium: the external force exceeds what the sliders can hold."""


@dataclass(frozen=True)
class Event:
    """A slider reaching a threshold: cycle (0 = the lead-in), segment of the cycle, lambda
    on it, the load (dT, F) there, and the (node, +1 | -1) pairs that reached cp | -cm."""

    cycle: int
    segment: int
    lam: Fraction
    dT: Fraction
    F: Fraction
    hits: tuple


@dataclass
class ExactResult:
    """States at the end of the lead-in (index 0) and of every cycle (index k): node
    displacements u, slider positions s, contact forces q (lists of n Fractions), assembly
    displacement mean_u = sum weight_i u_i, drift = mean_u[-1] - mean_u[-2] (None with no
    cycle), every event, and the numbers of rate problems solved."""

    u: list
    s: list
    q: list
    mean_u: list
    events: list = field(default_factory=list)
    rate_solves: int = 0

    @property
    def drift(self):
        return self.mean_u[-1] - self.mean_u[-2] if len(self.mean_u) > 1 else None

    @property
    def n_events(self) -> int:
        return len(self.events)

    drift_f = property(lambda self: None if self.drift is None else float(self.drift))
    mean_u_f = property(lambda self: np.array([float(x) for x in self.mean_u]))
    u_f = property(lambda self: _floats(self.u))
    s_f = property(lambda self: _floats(self.s))
    q_f = property(lambda self: _floats(self.q))


def _floats(rows) -> np.ndarray:
    return np.array([[float(x) for x in row] for row in rows])


def _exact(name, x, inf_ok=False):
    if isinstance(x, Fraction):
        return x
    x = float(x)
    if math.isinf(x) and x > 0 and inf_ok:
        return None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite{' or +inf' if inf_ok else ''}, got {x!r}")
    return Fraction(x)


def _vec(name, a, size, inf_ok=False):
    a = list(a) if isinstance(a, (list, tuple)) else np.asarray(a, dtype=float).ravel().tolist()
    if len(a) != size:
        raise ValueError(f"{name} must have {size} entries, got {len(a)}")
    return [_exact(f"{name}[{i}]", x, inf_ok) for i, x in enumerate(a)]


# ----------------------------------------------------------------------- exact linear algebra

def solve(A, b):
    """x with A x = b (Gaussian elimination on Fractions; A square and nonsingular)."""
    m = len(b)
    R = [list(A[i]) + [b[i]] for i in range(m)]
    for c in range(m):
        p = next(r for r in range(c, m) if R[r][c] != 0)
        R[c], R[p] = R[p], R[c]
        piv = R[c][c]
        for r in range(c + 1, m):
            f = R[r][c] / piv
            if f:
                R[r] = [x - f * y for x, y in zip(R[r], R[c])]
    x = [ZERO] * m
    for c in reversed(range(m)):
        x[c] = (R[c][m] - sum(R[c][j] * x[j] for j in range(c + 1, m))) / R[c][c]
    return x


def matvec(A, x):
    return [sum((a * y for a, y in zip(row, x)), ZERO) for row in A]


# ----------------------------------------------------------------------------------- the march

class _Chain:
    """The exact chain: Kb (elements), kt, thresholds (None = +inf), T (nodal force per K)."""

    def __init__(self, kb, le, kt, cp, cm, fw, alpha_T, weight):
        n = len(kt)
        if n < 2:
            raise ValueError("a chain needs at least 2 nodes")
        self.n = n
        self.kb, self.le = _vec("kb", kb, n - 1), _vec("le", le, n - 1)
        self.kt = _vec("kt", kt, n)
        self.cp, self.cm = _vec("cp", cp, n, True), _vec("cm", cm, n, True)
        self.fw, self.weight = _vec("fw", fw, n), _vec("weight", weight, n)
        self.alpha_T = _exact("alpha_T", alpha_T)
        for name in ("kb", "le", "kt", "cp", "cm"):
            if any(x is not None and x <= 0 for x in getattr(self, name)):
                raise ValueError(f"{name} must be > 0 everywhere")
        Kb = [[ZERO] * n for _ in range(n)]
        T = [ZERO] * n
        for e, k in enumerate(self.kb):
            Kb[e][e] += k
            Kb[e + 1][e + 1] += k
            Kb[e][e + 1] -= k
            Kb[e + 1][e] -= k
            f = k * self.alpha_T * self.le[e]
            T[e] -= f
            T[e + 1] += f
        self.Kb, self.T = Kb, T
        self.cache = {}

    def at_threshold(self, q):
        """((node, +1), ...) at q = cp, ((node, -1), ...) at q = -cm, in node order."""
        out = []
        for i in range(self.n):
            if self.cp[i] is not None and q[i] == self.cp[i]:
                out.append((i, 1))
            elif self.cm[i] is not None and q[i] == -self.cm[i]:
                out.append((i, -1))
        return tuple(out)

    def trial(self, S, b):
        """Rates with the sliders S sliding at constant force (q'_i = 0) and every other one
        stuck (s'_i = 0):  (Kb + Kt outside S) u' = b.  None if singular (S = every node)."""
        if len(S) == self.n:
            return None
        Km = [list(row) for row in self.Kb]
        for i in range(self.n):
            if i not in S:
                Km[i][i] += self.kt[i]
        udot = solve(Km, b)
        sdot = [udot[i] if i in S else ZERO for i in range(self.n)]
        return udot, sdot, [k * (a - c) for k, a, c in zip(self.kt, udot, sdot)]

    def rates(self, A, ddT, dF, guess):
        """(u', s', q') per unit lambda with the sliders A = ((node, sign), ...) at a
        threshold, for the load rates (ddT, dF); ``guess``: nodes thought to slide.

        The complementarity problem in z = sigma s'_A, w = -sigma q'_A has a positive
        definite matrix unless A is every node: Murty's least-index principal pivoting
        (finite for such matrices) from the guessed basis, every subset as a last resort."""
        key = (A, ddT, dF)
        if key not in self.cache:
            b = [t * ddT + w * dF for t, w in zip(self.T, self.fw)]
            if len(A) == self.n:
                out = self._all_at_threshold(A, b, dF, guess)
            else:
                out = self._pivot(A, b, guess)
            _verify(self, A, b, *out)
            self.cache[key] = out
        return self.cache[key]

    def _pivot(self, A, b, guess):
        def violated(S):
            out = self.trial(S, b)
            bad = [a for a, (i, c) in enumerate(A)
                   if (c * out[1][i] < 0 if i in S else c * out[2][i] > 0)]
            return out, bad

        nodes = [i for i, _ in A]
        S = {i for i in nodes if i in guess}
        for _ in range(4 * len(A) ** 2 + 10):
            out, bad = violated(S)
            if not bad:
                return out
            S ^= {nodes[bad[0]]}
        for k in range(len(A) + 1):                  # never needed in theory: a last resort
            for S in itertools.combinations(nodes, k):
                out, bad = violated(set(S))
                if not bad:
                    return out
        raise ArithmeticError("no solution of a positive definite LCP: a bug in the reference")

    def _all_at_threshold(self, A, b, dF, guess):
        """Every slider at a threshold.  Either every contact force stays (q' = 0: only if
        dF = 0; the rigid translation t is then free within the sliding directions and the
        rate of least motion, min sum kt u'^2, is taken), or some slider j sticks (the
        problem on the others is positive definite); else no equilibrium: slide-off."""
        n, sg = self.n, [c for _, c in A]
        if dF == 0:
            Km = [list(row) for row in self.Kb]     # Kb u' = b with u'_0 = 0, then u' + t
            Km[0] = [Fraction(int(j == 0)) for j in range(n)]
            up = solve(Km, [ZERO] + b[1:])
            lo = max((-up[i] for i in range(n) if sg[i] > 0), default=None)
            hi = min((-up[i] for i in range(n) if sg[i] < 0), default=None)
            if lo is None or hi is None or lo <= hi:
                t = -sum(k * x for k, x in zip(self.kt, up)) / sum(self.kt)
                t = t if lo is None else max(t, lo)
                t = t if hi is None else min(t, hi)
                udot = [x + t for x in up]
                return udot, list(udot), [ZERO] * n
        for j in range(n):                          # slider j sticks, the others: pivoting
            udot, sdot, qdot = self._pivot(A[:j] + A[j + 1:], b, guess)
            if sg[j] * qdot[j] <= 0:
                return udot, sdot, qdot
        raise ReferenceSlideOff("no equilibrium with every slider at its threshold")


def _verify(ch, A, b, udot, sdot, qdot):
    """Every condition of the rate problem, exactly: equilibrium Kb u' + q' = b, the contact
    law q' = kt (u' - s'), and the complementarity of each slider."""
    res = [x + y - z for x, y, z in zip(matvec(ch.Kb, udot), qdot, b)]
    law = [q - k * (u - s) for q, k, u, s in zip(qdot, ch.kt, udot, sdot)]
    on = dict(A)
    comp = [(sd == 0) if on.get(i) is None else
            (on[i] * sd >= 0 and on[i] * qd <= 0 and sd * qd == 0)
            for i, (sd, qd) in enumerate(zip(sdot, qdot))]
    if any(res) or any(law) or not all(comp):
        raise ArithmeticError("the rate problem is not solved: a bug in the reference")


def exact_march(kb, le, kt, cp, cm, fw, alpha_T, points, cycles, weight) -> ExactResult:
    """March the chain exactly: a lead-in from (dT, F) = (0, 0) to points[0], then the closed
    cycle points[0] -> points[1] -> ... -> points[-1] -> points[0], ``cycles`` times.

    kb, le : (n-1,) element stiffness and length;  kt, cp, cm, fw, weight : (n,) contact
    stiffness, thresholds mu+ N_i and mu- N_i (+inf: never slides that way), share of the
    external force, share in the assembly displacement;  alpha_T : 1/K;  points : sequence
    of (dT, F) (a repeated closing point is a zero-length segment and skipped).
    Raises :class:`ReferenceSlideOff` when no equilibrium exists.
    """
    ch = _Chain(kb, le, kt, cp, cm, fw, alpha_T, weight)
    pts = [(_exact("dT", a), _exact("F", b)) for a, b in points]
    if not pts or int(cycles) != cycles or cycles < 0:
        raise ValueError("points must not be empty and cycles must be a whole number >= 0")
    n = ch.n
    st = {"u": [ZERO] * n, "s": [ZERO] * n, "q": [ZERO] * n, "load": (ZERO, ZERO),
          "sliding": set()}
    res = ExactResult([], [], [], [])

    def record():
        res.u.append(list(st["u"]))
        res.s.append(list(st["s"]))
        res.q.append(list(st["q"]))
        res.mean_u.append(sum(w * x for w, x in zip(ch.weight, st["u"])))

    _segment(ch, st, pts[0], res, 0, 0)
    record()
    for c in range(1, int(cycles) + 1):
        for j in range(len(pts)):
            _segment(ch, st, pts[(j + 1) % len(pts)], res, c, j)
        record()
    return res


def _segment(ch, st, end, res, cycle, seg):
    (T0, F0), (T1, F1) = st["load"], end
    ddT, dF = T1 - T0, F1 - F0
    if ddT == 0 and dF == 0:
        return
    lam = ZERO
    u, s, q = st["u"], st["s"], st["q"]
    for _ in range(MAX_STEPS_PER_SEGMENT):
        A = ch.at_threshold(q)
        try:
            udot, sdot, qdot = ch.rates(A, ddT, dF, st["sliding"])
        except ReferenceSlideOff:
            raise ReferenceSlideOff(
                f"slide-off at dT = {float(T0 + lam * ddT):.9g} K, F = {float(F0 + lam * dF):.9g}"
                f" (cycle {cycle}, segment {seg}): the external force exceeds the sliders' "
                f"thresholds") from None
        res.rate_solves += 1
        st["sliding"] = {i for i in range(ch.n) if sdot[i] != 0}
        step, hits = 1 - lam, []
        for i in range(ch.n):
            if qdot[i] > 0 and ch.cp[i] is not None and q[i] < ch.cp[i]:
                t, c = (ch.cp[i] - q[i]) / qdot[i], 1
            elif qdot[i] < 0 and ch.cm[i] is not None and q[i] > -ch.cm[i]:
                t, c = (-ch.cm[i] - q[i]) / qdot[i], -1
            else:
                continue
            if t < step:
                step, hits = t, [(i, c)]
            elif t == step:
                hits.append((i, c))
        for i in range(ch.n):
            u[i] += udot[i] * step
            s[i] += sdot[i] * step
            q[i] += qdot[i] * step
        lam += step
        if hits:
            st["sliding"] |= {i for i, _ in hits}
            res.events.append(Event(cycle, seg, lam, T0 + lam * ddT, F0 + lam * dF,
                                    tuple(hits)))
        if lam == 1:
            st["load"] = end
            return
    raise ArithmeticError(f"more than {MAX_STEPS_PER_SEGMENT} events on one load segment")


def equilibrium_residual(kb, le, kt, fw, alpha_T, u, s, q, dT, F):
    """Exact residuals (node equilibrium, contact law q = kt (u - s)) of a state: all zero
    for a state in equilibrium.  Independent of the march's matrices."""
    kb, le, kt, fw = (_vec(nm, a, len(a)) for nm, a in
                      (("kb", kb), ("le", le), ("kt", kt), ("fw", fw)))
    aT, dT, F = _exact("alpha_T", alpha_T), Fraction(dT), Fraction(F)
    n = len(kt)
    Ne = [kb[e] * (u[e + 1] - u[e] - aT * le[e] * dT) for e in range(n - 1)]
    eq = [(Ne[i] if i < n - 1 else 0) - (Ne[i - 1] if i > 0 else 0) - q[i] + F * fw[i]
          for i in range(n)]
    law = [q[i] - kt[i] * (u[i] - s[i]) for i in range(n)]
    return eq + law


def march(chain, loading, cycles) -> ExactResult:
    """exact_march on an asperity Chain and Loading (its breakpoints; substeps are moot)."""
    pts = list(zip(loading.dT.tolist(), loading.F.tolist()))
    return exact_march(chain.kb, chain.le, chain.kt, chain.cp, chain.cm, chain.fw,
                       chain.alpha_T, pts, cycles, chain.weight)


def asymmetric_thresholds(base, r, sign=1):
    """(cp, cm) as Fractions: ``base`` (the thresholds of mu N) on one side and exactly
    (1 + r) times it on the other (cp if sign > 0, cm if sign < 0); r a Fraction (or float)."""
    low = [Fraction(float(x)) for x in base]
    high = [x * (1 + Fraction(r)) for x in low]
    return (high, low) if sign > 0 else (low, high)


if __name__ == "__main__":        # the reference's speed: python -m tests.chain_reference
    import time

    from asperity.microslip.chains import elastic_limit, strip_chain, two_node_chain
    from asperity.microslip.loading import Loading

    kts = (3.54 / 0.1) ** 2 * 2e11 * 2e-3
    for name, c, m in (("two-node", two_node_chain(1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1), 1.5),
                       *((f"strip n={n}", strip_chain(2e-3, 2e11, 1e6, 0.1, kts, 1.2e-5, n, 0.2,
                                                      0.1), 40) for n in (11, 15))):
        L = Loading.cycles_between(0.0, 2 * m * elastic_limit(c))
        t0 = time.perf_counter()
        r = march(c, L, 5)
        print(f"{name:10s} margin {m:4}, 5 cycles: {time.perf_counter() - t0:.3f} s, "
              f"{r.n_events} events, drift {r.drift_f:.6g} m per cycle")
