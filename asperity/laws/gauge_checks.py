"""What a gauge file can check about itself beyond its schema.

* Ranges: friction coefficients and force magnitudes in [MU_MIN, MU_MAX] (geometry.py),
  angles within a few turns, D's support function positive and of the magnitude of C.
* Consistency: the file records its data, its law and the quality of the fit of one to
  the other.  The fit report is recomputed from the file's own law and data and must match
  the recorded one (same code, so to rounding); for a star law, D must be scaled to C's
  convex hull as the fit leaves it.  A file whose C was scaled, or whose D or data were
  edited, is refused with the field that disagrees and by how much.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .geometry import MU_MAX, MU_MIN, TOL, TWO_PI

#: recorded fit-report fields recomputed from the law and the data
CHECKED_FIT_FIELDS = ("n_points", "max_radial_error", "rms_radial_error",
                      "max_angle_error_deg", "min_dissipation", "admissible", "C_convex",
                      "C_min_turn_deg", "D_convex", "D_min_turn_rate")


def _in(field: str, values, low: float, high: float) -> None:
    a = np.abs(np.asarray(values, dtype=float)).ravel()
    bad = (a < low) | (a > high)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        where = f" (item {k})" if a.size > 1 else ""
        raise InputError(f"field {field} must have magnitudes in [{low:g}, {high:g}], got "
                         f"{a[k]:g}{where}")


def check_ranges(obj: dict) -> None:
    """Ranges of the numbers of a schema-valid gauge-file object."""
    prm = obj["parameters"]
    if obj["law"] == "truncated-ellipse":
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            _in(f"parameters.{k}", [prm[k]], MU_MIN, MU_MAX)
        _in("parameters.theta_rad", [prm["theta_rad"]], 0.0, 2 * TWO_PI)
    elif obj["law"] == "componentwise":
        for k in ("mu_f", "mu_b", "mu_t"):
            _in(f"parameters.{k}", [prm[k]], MU_MIN, MU_MAX)
    else:
        pts = np.asarray(prm["C"]["points"], dtype=float)
        _in("parameters.C.points (|p|)", np.hypot(pts[:, 0], pts[:, 1]), MU_MIN, MU_MAX)
        _in("parameters.D.psi_rad", prm["D"]["psi_rad"], 0.0, 2 * TWO_PI)
        _in("parameters.D.h", prm["D"]["h"], MU_MIN * 1e-3, MU_MAX * 1e3)
        _in("parameters.D.dh_dpsi", prm["D"]["dh_dpsi"], 0.0, MU_MAX * 1e6)
    d = obj["data"]
    p = np.asarray(d["p"], dtype=float)
    _in("data.p (|p|)", np.hypot(p[:, 0], p[:, 1]), MU_MIN, MU_MAX)
    _in("data.psi_rad", d["psi_rad"], 0.0, 2 * TWO_PI)
    _in("frame.principal_direction_deg", [obj["frame"]["principal_direction_deg"]], 0.0, 720.0)


def _differ(a, b) -> bool:
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None:
        return a != b
    a, b = float(a), float(b)
    return abs(a - b) > TOL.fit_report * max(1.0, abs(a), abs(b))


def check_consistency(gl) -> None:
    """The recorded fit report and D's scale against the law and data of ``gl`` (a
    GaugeLaw rebuilt from a file)."""
    from .fitting import _quality
    from .sets import StarSet
    law, data = gl.law, gl.data
    extra = {}
    if isinstance(law.C, StarSet):
        D = law.D
        extra = dict(D_convex=D.is_convex(), D_min_turn_rate=D.min_turn_rate())
        shift = float(np.mean(np.log(D.h) - np.log(law.C.support(D.psi))))
        if not abs(shift) <= TOL.d_scale:
            raise InputError(f"field parameters.D is not scaled to C (mean ln(h_D / h_C) = "
                             f"{shift:.3g}, a factor {math.exp(shift):.4g}): C and D were not "
                             "fitted together; refit with `asperity fit`")
    else:
        turn = math.remainder(law.C.theta - math.radians(gl.principal_direction_deg), TWO_PI)
        if abs(turn) > TOL.fit_report * TWO_PI:
            raise InputError(f"field parameters.theta_rad ({law.C.theta:.9g}) is not the "
                             f"frame's principal direction ({gl.principal_direction_deg:.9g} "
                             "deg): the ellipse's t_a must be the file's t_a")
    again = _quality(law, data, extra).to_dict()
    recorded = gl.fit.to_dict()
    for key in CHECKED_FIT_FIELDS:
        if key in extra or key not in ("D_convex", "D_min_turn_rate"):
            if _differ(recorded.get(key), again.get(key)):
                raise InputError(
                    f"field fit.{key}: the file's law and data give {_show(again.get(key))}, "
                    f"the file records {_show(recorded.get(key))}: parameters, data and fit "
                    "do not agree (edited by hand?); refit with `asperity fit`")


def _show(x) -> str:
    return f"{x:.6g}" if isinstance(x, float) else str(x)
