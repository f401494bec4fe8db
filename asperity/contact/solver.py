"""Normal contact of a rigid rough surface and an elastic half-space: the Polonsky-Keer
constrained conjugate gradient with exact load control (SPEC.md section 7).

Problem: heights h (the rigid surface, its highest points touch first), an elastic
half-space of effective modulus E* pressed onto it at nominal pressure p_bar.  Unknowns:
the pixel pressures p and the approach d such that, with the half-space's displacement
u = K p (:mod:`.elastic`),

    g = u - h + d >= 0,   0 <= p <= H,   g = 0 where 0 < p < H,   g <= 0 where p = H,
    g > 0 only where p = 0,   sum p = p_bar x (pixel count of the whole map)

(H the hardness of the optional perfectly plastic cap, infinite without one; pixels where
p = H are plastic: the surface has flowed into the gap).  Undefined (NaN) pixels carry no
pressure.

Polonsky & Keer (Wear 231, 206, 1999) with Vollebregt's preconditioner, one iteration:

1. the gap g = u - h - gbar on the free set F = {0 < p < H}, gbar its mean there (the
   gap mean shift: the rigid-body approach is d = -gbar);
2. the preconditioned gap z = M g (Vollebregt, J. Comput. Phys. 257, 333, 2014): g on F
   and on the pixels step 4 moves, 0 elsewhere, multiplied by the inverse of the
   periodic half-space, |q| E* / 2 in Fourier space (single precision: an approximate
   inverse serves as well); Z = sum_F g z;
3. the conjugate direction t = z + (Z / Z_old) t on F, 0 elsewhere, restarted (t = z)
   when sum_F g t < :data:`THETA` Z, or when the last step moved more than
   :data:`RESTART_SHARE` of F's size in or out of the set.  t keeps its mean over F:
   the load control (step 5) takes it out, and the iteration converges faster than with
   t projected on the constant load (measured: 37 iterations for 43 at 512^2);
4. r = K t, rbar its mean over F, tau = sum_F g t / sum_F (r - rbar) t; p -= tau t on F;
   where p = 0 and g < 0 (overlap), and where p = H and g > 0 (a plastic pixel whose gap
   opened), p -= tau z; p clipped to [0, H];
5. load control: p scaled by the factor s that gives sum min(s p, H) = the load (plain
   scaling without a cap, as in the paper; with one, Newton steps on that concave,
   piecewise linear function, exact in a few passes).  When the pixels at H alone carry
   the load, scaling would take them all off the cap (and the next step put them back:
   the iteration cycled), so the least penetrating of them leave contact first
   (:func:`.loads.trim`);
6. the change eps = sum |p_new - p_old| / sum p (the residual reported): done below tol,
   when the result also satisfies the complementarity (no pixel out of contact below the
   half-space, none in contact off it, within :data:`GAP_TOL` of :func:`.gaps.reference_length`;
   else the directions restart and the iteration goes on, and a result reached that way
   reports the violation as its residual and did not converge).

A solve whose residual stops halving for :data:`STALL` iterations (pixels at the edge of a
plastic zone stepping in by M g and out by the clip, in turn) goes on without the
preconditioner.  A capped solve that does not converge in :data:`PLASTIC_FIRST_TRY`
iterations, or whose residual stops halving for :data:`PLASTIC_STALL` (a cap close to the
mean pressure, most of the contact at H: the set cycles at the zones' edges), turns to an
outer loop over the plastic set (:mod:`.plastic`) that starts from its pixels at H.

The iteration works in the unit of length L = :func:`.gaps.reference_length` (heights, gaps,
displacements) and of pressure L Pa (so that u = K p holds unchanged): its numbers are near
1 for heights of 1e-306 m as for 1 km, with no underflow or overflow of the sums.

u is updated without a transform (u - tau r, scaled) when no pixel was clipped or moved
by the gap; else, and every :data:`REFRESH` iterations, recomputed as K p.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import AsperityError, InputError, check_array, check_int, check_range
from . import elastic
from .checks import (  # noqa: F401  (the checks of the arguments, and their ranges)
    E_RANGE,
    PRESSURE_OVER_E,
    check_inputs,
    check_solver_memory,
    effective_modulus,
)
from .gaps import complementary, reference_length
from .loads import fill, scale_factor, start, trim

#: iterations between two full products u = K p when u is updated incrementally
REFRESH = 25
#: the conjugate direction is restarted (t = z) when sum g t < THETA Z: after the
#: contact set changed, the old direction may have lost its conjugacy (on an unchanged
#: set, with the exact step of the iteration, sum g t = Z)
THETA = 0.9
#: ... and when the gap moved more pixels in or out than this share of the free set (a
#: direction of two pixels times beta ~ 1e10, continued over the 66 pixels that entered,
#: gave steps of 1e-10 that passed the residual test on a wrong set).  Measured on the
#: rough map at 512^2 (periodic, free): no restart 36, 43 iterations; a restart on every
#: pixel moved 43, 81; on 5 % of the set 37, 42
RESTART_SHARE = 0.05
#: largest gap violation of a converged solution over the map's height range (a pixel
#: out of contact below the half-space, one in contact off it); converged solves stay
#: near 1e-9 (measured), a solve stuck in a wrong contact set near 0.1
GAP_TOL = 1e-6
#: iterations a capped solve tries before the outer loop over the plastic set (:mod:`.plastic`;
#: converged capped solves take 15 to 60, one whose set stalls never converges)
PLASTIC_FIRST_TRY = 300
#: default iteration limit
MAX_ITERATIONS = 10_000
#: ... or whose residual has not halved in this many iterations (a contact set that
#: cycles at the edge of the plastic zones: measured, converging capped solves halve it
#: every 1 to 10 iterations)
PLASTIC_STALL = 30
#: iterations without the residual halving after which a solve drops the preconditioner
#: (measured: a few pixels at the edge of a plastic zone entering by the preconditioned
#: gap and leaving clipped, every other iteration, for thousands of iterations; the
#: plain iteration moves them by their own gap and converges)
STALL = 30
#: the conjugate directions are preconditioned by the inverse of the half-space (the
#: module's docstring, steps 2 and 3; without: z = g, Polonsky and Keer's iteration).
#: Measured (self-affine map of the benchmark, p/E* 0.0025, tol 1e-8, one thread, CPU
#: time): periodic 512^2 36 iterations for 82, 0.55 s for 1.0; 1024^2 44 for 101, 2.95 s
#: for 5.0; free 512^2 43 for 75, 1.7 s for 2.3 (an iteration takes one transform more,
#: in single precision, on the unpadded grid)
PRECONDITION = True


class ContactNotConverged(AsperityError):
    """The iteration limit was reached; ``.result`` holds the last iterate."""

    def __init__(self, message: str, result):
        super().__init__(message)
        self.result = result


@dataclass(frozen=True)
class ContactResult:
    """The solved contact (see :func:`solve_contact`); arrays on the map's own grid."""

    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    area_fraction: float
    mean_pressure: float
    max_pressure: float
    mean_gap: float
    iterations: int
    residual: float
    converged: bool
    E_star: float
    boundary: str
    hardness: float | None
    pixel_size: tuple[float, float]
    pressure_asked: float
    #: share of the defined pixels at the hardness (0 without one)
    plastic_fraction: float = 0.0
    #: rigid-body approach d of the gap g = u - h + d, m
    approach: float = 0.0

    @property
    def full_contact(self) -> bool:
        """Every defined pixel is in contact."""
        return self.area_fraction >= 1.0

    def to_dict(self) -> dict:
        """The JSON keys of ``asperity contact --json``."""
        return {"area_fraction": self.area_fraction, "pressure_Pa": self.mean_pressure,
                "max_pressure_Pa": self.max_pressure, "mean_gap_m": self.mean_gap,
                "E_star_Pa": self.E_star, "boundary": self.boundary,
                "hardness_Pa": self.hardness, "iterations": self.iterations,
                "residual": self.residual, "converged": self.converged,
                "plastic_fraction": self.plastic_fraction}


