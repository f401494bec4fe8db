"""The strip assembly as a GetFEM model (``asperity risk ASSEMBLY --fe getfem``), beside
the slider chain.

The FE model: a 2D plane-stress body, length l along the slip axis x, height h, per metre
of width, modulus E, Poisson's ratio nu (the assembly's ``nu``, else :data:`NU_DEFAULT`),
free thermal strain alpha_T dT in x and y; its bottom face lies on a rigid textured
support, held in y, and tied in x by the bed: a spring k_t per unit area in series with a
slider holding mu+ p (towards +x) and mu- p (towards -x) at each bottom node (vertex
quadrature: the chain's lumped tributary lengths).  The friction is the GWFL strip law of
:mod:`.gwfl`; the load is the assembly's own history (lead-in and cycles, the tangential
force spread over the length or on an end face as ``force_at`` says), marched until the
drift per cycle repeats.  Q1 elements: N along l, ceil(N h / l) through h (at least 2).

What parts it from the chain (a bar E h on the bed): the shear compliance through the
height, h / (3 G) per unit area in series with the bed for the traction the bottom face
carries (G = E / (2 (1 + nu))), so the chain with k_t,eff = k_t / (1 + k_t h / (3 G))
follows the FE model to second order in h; and the discretisation.
"""
from __future__ import annotations

import math

from ..errors import InputError, check_int

#: Poisson's ratio when the assembly file gives none
NU_DEFAULT = 0.3
#: elements along l: range, default
MESH_RANGE = (4, 4000)
MESH_DEFAULT = 200
#: elements through h: at least, at most; elements in all, at most
THROUGH_H = (2, 200)
MAX_ELEMENTS = 200_000
#: load increments per load segment at least (the return mapping of one increment is exact
#: along a monotone segment of a uniform strip; more only resolve force histories)
INCREMENTS = 4
#: cycles marched at most, at least
MAX_CYCLES, MIN_CYCLES = 12, 2
#: drift change between two cycles, relative to |alpha_T| l dT range, counted as stabilised
STABILISED = 1e-6


def fe_mesh(asm, n: int) -> tuple[int, int]:
    """(elements along l, elements through h) for ``--fe-mesh n``."""
    lo, hi = MESH_RANGE
    n = check_int("--fe-mesh", n, lo, hi)
    p = asm.params
    ny = min(max(THROUGH_H[0], math.ceil(n * p["h"] / p["l"] - 1e-9)), THROUGH_H[1])
    if n * ny > MAX_ELEMENTS:
        raise InputError(f"--fe-mesh {n} gives {n} x {ny} = {n * ny} elements (at most "
                         f"{MAX_ELEMENTS}: h / l = {p['h'] / p['l']:.3g}); lower --fe-mesh")
    return n, ny


def check_fe_assembly(asm, where: str = "--fe getfem") -> None:
    if asm.model != "strip":
        raise InputError(f"{where} runs a strip assembly (assembly.model = \"strip\"); "
                         f"{asm.name} is {asm.model!r}")


def poisson(asm) -> tuple[float, str]:
    nu = asm.params.get("nu")
    return (NU_DEFAULT, f"default {NU_DEFAULT:g} (assembly.nu not given)") if nu is None \
        else (float(nu), "assembly.nu")


def shear_corrected_kt(k_t: float, h: float, E: float, nu: float) -> float:
    """The bed stiffness in series with the shear compliance through the height,
    k_t / (1 + k_t h / (3 G)), G = E / (2 (1 + nu))."""
    G = E / (2.0 * (1.0 + nu))
    return k_t / (1.0 + k_t * h / (3.0 * G))


def _series(loading, increments: int):
    from ..microslip.loading import Loading
    L = Loading(loading.dT, loading.F, max(loading.substeps, increments))
    a, b = L.lead_in()
    c, d = L.cycle_points()
    return ({"dT": a.tolist(), "F": b.tolist()}, {"dT": c.tolist(), "F": d.tolist()})


