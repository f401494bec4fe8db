r"""
A crawling body's gait
======================

A slender body that bends in a travelling wave (a snake, a crawling robot) moves on
direction-dependent friction: forward :math:`\mu_f` (towards the head), backward
:math:`\mu_b` and transverse :math:`\mu_t` (Hu, Nirody, Scott and Shelley, PNAS 2009;
SPEC.md section 9). This example crawls the default gait -- the curvature wave
:math:`\kappa L = 7 \cos 2\pi (s/L + t/T)`, L = 1 m, T = 1 s -- with :func:`asperity.crawl`:
the speed under the three rules that turn three coefficients into a law, the tube limit
the speed tends to as :math:`\mu_t / \mu_f` grows, and a dynamic run from rest.
"""
# sphinx_gallery_thumbnail_number = 2
import matplotlib.pyplot as plt
import numpy as np
from scipy.special import j0

import asperity

A, k = 7.0, 1.0

# %%
# One set of coefficients, three rules
# ------------------------------------
# Quasi-static (no inertia: the net friction force and torque vanish at every instant),
# so the speed depends only on the gait and the law. The speed is in body lengths per
# period, head-ward positive.
for rule in ("componentwise", "associated", "colinear"):
    c = asperity.crawl(mu_f=0.1, mu_b=0.15, mu_t=0.2, rule=rule, quasi_static=True)
    print(f"{rule:13s}: {c.speed_body_lengths_per_period:+.4f} body lengths a period "
          f"({c.law_description})")

# %%
# The rule is part of the law: on the same coefficients the speeds differ several-fold.
#
# The tube limit
# --------------
# As :math:`\mu_t / \mu_f` grows the body can no longer slip sideways and follows its own
# track, at :math:`J_0(A / 2\pi k) / k` body lengths a period. The associated and the
# componentwise rules approach it, isotropic friction (ratio 1) barely propels.
limit = j0(A / (2 * np.pi * k)) / k
ratios = np.array([1.0, 1.5, 2.0, 3.0, 5.0, 10.0, 30.0, 100.0, 1000.0])
speeds = {rule: [asperity.crawl(mu_f=0.1, mu_b=0.1, mu_t=0.1 * r, rule=rule,
                                quasi_static=True).speed_body_lengths_per_period
                 for r in ratios]
          for rule in ("componentwise", "associated")}
print(f"tube limit J0(A / 2 pi k) / k = {limit:.4f}")
for rule, u in speeds.items():
    print(f"{rule:13s}: " + ", ".join(f"{r:g}: {v:+.4f}" for r, v in zip(ratios, u)))
assert abs(speeds["associated"][-1] - limit) < 1e-3 * limit

fig, ax = plt.subplots(figsize=(6, 4))
for rule, u in speeds.items():
    ax.semilogx(ratios, u, "o-", label=rule)
ax.axhline(limit, color="k", ls=":", label="tube limit $J_0(A/2\\pi k)/k$")
ax.set_xlabel("$\\mu_t / \\mu_f$")
ax.set_ylabel("speed (body lengths a period)")
ax.legend()
plt.show()

# %%
# A dynamic run from rest
# -----------------------
# With inertia (g = 9.81 m/s^2, Froude number :math:`L / (g \mu_f T^2)` about 1) the body
# starts from rest; its speed settles within a few periods, and the run averages the
# second half. The heading turns during the start, then holds.
run = asperity.crawl(mu_f=0.1, mu_b=0.15, mu_t=0.2, rule="componentwise", periods=8)
qs = asperity.crawl(mu_f=0.1, mu_b=0.15, mu_t=0.2, rule="componentwise", quasi_static=True)
print(f"Froude number {run.froude:.3f}; speed per period:",
      np.round(run.speed_per_period, 4))
print(f"averaged over periods {run.transient_periods + 1}-{run.periods}: "
      f"{run.speed_body_lengths_per_period:+.4f} (quasi-static "
      f"{qs.speed_body_lengths_per_period:+.4f}); cost of transport "
      f"{run.cost_of_transport:.3f}")


# %%
# To draw the body, its shape in its own frame from the gait's closed form: tangent angle
# :math:`\phi = (A / 2\pi k)\,[\sin 2\pi(k s/L + t/T) - \text{mean}]`, positions the
# zero-mean integral of :math:`(\cos\phi, \sin\phi)`; the run's state
# :math:`(x, y, \theta)` places and turns it.
def body_shape(t, n=201):
    s = np.linspace(0.0, 1.0, n)
    phi = A / (2 * np.pi * k) * np.sin(2 * np.pi * (k * s + t))
    phi -= phi.mean()
    e = np.exp(1j * phi)                       # unit tangents
    z = np.concatenate([[0], np.cumsum(0.5 * (s[1] - s[0]) * (e[1:] + e[:-1]))])
    return z - z.mean()


fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(13, 4.5), width_ratios=(1, 1.2, 1.2))
for j, phase in enumerate((0.0, 0.25, 0.5, 0.75)):
    z = body_shape(phase) - 0.5j * j
    ax0.plot(z.real, z.imag, color=f"C{j}")
    ax0.plot(z.real[-1], z.imag[-1], "o", color=f"C{j}", ms=4)
    ax0.text(0.6, -0.5 * j, f"t = {phase:g} T", va="center")
ax0.set_aspect("equal")
ax0.set_xlim(-0.6, 0.9)
ax0.set_axis_off()
ax0.set_title("the gait in the body frame (dot: head)")
ax1.plot(run.q[:, 0], run.q[:, 1], "k", lw=0.8, label="centre of mass")
for i, colour in ((0, "C0"), (len(run.t) - 1, "C1")):
    x, y, theta = run.q[i]
    z = x + 1j * y + np.exp(1j * theta) * body_shape(run.t[i])
    ax1.plot(z.real, z.imag, color=colour, label=f"body at t = {run.t[i]:g} s")
    ax1.plot(z.real[-1], z.imag[-1], "o", color=colour, ms=4)
ax1.set_aspect("equal")
ax1.set_xlabel("x (m)")
ax1.set_ylabel("y (m)")
ax1.legend(fontsize=8, loc="upper right")
ax2.plot(np.arange(1, run.periods + 1), run.speed_per_period, "o-", label="dynamic")
ax2.axhline(qs.speed_body_lengths_per_period, color="k", ls=":", label="quasi-static")
ax2.set_xlabel("period")
ax2.set_ylabel("speed (body lengths a period)")
ax2.legend()
fig.tight_layout()
plt.show()

# %%
# From the command line: ``asperity crawl --mu-f 0.1 --mu-b 0.15 --mu-t 0.2
# --quasi-static``; gait files, gait optimisation and the checks in
# :doc:`/tutorials/crawling` and :doc:`/theory/crawling`.
