r"""
Ratcheting of the two-node assembly, and a risk map
===================================================

An assembly on asymmetric friction (:math:`\mu^+ \neq \mu^-`) can creep under a load with
zero mean: every thermal cycle its contacts slip a little further one way than the other.
This example solves Antoni et al.'s two-node model with SPEC.md's check values -- a bar
(k = 1e6 N/m, l0 = 0.1 m, alpha_T = 1.2e-5 1/K) on two contacts (k_t = 5e5 N/m,
N = 100 N, :math:`\mu^+ = 0.2`, :math:`\mu^- = 0.1`) -- checks its elastic limit and drift
per cycle against the closed forms, and then draws which wedge textures make the shipped
bushing (``surfaces/bushing-strip-mild.toml``) ratchet, with :func:`asperity.risk_map`.
"""
# sphinx_gallery_thumbnail_number = 3
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import asperity

SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"

k, l0, alpha_T, k_t, N, mu_plus, mu_minus = 1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1
chain = asperity.two_node_chain(k=k, l0=l0, alpha_T=alpha_T, k_t=k_t, N=N,
                                mu_plus=mu_plus, mu_minus=mu_minus)

# %%
# Drift per cycle against the temperature range
# ---------------------------------------------
# Closed forms (SPEC.md section 5): elastic limit
# :math:`\Delta T_c = \mu^- N (1/k + 2/k_t) / (\alpha_T l_0)`; the bar ratchets when the
# range exceeds :math:`2 \Delta T_c` and then drifts
# :math:`-\alpha_T l_0 (\Delta T - 2 \Delta T_c)` per cycle, towards :math:`-x` (the side
# of the smaller coefficient). :func:`asperity.assess` marches the cycles with the exact
# event-driven solver until the cycle repeats and extrapolates.
dT_c = mu_minus * N * (1 / k + 2 / k_t) / (alpha_T * l0)
print(f"dT_c closed form {dT_c:.6f} K")
ranges = np.linspace(10.0, 200.0, 39)
drift, verdicts = [], []
for dT in ranges:
    loading = asperity.Loading(dT=np.array([0.0, dT, 0.0]), F=np.zeros(3))
    out = asperity.assess(chain, loading, cycles=1e6)
    drift.append(out["drift_per_cycle_m"])
    verdicts.append(out["verdict"])
drift = np.array(drift)
closed = np.where(ranges > 2 * dT_c, -alpha_T * l0 * (ranges - 2 * dT_c), 0.0)
print(f"dT_c of the solver {out['dT_c_K']:.6f} K")
print(f"largest difference from the closed form: {np.max(np.abs(drift - closed)):.1e} m per "
      f"cycle (drift up to {np.max(np.abs(closed)):.1e})")
print("verdicts:", {v: verdicts.count(v) for v in sorted(set(verdicts))})
assert np.allclose(drift, closed, rtol=1e-9, atol=1e-15)

fig, ax = plt.subplots(figsize=(6, 3.8))
fine = np.linspace(ranges[0], ranges[-1], 400)
ax.plot(fine, np.where(fine > 2 * dT_c, -alpha_T * l0 * (fine - 2 * dT_c), 0.0) * 1e6, "k:",
        label="closed form")
for v, marker in (("shakedown", "s"), ("ratchet", "o")):
    sel = np.array(verdicts) == v
    ax.plot(ranges[sel], drift[sel] * 1e6, marker, ms=4, label=f"solver: {v}")
ax.axvline(2 * dT_c, color="0.6", lw=0.8)
ax.set_xlabel("temperature range (K)")
ax.set_ylabel("drift per cycle (um)")
ax.legend()
fig.tight_layout()
plt.show()