def solve_contact(heights, pixel_size, E_star, pressure, *, boundary="periodic",
                  hardness=None, tol=1e-8, max_iterations=None, initial=None,
                  progress=None, workers=None) -> ContactResult:
    """Normal contact of a rigid rough surface pressed onto an elastic half-space (SPEC.md 7).

    Frictionless; the highest points touch first.  Polonsky-Keer constrained conjugate
    gradient with exact load control (the docstring of ``asperity.contact.solver`` gives
    the problem and the algorithm).

    Parameters
    ----------
    heights : (nx, ny) array_like of float
        The rigid surface, m, axis 0 along x, NaN undefined (carries no pressure); at
        least 2 x 2 pixels.
    pixel_size : float or (float, float)
        Grid spacing, m: one number or (dx, dy).
    E_star : float
        Effective modulus of the half-space, Pa, in [1, 1e13]
        (:func:`asperity.effective_modulus`).
    pressure : float
        Nominal pressure over the whole map's projected area nx dx x ny dy, Pa, > 0 with
        ``pressure / E_star`` in [1e-12, 10].
    boundary : {"periodic", "free"}, default "periodic"
        The map is one period, or a non-periodic scan (zero-padded transforms).
    hardness : float or None, default None
        A perfectly plastic cap H, Pa, above the mean pressure over the defined pixels.
    tol : float, default 1e-8
        The iteration stops when the relative change of the pressure field
        (``sum |dp| / sum p``) falls below it, in [1e-15, 0.1]; reported as ``residual``.
    max_iterations : int or None, default None
        Iteration limit, in [1, 1e7]; None: 10000.
    initial : (nx, ny) array_like of float or None, default None
        A pressure field to start from (a previous result's ``pressure``), scaled to the
        load.
    progress : callable or None, default None
        ``progress(fraction, text)``; None: the active progress bar.
    workers : int or None, default None
        Threads of the transforms; None: the cores this process may use.

    Returns
    -------
    ContactResult
        ``pressure``, ``gap``, ``displacement`` (nx, ny) and ``contact`` (bool) fields;
        ``area_fraction`` of the defined pixels in contact; ``mean_pressure`` and
        ``max_pressure``, Pa; ``mean_gap`` and ``approach``, m; ``iterations``,
        ``residual``, ``converged``; ``plastic_fraction``; ``to_dict()`` the keys of
        ``asperity contact --json``.

    Raises
    ------
    asperity.InputError
        An argument out of range (one line naming it), or a map too large for the memory.
    asperity.AsperityError
        ``ContactNotConverged`` when the iteration limit is reached (the last iterate in
        its ``result``).

    See Also
    --------
    asperity.solve_load_curve, asperity.effective_modulus, asperity.ElasticContact

    Examples
    --------
    Westergaard's wavy surface ``h = Delta cos(2 pi x / lambda)`` (SPEC.md section 7): below
    ``p* = pi E* Delta / lambda`` the contact width 2a satisfies
    ``sin^2(pi a / lambda) = p / p*``, so at ``p = p*/2`` half the period touches, and the
    peak pressure is ``2 sqrt(p p*)`` = 1.4142 p*:

    >>> n, lam, delta, E = 128, 128e-6, 1e-7, 1e9
    >>> x = np.arange(n) * lam / n
    >>> h = np.tile(delta * np.cos(2 * np.pi * x / lam)[:, None], (1, 4))
    >>> p_star = np.pi * E * delta / lam
    >>> r = asperity.solve_contact(h, lam / n, E, 0.5 * p_star)
    >>> print(f"contact {r.area_fraction:.4f}, peak {r.max_pressure / p_star:.4f} p*, "
    ...       f"converged {r.converged}")
    contact 0.5078, peak 1.4142 p*, converged True
    """
    z, (dx, dy), E, pbar, boundary, H, n_def = check_inputs(heights, pixel_size, E_star,
                                                            pressure, boundary, hardness)
    tol, maxit, workers = check_options(tol, max_iterations, progress, workers)
    p0 = None if initial is None else check_array("initial", initial, shape=z.shape,
                                                  finite=False)
    space = elastic.HalfSpace(z.shape, dx, dy, E, boundary, workers=workers)
    return solve_on(space, z, pbar, H, n_def, tol, maxit, p0, progress)


