"""Numba kernel of the two-node model's closed form, for a block of cases at once
(:mod:`asperity.microslip.two_node_batch` wraps it; physics in SPEC.md section 5).

The two-node chain (bar of stiffness k and length l0 between two contacts of stiffness k_t,
thresholds cp = mu+ N and cm = mu- N, the external force F shared f0 = fw0 F, f1 = fw1 F)
has one internal force: the bar's tension B, with the contact forces q0 = B + f0 and
q1 = -B + f1, and with the sliders' positions s0, s1 fixed

    B = K (s1 - s0 - alpha_T l0 dT - (f0 - f1) / k_t),    1 / K = 1 / k + 2 / k_t.

The sliders hold B in [Lo, Hi], Hi = min(cp - f0, f1 + cm), Lo = max(-cm - f0, f1 - cp)
(not empty iff -2 cm < F < 2 cp: the capacity).  Both bounds change branch where
F = cp - cm: above it the slider that slides is node 0 towards +x at Hi and node 1 towards +x
at Lo; below it node 1 towards -x at Hi and node 0 towards -x at Lo.  Along a load increment
in which F stays on one side, B, Hi and Lo are linear in the load, so the end state is the
elastic predictor clamped to the end bounds (a one-dimensional play operator: the predictor
crosses a bound at most once), and the slip is the clamped excess, |dB| / K, on the node of
that bound.  An increment whose force crosses cp - cm is split there.  This is the exact
solution of the rate-independent chain at every load point, as the event-driven march
(:mod:`._march_kernels`) computes it, up to rounding.

Where a decision of the reference path (:func:`asperity.microslip.verdict.assess`) could go
either way within rounding -- a stabilisation, drift, slip or tolerance test within 1e-9 of
its threshold, a ceiling within 1e-9 of a whole number, a tie of the two bounds' branches
under slip (F constant at cp - cm), a margin or ratio at a refusal limit -- the case is
returned as NOT_COVERED and the caller solves it by the exact path.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

#: result codes
CLOSED = 0          # solved here
SLIDES_OFF = 1      # the load exceeds the capacity (check_capacity's outcome)
NOT_COVERED = 2     # the caller runs the exact per-case path
#: a decision within this relative distance of its threshold is left to the exact path
BAND = 1e-9
#: limits.SAME_FRICTION, STIFFNESS_RATIO, ASYMMETRY, MARGIN as literals (numba freezes a
#: global at compile time and its cache would not see limits.py change; a test keeps them
#: equal)
SAME_FRICTION, STIFFNESS_RATIO, ASYMMETRY, MARGIN = 1e-12, 1e9, 1e3, 1e4


@njit(cache=True)
def _near(x, threshold, scale):
    if math.isinf(threshold):
        return False
    return abs(x - threshold) <= BAND * max(abs(threshold), scale)


@njit(cache=True)
def _increment(st, K, kt, cp, cm, fw0, fw1, aTl, dTa, Fa, dTb, Fb, acc):
    """Advance st = [B, s0, s1] from the load (dTa, Fa) to (dTb, Fb); acc[0:2] += |slip| of
    each node.  False: a tie of the bounds' branches under slip (not covered)."""
    Fk = cp - cm                       # the force where both bounds change branch
    if math.isinf(cp) and math.isinf(cm):
        Fk = 0.0                       # never reached: no slider slides
    ts = np.array([0.0, 1.0, 1.0])
    parts = 1
    if (Fa - Fk) * (Fb - Fk) < 0.0:          # F crosses cp - cm: split the increment there
        ts[1] = (Fk - Fa) / (Fb - Fa)
        parts = 2
    ddT = dTb - dTa
    dF = Fb - Fa
    for part in range(parts):
        t0, t1 = ts[part], ts[part + 1]
        F0 = Fa if t0 == 0.0 else Fa + dF * t0
        F1 = Fb if t1 == 1.0 else Fa + dF * t1
        Fm = 0.5 * (F0 + F1)
        dth = aTl * ddT * (t1 - t0)
        ddf = (fw0 - fw1) * dF * (t1 - t0)
        Btr = st[0] + K * (-dth - ddf / kt)
        f0 = fw0 * F1
        f1 = fw1 * F1
        hi = min(cp - f0, f1 + cm)
        lo = max(-cm - f0, f1 - cp)
        B = Btr
        if B > hi:
            B = hi
        elif B < lo:
            B = lo
        dg = (B - Btr) / K             # the sliders' gap s1 - s0 changes by dg
        if dg != 0.0:
            if not math.isinf(Fk) and abs(Fm - Fk) <= BAND * (abs(cp) + abs(cm)):
                return False
            upper = dg < 0.0
            plus = Fm > Fk
            node = 0 if upper == plus else 1
            if plus:
                st[1 + node] += abs(dg)
            else:
                st[1 + node] -= abs(dg)
            acc[node] += abs(dg)
        st[0] = B
    return True


