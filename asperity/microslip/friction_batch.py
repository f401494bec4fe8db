"""mu+ and mu- of a block of wedge textures in one call: the block path of a study that
varies a texture's parameters (``"texture.alpha_deg"`` and the like).

Per case the study builds the texture from its table (:func:`asperity.texture.wedges.
texture_from_dict`) and takes its friction along the slip axis
(:func:`asperity.microslip.risk.assembly_friction` ->
:func:`asperity.microslip.friction.friction_from_texture`), some 0.2 ms of Python a case.
:func:`texture_friction_batch` does the same for thousands of cases at once: the range
checks of the texture classes as array comparisons, the two faces and the reservoir of
both directions of every case in one compiled loop (:mod:`._friction_batch_kernels`).

Exactness: where ``ok`` is True, mu+ and mu- are those of the per-case path bit for bit
(same operations in the same order, ``tan`` of the C library).  Where the per-case path
would refuse the case (a value outside its range, a texture with no friction along the
axis), or the case is one this path does not cover (another texture kind or an option it
does not know), ``ok`` is False and mu+ = mu- = NaN: the caller runs those cases through
the per-case path, which gives the one-line message or the result.
"""
from __future__ import annotations

import math
from dataclasses import MISSING, fields

import numpy as np

from ..errors import InputError, check_int, check_mu, check_range
from .limits import MU

#: wedge texture kinds this path covers -> (the class's numeric fields, the required ones)
KINDS = ("wedge", "gaussian-wedge")
#: the assembly's textured face, and the contact regimes (as asperity.microslip.risk)
FACES = ("support", "part")
CONTACTS = ("all-faces", "windward")
#: the slip axis an assembly may give, deg (as risk.check_axis_and_face)
AXIS_RANGE = (-360.0, 360.0)


def _classes():
    from ..texture.wedges import _TEXTURE_KINDS
    return _TEXTURE_KINDS


def _keys(kind: str) -> tuple[set[str], set[str]]:
    """(allowed keys of a table of ``kind``, its required keys), as texture_from_dict."""
    cls = _classes()[kind]
    names = [f for f in fields(cls) if not f.name.startswith("_")]
    return ({f.name for f in names} | {"kind"},
            {f.name for f in names if f.default is MISSING and f.default_factory is MISSING})


def resolve_slip_rules(friction_table: dict | None, slip_axis_deg=None,
                       textured: str | None = None) -> tuple[float | None, str]:
    """(slip axis in deg or None, textured face) of an assembly whose friction comes from a
    texture given apart from its file, as :func:`asperity.microslip.risk.assembly_friction`
    takes them: the arguments override the ``[friction]`` table's ``slip_axis_deg`` and
    ``textured``; its ``contact`` does not apply (the study's contact does)."""
    fr = friction_table or {}
    axis = slip_axis_deg if slip_axis_deg is not None else fr.get("slip_axis_deg")
    return axis, textured or fr.get("textured", "support")


# -- range checks: the texture classes' checks as array comparisons --------------------------

def _angle_ok(x):
    """_check_angle: (0, 90) deg and at least LIMITS['angle'][0]."""
    from ..texture.wedges import LIMITS
    return (x > 0.0) & (x < 90.0) & (x >= LIMITS["angle"][0])


def _mu_ok(x):
    """check_mu: a finite number in [0, 100]."""
    return (x >= 0.0) & (x <= 100.0)


def _length_ok(allow_zero: bool):
    def ok(x):
        from ..texture.wedges import LIMITS
        lo, hi = LIMITS["height"]
        return (x >= (0.0 if allow_zero else lo)) & (x <= hi)
    return ok


def _int_ok(low: int, high: int):
    def ok(x):
        # check_int of a float: integral and finite, int(x) within [low, high]; int(x) of a
        # float is exact, so int(x) <= high is x <= high unless high + 1 rounds to x
        top = float(high) if float(high) <= high else math.nextafter(float(high), -math.inf)
        return np.isfinite(x) & (x == np.floor(x)) & (x >= low) & (x <= top)
    return ok


def _gap_ok(x):
    """mean_gap's own check: a finite number >= 0 (the cap in base widths comes later)."""
    return np.isfinite(x) & (x >= 0.0)