def check_options(tol, max_iterations, progress, workers):
    """(tol, iteration limit, transform threads) checked (``progress`` a callable or
    None)."""
    from ..resources import cpu_cores
    tol = check_range("tol", tol, 1e-15, 0.1)
    maxit = MAX_ITERATIONS if max_iterations is None else \
        check_int("max_iterations", max_iterations, 1, 10 ** 7)
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be a callable(fraction, text), got "
                         f"{type(progress).__name__}")
    workers = cpu_cores() if workers is None else check_int("workers", workers, 1, 4096)
    return tol, maxit, workers


def solve_on(space, z, pbar: float, H, n_def: int, tol: float, maxit: int, p0,
             progress) -> ContactResult:
    """The solve of checked arguments (:func:`check_inputs`) on the half-space ``space``
    (an :class:`.elastic.HalfSpace` of z's shape, reused along a load curve)."""
    # in the unit of length L (heights, displacements, gaps) and of pressure L x Pa (so
    # that u = K p holds unchanged): every number of the iteration near 1, whatever the
    # scale of the heights (1e-306 m or 1 km) -- no underflow, no overflow
    L = reference_length(space, z, pbar)
    top = float(np.nanmax(z))
    zn = (z - top) / L                         # the highest point at 0
    Hn = math.inf if H is None else H / L
    first = maxit if H is None else min(maxit, PLASTIC_FIRST_TRY)
    out = _iterate(space, zn, pbar / L, Hn, n_def, tol, first, None if p0 is None
                   else p0 / L, progress, None if H is None else PLASTIC_STALL)
    if not out["converged"] and H is not None and maxit > out["iterations"]:
        from .plastic import solve_plastic    # the plastic set by an outer loop
        used = out["iterations"]
        start = out.pop("pressure")            # the plastic set starts from its pixels at H
        del out
        out = solve_plastic(_iterate, GAP_TOL, space, zn, pbar / L, Hn, n_def, tol,
                            maxit - used, progress, start)
        out["iterations"] += used
    del zn
    at = None if H is None else out["pressure"] >= Hn
    for k in ("pressure", "gap", "displacement"):
        out[k] *= L
    for k in ("mean_pressure", "max_pressure", "mean_gap"):
        out[k] = float(out[k] * L)
    if at is not None and at.any():            # the pixels at the cap: at H exactly
        out["pressure"][at] = H
        out["max_pressure"] = H
    out["approach"] = top + out["approach"] * L
    res = ContactResult(**out, E_star=space.E_star, boundary=space.boundary, hardness=H,
                        pixel_size=(space.dx, space.dy), pressure_asked=pbar)
    if not res.converged:
        raise ContactNotConverged(
            f"the contact solve did not converge in {res.iterations} "
            f"iteration{'s' * (res.iterations != 1)} (residual "
            f"{res.residual:.3g}, tolerance {tol:g}); allow more iterations or a looser "
            f"tolerance", res)
    return res


