r"""
A star-shaped law against an ellipse fit
========================================

Rigid asperities touch only the faces the motion climbs (the ``windward`` contact regime).
For the symmetric 30 deg wedge with local friction 0.3 (``surfaces/wedge-symmetric-30.toml``)
this gives a non-convex, star-shaped reservoir with a jump when sliding exactly along the
ridges (SPEC.md section 2). This example fits both laws the project offers to the same 360
directions -- the star-shaped Walker-Leine law and Antoni et al.'s truncated ellipse -- and
shows what the ellipse loses: the shape of C and the direction of the force.
"""
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import asperity

SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"

# %%
# The texture's reservoir
# -----------------------
# SPEC.md's check values: :math:`|p| = 1.061` at :math:`\psi = 0`,
# :math:`p = (0.585, 0.348)` at 89 deg and :math:`(-0.585, 0.348)` at 91 deg; at 90 deg
# the force is any point of the segment between them (``set_valued``).
texture = asperity.load_texture(SURFACES / "wedge-symmetric-30.toml")
d = asperity.derive(texture, contact="windward", n_directions=360)
r = d.reservoir
print(texture)
print(f"|p(0)| = {np.hypot(*r.p[0]):.4f}, p(89 deg) = ({r.p[89, 0]:.4f}, {r.p[89, 1]:.4f}), "
      f"p(91 deg) = ({r.p[91, 0]:.4f}, {r.p[91, 1]:.4f})")
print("set-valued at psi =", np.degrees(r.psi[r.set_valued]).round(1), "deg")

# %%
# Two fits
# --------
# ``kind="star"``: C is the polygon through the data (non-convex shapes are exact) and D
# is integrated from the sliding rule. ``kind="truncated-ellipse"``: four quarter
# ellipses fitted to the data, with the associated sliding rule (the force normal to C).
# Each fit is compared with the texture at 360 directions midway between the fitted ones.
gauges = {kind: asperity.fit_derivation(d, kind=kind) for kind in ("star", "truncated-ellipse")}
for kind, g in gauges.items():
    f = g.fit
    print(f"{kind:17s}: radial error max {f.max_radial_error:.2e}, rms "
          f"{f.rms_radial_error:.2e}; between the fitted directions force error "
          f"{f.holdout_max_magnitude_error:.1e}, angle {f.holdout_max_angle_deg:.1e} deg; "
          f"C convex: {f.C_convex}")
laws = {kind: asperity.law_from_gauge(g) for kind, g in gauges.items()}
for kind, law in laws.items():
    print(f"{kind:17s}:", ", ".join(f"{k} = {v:.4f}" for k, v in law.axes().items()))

# %%
# C and the force direction
# -------------------------
# Left: the reservoir C of each law over the texture's points. Right: the angle between
# the force :math:`p` and the sliding direction :math:`s`, the part that deflects a
# sliding body; for the texture the windward regime's lateral force jumps where the
# sliding direction crosses the ridges (90 and 270 deg).
psi = np.radians(np.arange(0.25, 360, 0.5))     # between the texture's directions
texture_p = asperity.derive(texture, contact="windward", n_directions=720).reservoir


def angle_to_slip(p, psi):
    a = np.degrees(np.arctan2(p[:, 1], p[:, 0]) - psi)
    return (a + 180.0) % 360.0 - 180.0


fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.5))
ax0.plot(r.p[:, 0], r.p[:, 1], "k.", ms=2, label="texture (windward)")
ax1.plot(np.degrees(texture_p.psi), angle_to_slip(texture_p.p, texture_p.psi), "k.", ms=2,
         label="texture (windward)")
for kind, law in laws.items():
    phi = np.linspace(0, 2 * np.pi, 721)
    rho = law.radial(phi)
    ax0.plot(rho * np.cos(phi), rho * np.sin(phi), label=kind)
    ax1.plot(np.degrees(psi), angle_to_slip(law.force(psi), psi), label=kind)
ax0.set_aspect("equal")
ax0.set_xlabel("p along $t_a$")
ax0.set_ylabel("p along $t_b$")
ax0.set_title("reservoir C")
ax0.legend(loc="center", fontsize=8)
ax1.set_xlabel("sliding direction $\\psi$ (deg)")
ax1.set_ylabel("angle from s to p (deg)")
ax1.set_xlim(0, 360)
ax1.set_title("direction of the force")
fig.tight_layout()
plt.show()

# %%
# What it does to a sliding body
# ------------------------------
# A point mass launched at 2 m/s at 60 deg from :math:`t_a` on each law (the Moreau
# solver, :func:`asperity.slide`): same texture, same launch, different paths.
for kind, law in laws.items():
    res = asperity.slide(law, u0=2.0, angle_deg=60.0)
    x, y = res.q_final
    print(f"{kind:17s}: rest at ({x:.4f}, {y:.4f}) m after {res.stop_time:.4f} s, deflected "
          f"{asperity.deflection_deg(60.0, (x, y)):+.2f} deg")

# %%
# The ellipse is close along :math:`t_a`, where the data are smooth, and off along the
# ridges, where the star-shaped C has its re-entrant corners: a convex set cannot follow
# them, and with its associated rule the force direction is off by up to the angle printed
# above. Use the star law when C is not convex (``asperity fit`` says so) and the
# ellipse where a code only takes an ellipse (an Abaqus ``*FRICTION, ANISOTROPIC`` block,
# :doc:`/tutorials/gauge-export`). Theory: :doc:`/theory/laws`.