def _scalar_checks():
    """field -> (scalar check of the class, raising InputError; array check -> bool)."""
    from ..texture.wedges import _check_angle, _check_length
    return {
        "alpha_deg": (lambda v: _check_angle("alpha_deg", v), _angle_ok),
        "beta_deg": (lambda v: _check_angle("beta_deg", v), _angle_ok),
        "mu_alpha": (lambda v: check_mu("mu_alpha", v), _mu_ok),
        "mu_beta": (lambda v: check_mu("mu_beta", v), _mu_ok),
        "height": (lambda v: _check_length("height", v), _length_ok(False)),
        "height_mean": (lambda v: _check_length("height_mean", v), _length_ok(False)),
        "height_std": (lambda v: _check_length("height_std", v, True), _length_ok(True)),
        "n_wedges": (lambda v: float(check_int("n_wedges", v, 1, 10_000_000)),
                     _int_ok(1, 10_000_000)),
        "seed": (lambda v: float(check_int("seed", v, 0, 2**63 - 1)), _int_ok(0, 2**63 - 1)),
        "mean_gap": (lambda v: check_range("mean_gap", v, 0.0, None, unit="m"), _gap_ok),
    }


def _block_size(varied: dict, slip_axis_deg) -> int:
    sizes = {np.shape(v) for v in varied.values()}
    if np.ndim(slip_axis_deg) == 1:
        sizes.add(np.shape(slip_axis_deg))
    if any(len(s) != 1 for s in sizes) or len(sizes) > 1:
        raise InputError(f"varied values and an array slip_axis_deg must be 1-d arrays of one "
                         f"length, got shapes {sorted(sizes)}")
    return sizes.pop()[0] if sizes else 1


def _columns(table: dict, varied: dict, m: int):
    """({field: (m,) float}, (m,) ok) of the fields the friction and the checks read, or
    (None, None) when some case cannot be built whatever its values (unknown kind or key,
    missing key, a field this path does not know, a fixed value outside its range)."""
    kind = table.get("kind", "wedge")
    if not isinstance(kind, str) or kind not in KINDS or "kind" in varied:
        return None, None
    allowed, required = _keys(kind)
    keys = set(table) | set(varied)
    if keys - allowed or required - keys:
        return None, None
    checks = _scalar_checks()
    if keys - {"kind"} - set(checks):            # a field this path does not know yet
        return None, None
    cols, ok = {}, np.ones(m, dtype=bool)
    for k in sorted(keys - {"kind"}):
        scalar, vector = checks[k]
        if k in varied:
            x = np.asarray(varied[k], dtype=np.float64)
            ok &= vector(x)
            cols[k] = x
        else:
            try:
                cols[k] = np.full(m, float(scalar(table[k])))
            except InputError:
                return None, None
    if kind == "gaussian-wedge":
        cols.setdefault("mean_gap", None)
    return cols, ok


def _directions(axis, m: int):
    """(cos psi, sin psi, ok) (m, 2) of each case's directions psi, psi + pi, psi =
    slip_axis_deg (default 0) in radians, as friction_from_texture computes them."""
    turn = np.array([0.0, math.pi])
    if axis is None or np.ndim(axis) == 0:
        try:
            deg = 0.0 if axis is None else check_range("slip_axis_deg", axis, *AXIS_RANGE)
        except InputError:
            return None, None, np.zeros(m, dtype=bool)
        psi = math.radians(deg) + turn
        return (np.broadcast_to(np.cos(psi), (m, 2)), np.broadcast_to(np.sin(psi), (m, 2)),
                np.ones(m, dtype=bool))
    deg = np.asarray(axis, dtype=np.float64)
    ok = (deg >= AXIS_RANGE[0]) & (deg <= AXIS_RANGE[1])
    psi = (np.where(ok, deg, 0.0) * (math.pi / 180.0))[:, None] + turn
    return np.cos(psi), np.sin(psi), ok


