"""A plain NumPy / scipy.fft Polonsky-Keer contact solver: the independent reference of the
contact tests and the "plain" peer of ``benchmarks/bench_contact.py``.

Written from the algorithm of Polonsky & Keer (Wear 231, 206-219, 1999), not from anyone's
code.  Rigid rough surface h (its highest points touch first) against an elastic half-space
of effective modulus E*: gap g = u(p) - h + d >= 0, p >= 0, g p = 0, mean pressure over the
map = p_mean (SPEC.md 7).  Pressures are pixel values (uniform over each dx x dy pixel).

* ``periodic``: u_k = 2 p_k / (E* |k|), the k = 0 term dropped (load control sets it);
* ``free``: Love's displacement of a uniformly loaded dx x dy rectangle (Johnson, Contact
  Mechanics, eq. 3.25, written with the antiderivative of 1/r), convolved on a grid
  zero-padded to twice the size (DC-FFT).

NaN heights mark undefined pixels: they carry no pressure.  ``hardness`` caps the pressure
(a perfectly plastic cap: pixels at H leave the CG set, the load goes to more contact).
"""
from __future__ import annotations

import numpy as np
import scipy.fft as sfft


def periodic_kernel(shape, dx, dy, E_star):
    """rfft2 multiplier of p -> u on a periodic (nx, ny) grid."""
    kx = 2 * np.pi * sfft.fftfreq(shape[0], dx)[:, None]
    ky = 2 * np.pi * sfft.rfftfreq(shape[1], dy)[None, :]
    k = np.hypot(kx, ky)
    k[0, 0] = np.inf                                   # mean displacement: load control
    return 2.0 / (E_star * k)


def love_coefficients(nx, ny, dx, dy, E_star):
    """Displacement at pixel offsets (i dx, j dy), i in [-nx, nx), j in [-ny, ny) (FFT order)
    of a unit pressure on one dx x dy pixel: u = (1 / (pi E*)) int int dA / r."""
    def F(X, Y):              # d^2 F / dX dY = 1 / sqrt(X^2 + Y^2), F(0, .) = F(., 0) = 0
        R = np.hypot(X, Y)
        with np.errstate(divide="ignore", invalid="ignore"):
            a = np.where(X != 0, X * np.log((Y + R) / np.abs(X)), 0.0)
            b = np.where(Y != 0, Y * np.log((X + R) / np.abs(Y)), 0.0)
        return a + b                    # X asinh(Y/X) + Y asinh(X/Y)
    x = np.fft.fftfreq(2 * nx, 1.0 / (2 * nx))[:, None] * dx
    y = np.fft.fftfreq(2 * ny, 1.0 / (2 * ny))[None, :] * dy
    a, b = dx / 2, dy / 2
    s = F(x + a, y + b) - F(x + a, y - b) - F(x - a, y + b) + F(x - a, y - b)
    return s / (np.pi * E_star)


def make_operator(shape, dx, dy, E_star, boundary, workers=-1):
    """p (nx, ny) -> u (nx, ny)."""
    nx, ny = shape
    if boundary == "periodic":
        G = periodic_kernel(shape, dx, dy, E_star)
        return lambda p: sfft.irfft2(sfft.rfft2(p, workers=workers) * G, s=shape,
                                     workers=workers)
    G = sfft.rfft2(love_coefficients(nx, ny, dx, dy, E_star), workers=workers)
    return lambda p: sfft.irfft2(sfft.rfft2(p, s=(2 * nx, 2 * ny), workers=workers) * G,
                                 s=(2 * nx, 2 * ny), workers=workers)[:nx, :ny]


def polonsky_keer(h, dx, dy, E_star, p_mean, boundary="periodic", hardness=None, tol=1e-10,
                  max_iterations=10000, initial=None, workers=-1):
    """Pressure (Pa, NaN on undefined pixels), gap (m), iterations, error.  ``tol``: the
    relative change of the pressure field between iterations (Polonsky & Keer's epsilon)."""
    h = np.asarray(h, float)
    ok = np.isfinite(h)
    z = np.where(ok, h, 0.0)
    K = make_operator(h.shape, dx, dy, E_star, boundary, workers)
    W = p_mean * h.size                                # load / pixel area
    H = np.inf if hardness is None else hardness
    p = np.where(ok, W / ok.sum(), 0.0) if initial is None else np.where(ok, initial, 0.0)
    p = np.clip(p, 0.0, H)
    t = np.zeros_like(p)
    G_old, delta, err = 1.0, 0.0, np.inf
    for it in range(1, max_iterations + 1):
        g = K(p) - z                                   # gap without the rigid offset d
        S = ok & (p > 0) & (p < H)                     # CG set: in contact, below the cap
        g -= g[S].mean() if S.any() else g[ok & (p > 0)].min()   # the offset d
        G = np.sum(g[S] ** 2)
        t = np.where(S, g + delta * (G / G_old) * t, 0.0)
        G_old = G
        r = K(t)
        r -= r[S].mean() if S.any() else 0.0
        rt = np.sum(r[S] * t[S])
        tau = np.sum(g[S] * t[S]) / rt if rt > 0 else 0.0
        p_old = p
        p = np.where(S, p - tau * t, p)
        p = np.clip(p, 0.0, H)
        over = ok & (((p == 0) & (g < 0)) | ((p == H) & (g > 0)))   # set to change
        delta = 0.0 if over.any() else 1.0
        p = np.clip(np.where(over, p - tau * g, p), 0.0, H)
        p = _rescale(p, W, H)
        err = np.abs(p - p_old).sum() / W
        if err < tol:
            break
    u = K(p)
    g = u - z
    c = ok & (p > 0) & (p < H)
    g -= g[c].mean() if c.any() else 0.0
    return (np.where(ok, p, np.nan), np.where(ok, np.maximum(g, 0.0) * (p == 0), np.nan),
            it, err)


def _rescale(p, W, H):
    """Scale the pressures below the cap so that the total is W (pixels at H stay)."""
    if not np.isfinite(H):
        return p * (W / p.sum())
    for _ in range(100):
        cap = p >= H
        free = p[~cap].sum()
        if free <= 0:
            return p
        p = np.where(cap, H, np.minimum(p * ((W - H * cap.sum()) / free), H))
        if abs(p.sum() - W) <= 1e-14 * W:
            return p
    return p
