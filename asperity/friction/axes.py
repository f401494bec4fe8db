"""Axis coefficients side by side: several derivations (windows of a scan, the members of a
law family, the cases of a study at several pressures) each find their own principal
direction t_a, an axis in [0, 180) deg, so two of them whose axes straddle 0/180 deg point
their t_a opposite ways and their mu_a+ / mu_a- (mu_b+ / mu_b-) are exchanged.  Listed side
by side, each is turned to point as one common reference direction: the axial mean of the
t_a (:func:`axial_spread`), each one's + and - exchanged when its t_a is more than 90 deg
from it (:func:`aligned`, :func:`align_rows`)."""
from __future__ import annotations

import numpy as np

AXES = ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus")


def axial_spread(degrees) -> dict:
    """Mean of axes (angles modulo 180 deg) and the largest deviation from it."""
    a = np.radians(np.asarray(degrees, dtype=float))
    if a.size == 0:
        return {"mean": None, "max_deviation": None}
    m = 0.5 * np.angle(np.exp(2j * a).sum())
    dev = np.abs((a - m + 0.5 * np.pi) % np.pi - 0.5 * np.pi)
    return {"mean": float(np.degrees(m) % 180.0), "max_deviation": float(np.degrees(dev.max()))}


def aligned(r: dict, mean_deg: float) -> tuple[dict, bool]:
    """A row's axis coefficients along the common principal direction ``mean_deg``:
    a principal direction is an axis (in [0, 180)), so a row whose t_a points the other
    way (more than 90 deg from the mean's) has its + and - exchanged; (axes, reversed)."""
    d = (r["principal_direction_deg"] - mean_deg + 180.0) % 360.0 - 180.0
    if abs(d) <= 90.0:
        return {a: r[a] for a in AXES}, False
    return {"mu_a_plus": r["mu_a_minus"], "mu_a_minus": r["mu_a_plus"],
            "mu_b_plus": r["mu_b_minus"], "mu_b_minus": r["mu_b_plus"]}, True


def align_rows(rows: list[dict]) -> float | None:
    """Turn the rows (dicts with ``principal_direction_deg`` and some of :data:`AXES`) in
    place to the axial mean of their t_a: the coefficients exchanged where t_a points the
    other way, ``axes_reversed`` set on each; the reference direction (deg, in [0, 180);
    None without rows).  Each row keeps its own ``principal_direction_deg``."""
    ref = axial_spread([r["principal_direction_deg"] for r in rows])["mean"]
    for r in rows:
        ax, flipped = aligned({a: r.get(a) for a in AXES} | r, ref)
        r.update({a: v for a, v in ax.items() if a in r})
        r["axes_reversed"] = flipped
    return ref


REFERENCE_WORDS = ("mu_a+/-: along and against t_a turned to point within 90 deg of the "
                   "reference direction {ref:.2f} deg (the axial mean of the t_a listed; "
                   "where a t_a points the other way its + and - are exchanged); mu_b+/-: "
                   "at +/-90 deg from it")