def strip_job(asm, mu_plus: float, mu_minus: float, nx: int, ny: int, *,
              increments: int = INCREMENTS, max_cycles: int = MAX_CYCLES) -> dict:
    """The GetFEM job of the strip assembly ``asm`` with these coefficients."""
    from .gwfl import strip_macros
    p = asm.params
    nu, _ = poisson(asm)
    lead, cycle = _series(asm.loading, increments)
    L = asm.loading
    scale = abs(p["alpha_T"]) * p["l"] * max(L.dT_range, max(abs(x) for x in L.dT))
    mus = [m for m in (mu_plus, mu_minus) if math.isfinite(m)] or [1.0]
    force = p["p"] * p["l"] * max(mus) + p["E"] * p["h"] * abs(p["alpha_T"]) * max(
        abs(x) for x in L.dT) + max(abs(x) for x in L.F)
    return {"task": "strip", "l": p["l"], "h": p["h"], "E": p["E"], "nu": nu,
            "alpha_T": p["alpha_T"], "k_t": p["k_t"], "p": p["p"],
            "mu_plus": mu_plus if math.isfinite(mu_plus) else None,
            "mu_minus": mu_minus if math.isfinite(mu_minus) else None,
            "macros": strip_macros(mu_plus, mu_minus), "nx": nx, "ny": ny,
            "force_at": asm.force_at, "lead_in": lead, "cycle": cycle,
            "max_cycles": max_cycles, "min_cycles": MIN_CYCLES,
            "stabilised": STABILISED * max(scale, 1e-300), "max_res": 1e-10 * force,
            "max_iter": 60}


def chain_drift(asm, mu_plus, mu_minus, k_t=None, max_marched: int = 200) -> float:
    """Drift per cycle of the assembly's slider chain (k_t replaced when given)."""
    from dataclasses import replace

    from ..microslip.quasi_static import simulate
    if k_t is not None:
        asm = replace(asm, params={**asm.params, "k_t": k_t})
    return float(simulate(asm.chain(mu_plus, mu_minus), asm.loading,
                          max_marched).drift_per_cycle)


def run_strip_fe(asm, mu_plus: float, mu_minus: float, *, mesh: int = MESH_DEFAULT,
                 chain_drift_m: float | None = None, increments: int = INCREMENTS,
                 timeout: float = 600.0) -> dict:
    """The ``fe`` block of ``asperity risk --fe getfem --json``: the FE drift per cycle,
    the chain's beside it (``chain_drift_m``, else computed), the shear-corrected chain,
    the FE model's elastic limit against the closed form, and the run's size and time."""
    from .getfem_runner import run_job
    check_fe_assembly(asm)
    nx, ny = fe_mesh(asm, mesh)
    job = strip_job(asm, mu_plus, mu_minus, nx, ny, increments=increments)
    r = run_job(job, timeout=timeout)
    p = asm.params
    nu, nu_from = poisson(asm)
    kt_eff = shear_corrected_kt(p["k_t"], p["h"], p["E"], nu)
    chain = chain_drift(asm, mu_plus, mu_minus) if chain_drift_m is None else chain_drift_m
    corrected = chain_drift(asm, mu_plus, mu_minus, k_t=kt_eff)
    d = float(r["drift_per_cycle_m"])
    scale = abs(p["alpha_T"]) * p["l"] * asm.loading.dT_range
    out = {"solver": "GetFEM, 2D plane stress, Q1", "drift_per_cycle_m": d,
           "chain_drift_per_cycle_m": chain, "difference_m": d - chain,
           "relative_difference": _rel(d, chain, scale),
           "chain_shear_corrected": {"k_t_eff_Pa_per_m": kt_eff, "drift_per_cycle_m":
                                     corrected, "relative_difference":
                                     _rel(d, corrected, scale)},
           "elastic_limit_K": r["elastic_limit_K"],
           "elastic_limit_closed_form_K": asm.dT_c_closed_form(mu_plus, mu_minus),
           "elastic_limit_shear_corrected_K": _dT_c(p, kt_eff, mu_plus, mu_minus),
           "first_slip_x_m": r["first_slip_x_m"],
           "first_slip_towards": r["first_slip_towards"],
           "nu": nu, "nu_from": nu_from}
    for k in ("elements", "elements_along_l", "elements_through_h", "nodes", "dofs",
              "increments", "newton_iterations", "max_newton_per_increment", "halvings",
              "cycles_run",
              "drifts_m", "mean_u_m", "seconds"):
        out[k] = r[k]
    out["explanation"] = explain(out, p)
    out["_profile"] = {"x_m": r["x_m"], "u_m": r["u_end_m"]}
    return out


