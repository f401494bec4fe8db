"""Wedge textures drawn as surfaces: a triangle mesh and a sampled height map of a few
periods, at any angle, for checking the surface path against the wedge closed form.
"""
from __future__ import annotations

import math

import numpy as np


def wedge_mesh(texture, periods: int = 3, width: float | None = None, angle_deg: float = 0.0):
    """A triangle mesh of ``periods`` periods of a wedge texture's profile, extruded along
    t_b over ``width`` (default: one period), turned by ``angle_deg`` about z.

    Returns (TriangleMesh, per-triangle friction).
    """
    from .topography import TriangleMesh
    prof = texture.profile()
    L = prof.period
    x = np.concatenate([prof.x[:-1] + k * L for k in range(periods)] + [[periods * L]])
    z = np.concatenate([prof.z[:-1]] * periods + [[prof.z[-1]]])
    mu_seg = np.tile(prof.mu, periods)
    keep = np.concatenate([np.diff(x) > 0, [True]])      # drop zero-length segments
    x, z = x[keep], z[keep]
    mu_seg = mu_seg[keep[:-1]]
    w = L if width is None else float(width)
    k = x.size
    verts = np.zeros((2 * k, 3))
    verts[:k, 0], verts[:k, 2] = x, z
    verts[k:, 0], verts[k:, 1], verts[k:, 2] = x, w, z
    i = np.arange(k - 1)
    tri = np.concatenate([np.column_stack([i, i + 1, k + i + 1]),
                          np.column_stack([i, k + i + 1, k + i])])
    mu = np.concatenate([mu_seg, mu_seg])
    if angle_deg:
        a = math.radians(angle_deg)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        verts[:, :2] = verts[:, :2] @ rot.T
    return TriangleMesh(vertices=verts, faces=tri.astype(np.int64),
                        source=f"{texture.kind} texture mesh", n_degenerate=0), mu


def wedge_heightmap(texture, n: int, periods: int = 3, ny: int = 4, angle_deg: float = 0.0,
                    offset: float = 0.0):
    """A height map sampling ``periods`` periods of a wedge texture's profile with ``n``
    pixels per period along x (spacing L/n), ``ny`` pixels along y, turned by
    ``angle_deg`` (the texture is sampled in the turned frame).  ``offset`` shifts the
    samples by that fraction of a pixel (so ridges need not fall on grid nodes).
    Returns (HeightMap, (nx, ny) per-pixel friction of the face under each pixel).
    """
    from .topography import HeightMap
    prof = texture.profile()
    L = prof.period
    h = L / n
    nx = n * periods + 1
    if angle_deg == 0.0:
        ny = max(2, ny)
    xs = (np.arange(nx) + offset) * h
    ys = np.arange(ny) * h
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    a = math.radians(angle_deg)
    u = X * math.cos(a) + Y * math.sin(a)          # coordinate along the texture's t_a
    z = prof.height(u)
    seg = np.clip(np.searchsorted(prof.x, np.mod(u, L), side="right") - 1, 0, prof.mu.size - 1)
    return (HeightMap(heights=z, dx=h, dy=h, source=f"{texture.kind} texture, {n} px/period",
                      n_undefined=0), prof.mu[seg])
