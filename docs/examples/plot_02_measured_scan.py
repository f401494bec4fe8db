r"""
A measured scan to a friction law
=================================

From a height map to a gauge file: read the shipped scan ``surfaces/scan-ridges.txt``
(64 x 64 pixels of 1 um, heights in metres, a Gwyddion text header: four asymmetric ridges
along y with fine roughness), triangulate it into facets with a local friction of 0.15,
find its principal direction :math:`t_a` and its coefficients with :func:`asperity.derive`,
fit a star-shaped (Walker-Leine) law with :func:`asperity.fit_derivation`, write it as a
gauge file with :func:`asperity.write_gauge` and read it back for the solver with
:func:`asperity.law_from_gauge`.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import asperity

# The shipped inputs sit beside the package in a checkout of asperity.
SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"
SCAN = SURFACES / "scan-ridges.txt"

# %%
# The heights
# -----------
# :func:`asperity.read_surface` reads the sizes and units from the file's header (a file
# without them needs ``unit`` and ``pixel_size``: nothing is guessed). ``heights[i, j]``
# is the height at :math:`x_i = i\,dx`, :math:`y_j = j\,dy`, in metres.
hm = asperity.read_surface(SCAN)
print(f"{hm.source}: {hm.nx} x {hm.ny} pixels of {hm.dx * 1e6:g} x {hm.dy * 1e6:g} um, "
      f"heights from {np.nanmin(hm.heights) * 1e6:.3f} to {np.nanmax(hm.heights) * 1e6:.3f} um")

# %%
# Facets and their quality
# ------------------------
# :func:`asperity.load_surface` removes the mean slope (``detrend="slope"``, the
# default), cuts every pixel cell into two triangles and gives each the local friction
# ``mu``. The data-quality figures say whether any facet is too steep to be climbed with
# that friction (self-locking, an infinite coefficient in some direction).
surface = asperity.load_surface(SCAN, mu=0.15)
print(surface.describe())
q = surface.quality
print(f"steepest facet {q['steepest_facet_deg']:.1f} deg; facets steeper than the "
      f"self-locking limit of {q['locking_limit_deg']:.2f} deg at mu = 0.15: "
      f"{q['facets_above_locking_limit']}")

# %%
# Directional friction
# --------------------
# For a surface the frame is the file's x, y; the principal direction :math:`t_a` is
# found from the second harmonic of :math:`T(\psi)` and the coefficients are taken along
# and against it.
d = asperity.derive(surface, n_directions=72)
print(f"t_a at {d.principal_direction_deg:.2f} deg from x, anisotropy {d.anisotropy:.4f}")
for key, value in d.axes.items():
    print(f"{key:11s} = {value:.5f}")

# %%
# A law and its gauge file
# ------------------------
# The star-shaped law puts its reservoir C through the 72 data points and integrates the
# convex sliding set D from their sliding rule. The fit report compares the law with the
# surface at 72 directions midway between the fitted ones (``holdout``).
gauge = asperity.fit_derivation(d, kind="star")
fit = gauge.fit
print(f"radial error at the data {fit.max_radial_error:.1e}; between them: force "
      f"{fit.holdout_max_magnitude_error:.1e}, angle {fit.holdout_max_angle_deg:.3f} deg; "
      f"admissible: {fit.admissible}, C convex: {fit.C_convex}, D convex: {fit.D_convex}")

with tempfile.TemporaryDirectory() as folder:
    path = Path(folder) / "scan-ridges-star.json"
    asperity.write_gauge(path, gauge)
    law = asperity.law_from_gauge(path)
print(f"{law.name}: {law.description}")
print("the law's axis coefficients:",
      ", ".join(f"{k} = {v:.5f}" for k, v in law.axes().items()))

# %%
# The map and the law
# -------------------
# Left: the heights with :math:`t_a` (across the ridges). Right: the friction resisting
# the slip, :math:`T = p \cdot s`, of the surface at the 72 fitted directions and of the
# law at 720, against the sliding direction from :math:`t_a`: a variation of a few per
# cent around 0.156.
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.2))
extent = (0, hm.nx * hm.dx * 1e6, 0, hm.ny * hm.dy * 1e6)
im = ax0.imshow(hm.heights.T * 1e6, origin="lower", extent=extent, cmap="viridis")
fig.colorbar(im, ax=ax0, label="height (um)")
c = 0.5 * extent[1]
angle = np.radians(d.principal_direction_deg)
ax0.annotate("", xy=(c + 20 * np.cos(angle), c + 20 * np.sin(angle)), xytext=(c, c),
             arrowprops={"arrowstyle": "->", "color": "w", "lw": 2})
ax0.text(c + 21, c + 2, "$t_a$", color="w")
ax0.set_xlabel("x (um)")
ax0.set_ylabel("y (um)")

psi = np.linspace(0, 2 * np.pi, 721)
T_law = np.einsum("ij,ij->i", law.force(psi), np.column_stack([np.cos(psi), np.sin(psi)]))
data = gauge.data
T_data = np.einsum("ij,ij->i", data.p, np.column_stack([np.cos(data.psi), np.sin(data.psi)]))
ax1.plot(np.degrees(psi), T_law, label="star law")
ax1.plot(np.degrees(data.psi), T_data, ".", label="surface (72 directions)")
ax1.set_xlim(0, 360)
ax1.set_xlabel("sliding direction $\\psi$ (deg from $t_a$)")
ax1.set_ylabel("T = p.s")
ax1.legend()
fig.tight_layout()
plt.show()

# %%
# The scallops between the fitted directions are the law's: its C is the polygon through
# the 72 points, so between them the force is a little smaller than the surface's (the
# ``holdout`` error printed above). More directions make them smaller: ``asperity fit``
# fits 720 by default.
#
# :math:`\mu_a^+` and :math:`\mu_a^-` differ by well under one per cent, :math:`\mu_a` and
# :math:`\mu_b` by a few: fine roughness on ridges of gentle slopes gives a nearly
# isotropic law. Steeper relief, a larger local friction, or load shares from an elastic
# contact (:ref:`the next example <sphx_glr_gallery_plot_03_elastic_family.py>`) change
# that. The command-line twin is ``asperity fit surfaces/scan-ridges.txt --mu 0.15 -o
# law.json`` (:doc:`/tutorials/measured-scan`).
