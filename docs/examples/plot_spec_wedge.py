"""
The SPEC wedge in closed form
=============================

The wedge texture of SPEC.md (30 deg on one side, 10 deg on the other) gives mu_a+ and mu_a-
along t_a in closed form.
"""
import asperity

tex = asperity.WedgeTexture(alpha_deg=30, beta_deg=10, mu_alpha=0.1, mu_beta=0.1)
print(tex)