def _dT_c(p: dict, k_t: float, mu_plus: float, mu_minus: float) -> float:
    from ..microslip.closed_forms import strip_dT_c
    return strip_dT_c(p["h"], p["E"], p["p"], p["l"], k_t, mu_plus, mu_minus, p["alpha_T"])


def _rel(a: float, b: float, scale: float) -> float | None:
    if b == 0.0:                    # no drift: the FE's within its stabilisation test
        return None if abs(a) > 10 * STABILISED * scale else 0.0
    return abs(a - b) / abs(b)


def explain(fe: dict, p: dict) -> str:
    """Why the FE drift differs from the chain's, in one paragraph."""
    c = fe["chain_shear_corrected"]
    r, rc = fe["relative_difference"], c["relative_difference"]
    if r is None or rc is None:
        return ("the chain has no drift here; the FE model's drift is its rounding and its "
                "discretisation")
    G = p["E"] / (2.0 * (1.0 + fe["nu"]))
    return (f"the chain is a bar E h on the bed; the FE body also shears through its height "
            f"(compliance h/(3G) = {p['h'] / (3 * G):.3g} m/Pa per unit area in series with "
            f"1/k_t = {1 / p['k_t']:.3g}): with k_t,eff = {c['k_t_eff_Pa_per_m']:.4g} Pa/m "
            f"the chain drifts {c['drift_per_cycle_m']:.4g} m/cycle, {100 * rc:.2g} % from "
            f"the FE model (against {100 * r:.2g} % with k_t); the rest is the mesh "
            f"({fe['elements_along_l']} x {fe['elements_through_h']} elements), the "
            f"lumping of the bed at the nodes and, as lam h = sqrt(k_t h / E) = "
            f"{math.sqrt(p['k_t'] * p['h'] / p['E']):.2g} grows towards 1, a shear through "
            "the height that is no longer linear")


def fe_lines(fe: dict) -> list[str]:
    """The FE part of ``asperity risk``'s text."""
    if "skipped" in fe:
        return [f"FE (GetFEM): not run: {fe['skipped']}"]
    rel = fe["relative_difference"]
    dc = fe["elastic_limit_K"]
    return [
        f"FE (GetFEM, plane stress, {fe['elements_along_l']} x {fe['elements_through_h']} "
        f"Q1 elements, nu = {fe['nu']:g} from {fe['nu_from']}): drift per cycle "
        f"{fe['drift_per_cycle_m']:+.6g} m beside the chain's "
        f"{fe['chain_drift_per_cycle_m']:+.6g} m"
        + (f" ({100 * rel:.3g} % apart)" if rel is not None else ""),
        (f"  FE elastic limit dT_c = {dc:.6g} K (closed form "
         f"{fe['elastic_limit_closed_form_K']:.6g} K, with k_t,eff "
         f"{fe['elastic_limit_shear_corrected_K']:.6g} K); {fe['cycles_run']} cycles, "
         f"{fe['increments']} increments, {fe['newton_iterations']} Newton iterations, "
         f"{fe['seconds']:.3g} s") if dc is not None else
        "  FE: no slip ever (self-locking both ways)",
        f"  why: {fe['explanation']}"]