def _iterate(space, z, pbar, H, n_def, tol, maxit, p0, progress, stall=None) -> dict:
    from ..progress import report
    from . import _pk_kernels as K
    tell = progress or report
    nx, ny = z.shape
    load = pbar * nx * ny                      # sum of the pixel pressures
    h = z - np.nanmax(z)                       # the highest point at 0 (rounding)
    p = start(z, h, load, H, n_def, p0)
    u = np.empty_like(h)
    t = np.zeros_like(h)
    r = np.empty_like(h)
    zp = np.empty_like(h) if PRECONDITION else np.empty(0)    # M g (the preconditioned gap)
    nz = np.empty(0)                           # the gap moves the pixels (not M g)
    hf, pf, uf, tf, rf, zf = (a.reshape(-1) for a in (h, p, u, t, r, zp))
    s, fixed = scale_factor(pf, load, H)
    if s is None:
        space.apply(p, u)
        fill(pf, uf, hf, load, H)
    else:
        K.rescale(pf, uf, rf, s, H, False, fixed)
    space.apply(p, u)
    c, G_old, delta, fresh, eps = 0.0, 1.0, 0, 0, math.inf
    it, best, it_best, pre = 0, math.inf, 0, PRECONDITION
    t_report = time.perf_counter()
    while it < maxit:
        it += 1
        s1, s2, n, _, _ = K.gap_sums(uf, hf, pf, H, c)
        tau = 0.0
        if n > 1:                              # one free pixel: its gap is the mean, no step
            gbar = c + s1 / n
            G = max(s2 - n * (gbar - c) ** 2, 0.0)
            c = gbar
            if pre:                            # z = M g
                K.masked_gap(uf, hf, pf, H, gbar, zf)
                space.precondition(zp, zp)
                G = K.precond_sum(uf, hf, pf, zf, H, gbar)
                beta = delta * G / G_old if G_old > 0 and G > 0 else 0.0
                if beta > 0.0 and K.precond_direction(uf, hf, pf, tf, zf, H, gbar,
                                                      beta) < THETA * G:
                    K.precond_direction(uf, hf, pf, tf, zf, H, gbar, 0.0)
                elif beta == 0.0:
                    K.precond_direction(uf, hf, pf, tf, zf, H, gbar, 0.0)
            else:
                beta = delta * G / G_old if G_old > 0 else 0.0
                if beta > 0.0 and K.direction(uf, hf, pf, tf, H, gbar, beta) < THETA * G:
                    K.direction(uf, hf, pf, tf, H, gbar, 0.0)     # restart: t = g
                elif beta == 0.0:
                    K.direction(uf, hf, pf, tf, H, gbar, 0.0)
            space.apply(t, r)
            sr, srt, st, sgt = K.step_sums(uf, hf, pf, tf, rf, H, gbar)
            denom = srt - sr / n * st
            tau = sgt / denom if denom > 0.0 and sgt > 0.0 else 0.0
            moves = zf if pre else nz
        if not tau > 0.0:                      # the gap step: one free pixel or none, or
            G = 0.0                            # the free set solved (no conjugate step)
            if n == 1:
                gbar = c + s1
            elif n == 0:
                gbar = float(np.max(np.where(p >= H, u - h, -np.inf)))
            t[...] = 0.0
            r[...] = 0.0
            tau = 1.0 / space.self_compliance
            moves = nz
            c = gbar
        total, clipped, moved = K.update(uf, hf, pf, tf, rf, H, gbar, tau, moves)
        delta = 0 if moved > RESTART_SHARE * n else 1     # the set changed: restart
        exact = clipped == 0 and moved == 0 and fresh < REFRESH
        if math.isfinite(H) and trim(pf, uf, hf, load, H, moves is nz):
            total, exact = -1.0, False         # the least penetrating pixels off the cap
        s, fixed = scale_factor(pf, load, H) if total != 0.0 else (None, False)
        if s is None and math.isinf(H):       # every pressure clipped: back to the last
            p[...] = r                         # iterate, restart the directions
            change, delta, exact = math.inf, 0, False
        elif s is None:                        # the set cannot carry the load: widen it
            fill(pf, uf, hf, load, H)
            change = float(np.abs(pf - rf).sum())
            exact = False
        else:
            exact = exact and not fixed
            change, _, capped = K.rescale(pf, uf, rf, s, H, exact, fixed)
            exact = exact and capped == 0
        if exact:
            fresh += 1
        else:
            space.apply(p, u)
            fresh = 0
        G_old = G
        eps = change / load
        now = time.perf_counter()
        if now - t_report > 0.2:
            t_report = now
            tell(min(1.0, max(0.0, math.log(max(eps, tol)) / math.log(tol))),
                 f"contact: iteration {it}, residual {eps:.2g}")
        if eps < tol:
            if complementary(K, space, p, u, h, H, fresh, max(GAP_TOL, 100.0 * tol), pbar):
                break
            delta = 0                          # a stalled set: restart the directions
        if eps < 0.5 * best:
            best, it_best = eps, it
        elif stall is not None and it - it_best >= stall:
            break                              # the residual no longer comes down
        elif pre and it - it_best >= STALL:    # pixels stepping in and out by M g, in a
            pre, delta, it_best = False, 0, it   # cycle: the plain iteration from here
    if fresh:                                  # the exact displacement of the result
        space.apply(p, u)
    s1, _, n, _, _ = K.gap_sums(uf, hf, pf, H, 0.0)
    if n > 0:
        gbar = s1 / n
    else:
        gbar = float(np.max(np.where(p >= H, u - h, -np.inf)))
    del r, rf, zp, zf, moves
    plastic = int(np.count_nonzero(p >= H)) if math.isfinite(H) else 0
    gap = t
    free_off, plastic_off, pen = K.gap_violation(uf, hf, pf, H, gbar)
    gap_sum, _, nc = K.final_fields(uf, hf, pf, tf, -gbar)
    d = float(np.nanmax(z)) - gbar             # approach for the heights as given
    # complementarity: no pixel out of contact below the half-space, none in contact off
    # it (the free set on it, the plastic pixels on or into it)
    off = max(pen, free_off, plastic_off) / reference_length(space, z, pbar)
    ok = eps < tol and off <= max(GAP_TOL, 100.0 * tol)
    return dict(pressure=p, gap=gap, displacement=u, contact=p > 0.0,
                area_fraction=nc / n_def, mean_pressure=float(np.nansum(p)) / (nx * ny),
                max_pressure=float(np.nanmax(p)), mean_gap=gap_sum / n_def,
                iterations=it, residual=float(eps if ok else max(eps, off)),
                converged=bool(ok),
                plastic_fraction=plastic / n_def, approach=d)

