"""Report section and figures of the cumulative microslip (SPEC.md section 5).

:func:`section` (folder) -> Markdown lines, figures written into ``folder``: Antoni et al.'s
figure 3 redrawn from the model (node displacement against cycles), the strip's slip
profiles, a risk map, the convergence of the strip's drift per cycle with the number of
nodes, the dT_c checks and the agreement of the two solution modes (the figures are drawn by
:mod:`asperity.microslip.plot`, which ``asperity risk --plot`` uses too).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..microslip.plot import plot_assembly_history, plot_risk_map

# the SPEC.md section 5 two-node check and a strip at lam l = 3.54
TWO_NODE = dict(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0)
STRIP = dict(h=2e-3, E=2e11, p=1e6, l=0.1, alpha_T=1.2e-5)
STRIP_LAM_L = 3.54
MU = (0.2, 0.1)


def _strip_kt() -> float:
    return (STRIP_LAM_L / STRIP["l"]) ** 2 * STRIP["E"] * STRIP["h"]


def _strip(n, mu=MU):
    from ..microslip.chains import strip_chain
    s = STRIP
    return strip_chain(s["h"], s["E"], s["p"], s["l"], _strip_kt(), s["alpha_T"], n, *mu)


def _two_node(mu=MU):
    from ..microslip.chains import two_node_chain
    t = TWO_NODE
    return two_node_chain(t["k"], t["l0"], t["alpha_T"], t["k_t"], t["N"], *mu)


def strip_convergence(ns=(21, 41, 81, 161, 321, 641, 1281), n_ref: int = 5121,
                      margin: float = 5.0) -> dict:
    """The strip's drift per cycle against n (cycles 0 -> 2 margin dT_c -> 0, dT_c the
    shear-lag closed form), errors against n_ref nodes and the fitted order."""
    from ..microslip.closed_forms import strip_dT_c
    from ..microslip.loading import Loading
    from ..microslip.quasi_static import simulate
    s = STRIP
    dTc = strip_dT_c(s["h"], s["E"], s["p"], s["l"], _strip_kt(), *MU, s["alpha_T"])
    L = Loading.cycles_between(0.0, 2 * margin * dTc)
    ref = simulate(_strip(n_ref), L, 20).drift_per_cycle
    rows = []
    for n in ns:
        d = simulate(_strip(n), L, 20).drift_per_cycle
        rows.append((n, d, abs(d / ref - 1)))
    e = np.array([r[2] for r in rows])
    h = np.array([1.0 / (r[0] - 1) for r in rows])
    ok = e > 0
    order = float(np.polyfit(np.log(h[ok]), np.log(e[ok]), 1)[0]) if ok.sum() >= 2 else math.nan
    return {"dT_c": dTc, "margin": margin, "reference_n": n_ref, "reference": ref,
            "rows": rows, "order": order}


def dT_c_checks() -> list[tuple]:
    """(model, n, numeric dT_c, closed form, relative error)."""
    from ..microslip.chains import elastic_limit
    from ..microslip.closed_forms import strip_dT_c, two_node_dT_c
    t, s = TWO_NODE, STRIP
    rows = [("two-node", 2, elastic_limit(_two_node()),
             two_node_dT_c(t["k"], t["k_t"], t["N"], *MU, t["alpha_T"], t["l0"]))]
    exact = strip_dT_c(s["h"], s["E"], s["p"], s["l"], _strip_kt(), *MU, s["alpha_T"])
    for n in (101, 201, 401, 801):
        rows.append(("strip", n, elastic_limit(_strip(n)), exact))
    return [(m, n, a, b, abs(a / b - 1)) for m, n, a, b in rows]


def section(folder: Path) -> list[str]:
    """Markdown lines of the microslip section; PNGs written into ``folder``."""
    from ..microslip.closed_forms import two_node_drift_per_cycle, two_node_dT_c
    from ..microslip.dynamic import simulate_dynamic
    from ..microslip.loading import Loading
    from ..microslip.quasi_static import long_life, simulate
    folder = Path(folder)
    t = TWO_NODE
    out = ["## Cumulative microslip: assemblies under thermal cycles", "",
           "Slider chains (SPEC.md 5): each contact node an elastic spring k_t in series with a "
           "slider at mu+ N (towards +x) and mu- N (towards -x). Quasi-static mode: the exact "
           "solution of the rate-independent chain (each slider's start and stop located exactly); "
           "dynamic mode: Moreau midpoint time-stepping with small masses and slow loading. "
           "Sign convention: drift < 0 is towards -x, the side of the smaller coefficient "
           "when mu+ > mu-.", ""]
    # figure 3
    dTc = two_node_dT_c(t["k"], t["k_t"], t["N"], *MU, t["alpha_T"], t["l0"])
    L3 = Loading.cycles_between(0.0, 3 * dTc)
    plot_assembly_history(_two_node(), L3, folder / "microslip_two_node.png",
                          title="two-node model (Antoni et al. fig. 3)")
    r = simulate(_two_node(), L3, 8, until_stable=False)
    want = two_node_drift_per_cycle(t["k"], t["k_t"], t["N"], *MU, t["alpha_T"], t["l0"],
                                    0.0, 3 * dTc)
    out += ["### Two-node model (Antoni et al. figure 3, redrawn from the model)", "",
            f"k = {t['k']:g} N/m, k_t = {t['k_t']:g} N/m, N = {t['N']:g} N, mu+ = {MU[0]}, "
            f"mu- = {MU[1]}, alpha_T = {t['alpha_T']:g} 1/K, l0 = {t['l0']:g} m, dT in "
            f"[0, 3 dT_c]: drift per cycle {r.drift_per_cycle:.6e} m (closed form "
            f"{want:.6e} m, SPEC.md: -5.0e-5), both nodes from the first full cycle on.", "",
            "![two-node model](microslip_two_node.png)", ""]
    # dT_c checks
    out += ["### Elastic limit dT_c against the closed forms", "",
            "| model | nodes | dT_c numeric (K) | closed form (K) | relative error |",
            "|---|---|---|---|---|"]
    for m, n, a, b, e in dT_c_checks():
        out.append(f"| {m} | {n} | {a:.8g} | {b:.8g} | {e:.2e} |")
    out += ["", f"Strip: h = {STRIP['h']:g} m, E = {STRIP['E']:g} Pa, p = {STRIP['p']:g} Pa, "
            f"l = {STRIP['l']:g} m, lam l = {STRIP_LAM_L}; shear-lag dT_c = mu- p lam "
            "coth(lam l/2) / (alpha_T k_t). The lumped discretisation converges at second "
            "order (error / 4 per halving of dx; SPEC.md quotes 2.6e-6 at 801 nodes).", ""]
    # strip profiles
    L5 = Loading.cycles_between(0.0, 10 * dT_c_checks()[-1][3])
    plot_assembly_history(_strip(201), L5, folder / "microslip_strip.png",
                          title="strip, 201 nodes, dT range 5 x 2 dT_c")
    out += ["### Strip: node displacements and slip profiles", "",
            "![strip](microslip_strip.png)", ""]
    # convergence
    cv = strip_convergence()
    out += ["### Strip drift per cycle against n", "",
            f"Cycles 0 -> {2 * cv['margin']:g} dT_c -> 0 (margin {cv['margin']:g}); reference "
            f"{cv['reference_n']} nodes: {cv['reference']:.8e} m per cycle. Fitted order of "
            f"the error in dx: {cv['order']:.2f} (irregular: the slip-zone boundaries fall "
            "between nodes).", "",
            "| nodes | drift per cycle (m) | relative error vs reference |", "|---|---|---|"]
    for n, d, e in cv["rows"]:
        out.append(f"| {n} | {d:.8e} | {e:.2e} |")
    out += [""]
    # modes agree
    rows = []
    for name, chain, L in (("two-node", _two_node(), L3), ("strip, 11 nodes", _strip(11),
                                                           L5)):
        qs = simulate(chain, L, 10).drift_per_cycle
        for sps in (20000, 80000, 320000):
            dyn = simulate_dynamic(chain, L, 3, steps_per_segment=sps)
            rows.append((name, sps, qs, dyn.drift_per_cycle, abs(dyn.drift_per_cycle / qs - 1),
                         dyn.solver["max_iterations_used"]))
    out += ["### Quasi-static and dynamic (Moreau) modes", "",
            "Dynamic: node and slider masses, each load segment one time unit, omega_max dt = "
            "0.5, mass-proportional damping; friction impulses from xi = prox_[-mu- N dt, "
            "mu+ N dt](xi + r w_E), r = 1/G (G the slider's Delassus term), fixed-point "
            "tolerance 1e-12, at most 100 iterations. The difference is first order in the "
            "loading rate (inertia and damping lag).", "",
            "| model | steps per segment | quasi-static drift (m) | Moreau drift (m) | "
            "relative difference | max prox iterations |", "|---|---|---|---|---|---|"]
    for name, sps, qs, dy, e, it in rows:
        out.append(f"| {name} | {sps} | {qs:.6e} | {dy:.6e} | {e:.2e} | {it} |")
    # risk map of the shipped bushing
    out += _risk_map_lines(folder)
    # long life
    ll = long_life(_strip(201), L5, 1e6)
    out += ["", "### Long life", "",
            f"Strip, 201 nodes: stabilised at cycle {ll.stabilised_at}; drift per cycle "
            f"{ll.drift_per_cycle:.6e} m; after 1e6 cycles {ll.drift_after(1e6):.6e} m "
            "(state of the stabilised cycle + (N - k) x drift, exact for a rate-independent "
            "chain whose cycle repeats up to a translation; tests check it against 300 "
            "marched cycles).", ""]
    return out


def _risk_map_lines(folder: Path) -> list[str]:
    from ..microslip.assembly import load_assembly
    from ..study.maps import risk_map
    from ..texture.wedges import load_texture
    root = Path(__file__).resolve().parents[2] / "surfaces"
    asm = root / "bushing-strip-mild.toml"
    tex = root / "wedge-asymmetric.toml"
    if not asm.is_file() or not tex.is_file():
        return ["", "(risk map skipped: surfaces/bushing-strip-mild.toml not found)", ""]
    grid = np.linspace(5.0, 40.0, 8)
    out = risk_map(load_assembly(asm), ("alpha", grid), ("beta", grid), load_texture(tex))
    plot_risk_map(out, folder / "microslip_risk_map.png")
    v = np.array(out["map"]["verdict"], dtype=object)
    return ["", "### Risk map of the shipped bushing (illustrative values)", "",
            f"`asperity risk surfaces/wedge-asymmetric.toml surfaces/bushing-strip-mild.toml "
            f"--map alpha=5:40:8 beta=5:40:8`: {int((v == 'ratchet').sum())} of {v.size} wedge "
            f"shapes ratchet under dT 0 -> 40 K (mu_alpha = 0.1, mu_beta = 0.2; colour: "
            f"drift per cycle, positive towards +x; hatched: shakedown (//) and alternating "
            f"slip (xx)).", "",
            "![risk map](microslip_risk_map.png)", ""]
