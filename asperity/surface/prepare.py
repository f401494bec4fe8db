"""A surface file made ready for its facets: the options checked before anything is read,
the file read, its spikes marked undefined, its form removed and its friction map read.
The first half of :func:`asperity.surface.facets.load_surface`, shared with the
contact-weighted loader (:func:`asperity.surface.contact_facets.load_elastic`)."""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError, check_choice, check_mu
from . import quality as Q
from .friction_map import MAX_MU, check_friction_map
from .topography import HeightMap

#: detrending choices: name -> polynomial degree (None: keep the form)
DETREND = {"none": None, "slope": "slope", "mean": 0, "plane": 1, "poly2": 2, "poly3": 3}


@dataclass
class Prepared:
    """surface: the HeightMap (spikes undefined, form removed) or TriangleMesh;
    friction_map: None, or the per-pixel / per-triangle array; info: the facets' info
    (file, detrend, height_scale, friction_map); quality: the spike filter's figures;
    level_slope: the facets' mean slope is to be removed (detrend "slope")."""

    surface: object
    friction_map: object
    info: dict
    quality: dict
    level_slope: bool


def check_surface_options(*, detrend, mu, despike, despike_window, max_slope):
    """(despike, max_slope) checked, with detrend and mu, before any file is read."""
    check_choice("detrend", detrend, tuple(DETREND))
    despike = Q.check_despike(despike, despike_window)
    max_slope = Q.check_max_slope(max_slope)
    if mu is not None:
        check_mu("mu", mu, MAX_MU)
    return despike, max_slope


def prepare_surface(path, *, unit, pixel_size, height_scale, detrend, friction_map, despike,
                    point_bytes) -> Prepared:
    """Read ``path`` (``point_bytes``: the memory a point will need, for the reader's
    check) and apply the spike filter (``despike``: checked (threshold, window) or None),
    the form removal (``detrend``) and the friction map (a file or an array)."""
    from .friction_map import read_friction_map
    from .quality import remove_spikes
    from .readers import read_surface
    s = read_surface(path, unit=unit, pixel_size=pixel_size, height_scale=height_scale,
                     point_bytes=point_bytes)
    spikes = 0
    if despike is not None:
        if not isinstance(s, HeightMap):
            raise InputError(f"despike applies to height maps, not to the mesh {s.source}")
        spikes = remove_spikes(s.heights, despike)
    if DETREND[detrend] not in (None, "slope"):
        from .detrend import detrend as _detrend
        s = _detrend(s, DETREND[detrend])
    fm = friction_map
    info = {"file": str(path), "detrend": detrend, "height_scale": float(height_scale)}
    if isinstance(friction_map, (str, bytes)) or hasattr(friction_map, "__fspath__"):
        info["friction_map"] = str(friction_map)
        fm = read_friction_map(friction_map, s)        # checked as it is read
    elif fm is not None:
        fm = check_friction_map(fm)
    quality = {"spike_filter": None if despike is None else
               {"threshold": despike[0], "window": despike[1]}, "spikes_removed": spikes}
    return Prepared(s, fm, info, quality, detrend == "slope")
