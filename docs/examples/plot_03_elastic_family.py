r"""
Load shares from an elastic contact: a law family
=================================================

The area-weighted homogenisation loads every facet alike. Pressed onto an elastic body,
a surface touches first at its highest points, and each facet's share of the load is the
normal force it carries in that contact (SPEC.md section 7). This example passes an
:class:`asperity.ElasticContact` (effective modulus :math:`E^*`, nominal pressures) to
:func:`asperity.derive_family`: first on a sharp sawtooth, whose load shares are known in
closed form, then on the shipped scan ``surfaces/scan-ridges.txt``, whose friction changes
with the load: one law per pressure, a law family.
"""
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import asperity

SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"
E_star = 1e9                         # Pa

# %%
# A sharp sawtooth keeps its area weighting
# -----------------------------------------
# Flanks of slopes 0.1 and 0.5 (5.71 and 26.57 deg), local friction 0.15. The elastic
# contact of a sharp crest puts on each flank its share of the horizontal length,
# :math:`0.1^{-1} / (0.1^{-1} + 0.5^{-1}) = 5/6` on the gentle one, at every load, so
# the coefficients stay close to the area-weighted closed form.
saw = asperity.WedgeTexture(np.degrees(np.arctan(0.1)), np.degrees(np.arctan(0.5)), 0.15, 0.15)
area = asperity.compute_axis_coefficients(saw)
print(f"area weighting: mu_a+ = {area['mu_a_plus']:.5f}, mu_a- = {area['mu_a_minus']:.5f}")
family = asperity.derive_family(saw, asperity.ElasticContact(E_star, [1e6, 1e7, 5e7]),
                                n_directions=8)
for p, member in zip(family.pressures, family.members):
    faces = member.texture.faces()
    share = faces.weight[0] / faces.weight.sum()
    print(f"p/E* = {p / E_star:.0e}: contact {member.texture.elastic['area_fraction']:6.2%} "
          f"of the period, gentle flank's load share {share:.4f} (5/6 = {5 / 6:.4f}), "
          f"mu_a+ = {member.axes['mu_a_plus']:.5f}, mu_a- = {member.axes['mu_a_minus']:.5f}")
    assert abs(share - 5 / 6) < 2e-3

# %%
# A measured scan: friction against load
# --------------------------------------
# The 64 x 64 scan pressed at eight pressures from :math:`10^{-4}` to
# :math:`3 \times 10^{-1} E^*` (free boundary: the scan is not periodic; each solve starts
# from the previous pressure's field). Heights are read with
# :func:`asperity.read_surface`; the local friction is 0.1 (the default of a height map).
# The coefficients are read along the file's :math:`\pm x` (across the ridges), since each
# member finds its own principal direction.
scan = asperity.read_surface(SURFACES / "scan-ridges.txt")
pressures = [1e5, 3e5, 1e6, 3e6, 1e7, 3e7, 1e8, 3e8]
family = asperity.derive_family(
    scan, asperity.ElasticContact(E_star, pressures, boundary="free"), n_directions=24)
area_d = asperity.derive(asperity.load_surface(SURFACES / "scan-ridges.txt", mu=0.1),
                         n_directions=24)


def along_x(d):
    """Tangential friction sliding along +x and along -x (psi = 0 and 180 deg)."""
    r = d.reservoir
    i0 = int(np.argmin(np.abs(r.psi)))
    i180 = int(np.argmin(np.abs(r.psi - np.pi)))
    return r.tangential[i0], r.tangential[i180]


plus, minus, fraction = [], [], []
for p, member in zip(family.pressures, family.members):
    fp, fm = along_x(member)
    plus.append(fp)
    minus.append(fm)
    fraction.append(member.texture.elastic["area_fraction"])
    pixels = round(fraction[-1] * scan.nx * scan.ny)
    print(f"p/E* = {p / E_star:.0e}: contact {fraction[-1]:6.2%} ({pixels:4d} pixels), "
          f"friction along +x "
          f"{fp:.4f}, along -x {fm:.4f}, t_a at {member.principal_direction_deg:6.2f} deg")
ap, am = along_x(area_d)
print(f"area weighting: along +x {ap:.4f}, along -x {am:.4f}")

ratio = np.array(pressures) / E_star
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4))
ax0.semilogx(ratio, plus, "o-", label="sliding along +x")
ax0.semilogx(ratio, minus, "s-", label="sliding along -x")
ax0.axhline(ap, color="C0", ls=":", label="area weighting, +x")
ax0.axhline(am, color="C1", ls="--", lw=0.8, label="area weighting, -x")
ax0.set_xlabel("p / E*")
ax0.set_ylabel("friction coefficient")
ax0.legend(fontsize=8)
ax1.loglog(ratio, fraction, "o-")
ax1.set_xlabel("p / E*")
ax1.set_ylabel("contact area fraction")
fig.tight_layout()
plt.show()

# %%
# At light load only the crests touch, and the friction is that of the facets there:
# the scan's coefficients along :math:`\pm x` part from the area-weighted ones. Nor do
# they return to them in nearly full contact: the pressure is then the nominal one plus
# the field that flattens the relief, of the order of :math:`E^*` times the slopes,
# whatever the load, so the area weighting comes back only at pressures far above that.
# At the lightest loads the contact spans a few pixels only: resolve each contact spot
# with tens of pixels before trusting such numbers (the contact is only as good as its
# grid),
# and mind what the model leaves out: plastic flow (``hardness`` caps the pressure) and
# the redistribution of load by sliding. From the command line: ``asperity derive
# surfaces/scan-ridges.txt --mu 0.15 --elastic 1e9 --pressure 1e6 1e7``, and ``asperity
# fit`` with several pressures writes the family as one gauge file that ``slide`` and
# ``risk`` take at a pressure (:doc:`/tutorials/elastic-contact`,
# :doc:`/theory/contact`).
