"""Report sections 5 and 6: wedge meshes and sampled height maps against the closed form,
and the measured surfaces of ``../shared/data/surfaces`` (when that folder is present).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .springs import TEXTURES

#: measured surfaces of the report: file, load_surface options, what to expect
MEASURED = [
    ("SkiInfiniteFocus.x3p", {}, "anisotropic, t_a across the grinding grooves"),
    ("matrix-4.txt.gz", {}, "parallel grooves along y: t_a near 0 deg (x)"),
    ("matrix-3.txt", {}, "isotropic AFM roughness (control)"),
    ("mi-1.mi", {"height_scale": 20.0}, "terraced steps: asymmetric along x (heights x 20)"),
    ("example_surface.stl.gz", {"unit": "mm"}, "rock fracture, open mesh (unit mm assumed)"),
]


def shared_surfaces() -> Path:
    """../shared/data/surfaces next to the project checkout."""
    return Path(__file__).resolve().parents[3] / "shared" / "data" / "surfaces"


def _surface_validation_section() -> list[str]:
    from ..friction.faces import compute_reservoir
    from ..friction.reservoir import directions
    from ..surface.facets import heightmap_facets, mesh_facets
    from ..surface.wedge_surfaces import wedge_heightmap, wedge_mesh
    from ..texture.wedges import WedgeTexture
    psi = directions(72)
    out = ["## 5. Surfaces: facet homogenisation against the closed form", "",
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


def _measured_section(folder: Path) -> list[str]:
    import time

    from ..friction.derive import derive
    from ..friction.faces import compute_reservoir
    from ..friction.plot import plot_derivation
    from ..surface.facets import load_surface
    root = shared_surfaces()
    out = ["## 6. Measured surfaces", ""]
    if not root.is_dir():
        return out + [f"(skipped: {root} is absent)", ""]
    out += ["`asperity derive FILE` with mu = 0.1, plane removed, uniform preload, 360 "
            "directions. t_a: principal direction (largest friction), degrees from +x; "
            "anisotropy (max T - min T) / mean T; asymmetry (mu_a+ - mu_a-) / mean.", "",
            "| file | expected | facets | undefined px | contact | t_a (deg) | mu_a+ | mu_a- | "
            "mu_b+ | mu_b- | anisotropy | asymmetry | time (s) |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    figs = []
    fits = ["Friction laws fitted to the measured surfaces (360 directions; off-grid: the law "
            "against the surface at the 360 directions midway):", "",
            "| file | contact | law | max radial | rms radial | max angle (deg) | "
            "off-grid magnitude | off-grid angle (deg) | min p.s |", "|---|---|---|---|---|---|---|---|---|"]
    for name, opts, expect in MEASURED:
        surf = load_surface(root / name, **opts)
        for contact in ("all-faces", "windward"):
            t0 = time.perf_counter()
            d = derive(surf, contact, n_directions=360)
            dt = time.perf_counter() - t0
            fits += _fit_rows(d, name)
            a = d.axes
            asym = (a["mu_a_plus"] - a["mu_a_minus"]) / (0.5 * (a["mu_a_plus"] + a["mu_a_minus"]))
            out.append(f"| {name} | {expect} | {surf.n_facets} | {surf.n_undefined} | {contact} | "
                       f"{d.principal_direction_deg:.1f} | {a['mu_a_plus']:.4f} | "
                       f"{a['mu_a_minus']:.4f} | {a['mu_b_plus']:.4f} | {a['mu_b_minus']:.4f} | "
                       f"{d.anisotropy:.3f} | {asym:+.3f} | {dt:.2f} |")
            if contact == "all-faces":
                fig = "measured_" + name.split(".")[0].lower() + ".png"
                plot_derivation(d, folder / fig,
                                other=compute_reservoir(surf, d.reservoir.psi, "windward"))
                figs += [f"![{name}]({fig})", ""]
    return out + [""] + fits + [""] + figs


def _fit_rows(d, name: str) -> list[str]:
    from ..errors import InputError
    from ..laws.fitting import fit_derivation
    rows = []
    for kind in ("truncated-ellipse", "star"):
        try:
            r = fit_derivation(d, kind).fit
        except InputError as exc:
            rows.append(f"| {name} | {d.contact} | {kind} | not fitted: {exc} | | | | | |")
            continue
        hold = (f"{r.holdout_max_magnitude_error:.2e} | {r.holdout_max_angle_deg:.3f}"
                if r.holdout_max_magnitude_error is not None else " | ")
        rows.append(f"| {name} | {d.contact} | {kind} | {r.max_radial_error:.2e} | "
                    f"{r.rms_radial_error:.2e} | {r.max_angle_error_deg:.3f} | {hold} | "
                    f"{r.min_dissipation:.4f} |")
    return rows
