"""The crawl's Newton-Euler equations integrated by an adaptive ODE solver, beside the
Moreau solver (issue 26's speed target: at least 50x faster than an adaptive ODE).

    python benchmarks/bench_crawl_ode.py [--points 201] [--periods 8] [--eps 1e-3] [--json]

The same equations as asperity.crawling.solver (curvature wave A = 7, k = 1, L = 1 m,
T = 1 s, g = 9.81, componentwise 0.1 : 0.15 : 0.2 with the law on the body), but the law
regularised as an ODE needs it: the unit slip gamma / |gamma| replaced by
gamma / sqrt(|gamma|^2 + eps^2) (eps in m/s).  The gait's tables (positions, velocities,
tangents, inertia and spin and their rates) are precomputed on 4000 instants a period and
interpolated linearly, so the ODE's right-hand side costs what the Moreau step's sums
cost.  scipy's solve_ivp with LSODA (stiff for small eps) and RK45, rtol 1e-6,
atol 1e-9; the speed in body lengths per period over the second half of the periods."""
from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=201)
    ap.add_argument("--periods", type=int, default=8)
    ap.add_argument("--eps", type=float, default=1e-3, help="regularisation (m/s)")
    ap.add_argument("--methods", default="LSODA,RK45")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    from scipy.integrate import solve_ivp

    from asperity.crawling.gait import CurvatureWave
    from asperity.crawling.solver import coefficient_law, crawl
    n, P, eps, g = args.points, args.periods, args.eps, 9.81
    gait = CurvatureWave()
    K = 4000
    tk = np.arange(K + 1) / K
    kin = gait.kinematics(tk, n)
    w = kin.weights
    dI = np.gradient(kin.inertia, tk)
    dS = np.gradient(kin.spin, tk)
    mu_f, mu_b, mu_t = 0.1, 0.15, 0.2

    def rhs(t, y):
        x = (t % 1.0) * K
        k = min(int(x), K - 1)
        f = x - k
        r = (1 - f) * kin.r[k] + f * kin.r[k + 1]
        v = (1 - f) * kin.v[k] + f * kin.v[k + 1]
        tau = (1 - f) * kin.tangent[k] + f * kin.tangent[k + 1]
        inertia = (1 - f) * kin.inertia[k] + f * kin.inertia[k + 1]
        di = (1 - f) * dI[k] + f * dI[k + 1]
        ds = (1 - f) * dS[k] + f * dS[k + 1]
        th, vx, vy, om = y[2], y[3], y[4], y[5]
        c, s = math.cos(th), math.sin(th)
        ox = c * r[:, 0] - s * r[:, 1]
        oy = s * r[:, 0] + c * r[:, 1]
        gx = vx - om * oy + c * v[:, 0] - s * v[:, 1]
        gy = vy + om * ox + s * v[:, 0] + c * v[:, 1]
        a = th + tau                                   # the law along the tangent
        ca, sa = np.cos(a), np.sin(a)
        lx = ca * gx + sa * gy
        ly = -sa * gx + ca * gy
        nrm = np.sqrt(lx * lx + ly * ly + eps * eps)
        fx_l = np.where(lx >= 0, mu_f, mu_b) * lx / nrm
        fy_l = mu_t * ly / nrm
        fx = -(ca * fx_l - sa * fy_l) * w * g          # per unit mass
        fy = -(sa * fx_l + ca * fy_l) * w * g
        torque = float(np.sum(ox * fy - oy * fx))
        return [vx, vy, om, float(fx.sum()), float(fy.sum()),
                (torque - di * om - ds) / inertia]

    out = {"points": n, "periods": P, "eps_m_s": eps}
    law = coefficient_law(mu_f, mu_b, mu_t)
    crawl(law, points=n, periods=1)                    # compile
    from asperity.crawling import solver
    solver._TABLES.clear()
    t0 = time.perf_counter()
    res = crawl(law, points=n, periods=P)
    out["moreau_s"] = time.perf_counter() - t0
    out["moreau_speed"] = res.speed_body_lengths_per_period
    for method in args.methods.split(","):
        t0 = time.perf_counter()
        sol = solve_ivp(rhs, (0.0, float(P)), np.zeros(6), method=method, rtol=1e-6,
                        atol=1e-9, dense_output=True)
        el = time.perf_counter() - t0
        half = P // 2
        speeds = []
        for p in range(half, P):
            ts = np.linspace(p, p + 1, 201)
            ys = sol.sol(ts)
            th = ys[2].mean()
            d = ys[:2, -1] - ys[:2, 0]
            speeds.append(d[0] * math.cos(th) + d[1] * math.sin(th))
        out[method] = {"s": el, "rhs_evaluations": int(sol.nfev), "status": int(sol.status),
                       "speed": float(np.mean(speeds)),
                       "moreau_speedup": el / out["moreau_s"]}
    print(json.dumps(out, indent=2) if args.json else out)


if __name__ == "__main__":
    main()
