"""Physically meaningful ranges of the microslip inputs, in one place, and their checks.

Every number of an assembly (file or Python API) is checked against these ranges before
any work: the message names the field, the range and what came, on one line.  The ranges
are wide (a rubber pad to a diamond film, a micrometre to a kilometre) but finite, so that
no product or quotient of the model (``E h``, ``dT_c``, the drift) can overflow or
underflow, and subnormal or absurd values (5e-324, 1e-300 m, 1e308) are refused.

``alpha_T`` is the expansion coefficient of the part *relative to its support*: it is
signed (a part that expands less than its housing has ``alpha_T < 0``), never 0.
"""
from __future__ import annotations

import math

from ..errors import InputError, check_int, check_range

#: field -> (low, high, unit) of the strip (per unit width)
STRIP = {"h": (1e-7, 10.0, "m"), "E": (1e4, 1e13, "Pa"), "p": (1e-3, 1e10, "Pa"),
         "l": (1e-6, 1e3, "m"), "k_t": (1e3, 1e20, "Pa/m")}
#: field -> (low, high, unit) of the two-node model
TWO_NODE = {"k": (1e-3, 1e15, "N/m"), "l0": (1e-6, 1e3, "m"), "k_t": (1e-3, 1e15, "N/m"),
            "N": (1e-6, 1e9, "N")}
#: (low, high, unit) of the two-node model's optional contact_area (one node's)
CONTACT_AREA = (1e-12, 1e6, "m^2")
#: |alpha_T| (1/K): invar against its housing to a polymer against steel, with room
ALPHA_T = (1e-9, 1e-3)
#: a slider's friction coefficient (a texture near self-locking gives large values;
#: +inf is a self-locking direction); explicit coefficients in a file stay below MU_FILE
MU = (1e-6, 1e4)
MU_FILE = 100.0
#: temperature change from the assembly temperature, K
DT = (-5000.0, 5000.0)
#: tangential force, N (two-node) or N/m (strip)
FORCE = (-1e12, 1e12)
#: displacement tolerance, m
TOLERANCE = (1e-9, 1e3)
#: cycles to assess (extrapolated beyond those marched)
CYCLES = (1.0, 1e15)
#: nodes of a strip (1e6 nodes resolve any slip zone; one increment then takes ~0.1 s)
NODES = (2, 1_000_000)
#: load increments per segment, breakpoints of one cycle, load points per cycle
SUBSTEPS = (1, 100_000)
HISTORY_POINTS = (2, 10_000)
POINTS_PER_CYCLE = 10_000_000
#: what the chain solvers resolve in double precision (checked on every chain and load):
#: element / contact stiffness both ways (max kb / min kt, max kt / min kb; a strip:
#: (lam dx)^-2 and (lam dx)^2), the friction
#: asymmetry max(mu+, mu-) / min(mu+, mu-) of finite coefficients, and the margin
#: dT range / (2 dT_c) (beyond it friction holds under 1e-4 of the free thermal force)
STIFFNESS_RATIO = 1e9
ASYMMETRY = 1e3
MARGIN = 1e4
#: coefficients whose relative difference |mu+ - mu-| / max(mu+, mu-) is at most this are
#: the same coefficient (the rounding of a symmetric texture: symmetric sliders, no drift);
#: any larger difference is resolved (the chain solvers decide which threshold is reached
#: first from the thresholds themselves, see microslip._chain_kernels)
SAME_FRICTION = 1e-12


def same_friction(mu_plus: float, mu_minus: float) -> bool:
    """mu+ and mu- equal but for rounding (relative difference at most SAME_FRICTION)."""
    if mu_plus == mu_minus:
        return True
    if not (math.isfinite(mu_plus) and math.isfinite(mu_minus)):
        return False                     # a self-locking side is never the other's value
    return abs(mu_plus - mu_minus) <= SAME_FRICTION * max(abs(mu_plus), abs(mu_minus))


def check_param(name: str, value, rng: tuple) -> float:
    """A model parameter in its range (low, high, unit)."""
    lo, hi, unit = rng
    return check_range(name, value, lo, hi, unit=unit)


def check_alpha_T(name: str, value) -> float:
    """The signed relative expansion coefficient: |alpha_T| in ALPHA_T, 1/K."""
    lo, hi = ALPHA_T
    x = check_range(name, value, unit="1/K")          # a finite real number
    if not lo <= abs(x) <= hi:
        raise InputError(f"{name} must be in [-{hi:g}, -{lo:g}] or [{lo:g}, {hi:g}] 1/K "
                         f"(signed: < 0 when the part expands less than its support), "
                         f"got {x:g}")
    return x


def check_mu(name: str, value, high: float = MU[1], self_locking: bool = True) -> float:
    """A slider's coefficient in [MU[0], high], or +inf (a self-locking direction) when
    ``self_locking``."""
    if self_locking:
        x = check_range(name, value, 0.0, None, allow_inf=True)
        if math.isinf(x):
            return x
    lo = MU[0]
    return check_range(name, value, lo, high,
                       unit="(or inf: self-locking)" if self_locking else "")


def check_dT(name: str, value) -> float:
    return check_range(name, value, *DT, unit="K")


def check_force(name: str, value) -> float:
    return check_range(name, value, *FORCE)


def check_tolerance(name: str, value, scale: float = 1.0, unit: str = "m") -> float:
    """A displacement tolerance; ``scale`` converts the unit it is given in to m."""
    return check_range(name, value, TOLERANCE[0] / scale, TOLERANCE[1] / scale,
                       unit=unit) * scale


def check_cycles(name: str, value) -> float:
    return check_range(name, value, *CYCLES)


def check_nodes(name: str, value) -> int:
    return check_int(name, value, *NODES)


def check_substeps(name: str, value) -> int:
    return check_int(name, value, *SUBSTEPS)
