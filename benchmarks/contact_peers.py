"""The contact solver's peers, shared by ``tests/test_contact_oracle.py`` and
``benchmarks/bench_contact.py``: a random self-affine height map, and ContactMechanics
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


def self_affine(nx, ny=None, hurst=0.8, rms_slope=0.1, dx=1.0, dy=None, seed=0):
    """(nx, ny) periodic random height map (m when dx is), power spectrum C(q) ~ q^-2(1+H)
    (random phases), zero mean, scaled to the given rms slope (periodic forward
    differences, sqrt(mean(dz/dx^2 + dz/dy^2)))."""
    ny = nx if ny is None else ny
    dy = dx if dy is None else dy
    rng = np.random.default_rng(seed)
    qx = np.fft.fftfreq(nx, dx)[:, None]
    qy = np.fft.rfftfreq(ny, dy)[None, :]
    q = np.hypot(qx, qy)
    q[0, 0] = np.inf
    spec = np.fft.rfft2(rng.standard_normal((nx, ny))) * q ** (-(1.0 + hurst))
    z = np.fft.irfft2(spec, s=(nx, ny))
    z -= z.mean()
    gx = (np.roll(z, -1, 0) - z) / dx
    gy = (np.roll(z, -1, 1) - z) / dy
    return z * (rms_slope / np.sqrt(np.mean(gx * gx + gy * gy)))


def cm_available():
    try:
        import ContactMechanics  # noqa: F401
    except Exception as exc:                  # pragma: no cover - depends on the machine
        return f"ContactMechanics cannot be imported ({type(exc).__name__}: {exc})"
    return None


def cm_solve(h, dx, dy, E_star, p_mean, boundary="periodic", hardness=None, tol=1e-10,
             max_iterations=100000):
    """ContactMechanics' constrained conjugate gradient (Polonsky-Keer) on asperity's
    problem: (pressure Pa with NaN on undefined pixels, gap m, iterations, converged)."""
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
    res = constrained_conjugate_gradients(
        sub, z, hardness=None if hardness is None else hardness / E_star * area,
        external_force=load, pentol=tol * rms, forcetol=tol * load / ok.sum(),
        thermotol=tol, maxiter=max_iterations)
    p = np.asarray(res.jac)[:nx, :ny] / area * E_star
    gap = (np.asarray(res.x)[:nx, :ny] - np.where(ok, h / dx, 0.0) - res.offset) * dx
    p = np.where(ok, p, np.nan)
    gap = np.where(ok, np.where(p > 0, 0.0, gap), np.nan)
    return p, gap, int(res.nit), bool(res.success)
