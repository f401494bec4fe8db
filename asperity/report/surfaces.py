"""Report section: wedge meshes and sampled height maps against the closed form (the
surface path checked on textures whose answer is known)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .springs import TEXTURES


def section(folder: Path) -> list[str]:
    from ..friction.faces import compute_reservoir
    from ..friction.reservoir import directions
    from ..surface.facets import heightmap_facets, mesh_facets
    from ..surface.wedge_surfaces import wedge_heightmap, wedge_mesh
    from ..texture.wedges import WedgeTexture
    psi = directions(72)
    out = ["## Surfaces: facet homogenisation against the closed form", "",
           "A mesh of three periods of the wedge texture (extruded profile, per-triangle "
           "friction) against the closed form, largest relative difference of p over 72 "
           "directions:", "", "| texture | contact | max rel. difference |", "|---|---|---|"]
    for a, b, ma, mb in TEXTURES:
        t = WedgeTexture(a, b, ma, mb)
        mesh, mu = wedge_mesh(t, periods=3)
        for contact in ("all-faces", "windward"):
            ref = compute_reservoir(t, psi, contact)
            got = compute_reservoir(mesh_facets(mesh, friction_map=mu), psi, contact)
            ok = ~ref.locked
            dev = np.hypot(*(got.p[ok] - ref.p[ok]).T) / np.hypot(*ref.p[ok].T) if ok.any() \
                else np.zeros(1)
            out.append(f"| {a}/{b} deg, mu {ma}/{mb} | {contact} | {dev.max():.1e} |")
    out += ["", "Height maps sampling alpha = 30, beta = 10 deg (mu 0.1 on both faces) with n "
            "pixels per period, RMS over directions of |p_map - p| / |p|, mean over 8 grid "
            "offsets, and the observed order log2(e(n)/e(2n)):", "",
            "| n | all-faces | order | windward | order |", "|---|---|---|---|---|"]
    t = WedgeTexture(30, 10, 0.1, 0.1)
    ns = [16, 32, 64, 128, 256, 512]
    errs = {}
    for contact in ("all-faces", "windward"):
        ref = compute_reservoir(t, psi, contact).p
        e = []
        for n in ns:
            acc = []
            for off in (np.arange(8) + 0.5) / 8:
                hm, mu = wedge_heightmap(t, n, periods=1, ny=2, offset=off)
                got = compute_reservoir(heightmap_facets(hm, friction_map=mu), psi, contact).p
                acc.append(np.sqrt(np.mean(np.sum((got - ref) ** 2, 1) / np.sum(ref ** 2, 1))))
            e.append(float(np.mean(acc)))
        errs[contact] = e
    for k, n in enumerate(ns):
        row = [f"{n}"]
        for contact in ("all-faces", "windward"):
            e = errs[contact]
            row += [f"{e[k]:.3e}", f"{math.log2(e[k - 1] / e[k]):.2f}" if k else ""]
        out.append("| " + " | ".join(row) + " |")
    return out + ["", "First order: the cells that straddle a ridge or a valley (a share O(h)) "
                  "carry a blended gradient.", ""]