def texture_friction_batch(table: dict, varied: dict, *, contact: str = "all-faces",
                           slip_axis_deg=None, textured: str = "support"
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(mu_plus, mu_minus, ok), (m,) arrays, of m wedge textures along the slip axis.

    table         : the ``[texture]`` table of the texture file, as the study holds it
                    (kind "wedge" or "gaussian-wedge"; the values of the fields not varied)
    varied        : {field: (m,) float} the fields the study varies (keys after
                    ``texture.``), each case's values put in the table as the study does
    contact       : "all-faces" or "windward"
    slip_axis_deg : the slip axis in the texture's frame, deg (None: t_a, 0 deg), a number or
                    an (m,) array (a study varying ``friction.slip_axis_deg``); the assembly
                    rules: :func:`resolve_slip_rules`
    textured      : "support" (mu+ = T(psi), mu- = T(psi + 180 deg)) or "part" (swapped)

    Where ``ok`` is True, mu+ and mu- equal those of ``friction_from_texture(
    texture_from_dict(table_i), contact, slip_axis_deg, textured)`` bit for bit, +inf for
    a self-locking direction.  Where it is False (NaN): a case the per-case path refuses or
    this path does not cover; run it through the per-case path for its message.  With
    ``varied`` empty the block is the one table (m = 1, or the slip axes' length).
    """
    if not isinstance(table, dict) or not isinstance(varied, dict):
        raise InputError("table and varied must be dicts (the texture table, field -> values)")
    m = _block_size(varied, slip_axis_deg)
    nan = np.full(m, np.nan)
    cols, ok = _columns(table, varied, m)
    if cols is None or contact not in CONTACTS or textured not in FACES:
        return nan, nan.copy(), np.zeros(m, dtype=bool)
    cs, sn, axis_ok = _directions(slip_axis_deg, m)
    ok &= axis_ok
    if not ok.any():
        return nan, nan.copy(), ok
    T, ta, tb = _tangential(cols, cs, sn, contact, ok)
    ok &= np.isfinite(ta) & np.isfinite(tb) & ~np.isnan(T).any(axis=1)
    if "height_mean" in cols:
        ok &= _gaussian_ok(cols, ta, tb)
    plus, minus = (1, 0) if textured == "part" else (0, 1)
    mu_p, mu_m = T[:, plus].copy(), T[:, minus].copy()
    # _check_some_friction: no friction along the axis (inf counts as friction)
    ok &= np.minimum(mu_p, mu_m) >= MU[0]
    mu_p[~ok] = np.nan
    mu_m[~ok] = np.nan
    return mu_p, mu_m, ok


def _tangential(cols: dict, cs, sn, contact: str, ok):
    """(T (m, 2), tan alpha, tan beta) by the kernel; NaN where ok is False."""
    from ..friction.reservoir import LEVEL_SLOPE_TOL, LOCK_TOL
    from ._friction_batch_kernels import wedge_tangential
    m = ok.size
    deg = math.pi / 180.0                        # math.radians(x) is x * (pi / 180)
    T = np.empty((m, 2))
    ta, tb = np.full(m, np.nan), np.full(m, np.nan)
    status = np.empty(m, dtype=np.int64)
    wedge_tangential(np.ascontiguousarray(cols["alpha_deg"] * deg),
                     np.ascontiguousarray(cols["beta_deg"] * deg),
                     np.ascontiguousarray(cols["mu_alpha"]), np.ascontiguousarray(cols["mu_beta"]),
                     np.ascontiguousarray(cs), np.ascontiguousarray(sn), contact == "windward",
                     LEVEL_SLOPE_TOL, LOCK_TOL, ok, T, ta, tb, status)
    return T, ta, tb


def _gaussian_ok(cols: dict, ta, tb):
    """GaussianWedgeTexture's checks across fields: mean_gap at most 100 mean base widths
    (width = height_mean (1/tan alpha + 1/tan beta), the same floats as the class), and
    height_std at most 3 x height_mean."""
    from ..texture.wedges import LIMITS
    hm = cols["height_mean"]
    ok = ~(cols["height_std"] > 3.0 * hm)
    gap = cols["mean_gap"]
    if gap is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            width = hm * (1.0 / ta + 1.0 / tb)
        ok &= ~(gap > LIMITS["gap_widths"][1] * width)
    return ok