@njit(cache=True)
def two_node_block(k, l0, aT, kt, N, mp, mm, dT, F, substeps, fw0, fw1, cycles, tol,
                   max_marched, no_drift, stabilised, out, code):
    """Closed-form verdict of m two-node cases (arrays (m,), dT and F (m, P) breakpoints).
    out (m, 10): mu_plus, mu_minus, dT_c, margin, drift_per_cycle, drift_after,
    cycles_to_tolerance (NaN: none), stabilised_at (-1: none), extrapolated, verdict
    (0 shakedown, 1 alternating-slip, 2 ratchet, 3 slides-off); code (m,): CLOSED,
    SLIDES_OFF or NOT_COVERED."""
    m = k.size
    P = dT.shape[1]
    sub = substeps
    for c in range(m):
        code[c] = NOT_COVERED
        p_, q_ = mp[c], mm[c]
        if p_ == q_ or (math.isfinite(p_) and math.isfinite(q_)
                        and abs(p_ - q_) <= SAME_FRICTION * max(abs(p_), abs(q_))):
            q_ = p_                        # chains._built: the same coefficient
        # chains._check_resolvable and check_margin refuse: the exact path says why
        ratio = max(k[c] / kt[c], kt[c] / k[c])
        if ratio > STIFFNESS_RATIO * (1.0 - BAND):
            continue
        if math.isfinite(p_) and math.isfinite(q_) and \
                max(p_, q_) > ASYMMETRY * min(p_, q_) * (1.0 - BAND):
            continue
        cp = p_ * N[c]
        cm = q_ * N[c]
        Kc = 1.0 / (1.0 / k[c] + 2.0 / kt[c])
        aTl = aT[c] * l0[c]
        dTc = min(p_, q_) * N[c] * (1.0 / k[c] + 2.0 / kt[c]) / (abs(aT[c]) * l0[c])
        dmax = -np.inf
        dmin = np.inf
        absmax = 0.0
        for j in range(P):
            dmax = max(dmax, dT[c, j])
            dmin = min(dmin, dT[c, j])
            absmax = max(absmax, abs(dT[c, j]))
        rng = dmax - dmin
        margin = rng / (2.0 * dTc) if math.isfinite(dTc) and dTc > 0 else 0.0
        if margin > MARGIN * (1.0 - BAND):
            continue
        out[c, 0] = p_
        out[c, 1] = q_
        out[c, 2] = dTc
        out[c, 3] = margin
        # check_capacity: the load (with the stress-free start) against 2 cp and 2 cm
        fhi = 0.0
        flo = 0.0
        for j in range(P):
            fhi = max(fhi, F[c, j])
            flo = min(flo, F[c, j])
        if _near(fhi, 2.0 * cp, 0.0) or _near(-flo, 2.0 * cm, 0.0):
            continue
        if fhi >= 2.0 * cp or -flo >= 2.0 * cm:
            out[c, 4:9] = np.nan
            out[c, 7] = -1.0
            out[c, 9] = 3.0
            code[c] = SLIDES_OFF
            continue
        scale = abs(aT[c]) * l0[c] * max(rng, absmax)
        el = 0.0
        for th in (cp, cm):
            if math.isfinite(th):
                el = max(el, th / kt[c])
        scale = max(scale, el, 1e-300)
        cap = 0.0
        for th in (cp, cm):
            if math.isfinite(th):
                cap = max(cap, th)
        cap = cap if cap > 0 else 1.0
        st = np.zeros(3)
        acc = np.zeros(2)
        ok = True
        a_dT = 0.0
        a_F = 0.0
        if dT[c, 0] != 0.0 or F[c, 0] != 0.0:                    # the lead-in
            for i in range(1, sub + 1):
                b_dT = 0.0 + (dT[c, 0] - 0.0) * i / sub
                b_F = 0.0 + (F[c, 0] - 0.0) * i / sub
                ok = ok and _increment(st, Kc, kt[c], cp, cm, fw0, fw1, aTl, a_dT, a_F,
                                       b_dT, b_F, acc)
                a_dT, a_F = b_dT, b_F
        ncyc = int(min(max_marched, math.ceil(cycles[c])))
        mean = np.empty(ncyc + 1)
        F0 = F[c, 0]
        mean[0] = 0.5 * (st[1] + (st[0] + fw0 * a_F) / kt[c]) + \
            0.5 * (st[2] + (-st[0] + fw1 * a_F) / kt[c])
        qp0 = st[0] + fw0 * a_F
        qp1 = -st[0] + fw1 * a_F
        stab = -1
        slip = False
        slip_near = False
        kk = 0
        for cyc in range(1, ncyc + 1):
            smax = 0.0
            for j in range(P - 1):
                for i in range(1, sub + 1):
                    b_dT = dT[c, j] + (dT[c, j + 1] - dT[c, j]) * i / sub
                    b_F = F[c, j] + (F[c, j + 1] - F[c, j]) * i / sub
                    acc[0] = 0.0
                    acc[1] = 0.0
                    ok = ok and _increment(st, Kc, kt[c], cp, cm, fw0, fw1, aTl, a_dT, a_F,
                                           b_dT, b_F, acc)
                    smax = max(smax, acc[0], acc[1])
                    a_dT, a_F = b_dT, b_F
            q0 = st[0] + fw0 * F0
            q1 = -st[0] + fw1 * F0
            mean[cyc] = 0.5 * (st[1] + q0 / kt[c]) + 0.5 * (st[2] + q1 / kt[c])
            kk = cyc
            thr = no_drift * scale
            slip_near = _near(smax, thr, 1e-3 * scale)      # decides the last cycle only
            slip = smax > thr
            dq = max(abs(q0 - qp0), abs(q1 - qp1))
            if _near(dq, stabilised * cap, cap * 1e-3):
                ok = False
            if dq <= stabilised * cap:
                stab = cyc if stab < 0 else stab
                if cyc >= 2:
                    break
            else:
                stab = -1
            qp0, qp1 = q0, q1
        if not ok or slip_near:
            continue
        d = mean[kk] - mean[kk - 1]
        if _near(abs(d), no_drift * scale, 1e-3 * scale):
            continue
        if abs(d) <= no_drift * scale:
            d = 0.0
        cyc_f = cycles[c]
        if cyc_f <= kk and cyc_f == math.floor(cyc_f):
            after = mean[int(cyc_f)]
        else:
            after = mean[kk] + (cyc_f - kk) * d
        to = np.nan
        if not math.isnan(tol[c]):
            hit = -1
            for i in range(kk + 1):
                if _near(abs(mean[i]), tol[c], 0.0):
                    ok = False
                if abs(mean[i]) >= tol[c] and hit < 0:
                    hit = i
            if hit >= 0:
                to = float(hit)
            elif d != 0.0:
                mk = mean[kk]
                same = mk == 0.0 or (mk > 0) == (d > 0)
                x = (tol[c] - abs(mk)) / abs(d) if same else (tol[c] + abs(mk)) / abs(d)
                if abs(mk) <= BAND * scale or abs(x - round(x)) <= BAND * max(1.0, abs(x)):
                    ok = False
                to = float(kk + max(math.ceil(x), 1))
        if not ok:
            continue
        out[c, 4] = d
        out[c, 5] = after
        out[c, 6] = to
        out[c, 7] = float(stab)
        out[c, 8] = 1.0 if cyc_f > kk else 0.0
        out[c, 9] = 2.0 if d != 0.0 else (1.0 if slip else 0.0)
        code[c] = CLOSED