# %%
# Cycles from the stress-free state
# ---------------------------------
# The first cycle differs from the steady ones (node 1 moves
# :math:`-\alpha_T l_0 (\Delta T - \Delta T_c)` on the first heating), which matters for
# "how many cycles until the tolerance?". Six cycles over :math:`[0, 3 \Delta T_c]`,
# 20 load points a segment for the trace:
loading = asperity.Loading(dT=np.array([0.0, 3 * dT_c, 0.0]), F=np.zeros(3), substeps=20)
res = asperity.simulate_microslip(chain, loading, cycles=6, until_stable=False)
print(f"drift per cycle {res.drift_per_cycle:.3e} m (closed form "
      f"{-alpha_T * l0 * dT_c:.3e}), stabilised at cycle {res.stabilised_at}")
print("mean displacement at the end of each cycle (um):", np.round(res.mean_u * 1e6, 3))
out = asperity.assess(chain, loading, cycles=1e6, tolerance=1e-3)
print(f"verdict {out['verdict']}: {out['cycles_to_tolerance']} cycles to 1 mm, "
      f"{out['drift_after_cycles_m']:.2f} m after 1e6 cycles if nothing else changes")

tr = res.trace
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4))
ax0.plot(tr["t"], tr["dT"], "k")
ax0.set_xlabel("load cycles")
ax0.set_ylabel("temperature change (K)")
for i, node in enumerate(tr["nodes"]):
    ax1.plot(tr["t"], tr["u"][:, i] * 1e6, label=f"node {node}")
ax1.set_xlabel("load cycles")
ax1.set_ylabel("displacement (um)")
ax1.legend()
fig.tight_layout()
plt.show()

# %%
# A risk map of the shipped bushing
# ---------------------------------
# The bushing strip of ``surfaces/bushing-strip-mild.toml`` (illustrative values, cycles
# 0 -> 40 K) with the friction of a wedge texture along its axis: the verdict and drift
# per cycle over a grid of the two wedge angles, the faces' local friction kept at
# 0.1 / 0.2 (the texture of the assembly file). ``alternating-slip``: the strip's ends
# slip back and forth but it does not walk.
assembly = asperity.load_assembly(SURFACES / "bushing-strip-mild.toml")
alphas = betas = np.linspace(5.0, 40.0, 8)
rmap = asperity.risk_map(assembly, ("alpha", alphas), ("beta", betas))
verdict = np.array(rmap["map"]["verdict"])           # rows: beta, columns: alpha
dpc = np.array(rmap["map"]["drift_per_cycle_m"])
n_ratchet = int(np.sum(verdict == "ratchet"))
print(f"{n_ratchet} of {verdict.size} wedge shapes ratchet; largest drift "
      f"{np.max(np.abs(dpc)) * 1e9:.1f} nm per cycle")
print(rmap["sign_convention"])

fig, ax = plt.subplots(figsize=(6, 5))
step = alphas[1] - alphas[0]
edges = (alphas[0] - step / 2, alphas[-1] + step / 2, betas[0] - step / 2, betas[-1] + step / 2)
im = ax.imshow(dpc * 1e9, origin="lower", extent=edges, cmap="viridis")
fig.colorbar(im, ax=ax, label="drift per cycle (nm, + towards +x)")
for i, b in enumerate(betas):
    for j, a in enumerate(alphas):
        if verdict[i, j] != "ratchet":
            ax.add_patch(plt.Rectangle((a - step / 2, b - step / 2), step, step, fill=False,
                                       hatch="xx" if verdict[i, j] == "alternating-slip"
                                       else "//", color="w", lw=0))
ax.set_xlabel("alpha (deg)")
ax.set_ylabel("beta (deg)")
ax.set_title("bushing 0 -> 40 K: hatched = no ratchet")
plt.show()

# %%
# The command-line twins: ``asperity risk surfaces/two-node-spec.toml`` and ``asperity
# risk surfaces/wedge-asymmetric.toml surfaces/bushing-strip-mild.toml --map alpha=5:40:8
# beta=5:40:8`` (:doc:`/tutorials/creep-risk`); the chains and how they are solved in
# :doc:`/theory/microslip`.
