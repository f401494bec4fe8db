r"""
A disc that slides and spins
============================

A rigid body touches its support at many points, each sliding at its own velocity. For a
uniformly loaded disc on isotropic Coulomb friction the force and torque have closed forms
(SPEC.md section 8), and sliding and spinning stop at the same instant, with the ratio
:math:`v / (R\omega)` tending to 0.653. This example runs the body solver
(:func:`asperity.slide_body` on :func:`asperity.disc_footprint`) against the closed forms'
ODE (:func:`asperity.disc_reference`), and then spins a disc from rest on an asymmetric
law: it drifts, at the acceleration :func:`asperity.spin_drift_force` predicts.
"""
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from scipy.optimize import brentq

import asperity

SURFACES = Path(asperity.__file__).resolve().parents[1] / "surfaces"
g, R = 9.81, 0.05

# %%
# The closed forms
# ----------------
# Force :math:`-\mu N f(\varepsilon)` along the velocity and torque
# :math:`-\mu N R\, m(\varepsilon)` against the spin, :math:`\varepsilon = v / (R\omega)`
# (:func:`asperity.disc_f_m`). With :math:`I = mR^2/2`, :math:`\varepsilon` flows to the
# fixed point :math:`f(\varepsilon_0) = 2 \varepsilon_0 m(\varepsilon_0)`:
def fixed_point(eps):
    f, m = asperity.disc_f_m(eps)
    return f - 2 * eps * m


eps0 = brentq(fixed_point, 0.1, 2.0, xtol=1e-12)
print(f"terminal ratio of the disc: {eps0:.6f}")

# %%
# Slide and spin to rest
# ----------------------
# A disc of radius 5 cm and 1 kg, launched at 1 m/s and 20 rad/s on :math:`\mu = 0.3`,
# sampled at its default 1024 contact points, dt = 1e-4 s.
mu, v0, w0 = 0.3, 1.0, 20.0
run = asperity.slide_body(asperity.coulomb_law(mu), asperity.disc_footprint(R),
                          u0=v0, angle_deg=30.0, omega0=w0)
ref = asperity.disc_reference(v0, w0, mu, g=g, R=R)
s = run.summary
print(f"body solver: stop {s['stop_time']:.4f} s (slide {s['slide_stop_time']:.4f}, spin "
      f"{s['spin_stop_time']:.4f}), distance {s['distance']:.5f} m, turned "
      f"{s['final_angle_rad']:.4f} rad, {s['steps']} steps, status {s['status']}")
print(f"closed forms: stop {ref.stop_time:.4f} s, distance {ref.distance:.5f} m, turned "
      f"{ref.turned:.4f} rad")
assert abs(s["stop_time"] - ref.stop_time) < 5e-3 * ref.stop_time
assert abs(s["distance"] - ref.distance) < 5e-3 * ref.distance

res = run.result
speed = np.hypot(res.u[:, 0], res.u[:, 1])
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4))
ax0.plot(res.t, speed, label="v, body solver")
ax0.plot(res.t, R * np.abs(res.u[:, 2]), label="R$\\omega$, body solver")
ax0.plot(ref.t, ref.v, "k:", label="closed forms")
ax0.plot(ref.t, R * ref.omega, "k:")
ax0.set_xlabel("t (s)")
ax0.set_ylabel("speed (m/s)")
ax0.legend()
moving = (speed > 1e-3) & (np.abs(res.u[:, 2]) > 1e-3 / R)
ax1.plot(res.t[moving], speed[moving] / (R * np.abs(res.u[moving, 2])), label="body solver")
ax1.plot(ref.t, ref.v / (R * np.maximum(ref.omega, 1e-300)), "k:", label="closed forms")
ax1.axhline(eps0, color="0.5", lw=0.8)
ax1.set_ylim(0.6, 1.05)
ax1.set_xlabel("t (s)")
ax1.set_ylabel("v / (R $\\omega$)")
ax1.legend()
fig.tight_layout()
plt.show()

