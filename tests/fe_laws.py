"""Laws for the FE routine tests, built once per process: an asymmetric truncated ellipse and
a star law fitted to the asymmetric wedge texture (all faces in contact), the windward star
law of the same texture (D with flat edges: set-valued directions), and Hu et al.'s
componentwise law, and a strongly non-associated law with several returns; plus their
generated FRIC libraries."""
from __future__ import annotations

from functools import cache

from asperity.report.fe_abaqus import rot, steady_tau  # noqa: F401 (the tests' reference)


@cache
def law(name: str):
    """The report's four laws (ellipse, star, windward, componentwise), or a strongly
    non-associated one (skewed, skewed-mirrored)."""
    if name in ("skewed", "skewed-mirrored"):
        # D turned 29 deg against an asymmetric C, so that a trial stress can have several
        # returns on the boundary of C, far apart
        from types import SimpleNamespace

        from asperity.laws.sets import TruncatedEllipse
        from asperity.laws.walker_leine import WalkerLeineLaw
        turn = 0.5 if name == "skewed" else -0.5      # its mirror image: roots met in the
        wl = WalkerLeineLaw(TruncatedEllipse(0.5, 0.3, 0.2, 0.2),   # other order
                            TruncatedEllipse(0.1, 0.1, 0.6, 0.6, theta=turn))
        return SimpleNamespace(force=wl.force, law=wl, kind=name)
    from asperity.report.fe_abaqus import law as report_law
    return report_law(name)


@cache
def fric_library(name: str):
    from fe_builds import library

    from asperity.fe.abaqus_fric import routine_source
    return library(routine_source(law(name), "fric", header=[f"test law {name}"]))
