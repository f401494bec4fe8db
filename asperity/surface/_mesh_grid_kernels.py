"""Numba kernels of a mesh's upper envelope on a grid (wrapper: :mod:`asperity.surface.mesh_grid`).

For each triangle, the grid nodes inside its projection (barycentric coordinates all at
least ``-eps``, so nodes on an edge or a vertex belong to every triangle that shares it)
take the height of the triangle's plane there when it is higher than what they hold: the
highest point of the mesh above each node, what a ray cast from above meets first.  The
same walk (``mode`` 1 and 2 of :func:`_walk`) finds, for each node, the triangles on top
there (within ``ztol`` of the envelope: every triangle that shares the edge or vertex a
node lies on) and shares the node's force equally between them.
"""
from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def _walk(v, f, x0, y0, h, z, eps, mode, ztol, count, p, out):
    """mode 0: z = the envelope (z starts -inf); 1: count[i, j] += 1 for each triangle on
    top at the node; 2: out[t] += p[i, j] / count[i, j] for each such triangle t."""
    nx, ny = z.shape
    for t in range(f.shape[0]):
        a, b, c = f[t, 0], f[t, 1], f[t, 2]
        xa, ya, za = v[a, 0], v[a, 1], v[a, 2]
        xb, yb, zb = v[b, 0], v[b, 1], v[b, 2]
        xc, yc, zc = v[c, 0], v[c, 1], v[c, 2]
        det = (yb - yc) * (xa - xc) + (xc - xb) * (ya - yc)
        span = max(abs(xa - xc), abs(xb - xc), abs(ya - yc), abs(yb - yc))
        if abs(det) <= 1e-12 * span * span:
            continue
        i0 = max(0, int(math.ceil((min(xa, xb, xc) - x0) / h - 1e-9)))
        i1 = min(nx - 1, int(math.floor((max(xa, xb, xc) - x0) / h + 1e-9)))
        j0 = max(0, int(math.ceil((min(ya, yb, yc) - y0) / h - 1e-9)))
        j1 = min(ny - 1, int(math.floor((max(ya, yb, yc) - y0) / h + 1e-9)))
        for i in range(i0, i1 + 1):
            x = x0 + i * h
            for j in range(j0, j1 + 1):
                y = y0 + j * h
                l1 = ((yb - yc) * (x - xc) + (xc - xb) * (y - yc)) / det
                l2 = ((yc - ya) * (x - xc) + (xa - xc) * (y - yc)) / det
                l3 = 1.0 - l1 - l2
                if l1 >= -eps and l2 >= -eps and l3 >= -eps:
                    zz = l1 * za + l2 * zb + l3 * zc
                    if mode == 0:
                        if zz > z[i, j]:
                            z[i, j] = zz
                    elif zz >= z[i, j] - ztol:
                        if mode == 1:
                            count[i, j] += 1
                        else:
                            out[t] += p[i, j] / count[i, j]
