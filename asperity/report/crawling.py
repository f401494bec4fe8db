"""Report section: crawling (issue 26).  A body bending with the curvature wave
kappa L = A cos 2 pi (k s / L + t / T) on three friction coefficients: the tube limit
(speed against mu_t / mu_f for the three rules, against J0(A / 2 pi k) / k), the three
rules on the same coefficients, the quasi-static speed against the dynamic one over the
Froude number, and PyElastica's continuum snake side by side (its speed and wall time
read from benchmarks/crawl_pyelastica_results.json, which benchmarks/crawl_pyelastica.py
writes; PyElastica is the benchmark's, not the package's)."""
from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

A, K = 7.0, 1.0
RULES = ("componentwise", "associated", "colinear")
#: mu_t / mu_f of the tube limit (mu_b = mu_f); the colinear rule's own, fewer (below)
RATIOS = (1.0, 1.5, 2.0, 3.0, 5.0, 10.0, 30.0, 100.0, 1000.0)
#: the colinear rule's quasi-static solve is slow past mu_t / mu_f = 3 (tens of seconds a
#: run, some steps not converged at 100 points): its ratios, and one far point on 50 points
COLINEAR_RATIOS = (1.0, 1.5, 2.0, 3.0)
COLINEAR_FAR = (1000.0, 50, 200)
#: the three rules on the same coefficients (mu_f, mu_b, mu_t)
SPREAD = ((0.1, 0.15, 0.2), (0.1, 0.1, 0.3), (0.1, 0.2, 0.3), (0.2, 0.3, 0.1))
#: Froude numbers of the dynamic runs (coefficients SPREAD[0], componentwise, L = 1 m)
FROUDE = (0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0)
POINTS, STEPS = 100, 400
BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "crawl_pyelastica_results.json"


def tube_limit(amplitude: float = A, waves: float = K) -> float:
    """J0(A / 2 pi k) / k: body lengths a period of a body sliding along its own track."""
    from scipy.special import j0
    return float(j0(amplitude / (2 * math.pi * waves)) / waves)


def _qs(mu_f, mu_b, mu_t, rule, points=POINTS, steps=STEPS):
    from ..crawling.solver import coefficient_law, crawl
    return crawl(coefficient_law(mu_f, mu_b, mu_t, rule), amplitude=A, waves=K,
                 quasi_static=True, points=points, steps_per_period=steps)


def _speed(res) -> str:
    return f"{res.speed_body_lengths_per_period:+.4f}" if res.ok else \
        f"({res.speed_body_lengths_per_period:+.4f}, {res.status})"


def tube(folder: Path) -> list[str]:
    plt = _pyplot()
    limit = tube_limit()
    runs = {r: {x: _qs(0.1, 0.1, 0.1 * x, r) for x in
                (COLINEAR_RATIOS if r == "colinear" else RATIOS)} for r in RULES}
    far_x, far_n, far_steps = COLINEAR_FAR
    far = _qs(0.1, 0.1, 0.1 * far_x, "colinear", far_n, far_steps)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for rule in RULES:
        xs = [x for x, res in runs[rule].items() if res.ok]
        ax.semilogx(xs, [runs[rule][x].speed_body_lengths_per_period for x in xs], "o-",
                    label=f"rule {rule}")
    ax.semilogx([far_x], [far.speed_body_lengths_per_period], "s", color="C2", mfc="none",
                label=f"colinear, {far_n} points, {far_steps} steps")
    ax.axhline(limit, color="k", ls="--", lw=1, label=f"J0(A / 2 pi k) / k = {limit:.4f}")
    ax.set_xlabel("mu_t / mu_f  (mu_b = mu_f = 0.1)")
    ax.set_ylabel("U (body lengths per period)")
    ax.set_title(f"quasi-static, A = {A:g}, k = {K:g}, {POINTS} points")
    ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, folder / "crawl_tube_limit.png")
    plt.close(fig)
    out = ["### The tube limit", "",
           (f"As mu_t / mu_f grows a body sliding along its own track crawls J0(A / 2 pi k) / k "
           f"body lengths a period: {limit:.4f} for A = {A:g}, k = {K:g}. Quasi-static, "
           f"mu_b = mu_f = 0.1, {POINTS} points, {STEPS} steps a period (U: body lengths a "
           "period, head-ward positive):"), "",
           "| mu_t / mu_f | " + " | ".join(RULES) + " | tube limit |",
           "|---|---|---|---|---|"]
    for x in RATIOS:
        cells = [_speed(runs[r][x]) if x in runs[r] else "-" for r in RULES]
        out.append(f"| {x:g} | " + " | ".join(cells) + f" | {limit:.4f} |")
    out.append(f"| {far_x:g} ({far_n} points, {far_steps} steps) | - | - | {_speed(far)} | "
               f"{limit:.4f} |")
    cw = runs["componentwise"][RATIOS[-1]].speed_body_lengths_per_period
    asc = runs["associated"][RATIOS[-1]].speed_body_lengths_per_period
    out += ["", (f"Isotropic friction (mu_t / mu_f = 1) barely propels: the "
                 f"{runs['componentwise'][1.0].speed_body_lengths_per_period:+.4f} left is a "
                 "small drift of the nonlinear law, the same for the three rules. "
                 f"At mu_t / mu_f = {RATIOS[-1]:g} the componentwise rule is "
            f"{100 * (cw / limit - 1):+.2f} % from the limit and the associated one "
            f"{100 * (asc / limit - 1):+.2f} %. The colinear rule does not tend to it: its "
            "force stays opposite to the slip, so a point slipping at a small angle to the "
            "tangent meets a lateral force of only about mu_f tan(angle), however large mu_t "
            f"is; it levels off near {far.speed_body_lengths_per_period:.3f}. (Its quasi-static "
            "solve past mu_t / mu_f = 3 takes tens of seconds a run and leaves some steps "
            "unconverged at 100 points: fewer ratios here.)"), "",
            "![tube limit](crawl_tube_limit.png)", ""]
    return out


