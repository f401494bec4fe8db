"""Checks of what builds facets: the fields of a :class:`~asperity.surface.facets.FacetSurface`
(however it was built: by the readers or by a caller's own arrays) and the contact options
shared by :func:`~asperity.surface.facets.load_surface` and the tiled derivation.  Every
refusal is one InputError line naming the argument."""
from __future__ import annotations

import numpy as np

from ..errors import (
    InputError,
    check_array,
    check_flag,
    check_instance,
    check_mu,
    check_range,
    is_array,
)
from .friction_map import MAX_MU
from .topography import MAX_COORDINATE

#: values checked at once (no temporary the size of a scan's facets)
_PIECE = 1 << 20


def check_values(name: str, a: np.ndarray, low: float | None = None,
                 high: float | None = None) -> None:
    """InputError unless every value of ``a`` is finite and within [low, high]."""
    for lo in range(0, a.size, _PIECE):
        piece = a[lo:lo + _PIECE]
        ok = np.isfinite(piece)
        if low is not None:
            ok &= piece >= low
        if high is not None:
            ok &= piece <= high
        if not ok.all():
            k = lo + int(np.flatnonzero(~ok)[0])
            rng = ("finite" if low is None else f"finite and >= {low:g}" if high is None
                   else f"in [{low:g}, {high:g}]")
            raise InputError(f"{name} must be {rng}, got {a[k]:g} at index {k}")


def check_fields(gx, gy, mu, weight, info, preview, extent, quality):
    """(gx, gy, mu, weight, preview) of a FacetSurface as arrays (mu: a float or an
    array), the others checked: gradients finite, weights finite, >= 0 and not all zero,
    mu in [0, MAX_MU], info a dict, preview None or a 2-d height array (NaN where
    undefined, as a masked array's masked values), extent None or two sizes > 0, quality
    None or a dict."""
    gx = check_array("gx", gx, ndim=1, finite=False, min_size=1)
    check_values("gx", gx)
    gy = check_array("gy", gy, ndim=1, finite=False)
    check_values("gy", gy)
    w = check_array("weight", weight, ndim=1, finite=False)
    check_values("weight", w, 0.0)
    n = gx.size
    for name, a in (("gy", gy), ("weight", w)):
        if a.shape != (n,):
            raise InputError(f"{name} must have the shape of gx ({n},), got {a.shape}")
    if not np.any(w > 0):
        raise InputError("weight must not be all zero (no facet carries load)")
    if is_array(mu):
        mu = check_array("mu", mu, ndim=1, finite=False)
        check_values("mu", mu, 0.0, MAX_MU)
        if mu.shape != (n,):
            raise InputError(f"mu must be a number or an array of the shape of gx ({n},), "
                             f"got {mu.shape}")
    else:
        mu = check_mu("mu", mu, MAX_MU)
    check_instance("info", info, dict)
    pv = None
    if preview is not None:
        pv = check_array("preview", preview, ndim=2, finite=False, min_size=1)
        if np.isinf(pv).any():
            raise InputError("preview must hold finite heights or NaN")
    if extent is not None:
        ext = check_array("extent", extent, shape=(2,))
        if not np.all(ext > 0):
            raise InputError(f"extent must be two sizes > 0 (m), got {ext.tolist()}")
    if quality is not None:
        check_instance("quality", quality, dict)
    return gx, gy, mu, w, pv


def check_options(rest_level, bearing_fraction, level_slope, info):
    """(rest_level, bearing_fraction) checked, and level_slope a bool, info None or a dict."""
    if rest_level is not None:
        rest_level = check_range("rest_level", rest_level, -MAX_COORDINATE, MAX_COORDINATE,
                                 unit="m")
    if bearing_fraction is not None:
        bearing_fraction = check_range("bearing_fraction", bearing_fraction, 0.0, 1.0,
                                       low_open=True)
    check_flag("level_slope", level_slope)
    if info is not None and not isinstance(info, dict):
        raise InputError(f"info must be a dict or None, got {type(info).__name__}")
    return rest_level, bearing_fraction


def check_pressure_field(pressure, z: np.ndarray, rest_level: bool) -> np.ndarray | None:
    """A node-pressure field for the map ``z`` (None stays None): its shape, finite and >= 0
    on every defined pixel (NaN allowed on undefined ones), as a float array; not with a
    rest level (``rest_level`` True: one was given)."""
    if pressure is None:
        return None
    if rest_level:
        raise InputError("give a pressure field or a rest level (bearing fraction), not both")
    p = check_array("pressure", pressure, ndim=2, finite=False)
    if p.shape != z.shape:
        raise InputError(f"pressure has shape {p.shape}, the height map {z.shape}")
    bad = np.isfinite(z) & ~(np.isfinite(p) & (p >= 0))
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise InputError(f"pressure must be finite and >= 0 Pa on the defined pixels, got "
                         f"{p[i, j]:g} at pixel ({i}, {j}) ({int(bad.sum())} such pixels)")
    return p
