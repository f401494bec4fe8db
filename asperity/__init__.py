"""asperity: direction-dependent friction from surface textures.

The package import is kept light: numerical modules (numba kernels, matplotlib)
are imported only when first used.  Public names are resolved lazily.
"""
from __future__ import annotations

import importlib
import os

__version__ = "0.1.0"

# numba's OpenMP threads sleep between parallel regions rather than spin: the kernels run in
# pieces (Ctrl-C, progress), and on a loaded machine a spinning thread takes the core from
# the main thread, ~8 ms per piece (measured on 2 cores; a scan in tiles has thousands of
# pieces).  Set before numba loads OpenMP; a value in the environment is kept.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

_LAZY = {
    "WedgeTexture": "asperity.texture.wedges",
    "GaussianWedgeTexture": "asperity.texture.wedges",
    "load_texture": "asperity.texture.wedges",
    "compute_H": "asperity.texture.closed_form",
    "compute_reservoir": "asperity.friction.faces",
    "compute_axis_coefficients": "asperity.friction.faces",
    "SpringModel": "asperity.texture.spring_model",
    "simulate_sliding": "asperity.texture.springs",
    "simulate_reservoir": "asperity.texture.springs",
    "simulate_loading_curve": "asperity.texture.springs",
    "load_surface": "asperity.surface.facets",
    "FacetSurface": "asperity.surface.facets",
    "read_surface": "asperity.surface.readers",
    "compute_facet_reservoir": "asperity.friction.facet_reservoir",
    "derive": "asperity.friction.derive",
    "derive_scan": "asperity.friction.tiled",
    "derive_windows": "asperity.friction.elastic_windows",
    "fit_derivation": "asperity.laws.fitting",
    "WalkerLeineLaw": "asperity.laws.walker_leine",
    "TruncatedEllipse": "asperity.laws.sets",
    "read_gauge": "asperity.laws.gauge_file",
    "write_gauge": "asperity.laws.gauge_file",
    "GaugeFamily": "asperity.laws.family",
    "PlanarLaw": "asperity.laws.planar",
    "coulomb_law": "asperity.laws.planar",
    "ellipse_law": "asperity.laws.planar",
    "truncated_ellipse_law": "asperity.laws.planar",
    "collinear_law": "asperity.laws.planar",
    "componentwise_law": "asperity.laws.planar",
    "star_law": "asperity.laws.planar",
    "windward_star_law": "asperity.laws.planar",
    "law_from_gauge": "asperity.laws.planar",
    "slide": "asperity.dynamics.moreau",
    "simulate_body": "asperity.dynamics.body",
    "ratchet_drift_square": "asperity.dynamics.references",
    "deflection_deg": "asperity.dynamics.moreau",
    "simulate_microslip": "asperity.microslip.quasi_static",
    "long_life": "asperity.microslip.quasi_static",
    "assess": "asperity.microslip.verdict",
    "two_node_chain": "asperity.microslip.chains",
    "strip_chain": "asperity.microslip.chains",
    "Loading": "asperity.microslip.loading",
    "load_assembly": "asperity.microslip.assembly",
    "assembly_friction": "asperity.microslip.risk",
    "assess_assembly": "asperity.microslip.risk",
    "risk_map": "asperity.study.maps",
    "solve_contact": "asperity.contact.solver",
    "effective_modulus": "asperity.contact.solver",
    "solve_load_curve": "asperity.contact.curve",
    "ElasticContact": "asperity.surface.contact_facets",
    "load_elastic": "asperity.surface.contact_facets",
    "derive_family": "asperity.friction.family",
    "Footprint": "asperity.bodies.footprint",
    "disc_footprint": "asperity.bodies.footprint",
    "ring_footprint": "asperity.bodies.footprint",
    "rectangle_footprint": "asperity.bodies.footprint",
    "polygon_footprint": "asperity.bodies.footprint",
    "mesh_patch": "asperity.bodies.pressure",
    "pressure_footprint": "asperity.bodies.pressure",
    "contact_footprint": "asperity.bodies.pressure",
    "read_pressure": "asperity.bodies.pressure",
    "read_body": "asperity.bodies.body_file",
    "disc_f_m": "asperity.bodies.closed_forms",
    "ring_f_m": "asperity.bodies.closed_forms",
    "spin_drift_force": "asperity.bodies.closed_forms",
    "disc_reference": "asperity.bodies.closed_forms",
    "slide_body": "asperity.dynamics.body_api",
    "crawl": "asperity.crawling.solver",
    "coefficient_law": "asperity.crawling.solver",
    "CrawlSettings": "asperity.crawling.solver",
    "Force": "asperity.dynamics.force",
    "AsperityError": "asperity.errors",
    "InputError": "asperity.errors",
}

__all__ = ["__version__", *_LAZY]


#: public names that differ from the module's own
_RENAMED = {"simulate_microslip": "simulate", "law_from_gauge": "from_gauge",
            "disc_footprint": "disc", "ring_footprint": "ring",
            "rectangle_footprint": "rectangle", "polygon_footprint": "polygon",
            "pressure_footprint": "from_pressure", "contact_footprint": "from_contact"}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'asperity' has no attribute {name!r}")
    return getattr(importlib.import_module(module), _RENAMED.get(name, name))