# %%
# Both stop together. The ratio falls from 1 towards 0.653 but approaches it only slowly
# (its distance from 0.653 falls like a power of the speed), so a run to rest at one step
# size ends within a few per cent of it. Fewer
# contact points are faster and less accurate: the force error falls as 1/N.
#
# Spun from rest on an asymmetric law
# -----------------------------------
# Every point of a disc spinning in place slides in another direction, and with uniform
# pressure every direction carries the same share of the load: the net force is
# :math:`-N / (2\pi) \int p(\psi)\,d\psi`, zero for a centrally symmetric law, not for an
# asymmetric one. The star law fitted to the asymmetric wedge texture in the windward
# regime:
texture = asperity.load_texture(SURFACES / "wedge-asymmetric.toml")
d = asperity.derive(texture, contact="windward", n_directions=360)
law = asperity.law_from_gauge(asperity.fit_derivation(d, kind="star"))
predicted = g * asperity.spin_drift_force(law)
spin = asperity.slide_body(law, asperity.disc_footprint(R), u0=0.0, angle_deg=0.0,
                           omega0=40.0)
first = (spin.result.u[1, :2] - spin.result.u[0, :2]) / spin.result.dt
print(f"initial acceleration: simulated ({first[0]:+.4f}, {first[1]:+.1e}) m/s^2, "
      f"predicted ({predicted[0]:+.4f}, {predicted[1]:+.1e}) m/s^2")
x, y = spin.summary["rest"]
print(f"rest at ({x * 1e3:+.2f}, {y * 1e3:+.3f}) mm after {spin.summary['stop_time']:.4f} s")
assert np.linalg.norm(first - predicted) < 1e-2 * np.linalg.norm(predicted)

t, q = spin.result.t, spin.result.q
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 3.8))
ax0.plot(t, q[:, 0] * 1e3, label="body solver")
early = t < 0.1
ax0.plot(t[early], 0.5 * predicted[0] * t[early] ** 2 * 1e3, "k:",
         label="$a t^2 / 2$, a from spin_drift_force")
ax0.set_xlabel("t (s)")
ax0.set_ylabel("x of the centre (mm)")
ax0.legend()
circle = np.linspace(0, 2 * np.pi, 100)
for k, style in ((0, ":"), (-1, "-")):
    ax1.plot((q[k, 0] + R * np.cos(circle)) * 1e3, (q[k, 1] + R * np.sin(circle)) * 1e3,
             style, color="0.4")
ax1.annotate("", xy=(q[-1, 0] * 1e3, 0), xytext=(0, 0),
             arrowprops={"arrowstyle": "->", "color": "C0", "lw": 2})
ax1.set_aspect("equal")
ax1.set_xlabel("x along $t_a$ (mm)")
ax1.set_ylabel("y (mm)")
ax1.set_title("start (dotted) and rest (solid)")
fig.tight_layout()
plt.show()

# %%
# The drift is along :math:`-t_a`. The same texture in the ``all-faces`` regime (compliant
# contact, a nearly symmetric reservoir) and a centrally symmetric law drift far less, or
# not at all:
soft = asperity.law_from_gauge(asperity.fit_derivation(asperity.derive(texture, n_directions=360)))
for name, other in (("wedge, all-faces (star fit)", soft),
                    ("ellipse 0.3 / 0.15", asperity.ellipse_law(0.3, 0.15))):
    a = g * asperity.spin_drift_force(other)
    print(f"{name:27s}: predicted acceleration ({a[0]:+.5f}, {a[1]:+.1e}) m/s^2")

# %%
# From the
# command line: ``asperity slide --mu1 0.3 --u0 1 --angle 30 --omega0 20 --body disc
# --radius 0.05`` (:doc:`/tutorials/bodies`, :doc:`/theory/bodies`).
