"""Laws for the FE routine tests, built once per process: an asymmetric truncated ellipse and
a star law fitted to the asymmetric wedge texture (all faces in contact), the windward star
law of the same texture (D with flat edges: set-valued directions), and Hu et al.'s
componentwise law, and a strongly non-associated law with several returns; plus their
generated FRIC libraries."""
from __future__ import annotations

import math
from functools import cache

import numpy as np


@cache
def law(name: str):
    from asperity.friction.derive import derive
    from asperity.laws.fitting import fit_derivation
    from asperity.texture.wedges import WedgeTexture
    if name == "componentwise":
        from asperity.laws.componentwise import componentwise_gauge
        return componentwise_gauge(mu_f=0.1, mu_b=0.15, mu_t=0.2)
    if name in ("skewed", "skewed-mirrored"):
        # strongly non-associated: D turned 29 deg against an asymmetric C, so that a trial
        # stress can have several returns on the boundary of C, far apart
        from types import SimpleNamespace

        from asperity.laws.sets import TruncatedEllipse
        from asperity.laws.walker_leine import WalkerLeineLaw
        turn = 0.5 if name == "skewed" else -0.5      # its mirror image: roots met in the
        wl = WalkerLeineLaw(TruncatedEllipse(0.5, 0.3, 0.2, 0.2),   # other order
                            TruncatedEllipse(0.1, 0.1, 0.6, 0.6, theta=turn))
        return SimpleNamespace(force=wl.force, law=wl, kind=name)
    contact = "windward" if name == "windward" else "all-faces"
    kind = "truncated-ellipse" if name == "ellipse" else "star"
    return fit_derivation(derive(WedgeTexture(20, 40, 0.15, 0.1), contact, "closed-form", 72),
                          kind)


@cache
def fric_library(name: str):
    from fe_builds import library

    from asperity.fe.abaqus_fric import routine_source
    return library(routine_source(law(name), "fric", header=[f"test law {name}"]))


def rot(th: float) -> np.ndarray:
    return np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])


def steady_tau(gl, phi: float, th: float, side: int, press: float) -> np.ndarray:
    """TAU of steady sliding along local angle phi (SPEC.md section 10): texture on the
    main surface PRESS R(th) p(phi - th), on the secondary -PRESS R(th) p(phi + 180 - th)."""
    psi = phi - th if side > 0 else phi + math.pi - th
    p = gl.force(np.array([psi])).p[0]
    return (1.0 if side > 0 else -1.0) * press * rot(th) @ p
