"""asperity: direction-dependent friction from surface textures.

The package import is kept light: numerical modules (numba kernels, matplotlib)
are imported only when first used.  Public names are resolved lazily.
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

_LAZY = {
    "WedgeTexture": "asperity.texture",
    "GaussianWedgeTexture": "asperity.texture",
    "load_texture": "asperity.texture",
    "compute_H": "asperity.closed_form",
    "compute_reservoir": "asperity.closed_form",
    "compute_axis_coefficients": "asperity.closed_form",
    "SpringModel": "asperity.springs",
    "simulate_sliding": "asperity.springs",
    "simulate_reservoir": "asperity.springs",
    "simulate_loading_curve": "asperity.springs",
    "load_surface": "asperity.surface",
    "FacetSurface": "asperity.surface",
    "read_surface": "asperity.surface_io",
    "compute_facet_reservoir": "asperity.facet_reservoir",
    "fit_derivation": "asperity.gauges",
    "WalkerLeineLaw": "asperity.gauges",
    "TruncatedEllipse": "asperity.gauges",
    "read_gauge": "asperity.gauge_file",
    "write_gauge": "asperity.gauge_file",
    "PlanarLaw": "asperity.laws",
    "coulomb_law": "asperity.laws",
    "ellipse_law": "asperity.laws",
    "truncated_ellipse_law": "asperity.laws",
    "collinear_law": "asperity.laws",
    "star_law": "asperity.laws",
    "windward_star_law": "asperity.laws",
    "law_from_gauge": "asperity.laws",
    "slide": "asperity.moreau",
    "ratchet_drift_square": "asperity.moreau",
    "deflection_deg": "asperity.moreau",
    "simulate_microslip": "asperity.microslip",
    "long_life": "asperity.microslip",
    "assess": "asperity.microslip",
    "two_node_chain": "asperity.microslip",
    "strip_chain": "asperity.microslip",
    "Loading": "asperity.microslip",
    "load_assembly": "asperity.assembly",
    "AsperityError": "asperity.errors",
    "InputError": "asperity.errors",
}

__all__ = ["__version__", *_LAZY]


#: public names that differ from the module's own
_RENAMED = {"simulate_microslip": "simulate", "law_from_gauge": "from_gauge"}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'asperity' has no attribute {name!r}")
    return getattr(importlib.import_module(module), _RENAMED.get(name, name))