def spread() -> list[str]:
    out = ["### The three rules on the same coefficients", "",
           (f"Quasi-static, A = {A:g}, k = {K:g}, {POINTS} points. The rule is part of the law: "
           "on the same three coefficients the speeds differ several-fold."), "",
           "| mu_f, mu_b, mu_t | " + " | ".join(RULES) + " | largest / smallest |",
           "|---|---|---|---|---|"]
    for c in SPREAD:
        res = [_qs(*c, r) for r in RULES]
        u = [abs(x.speed_body_lengths_per_period) for x in res]
        out.append(f"| {', '.join(f'{v:g}' for v in c)} | "
                   + " | ".join(_speed(x) for x in res) + f" | {max(u) / min(u):.2f} |")
    return out + ["", ("Crawling head-ward no point of this gait slides backwards, so mu_b does "
                       "not change the speed (rows 2 and 3, componentwise and associated); "
                       "mu_t < mu_f (the last row) crawls tail-ward under every rule."), ""]


def froude(folder: Path) -> list[str]:
    from ..crawling.solver import coefficient_law, crawl
    plt = _pyplot()
    mu = SPREAD[0]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    out = ["### Quasi-static against dynamic: the Froude number", "",
           (f"mu_f, mu_b, mu_t = {', '.join(f'{v:g}' for v in mu)}, L = 1 m, g = 9.81 m/s^2, "
           f"{POINTS} points, {STEPS} steps a period; the period T sets the Froude number "
           "Fr = L / (g mu_f T^2). Dynamic runs start from rest and average periods 5-8; "
           "the quasi-static speed does not depend on T."), "",
           "| rule | quasi-static | " + " | ".join(f"Fr {f:g}" for f in FROUDE) + " |",
           "|---|---|" + "---|" * len(FROUDE)]
    notes = []
    for j, rule in enumerate(RULES[:2]):
        law = coefficient_law(*mu, rule)
        qs = _qs(*mu, rule)
        dyn = [crawl(law, amplitude=A, waves=K, period=1.0 / math.sqrt(9.81 * mu[0] * f),
                     points=POINTS, periods=8) for f in FROUDE]
        ax.semilogx(FROUDE, [d.speed_body_lengths_per_period for d in dyn], "o-",
                    color=f"C{j}", label=f"dynamic, {rule}")
        ax.axhline(qs.speed_body_lengths_per_period, color=f"C{j}", ls="--", lw=1,
                   label=f"quasi-static, {rule}")
        out.append(f"| {rule} | {_speed(qs)} | " + " | ".join(_speed(d) for d in dyn) + " |")
        rel = dyn[0].speed_body_lengths_per_period / qs.speed_body_lengths_per_period - 1
        notes.append(f"{rule} {100 * rel:+.2f} %")
    ax.set_xlabel("Froude number L / (g mu_f T^2)")
    ax.set_ylabel("U (body lengths per period)")
    ax.set_title(f"A = {A:g}, k = {K:g}, mu = {mu[0]:g}, {mu[1]:g}, {mu[2]:g}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, folder / "crawl_froude.png")
    plt.close(fig)
    return out + ["", (f"At Fr = {FROUDE[0]:g} the dynamic speed is the quasi-static one "
                  f"({'; '.join(notes)}); inertia changes the speed as Fr grows."), "",
                  "![Froude number](crawl_froude.png)", ""]


def pyelastica(folder: Path) -> list[str]:
    from ..crawling.gait import CurvatureWave
    from ..crawling.solver import coefficient_law, crawl
    if not BENCH.is_file():
        return ["### PyElastica's continuum snake", "",
                (f"Not run: {BENCH.name} is not in benchmarks/ (benchmarks/crawl_pyelastica.py "
                "writes it)."), ""]
    pe = json.loads(BENCH.read_text())
    prm, el = pe["parameters"], pe["pyelastica"]
    mu = prm["mu_forward"]
    gait = CurvatureWave(amplitude=7.0, waves=1.0, period=prm["period_s"],
                         length=prm["length_m"])
    law = coefficient_law(mu, 1.5 * mu, 2.0 * mu, "componentwise")
    crawl(law, gait=gait, points=51, periods=1, g=prm["gravity_m_s2"])      # compiled
    t0 = time.perf_counter()
    res = crawl(law, gait=gait, points=51, periods=int(el["periods"]), g=prm["gravity_m_s2"])
    wall = time.perf_counter() - t0
    ours, theirs = res.speed_body_lengths_per_period, el["speed_body_lengths_per_period"]
    ref = pe.get("reference_quasi_static") or {}
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.2))
    n = np.arange(1, len(el["speed_per_period"]) + 1)
    ax.plot(n, el["speed_per_period"], "s-", label=f"PyElastica {el['elastica_version']} "
            f"(Cosserat rod, {prm['n_elem']} elements)")
    ax.plot(np.arange(1, res.periods + 1), res.speed_per_period, "o-",
            label="asperity crawl, dynamic, 51 points")
    ax.set_xlabel("period")
    ax.set_ylabel("U (body lengths per period)")
    ax.set_title(f"PyElastica's continuum snake: Fr = {res.froude:.3g}, mu 1 : 1.5 : 2, "
                 "componentwise")
    ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, folder / "crawl_pyelastica.png")
    plt.close(fig)
    return ["### PyElastica's continuum snake side by side", "",
            (f"PyElastica's example (`{prm['source']}`), rebuilt and run by "
            f"benchmarks/crawl_pyelastica.py: a rod of {prm['length_m']:g} m in "
            f"{prm['n_elem']} elements driven by its muscle torques, period "
            f"{prm['period_s']:g} s, friction forward : backward : lateral = 1 : 1.5 : 2 "
            f"(mu_forward {mu:.4g} for Fr = {prm['froude']:g}), regularised. Ours: its gait's "
            f"main curvature term (CurvatureWave A = 7, k = 1, T = {prm['period_s']:g} s, "
            f"L = {prm['length_m']:g} m), the same coefficients by the componentwise rule, "
            f"g = {prm['gravity_m_s2']:g} m/s^2, 51 points, {res.periods} periods, exact "
            "stick, from rest; speeds averaged after each run's transient."), "",
            "| run | U (body lengths per period) | periods averaged | wall time (s) |",
            "|---|---|---|---|",
            (f"| PyElastica {el['elastica_version']} | {theirs:.4f} | "
            f"{el['transient_periods'] + 1}-{int(el['periods'])} | {el['wall_time_s']:.1f} "
            "(recorded by the benchmark) |"),
            (f"| asperity crawl, dynamic | {ours:.4f} | {res.transient_periods + 1}-"
            f"{res.periods} | {wall:.2f} (this report's run) |")]  + (
            [(f"| quasi-static reference on PyElastica's fitted gait (tests/crawl_reference.py) "
             f"| {ref['U']:.4f} | - | {ref.get('wall_time_s', float('nan')):.1f} |")]
            if "U" in ref else []) + [
            "", (f"Ours against PyElastica: {100 * (ours / theirs - 1):+.2f} % (the test "
            "asks for 2 %). Wall times on a shared machine: the ratio is indicative; "
            "benchmarks/bench_crawl.py times both in one run."), "",
            "![PyElastica side by side](crawl_pyelastica.png)", ""]


def _pyplot():
    from ..io import pyplot
    return pyplot()


def _save(fig, path: Path) -> None:
    from ..io import save_figure_atomic
    save_figure_atomic(fig, path, dpi=110)


def section(folder: Path) -> list[str]:
    folder = Path(folder)
    return (["## Crawling: bodies that change shape", "",
             ("A slender body whose shape follows a gait crawls on direction-dependent "
             "friction (`asperity crawl`, issue 26): the curvature wave "
             "kappa L = A cos 2 pi (k s / L + t / T) on laws of three coefficients "
             "(forward mu_f towards the head, backward mu_b, transverse mu_t) made by a rule: "
             "componentwise (Hu et al.), associated (the truncated ellipse) or colinear."), ""]
            + tube(folder) + spread() + froude(folder) + pyelastica(folder))
