"""The componentwise law (Hu, Nirody, Scott and Shelley, PNAS 106:10081, 2009) as a gauge
file: three coefficients and the rule named, with the law's own forces as its data.

The law itself is :func:`asperity.laws.planar.componentwise_law`; a gauge file of it has
``"law": "componentwise"``, ``parameters = {"rule": "componentwise", "mu_f", "mu_b",
"mu_t"}`` (forward = +t_a, backward = -t_a, transverse = +-t_b), the closed-form forces at
``directions`` sliding directions as ``data`` and the fit report of the law against them
(zero errors to rounding), so every reader of gauge files (``law``, ``slide``, bodies,
plots) takes it as it is.
"""
from __future__ import annotations

import math

import numpy as np

RULE = "componentwise"
#: the source of a componentwise gauge file: given by coefficients, not fitted to a texture
CONTACT = "coefficients"
NAMES = ("mu_f", "mu_b", "mu_t")


def closed_form(psi, mu_f: float, mu_b: float, mu_t: float) -> np.ndarray:
    """(m, 2) p = (mu_{f|b} cos psi, mu_t sin psi), mu_f where cos psi >= 0."""
    c, s = np.cos(psi), np.sin(psi)
    return np.column_stack([np.where(c >= 0, mu_f, mu_b) * c, mu_t * s])


def componentwise_pair(mu_f: float, mu_b: float, mu_t: float):
    """The WalkerLeineLaw of the rule: C the truncated ellipse (mu_f, mu_b, mu_t, mu_t), D
    the one of semi-axes sqrt(mu_i min mu) (inside C, touching it on the smallest axis).

    D's boundary point of outward normal u is (A^2 u_x, B^2 u_y) / h(u) with A^2 =
    mu_{f|b} min mu, B^2 = mu_t min mu: on the ray of (mu_{f|b} u_x, mu_t u_y), a point
    of C's boundary -- the force of the rule."""
    from .geometry import check_mu_law
    from .sets import TruncatedEllipse
    from .walker_leine import WalkerLeineLaw
    f, b, t = (check_mu_law(n, v) for n, v in zip(NAMES, (mu_f, mu_b, mu_t)))
    m = min(f, b, t)
    D = TruncatedEllipse(*(math.sqrt(v * m) for v in (f, b, t, t)))
    return WalkerLeineLaw(TruncatedEllipse(f, b, t, t), D)


def coefficients(law) -> dict:
    """{"mu_f", "mu_b", "mu_t"} of a componentwise PlanarLaw or WalkerLeineLaw (from C)."""
    C = getattr(law, "law", law).C
    return {"mu_f": float(C.mu_a_plus), "mu_b": float(C.mu_a_minus), "mu_t": float(C.mu_b_plus)}


def parameters(law) -> dict:
    """The ``parameters`` object of a gauge file of the law."""
    return {"rule": RULE, **coefficients(law)}


def from_parameters(prm: dict):
    """The WalkerLeineLaw of a gauge file's ``parameters`` (schema-checked)."""
    return componentwise_pair(prm["mu_f"], prm["mu_b"], prm["mu_t"])


def componentwise_gauge(mu_f: float, mu_b: float, mu_t: float, directions: int = 360):
    """The GaugeLaw of the componentwise law (write it with :func:`write_gauge`)."""
    from ..errors import check_int
    from .fitting import GaugeLaw, ReservoirData, _quality
    n = check_int("directions", directions, 8, 100_000)
    law = componentwise_pair(mu_f, mu_b, mu_t)
    k = coefficients(law)
    psi = 2 * math.pi * np.arange(n) / n
    data = ReservoirData(psi, closed_form(psi, k["mu_f"], k["mu_b"], k["mu_t"]),
                         np.zeros(n, np.int64))
    source = {"texture": {"kind": "coefficients", "rule": RULE, **k,
                          "reference": "Hu, Nirody, Scott and Shelley, PNAS 106:10081 (2009)"},
              "contact": CONTACT, "n_directions": n}
    return GaugeLaw(RULE, law, data, _quality(law, data, {}), source, 0.0)
