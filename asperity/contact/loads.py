"""The load control of the contact iteration (:mod:`asperity.contact.solver`): the first
pressure field, the factor that scales a field to the load under a hardness cap, and the
bearing-area fill of a plastic solve whose contact set is too small."""
from __future__ import annotations

import math

import numpy as np


def start(z: np.ndarray, h: np.ndarray, load: float, H: float, n_def: int, p0):
    """The first pressure field: ``p0`` made admissible (0 on undefined pixels, in
    [0, H]), else uniform over the defined pixels; scaled to the load afterwards."""
    undefined = np.isnan(h)
    if p0 is not None:
        p = np.nan_to_num(p0, nan=0.0, posinf=0.0, neginf=0.0)
        np.clip(p, 0.0, H, out=p)
        p[undefined] = 0.0
        if p.sum() > 0.0:
            return p
    p = np.full(z.shape, load / n_def)
    p[undefined] = 0.0
    return p


def scale_factor(p: np.ndarray, load: float, H: float):
    """(s, fixed): the factor s with sum min(s p, H) = load over the pixels below H, those
    at H kept there (``fixed``); when they alone carry the load or more, every pixel is
    scaled (``fixed`` False).  s None: the contact set cannot carry the load even at H
    everywhere."""
    from . import _pk_kernels as K
    below, n_at = K.load_sums(p, H)
    fixed = n_at > 0 and H * n_at < load
    if not fixed and n_at:
        below += H * n_at
    if below <= 0.0:                           # every pixel at H: carried to rounding?
        return (1.0, True) if n_at and abs(load - H * n_at) <= 1e-12 * load else \
            (None, fixed)
    s = (load - (H * n_at if fixed else 0.0)) / below
    if math.isinf(H):
        return s, False
    for _ in range(100):                       # Newton from the left: monotone, finite
        f, df = K.capped_sums(p, s, H, fixed)
        if abs(load - f) <= 1e-15 * load:
            break
        if df <= 0.0:
            return None, fixed
        s += (load - f) / df
    return s, fixed


def fill(p, u, h, load: float, H: float) -> None:
    """Every contact pixel at H and the rest of the load on the most penetrating pixels
    out of contact (the bearing-area step of a plastic solve whose set is too small)."""
    on = p > 0.0
    p[on] = H
    rest = load - H * np.count_nonzero(on)
    g = np.where((~on) & ~np.isnan(h), u - h, np.inf)
    k = min(math.ceil(rest / H), g.size)
    if k <= 0:                                 # the contact pixels at H carry it
        return
    idx = np.argpartition(g, k - 1)[:k] if k < g.size else np.arange(g.size)
    idx = idx[np.argsort(g[idx])]
    p[idx] = H
    p[idx[-1]] = rest - H * (k - 1)


def trim(p, u, h, load: float, H: float, regroup: bool) -> bool:
    """When the pixels at H alone carry the load or more (the load control would scale
    every pixel off the cap, and the iteration cycle between the two sets): the least
    penetrating of them (the largest u - h) out of contact until they carry less.
    ``regroup`` (after a gap step: the free set is a pixel or two): every contact pixel
    in the order of u - h, at H as long as they leave load for the next one, that one
    with the rest, the others out of contact (a free pixel cut off from the plastic zone
    goes first).  Returns whether it changed p."""
    k = at_most(load, H)
    if int(np.count_nonzero(p >= H)) <= k:
        return False
    idx = np.flatnonzero(p > 0.0 if regroup else p >= H)
    idx = idx[np.argsort(u[idx] - h[idx], kind="stable")]
    p[idx[:k]] = H
    if regroup:
        p[idx[k]] = load - H * k
        k += 1
    p[idx[k:]] = 0.0
    return True


def at_most(load: float, H: float) -> int:
    """The most pixels at H that leave some of ``load`` (1e-9 of it, beyond rounding) to
    the others."""
    k = max(math.ceil(load / H) - 1, 0)
    while k > 0 and load - H * k <= 1e-9 * load:
        k -= 1
    return k
