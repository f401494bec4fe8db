"""``asperity.Force``, the public external load of a sliding body (issue 25, item 7): the
name resolves from the package (lazily, the old home ``asperity.dynamics.moreau`` kept), its
waveforms are the documented ones, and ``slide_body`` and ``simulate_body`` take it, checked
against the closed forms of a body pushed from rest:

* a uniformly loaded body on a law whose principal axis lies along the push slides without
  turning; while it slides every contact resists with mu_axis of its weight, so
  v(t) = (F / m - mu_axis g) t and x(t) = v(t) t / 2 (the midpoint scheme is exact for a
  constant acceleration), mu_axis = mu1 along t_a and mu2 along t_b of an associated ellipse;
  below mu_axis m g it does not move;
* a torque T on four contacts at radius r on Coulomb friction: the friction torque is at most
  mu m g r, so omega(t) = (T - mu m g r sign T) t / I, the centre still; below, at rest.

The texture angle turns the law, not the force: a push along t_a at a texture angle of 35 or
120 deg meets mu1 only if the force is kept in the world frame (a force turned with the
texture meets a mix of mu1 and mu2 and drifts sideways: the issue's planted bug)."""
from __future__ import annotations

import doctest
import math
import subprocess
import sys

import numpy as np
import pytest

import asperity
from asperity import Force, coulomb_law, disc_footprint, ellipse_law, simulate_body, slide_body
from asperity.errors import InputError

G = 9.81


def test_force_is_public_and_lazy():
    from asperity.dynamics import moreau
    assert "Force" in asperity.__all__ and Force is moreau.Force   # the old import still works
    code = ("import sys, asperity\n"
            "print([m for m in sys.modules if m.startswith('asperity.')])\n"
            "from asperity import Force\n"
            "print(Force.__module__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60, check=False)
    assert out.stdout.split("\n")[:2] == ["[]", "asperity.dynamics.force"], out.stderr


def test_docstring_example_runs():
    """The docstring's example (units and numbers) is what the library gives."""
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    for test in doctest.DocTestFinder().find(Force, "Force", globs={}):
        runner.run(test)
    assert runner.summarize(verbose=False).attempted >= 5
    assert runner.summarize(verbose=False).failed == 0


def test_waveforms():
    t = np.array([0.0, 0.1, 0.24, 0.26, 0.49, 0.5, 0.75, 1.1])
    T = 0.5
    sq = Force(constant=(1.0, -2.0), amplitude=(3.0, 0.0, 0.5), period=T, waveform="square")(t)
    w = np.where(np.mod(t / T, 1.0) < 0.5, 1.0, -1.0)
    np.testing.assert_allclose(sq, np.column_stack([1.0 + 3.0 * w, np.full_like(t, -2.0),
                                                    0.5 * w]), rtol=0, atol=1e-15)
    sine = Force(amplitude=(0.0, 2.0), period=T, waveform="sine")(t)
    np.testing.assert_allclose(sine[:, 1], 2.0 * np.sin(2 * np.pi * t / T), atol=1e-15)
    assert np.all(sine[:, [0, 2]] == 0.0)
    # waveform "none": the amplitude is not applied
    assert np.all(Force(constant=(0.0, 0.0, 1.5), amplitude=(9.0, 9.0))(t)
                  == [[0.0, 0.0, 1.5]] * len(t))


@pytest.mark.parametrize("value, words", [
    ([1.0, 2.0, 3.0, 4.0], "constant must be 1 to 3 numbers"),
    ([], "constant must be 1 to 3 numbers"),
    ([[1.0, 2.0]], "constant must have 1 dimension"),
    ([2e12, 0.0], "within +-1e12"),
    ([math.nan, 0.0], "constant must be finite"),
    (True, "constant must have 1 dimension"),
])
def test_bad_loads_are_refused_in_one_line(value, words):
    with pytest.raises(InputError) as exc:
        Force(constant=value)
    assert words in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("texture_angle", [0.0, 35.0, 120.0])
@pytest.mark.parametrize("axis, mu", [(0.0, 0.3), (90.0, 0.1)])      # t_a: mu1, t_b: mu2
def test_slide_body_pushed_along_a_principal_axis(texture_angle, axis, mu):
    m, dt, t_end = 2.0, 1e-3, 0.2
    e = np.array([math.cos(math.radians(texture_angle + axis)),
                  math.sin(math.radians(texture_angle + axis))])
    body = disc_footprint(0.05, contact_points=64)
    for ratio in (1.5, 0.8):                   # F above and below what friction holds
        F = ratio * mu * m * G
        s = slide_body(ellipse_law(0.3, 0.1), body, 0.0, 0.0, mass=m, dt=dt, t_end=t_end,
                       force=Force(constant=tuple(F * e)), texture_angle_deg=texture_angle)
        r = s.result
        assert r.status == "ok" and r.t[-1] == pytest.approx(t_end)
        acc = max(F / m - mu * G, 0.0)
        v, x = acc * r.t, 0.5 * acc * r.t ** 2
        err = f"push {ratio} x mu m g along {texture_angle + axis} deg, mu = {mu}"
        np.testing.assert_allclose(r.u[:, :2], v[:, None] * e, rtol=0, atol=1e-9,
                                   err_msg=err)
        np.testing.assert_allclose(r.q[:, :2], x[:, None] * e, rtol=0, atol=1e-10,
                                   err_msg=err)
        assert np.abs(r.u[:, 2]).max() < 1e-9, err              # no spin from a push


@pytest.mark.parametrize("ratio", [0.5, 2.0, -3.0])
def test_simulate_body_turned_by_a_torque(ratio):
    r0, mu, m, dt, t_end = 0.02, 0.2, 1.5, 1e-3, 0.1
    inertia = m * r0 ** 2
    Tf = mu * m * G * r0                       # the most torque friction holds
    T = ratio * Tf
    res = simulate_body([[r0, 0.0], [-r0, 0.0], [0.0, r0], [0.0, -r0]], [0.25] * 4,
                        coulomb_law(mu), mass=m, inertia=inertia, u0=[0.0, 0.0, 0.0],
                        dt=dt, t_end=t_end, force=Force(constant=(0.0, 0.0, T)))
    assert res.status == "ok"
    alpha = (T - math.copysign(Tf, T)) / inertia if abs(T) > Tf else 0.0
    np.testing.assert_allclose(res.u[:, 2], alpha * res.t, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(res.q[:, 2], 0.5 * alpha * res.t ** 2, rtol=1e-9, atol=1e-12)
    assert np.abs(res.u[:, :2]).max() < 1e-12 and np.abs(res.q[:, :2]).max() < 1e-12
