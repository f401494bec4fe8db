"""Closed forms of a footprint that slides and spins on isotropic Coulomb friction, the drift
of a pure spin on a direction-dependent law, and the reference ODE of the disc and the ring
(SPEC.md section 8; Farkas, Bartels, Unger, Wolf, PRL 90, 248302, 2003).

A body slides at speed v and spins at omega; eps = v / (R omega).  The friction of a
uniformly loaded footprint of radius R under load N is a force -mu N f(eps) along the
velocity and a torque -mu N R m(eps) against the spin:

* the **disc** (:func:`disc_f_m`), SPEC.md 8: f(1) = 8/(3 pi), m(1) = 8/(9 pi), m(0) = 2/3;
* the **thin ring** (:func:`ring_f_m`), derived here.  A point at angle phi moves at
  v e_x + omega R (-sin phi, cos phi); averaging its unit velocity and its moment over
  phi gives

      f(eps) = (1/2pi) int (eps - sin phi) / rho dphi,  m(eps) = (1/2pi) int (1 - eps sin phi) / rho dphi,
      rho = sqrt(1 + eps^2 - 2 eps sin phi),

  i.e. with k = 2 sqrt(eps)/(1 + eps) and K, E of modulus k,
  m = [(1 - eps) K + (1 + eps) E] / pi,  f = [(eps - 1) K + (1 + eps) E] / (pi eps),
  and by Landen's transformation (modulus eps, or 1/eps beyond 1)

      eps <= 1:  m = (2/pi) E(eps),        f = (2/(pi eps)) [E(eps) - (1 - eps^2) K(eps)],
      eps >= 1:  m = (2 eps/pi) [E(1/eps) - (1 - 1/eps^2) K(1/eps)],  f = (2/pi) E(1/eps).

  So f(eps) = m(1/eps): f(1) = m(1) = 2/pi, m(0) = 1, f ~ eps/2 for a slow slide and
  m ~ 1/(2 eps) for a slow spin.

Both are written with B(k) = (E - k'^2 K)/k^2 (no cancellation), and evaluated from the
power series of K, E in k^2 where k^2 <= 1/4 (else scipy's ellipk/ellipe), so that they are
accurate to a few ulps for every eps in [0, inf], the limits included.

With I = k_I M R^2 (k_I = 1/2 disc, 1 ring): dv/dt = -mu g f, domega/dt = -(mu g/(k_I R)) m,
and d eps/dt = (mu g / (R omega)) (eps m / k_I - f): the fixed point f(eps0) = eps0 m(eps0) / k_I
is eps0 = 0.653002 for the disc and exactly 1 for the ring (f(1) = m(1)); both attract, so
slide and spin stop together.  :func:`disc_reference` integrates this ODE to rest.

:func:`spin_drift_force`: a pure spin (v = 0) of a uniformly loaded footprint on a law whose
sliding force is p(psi) feels the net force -N/(2 pi) int p(psi) dpsi, zero for a centrally
symmetric law (p(psi + pi) = -p(psi)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_array, check_choice, check_instance, check_range

#: I / (M R^2) of each footprint the reference knows
INERTIA_FACTOR = {"disc": 0.5, "ring": 1.0}
#: the terminal ratio v / (R omega) as slide and spin stop (the attracting fixed point)
TERMINAL_RATIO = {"disc": 0.6530018, "ring": 1.0}

_SERIES_X = 0.25            # below this k^2, power series (no cancellation); above, scipy
_N_TERMS = 48               # 0.25**48 ~ 1e-29


def _series_coefficients(n: int):
    """Coefficients in x = k^2 of K, E and B = (E - (1-x) K)/x (each times 2/pi)."""
    c = np.empty(n + 2)
    c[0] = 1.0
    for j in range(1, n + 2):
        c[j] = c[j - 1] * ((2 * j - 1) / (2 * j)) ** 2
    j = np.arange(n + 2)
    Kc, Ec = c, c / (1.0 - 2.0 * j)
    Bc = Ec[1:] - Kc[1:] + Kc[:-1]            # B_j = E_{j+1} - K_{j+1} + K_j
    return Kc[:n], Ec[:n], Bc[:n]


_KC, _EC, _BC = _series_coefficients(_N_TERMS)
#: series of S(x) = [E - (2 - 3x) B] / x (the disc's torque beyond eps = 1): S_j = E_{j+1}
#: - 2 B_{j+1} + 3 B_j; its constant term E_0 - 2 B_0 = 0 is dropped exactly
_SC = _EC[1:] - 2.0 * _BC[1:] + 3.0 * _BC[:-1]


def _poly(coef, x):
    out = np.zeros_like(x)
    for c in coef[::-1]:
        out = out * x + c
    return out


def _ekb(x: np.ndarray):
    """E, B (and S for the disc) of parameter x = k^2 in [0, 1], arrays."""
    from scipy.special import ellipe, ellipk
    small = x <= _SERIES_X
    xs = np.where(small, x, 0.0)
    half_pi = 0.5 * math.pi
    E = half_pi * _poly(_EC, xs)
    B = half_pi * _poly(_BC, xs)
    S = half_pi * _poly(_SC, xs)
    if not np.all(small):
        xl = np.where(small, 0.5, x)
        El = ellipe(xl)
        with np.errstate(invalid="ignore", divide="ignore"):
            kk = np.where(xl < 1.0, (1.0 - xl) * ellipk(xl), 0.0)    # (1 - x) K -> 0 at x = 1
        Bl = (El - kk) / xl
        Sl = (El - (2.0 - 3.0 * xl) * Bl) / xl
        E, B, S = (np.where(small, a, b) for a, b in ((E, El), (B, Bl), (S, Sl)))
    return E, B, S


def _eps_array(eps):
    if isinstance(eps, (bool, np.bool_)) or (isinstance(eps, (list, tuple)) and any(
            isinstance(x, (bool, np.bool_)) for x in eps)):
        raise InputError(f"eps (v / (R omega)) must be a number or an array, got {eps!r}")
    a = check_array("eps", eps, ndim=None, finite=False)
    if np.any(np.isnan(a)) or np.any(a < 0):
        bad = a[np.isnan(a) | (a < 0)].ravel()[0]
        raise InputError(f"eps (v / (R omega)) must be in [0, inf], got {bad:g}")
    return a


def disc_f_m(eps):
    """Force and torque factors (f, m) of a uniformly loaded disc that slides and spins on
    isotropic Coulomb friction (SPEC.md 8).

    A disc of radius R under load N sliding at v and spinning at omega feels the force
    -mu N f(eps) along the velocity and the torque -mu N R m(eps) against the spin.

    Parameters
    ----------
    eps : float or array_like of float
        v / (R omega), in [0, inf]: inf is a pure slide, 0 a pure spin.

    Returns
    -------
    f : float or numpy.ndarray
        The force factor, in [0, 1] (f(0) = 0, f(inf) = 1); an array for an array ``eps``.
    m : float or numpy.ndarray
        The torque factor, in [0, 2/3] (m(0) = 2/3, m(inf) = 0).

    Raises
    ------
    InputError
        ``eps`` negative or NaN.

    See Also
    --------
    asperity.ring_f_m, asperity.disc_reference, asperity.disc_footprint

    Notes
    -----
    With K, E the complete elliptic integrals of modulus k (SPEC.md 8), for eps <= 1

    .. math::

        f = \\frac{4}{3 \\pi \\epsilon}\\left[(1 + \\epsilon^2) E(\\epsilon)
            - (1 - \\epsilon^2) K(\\epsilon)\\right], \\quad
        m = \\frac{4}{9 \\pi}\\left[(4 - 2 \\epsilon^2) E(\\epsilon)
            - (1 - \\epsilon^2) K(\\epsilon)\\right],

    and the forms of modulus 1/eps beyond 1.  Written with B(k) = (E - k'^2 K)/k^2 (no
    cancellation) and evaluated from the power series of K, E where k^2 <= 1/4, they are
    accurate to a few ulps for every eps, the limits included.

    Examples
    --------
    f(1) = 8/(3 pi), m(1) = 8/(9 pi), m(0) = 2/3:

    >>> f, m = asperity.disc_f_m(1.0)
    >>> print(f"{f:.6f} {8 / (3 * np.pi):.6f} {m:.6f} {8 / (9 * np.pi):.6f}")
    0.848826 0.848826 0.282942 0.282942
    >>> f, m = asperity.disc_f_m(np.array([0.0, 0.5, 2.0, np.inf]))
    >>> f.round(6).tolist(), m.round(6).tolist()
    ([0.0, 0.483844, 0.967688, 1.0], [0.666667, 0.547748, 0.127809, 0.0])
    """
    e = _eps_array(eps)
    low = e <= 1.0
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        inv = np.where(low, 1.0, 1.0 / np.where(e == 0, 1.0, e))
        x = np.where(low, e * e, inv * inv)
        E, B, S = _ekb(x)
        f = np.where(low, (4.0 / (3.0 * math.pi)) * e * (E + B),
                     (4.0 / (3.0 * math.pi)) * (E + B))
        m = np.where(low, (4.0 / (9.0 * math.pi)) * ((3.0 - 2.0 * x) * E + x * B),
                     (4.0 / (9.0 * math.pi)) * S * inv)
    return _out(f, eps), _out(m, eps)


def ring_f_m(eps):
    """Force and torque factors (f, m) of a uniformly loaded thin ring that slides and spins
    on isotropic Coulomb friction.

    A ring of radius R under load N sliding at v and spinning at omega feels the force
    -mu N f(eps) along the velocity and the torque -mu N R m(eps) against the spin.

    Parameters
    ----------
    eps : float or array_like of float
        v / (R omega), in [0, inf]: inf is a pure slide, 0 a pure spin.

    Returns
    -------
    f : float or numpy.ndarray
        The force factor, in [0, 1] (f(0) = 0, f(inf) = 1); an array for an array ``eps``.
    m : float or numpy.ndarray
        The torque factor, in [0, 1] (m(0) = 1, m(inf) = 0).

    Raises
    ------
    InputError
        ``eps`` negative or NaN.

    See Also
    --------
    asperity.disc_f_m, asperity.disc_reference, asperity.ring_footprint

    Notes
    -----
    Derived in the module's docstring (``asperity.bodies.closed_forms``): by Landen's
    transformation, with K, E of modulus eps (or 1/eps beyond 1),

    .. math::

        \\epsilon \\le 1: \\; m = \\frac{2}{\\pi} E(\\epsilon), \\quad
        f = \\frac{2}{\\pi \\epsilon}\\left[E(\\epsilon)
            - (1 - \\epsilon^2) K(\\epsilon)\\right],

    and f(eps) = m(1/eps): f(1) = m(1) = 2/pi, f ~ eps/2 for a slow slide and
    m ~ 1/(2 eps) for a slow spin.

    Examples
    --------
    >>> f, m = asperity.ring_f_m(1.0)
    >>> print(f"{f:.6f} {m:.6f} {2 / np.pi:.6f}")
    0.636620 0.636620 0.636620
    >>> print(f"{asperity.ring_f_m(3.0)[0]:.12f} {asperity.ring_f_m(1 / 3)[1]:.12f}")
    0.971614975269 0.971614975269
    """
    e = _eps_array(eps)
    low = e <= 1.0
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        inv = np.where(low, 1.0, 1.0 / np.where(e == 0, 1.0, e))
        x = np.where(low, e * e, inv * inv)
        E, B, _ = _ekb(x)
        small = (2.0 / math.pi) * E                  # m below 1, f beyond 1
        big = (2.0 / math.pi) * B                    # times eps: f below 1; times 1/eps: m
        f = np.where(low, big * e, small)
        m = np.where(low, small, big * inv)
    return _out(f, eps), _out(m, eps)


def footprint_f_m(kind: str, eps):
    """(f, m) of ``kind`` "disc" or "ring"."""
    check_choice("kind", kind, tuple(INERTIA_FACTOR))
    return disc_f_m(eps) if kind == "disc" else ring_f_m(eps)


def _out(a, like):
    return float(a) if np.ndim(like) == 0 else a


def terminal_ratio(kind: str = "disc", tol: float = 1e-14) -> float:
    """The fixed point eps0 of d eps/dt: f(eps0) = eps0 m(eps0) / k_I (0.653002 for the
    disc, 1 for the ring), by bisection on [0.1, 10]."""
    from scipy.optimize import brentq
    check_choice("kind", kind, tuple(INERTIA_FACTOR))
    k = INERTIA_FACTOR[kind]

    def g(e):
        f, m = footprint_f_m(kind, e)
        return f - e * m / k
    return float(brentq(g, 0.1, 10.0, xtol=tol, rtol=4 * np.finfo(float).eps))


# ----------------------------------------------------------------------------- spin drift

def spin_drift_force(law, n: int = 4096) -> np.ndarray:
    """Net friction force per unit normal load of a pure spin with uniform pressure on a
    direction-dependent law (SPEC.md 8).

    Parameters
    ----------
    law : PlanarLaw
        The friction law (:func:`asperity.coulomb_law`, :func:`asperity.law_from_gauge`,
        ...), whose sliding force per unit load is p(psi).
    n : int, optional
        Sliding directions of the periodic trapezoid rule, in [8, 1e7] (default 4096):
        spectrally accurate for a smooth p; for a law with corners the error is O(1/n^2).

    Returns
    -------
    (2,) numpy.ndarray
        -1/(2 pi) int_0^2pi p(psi) dpsi in the law's frame, per unit normal load.  The
        body's acceleration is g times this.

    Raises
    ------
    InputError
        ``law`` not a PlanarLaw, ``n`` outside its range.

    See Also
    --------
    asperity.slide_body, asperity.disc_f_m

    Notes
    -----
    Each point of a spinning footprint slides in the direction psi of omega x r, and with
    uniform pressure every direction carries the same share of the load; the sum of the
    points' forces -p(psi) is the average of -p.  Zero for a centrally symmetric law
    (p(psi + pi) = -p(psi): Coulomb, the ellipse), not for an asymmetric one (a truncated
    ellipse with mu_a+ != mu_a-, the windward star): the part drifts.

    Examples
    --------
    Hu et al.'s componentwise law, p = (mu_f|mu_b cos psi, mu_t sin psi), drifts by
    -(mu_f - mu_b)/pi along x; Coulomb friction does not drift:

    >>> law = asperity.componentwise_law(0.2, 0.1, 0.15)
    >>> print(f"{asperity.spin_drift_force(law)[0]:.6f} {-(0.2 - 0.1) / np.pi:.6f}")
    -0.031831 -0.031831
    >>> bool(np.allclose(asperity.spin_drift_force(asperity.coulomb_law(0.3)), 0.0))
    True
    """
    from ..errors import check_int
    from ..laws.planar import PlanarLaw
    check_instance("law", law, PlanarLaw)
    n = check_int("n", n, 8, 10**7)
    psi = 2.0 * math.pi * np.arange(n) / n
    return -np.mean(law.force(psi), axis=0)


# ----------------------------------------------------------------------------- reference ODE

@dataclass(frozen=True)
class DiscReference:
    """An accurate integration of the disc's (or ring's) closed forms to rest.

    Attributes
    ----------
    stop_time : float
        When the motion ends, s.
    slide_stop_time : float
        When v reaches 0, s.
    spin_stop_time : float
        When omega reaches 0, s.
    distance : float
        Path length slid, m.
    turned : float
        Angle turned, rad.
    terminal_ratio : float or None
        v / (R omega) as the motion ends (None when one of them was zero from the
        start).
    together : bool
        Slide and spin stop at the same time.
    t, v, omega : ndarray
        The path (t increasing).
    kind : str
        ``"disc"`` or ``"ring"``.
    """

    stop_time: float
    slide_stop_time: float
    spin_stop_time: float
    distance: float
    turned: float
    terminal_ratio: float | None
    together: bool
    t: np.ndarray
    v: np.ndarray
    omega: np.ndarray
    kind: str


def disc_reference(v0: float, omega0: float, mu: float, g: float = 9.81, R: float = 0.05,
                   kind: str = "disc", rtol: float = 1e-12) -> DiscReference:
    """Integrate the closed forms of a disc (or thin ring) that slides and spins, to rest.

    Parameters
    ----------
    v0 : float
        Initial sliding speed, m/s, in [0, 1e4].
    omega0 : float
        Initial spin, rad/s, in [0, 1e6].
    mu : float
        Coulomb coefficient, in [1e-6, 100].
    g : float, optional
        Gravity, m/s^2, in [1e-6, 1e4] (default 9.81).
    R : float, optional
        Radius, m, in [1e-9, 1e3] (default 0.05).
    kind : str, optional
        "disc" (default; I = M R^2 / 2) or "ring" (I = M R^2).
    rtol : float, optional
        Relative tolerance of scipy's ``solve_ivp`` (DOP853), in [1e-14, 1e-3]
        (default 1e-12).

    Returns
    -------
    DiscReference
        A frozen record: ``stop_time``, ``slide_stop_time``, ``spin_stop_time`` (s),
        ``distance`` (m, the path slid), ``turned`` (rad), ``terminal_ratio`` (v / (R omega)
        as the motion ends; None when v0 or omega0 is 0), ``together`` (slide and spin stop
        at the same time), the path ``t``, ``v``, ``omega`` (arrays, t increasing) and
        ``kind``.

    Raises
    ------
    InputError
        A value outside its range.

    See Also
    --------
    asperity.disc_f_m, asperity.ring_f_m, asperity.slide_body

    Notes
    -----
    dv/dt = -mu g f(eps), domega/dt = -(mu g / (k_I R)) m(eps), eps = v / (R omega),
    k_I = 1/2 for the disc, 1 for the ring.  Both stop at the same finite time, and the
    ODE is singular there (d eps/dt ~ 1/omega), so it is integrated in the variable
    lambda = ln(omega0 / omega) instead of t: with w = R omega, a = mu g,

    .. math::

        \\frac{d\\epsilon}{d\\lambda} = \\epsilon - \\frac{k_I f(\\epsilon)}{m(\\epsilon)},
        \\quad \\frac{dt}{d\\lambda} = \\frac{k_I w}{a m(\\epsilon)},
        \\quad \\frac{ds}{d\\lambda} = \\epsilon w \\frac{dt}{d\\lambda},
        \\quad \\frac{d\\theta}{d\\lambda} = \\frac{w}{R} \\frac{dt}{d\\lambda},

    from lambda = 0 until w has fallen to 1e-40 of max(v0, R omega0).  eps follows a
    one-dimensional flow whose only fixed point, f(eps0) = eps0 m(eps0) / k_I, attracts
    every start with v0, omega0 > 0: the terminal ratio is eps0 (0.653002 disc, 1 ring)
    and slide and spin stop together.

    Pure slide (omega0 = 0): the point mass, t = v0 / (mu g), distance v0^2 / (2 mu g).
    Pure spin (v0 = 0): t = k_I R omega0 / (mu g m(0)) (disc: m(0) = 2/3,
    t = 3 R omega0 / (4 mu g); ring: m(0) = 1, t = R omega0 / (mu g)); no terminal ratio,
    ``together`` False (one of the two never moved).

    Examples
    --------
    A disc launched at 0.5 m/s spinning at 20 rad/s on mu = 0.3 stops sliding and spinning
    together, at the terminal ratio of SPEC.md 8:

    >>> ref = asperity.disc_reference(0.5, 20.0, 0.3)
    >>> print(f"{ref.stop_time:.4f} s {ref.distance:.4f} m ratio {ref.terminal_ratio:.6f}")
    0.3233 s 0.0835 m ratio 0.653002
    >>> ref.together
    True
    >>> ref = asperity.disc_reference(1.0, 0.0, 0.3)                 # a pure slide
    >>> print(f"{ref.stop_time:.6f} {1.0 / (0.3 * 9.81):.6f}")
    0.339789 0.339789
    """
    from scipy.integrate import solve_ivp
    v0 = check_range("v0", v0, 0.0, 1e4, unit="m/s")
    omega0 = check_range("omega0", omega0, 0.0, 1e6, unit="rad/s")
    mu = check_range("mu", mu, 1e-6, 100.0)
    g = check_range("g", g, 1e-6, 1e4, unit="m/s^2")
    R = check_range("R", R, 1e-9, 1e3, unit="m")
    check_choice("kind", kind, tuple(INERTIA_FACTOR))
    rtol = check_range("rtol", rtol, 1e-14, 1e-3)
    kI = INERTIA_FACTOR[kind]
    a = mu * g
    w0 = R * omega0
    m0 = footprint_f_m(kind, 0.0)[1]
    if v0 == 0.0 or omega0 == 0.0:            # one of them alone: constant deceleration
        ts = v0 / a
        tw = kI * w0 / (a * m0)
        t = np.linspace(0.0, max(ts, tw), 201)
        v = np.maximum(v0 - a * t, 0.0)
        w = np.maximum(w0 - a * m0 / kI * t, 0.0)
        return DiscReference(max(ts, tw), ts, tw, v0 * ts / 2, w0 * tw / (2 * R), None,
                             False, t, v, w / R, kind)

    def rhs(lam, y):
        e = max(y[0], 0.0)
        f, m = footprint_f_m(kind, e)
        w = w0 * math.exp(-lam)
        dt = kI * w / (a * m)
        return [e - kI * f / m, dt, e * w * dt, w / R * dt]

    lam_end = math.log(w0 / (1e-40 * max(v0, w0)))
    sol = solve_ivp(rhs, (0.0, lam_end), [v0 / w0, 0.0, 0.0, 0.0], method="DOP853",
                    rtol=rtol, atol=[rtol * 1e-3, rtol * 1e-3 * w0 / a,
                                     rtol * 1e-3 * w0 * w0 / a, rtol * 1e-3 * w0 * w0 / (a * R)],
                    dense_output=True)
    if sol.status != 0:                       # pragma: no cover -- scipy gave up
        raise InputError(f"disc_reference: the integration failed ({sol.message})")
    eps, t, s, th = (sol.y[i] for i in range(4))
    w = w0 * np.exp(-sol.t)
    stop = float(t[-1])
    return DiscReference(stop, stop, stop, float(s[-1]), float(th[-1]), float(eps[-1]),
                         True, t, eps * w, w / R, kind)
