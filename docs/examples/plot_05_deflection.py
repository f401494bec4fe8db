r"""
A point mass deflected towards low friction
===========================================

On an anisotropic surface the friction force is not opposite to the velocity, so a body
launched obliquely does not slide straight. This example launches a point mass at 2 m/s
from the origin at several angles from :math:`t_a` on three laws with the same axis
coefficients, :math:`\mu_1 = 0.6` along :math:`t_a` and :math:`\mu_2 = 0.3` along
:math:`t_b` (Walker and Leine's comparison, SPEC.md section 4): the collinear law (force
along the velocity), the associated ellipse and the star-shaped law. It integrates each
with the Moreau midpoint scheme (:func:`asperity.slide`, exact stick) and checks the
solver against the closed forms of Coulomb friction first.
"""
import matplotlib.pyplot as plt
import numpy as np

import asperity

g, u0 = 9.81, 2.0

# %%
# Closed forms first
# ------------------
# With isotropic Coulomb friction a mass launched at :math:`u_0` stops after
# :math:`u_0 / (\mu g)` and :math:`u_0^2 / (2 \mu g)`; along a principal axis of the
# ellipse the same holds with that axis's coefficient. The stop time is a whole number of
# steps (dt = 1e-4 s), so it matches to a step; the distance to second order in dt.
checks = [("Coulomb mu = 0.3", asperity.coulomb_law(0.3), 37.0, 0.3),
          ("ellipse along t_a", asperity.ellipse_law(0.6, 0.3), 0.0, 0.6),
          ("ellipse along t_b", asperity.ellipse_law(0.6, 0.3), 90.0, 0.3)]
for name, law, angle, mu in checks:
    res = asperity.slide(law, u0=u0, angle_deg=angle)
    dist = float(np.hypot(*res.q_final))
    t_ref, d_ref = u0 / (mu * g), u0 ** 2 / (2 * mu * g)
    print(f"{name:18s}: stop {res.stop_time:.4f} s (closed form {t_ref:.4f}), "
          f"distance {dist:.6f} m (closed form {d_ref:.6f}, relative difference "
          f"{abs(dist - d_ref) / d_ref:.1e})")
    assert abs(res.stop_time - t_ref) <= res.dt and abs(dist - d_ref) < 1e-3 * d_ref

# %%
# Three laws, five launch angles
# ------------------------------
# ``deflection_deg`` is the signed angle from the launch direction to the line from the
# start to the rest point, positive towards :math:`t_b`: here towards the low-friction
# axis.
laws = {"collinear": asperity.collinear_law(mu1=0.6, mu2=0.3),
        "associated ellipse": asperity.ellipse_law(0.6, 0.3),
        "star-shaped": asperity.star_law(0.6, 0.3)}
angles = (15.0, 30.0, 45.0, 60.0, 75.0)
fig, axes = plt.subplots(1, 3, figsize=(12, 4.3), sharex=True, sharey=True)
for ax, (name, law) in zip(axes, laws.items()):
    print(f"{name}: {law.description}")
    for angle in angles:
        res = asperity.slide(law, u0=u0, angle_deg=angle)
        x, y = res.q_final
        defl = asperity.deflection_deg(angle, (x, y))
        print(f"  launched at {angle:4.1f} deg: rest at ({x:.4f}, {y:.4f}) m after "
              f"{res.stop_time:.4f} s, deflected {defl:+7.3f} deg")
        line, = ax.plot(res.q[:, 0], res.q[:, 1], lw=1.5)
        a = np.radians(angle)
        ax.plot([0, 0.6 * np.cos(a)], [0, 0.6 * np.sin(a)], ":", color=line.get_color(),
                lw=0.8)
        ax.plot(x, y, "o", color=line.get_color(), ms=4)
    ax.set_title(name)
    ax.set_aspect("equal")
    ax.set_xlabel("x along $t_a$ (m)")
axes[0].set_ylabel("y along $t_b$ (m)")
fig.suptitle("paths (solid) and launch directions (dotted), $u_0$ = 2 m/s")
fig.tight_layout()
plt.show()

# %%
# The collinear path is straight (no lateral force), the ellipse and the star law bend
# towards :math:`t_b`, the low-friction axis; the star law's sliding set has a flat edge
# across :math:`t_b`, so its paths end sliding exactly along :math:`t_b`. The same runs
# from the command line: ``asperity slide --law ellipse --mu1 0.6 --mu2 0.3 --u0 2
# --angle 30`` (:doc:`/tutorials/bodies`); the scheme and its convergence in
# :doc:`/theory/sliding`.
