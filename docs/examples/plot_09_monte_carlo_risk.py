r"""
Risk under scatter: a small Monte Carlo
=======================================

Production scatters the texture and service scatters the temperatures: the question
becomes "what fraction of the parts ratchet, and how far do the worst creep?". This example
samples the inputs with NumPy and runs each case through the Python API
(:func:`asperity.assess`, :func:`asperity.assembly_friction`,
:func:`asperity.assess_assembly`): first the two-node model, whose probability of ratchet
has a closed form to check the estimate against, then the shipped bushing strip under the
scatter of ``surfaces/bushing-tolerance.toml``. For thousands of cases, resumable stores,
Sobol indices and a Dask cluster use ``asperity study`` instead
(:doc:`/tutorials/creep-risk`).
"""
import dataclasses
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import asperity

SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"
rng = np.random.default_rng(4)


def wilson(successes, n, z=1.96):
    """95 % Wilson score interval of a binomial proportion."""
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


# %%
# The two-node model: an estimate against its closed form
# -------------------------------------------------------
# SPEC.md's two-node bar (:math:`\Delta T_c` = 41.67 K) cycled 0 -> :math:`\Delta T_{max}`
# with :math:`\Delta T_{max}` uniform in [50, 150] K ratchets iff
# :math:`\Delta T_{max} > 2 \Delta T_c`, so
# :math:`P = (150 - 2 \Delta T_c) / 100 = 2/3`. 2000 cases:
chain = asperity.two_node_chain(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0,
                                mu_plus=0.2, mu_minus=0.1)
dT_c = 0.1 * 100.0 * (1 / 1e6 + 2 / 5e5) / (1.2e-5 * 0.1)
n = 2000
dT_max = rng.uniform(50.0, 150.0, n)
ratchets = sum(
    asperity.assess(chain, asperity.Loading(dT=np.array([0.0, t, 0.0]), F=np.zeros(3)),
                    cycles=1e6)["verdict"] == "ratchet"
    for t in dT_max)
lo, hi = wilson(ratchets, n)
exact = (150.0 - 2 * dT_c) / 100.0
print(f"P(ratchet): closed form {exact:.4f}, estimate {ratchets / n:.4f} "
      f"(95 % interval {lo:.4f} - {hi:.4f}), covered: {lo <= exact <= hi}")

# %%
# The bushing under production scatter
# ------------------------------------
# The strip of ``surfaces/bushing-strip.toml`` (illustrative values) with the friction of
# the asymmetric wedge texture, whose angles scatter normally (sd 1.5 deg) and whose face
# friction scatters by +-20 % (uniform), cycled 0 -> :math:`\Delta T_{max}` with
# :math:`\Delta T_{max}` uniform in 90-140 K: the inputs of
# ``surfaces/bushing-tolerance.toml``, 400 cases here.
base = asperity.load_assembly(SURFACES / "bushing-strip.toml")
cases = 400
inputs = {"alpha_deg": rng.normal(30.0, 1.5, cases), "beta_deg": rng.normal(10.0, 1.5, cases),
          "mu_alpha": rng.uniform(0.08, 0.12, cases), "mu_beta": rng.uniform(0.16, 0.24, cases),
          "dT_max": rng.uniform(90.0, 140.0, cases)}
verdicts, drift, to_tol = [], np.empty(cases), np.empty(cases)
for i in range(cases):
    texture = asperity.WedgeTexture(inputs["alpha_deg"][i], inputs["beta_deg"][i],
                                    inputs["mu_alpha"][i], inputs["mu_beta"][i])
    loading = asperity.Loading(dT=np.array([0.0, inputs["dT_max"][i], 0.0]), F=np.zeros(3))
    assembly = dataclasses.replace(base, loading=loading)
    out = asperity.assess_assembly(assembly, asperity.assembly_friction(assembly, texture))
    verdicts.append(out["verdict"])
    drift[i] = out["drift_per_cycle_m"]
    to_tol[i] = out["cycles_to_tolerance"] or np.inf
verdicts = np.array(verdicts)
share = np.mean(verdicts == "ratchet")
lo, hi = wilson(np.sum(verdicts == "ratchet"), cases)
print(f"{share:.1%} of the cases ratchet (95 % interval {lo:.1%} - {hi:.1%})")
print("verdicts:", ", ".join(f"{v} {np.sum(verdicts == v)}" for v in sorted(set(verdicts))))
p50, p95 = np.percentile(np.abs(drift), [50, 95])
print(f"creep per cycle: median {p50 * 1e6:.4f} um, 95th percentile {p95 * 1e6:.4f} um")
print(f"5 % of the cases reach the {base.tolerance * 1e3:g} mm tolerance within "
      f"{np.percentile(to_tol, 5):.0f} cycles")

# %%
# Which input matters? The rank correlation of each input with the drift per cycle
# (Spearman: the correlation of the ranks).


def ranks(x):
    r = np.empty(x.size)
    r[np.argsort(x)] = np.arange(x.size)
    return r


rho = {k: float(np.corrcoef(ranks(v), ranks(drift))[0, 1]) for k, v in inputs.items()}
for key, value in sorted(rho.items(), key=lambda kv: -abs(kv[1])):
    print(f"  {key:9s} {value:+.3f}")

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4))
ax0.hist(drift * 1e6, bins=30, color="C0")
ax0.set_xlabel("drift per cycle (um, + towards +x)")
ax0.set_ylabel("cases")
ax0.set_title(f"{cases} bushings")
top = max(rho, key=lambda key: abs(rho[key]))
for v in sorted(set(verdicts)):
    sel = verdicts == v
    ax1.plot(inputs[top][sel], drift[sel] * 1e6, ".", label=v)
ax1.set_xlabel(top)
ax1.set_ylabel("drift per cycle (um)")
ax1.legend()
fig.tight_layout()
plt.show()

# %%
# With 400 cases the interval on the share is as wide as printed above; ``asperity study
# surfaces/bushing-tolerance.toml --plot`` runs the 10 000 cases of the same study on
# the block path (vectorised over cases) with Sobol indices and a resumable store.
