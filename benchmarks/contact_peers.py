"""The contact solver's peers, shared by ``tests/test_contact_oracle.py`` and
``benchmarks/bench_contact.py``: a random self-affine height map (the benchmark's,
:func:`asperity.contact.bench.self_affine`), and ContactMechanics
(PyPI ``ContactMechanics``, MIT; a test and benchmark peer only, never imported by the
package) called in asperity's conventions.

ContactMechanics' conventions, and how :func:`cm_solve` maps asperity's onto them:

* ``young`` of an infinite half-space without ``poisson`` is the contact modulus E*
  (Johnson's), the same E* as SPEC.md 7: passed as 1 (pressures in units of E*);
* its heights are the rigid surface, pushed up into the elastic body (gap u - h - offset),
  so the highest points touch first, as in asperity: heights pass unchanged (in units of
  dx, the pixel size along axis 0; ``physical_sizes`` = (nx, ny dy / dx));
* its solver works with pixel *forces* (pressure x area per pixel), compressive forces
  negative inside, positive in ``result.jac``; ``external_force`` is the total load =
  nominal pressure x nx ny dx dy (the whole map, undefined pixels included, as asperity's
  pressure is nominal over the map's projected area); its ``hardness`` is a force per pixel
  too (H x area per pixel);
* ``FreeFFTElasticHalfSpace`` pads to (2 nx, 2 ny) itself; its nominal area is the
  unpadded map's;
* undefined pixels: a masked height array (they are taken out of the CG set and carry no
  force);
* its convergence tests are absolute (``pentol`` a penetration, ``forcetol`` a pixel force)
  plus ``thermotol`` relative: :func:`cm_solve` sets them from ``tol`` relative to the rms
  height and to the mean pixel force.
"""
from __future__ import annotations

import numpy as np

from asperity.contact.bench import self_affine  # noqa: F401  (the maps of tests and bench)


def cm_available():
    try:
        import ContactMechanics  # noqa: F401
    except Exception as exc:                  # pragma: no cover - depends on the machine
        return f"ContactMechanics cannot be imported ({type(exc).__name__}: {exc})"
    return None


def cm_solve(h, dx, dy, E_star, p_mean, boundary="periodic", hardness=None, tol=1e-10,
             max_iterations=100000, initial=None):
    """ContactMechanics' constrained conjugate gradient (Polonsky-Keer) on asperity's
    problem: (pressure Pa with NaN on undefined pixels, gap m, iterations, converged).
    ``initial``: a pressure (Pa) to start from (its pixel forces)."""
    from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    h = np.asarray(h, float)
    nx, ny = h.shape
    ok = np.isfinite(h)
    z = np.ma.masked_invalid(h / dx) if not ok.all() else h / dx
    sizes = (float(nx), ny * dy / dx)
    area = dy / dx                                      # area per pixel, units of dx^2
    cls = PeriodicFFTElasticHalfSpace if boundary == "periodic" else FreeFFTElasticHalfSpace
    sub = cls((nx, ny), 1.0, physical_sizes=sizes)
    load = p_mean / E_star * nx * ny * area
    rms = float(np.std(h[ok] / dx))
    f0 = None
    if initial is not None:                             # compressive forces are negative
        f0 = np.zeros(sub.nb_subdomain_grid_pts)
        f0[:nx, :ny] = -np.where(ok, np.nan_to_num(initial), 0.0) / E_star * area
    res = constrained_conjugate_gradients(
        sub, z, hardness=None if hardness is None else hardness / E_star * area,
        external_force=load, pentol=tol * rms, forcetol=tol * load / ok.sum(),
        thermotol=tol, maxiter=max_iterations, initial_forces=f0)
    p = np.asarray(res.jac)[:nx, :ny] / area * E_star
    gap = (np.asarray(res.x)[:nx, :ny] - np.where(ok, h / dx, 0.0) - res.offset) * dx
    p = np.where(ok, p, np.nan)
    gap = np.where(ok, np.where(p > 0, 0.0, gap), np.nan)
    return p, gap, int(res.nit), bool(res.success)
