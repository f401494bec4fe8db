r"""
The SPEC wedge: mu_a+ and mu_a- in closed form
==============================================

A periodic sawtooth of ridges along :math:`t_b`: a face of 30 deg rising towards
:math:`+t_a` with local friction 0.1 and a face of 10 deg falling towards it with local
friction 0.2 (the wedge of SPEC.md section 2). Sliding along :math:`+t_a` climbs the steep
face, sliding along :math:`-t_a` the gentle one, so the macroscopic friction depends on the
direction: :math:`\mu_a^+ \neq \mu_a^-`. This example computes the four axis coefficients with
:func:`asperity.compute_axis_coefficients`, checks them against SPEC.md's formula written
out here, and draws the friction force :math:`p(\psi)` for every sliding direction in both
contact regimes with :func:`asperity.derive`.
"""
import math

import matplotlib.pyplot as plt
import numpy as np

import asperity

# %%
# The axis coefficients
# ---------------------
# :math:`\mu_a^+` is for sliding along :math:`+t_a` (up the 30 deg face),
# :math:`\mu_a^-` along :math:`-t_a`, :math:`\mu_b^\pm` along the ridges. The wedge
# height does not enter: the friction depends on the angles and the local friction only.
texture = asperity.WedgeTexture(alpha_deg=30.0, beta_deg=10.0, mu_alpha=0.1, mu_beta=0.2)
mu = asperity.compute_axis_coefficients(texture, contact="all-faces")
for key in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
    print(f"{key:11s} = {mu[key]:.6f}")

# %%
# The same from SPEC.md's closed form: a spring tip climbing a face of signed slope
# :math:`y` with local friction :math:`x` carries the force ratio
# :math:`H(x, y) = (x + \tan y) / (1 - x \tan y)`, and each face is weighted by its
# horizontal length, :math:`\propto 1/\tan` of its angle.


def H(x, y):
    return (x + math.tan(y)) / (1.0 - x * math.tan(y))


a, b = math.radians(30.0), math.radians(10.0)
ta, tb = math.tan(a), math.tan(b)
mu_a_plus = (H(0.1, a) * tb + H(0.2, -b) * ta) / (ta + tb)
mu_a_minus = (H(0.2, b) * ta + H(0.1, -a) * tb) / (ta + tb)
mu_b = (0.1 * tb / math.cos(a) + 0.2 * ta / math.cos(b)) / (ta + tb)
print(f"closed form: mu_a+ = {mu_a_plus:.6f}, mu_a- = {mu_a_minus:.6f}, mu_b = {mu_b:.6f}")
diff = max(abs(mu_a_plus - mu["mu_a_plus"]), abs(mu_a_minus - mu["mu_a_minus"]),
           abs(mu_b - mu["mu_b_plus"]), abs(mu_b - mu["mu_b_minus"]))
print(f"largest difference: {diff:.1e}")
assert diff < 1e-12

# %%
# Every sliding direction
# -----------------------
# :func:`asperity.derive` evaluates the reservoir point
# :math:`p(\psi) = -\lambda_T / \lambda_N` for sliding directions
# :math:`s = \cos\psi\, t_a + \sin\psi\, t_b`. In the ``all-faces`` regime (compliant
# springs touch every face) the reservoir is convex and close to a circle; in the
# ``windward`` regime (rigid asperities touch only the faces the motion climbs) it is
# star-shaped, and sliding exactly along the ridges is set-valued.
fig, ax = plt.subplots(figsize=(7, 3.8))
for contact, style in (("all-faces", "-"), ("windward", "--")):
    d = asperity.derive(texture, contact=contact, n_directions=360)
    p = d.reservoir.p
    ax.plot(p[:, 0], p[:, 1], style, label=contact)
    print(f"{contact:9s}: mu_a+ = {d.axes['mu_a_plus']:.4f}, mu_a- = {d.axes['mu_a_minus']:.4f}, "
          f"largest lateral force {np.max(np.abs(d.reservoir.lateral)):.4f}, "
          f"smallest dissipation p.s = {d.admissibility.min_dissipation:.4f}")
ax.plot(0, 0, "k+")
ax.set_aspect("equal")
ax.set_xlabel("p along $t_a$")
ax.set_ylabel("p along $t_b$")
ax.set_title("reservoir $p(\\psi)$ of the 30/10 deg wedge")
ax.legend(loc="upper right", fontsize=8)
fig.tight_layout()
plt.show()

# %%
# The force is not opposite to the slip: the lateral part :math:`L = p \cdot s_\perp`
# deflects a sliding body (see
# :ref:`the point-mass example <sphx_glr_gallery_plot_05_deflection.py>`). Its size
# against the tangential part :math:`T = p \cdot s`:
d = asperity.derive(texture, n_directions=360)
psi = np.degrees(d.reservoir.psi)
fig, ax = plt.subplots(figsize=(7, 3.5))
ax.plot(psi, d.reservoir.tangential, label="T, against the slip")
ax.plot(psi, d.reservoir.lateral, label="L, sideways (+90 deg from the slip)")
ax.axhline(0, color="0.6", lw=0.8)
ax.set_xlabel("sliding direction $\\psi$ (deg from $t_a$)")
ax.set_ylabel("force / normal load")
ax.set_xlim(0, 360)
ax.legend()
fig.tight_layout()
plt.show()

# %%
# Next: the same numbers from the command line, ``asperity derive
# surfaces/wedge-asymmetric.toml`` (:doc:`/tutorials/texture-law`), and the physics in
# :doc:`/theory/texture`.
