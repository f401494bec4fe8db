"""``asperity report``: regenerate reports/ (Markdown + PNG), the validation record.

Sections: SPEC.md check values, closed form against the spring simulation for a table
of textures (both contact regimes), polar diagrams of both regimes, a loading curve,
surfaces: wedge meshes and sampled height maps against the closed form, and the measured
surfaces of ``../shared/data/surfaces`` (when that folder is present).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .io import write_text_atomic

TEXTURES = [(30, 10, 0.1, 0.2), (5, 5, 0.1, 0.1), (30, 30, 0.3, 0.3), (60, 15, 0.3, 0.1)]
PSI_DEG = [0, 30, 60, 89, 90, 120, 180, 240, 300]


def _spec_section() -> list[str]:
    from .closed_form import compute_axis_coefficients, compute_reservoir
    from .texture import WedgeTexture
    rows = []
    a = compute_axis_coefficients(WedgeTexture(30, 10, 0.1, 0.2))
    rows += [("alpha=30, beta=10, mu=0.1/0.2: mu_a+", 0.185697, a["mu_a_plus"]),
             ("same: mu_a-", 0.193238, a["mu_a_minus"]),
             ("same: mu_b+- ", 0.182587, a["mu_b_plus"])]
    b = compute_axis_coefficients(WedgeTexture(5, 5, 0.1, 0.1))
    rows.append(("alpha=beta=5, mu=0.1: mu_a+ = mu_a-", 0.100773, b["mu_a_plus"]))
    r = compute_reservoir(WedgeTexture(30, 30, 0.3, 0.3), np.radians([0.0, 89.0]), "windward")
    rows += [("windward 30/30, mu=0.3: |p(0)|", 1.061, float(np.hypot(*r.p[0]))),
             ("same: p_a(89 deg)", 0.585, float(r.p[1, 0])),
             ("same: p_b(89 deg)", 0.348, float(r.p[1, 1]))]
    out = ["## 1. SPEC.md check values (closed form)", "",
           "| quantity | SPEC.md | asperity | difference |", "|---|---|---|---|"]
    out += [f"| {q} | {s:g} | {v:.6f} | {v - s:+.1e} |" for q, s, v in rows]
    return out + [""]


def _springs_section() -> list[str]:
    from .closed_form import compute_reservoir
    from .springs import SpringModel, simulate_reservoir
    from .texture import WedgeTexture
    psi = np.radians(PSI_DEG)
    models = {"k_f = inf": SpringModel(n_springs=64, steps_per_period=32000),
              "k_f/k_n = 1e5": SpringModel(k_f=1e8, n_springs=64, steps_per_period=32000)}
    out = ["## 2. Closed form against the spring-on-wedge simulation", "",
           "Largest relative deviation |p_springs - p_closed| / |p_closed| over psi = "
           + ", ".join(map(str, PSI_DEG)) + " deg (64 springs per pitch, 32000 samples per "
           "pitch; at psi = 90 deg, along the ridges, the body does not travel across the texture and 32000 springs per pitch sample it instead).", "",
           "| alpha, beta (deg) | mu_alpha, mu_beta | contact | springs | max rel. deviation |",
           "|---|---|---|---|---|"]
    for a, b, ma, mb in TEXTURES:
        t = WedgeTexture(a, b, ma, mb)
        for contact in ("all-faces", "windward"):
            cf = compute_reservoir(t, psi, contact)
            for name, m in models.items():
                sim = simulate_reservoir(t, psi, m, contact)
                ok = ~(cf.locked | cf.set_valued | sim.locked)
                dev = np.hypot(*(sim.p[ok] - cf.p[ok]).T) / np.hypot(*cf.p[ok].T)
                out.append(f"| {a}, {b} | {ma}, {mb} | {contact} | {name} | {dev.max():.2e} |")
    return out + [""]


def _figures(folder: Path) -> list[str]:
    from .closed_form import compute_reservoir
    from .derive import derive
    from .plotting import plot_derivation
    from .texture import WedgeTexture
    out = ["## 3. Polar reservoirs of both contact regimes", ""]
    for contact in ("all-faces", "windward"):
        t = WedgeTexture(30, 30, 0.3, 0.3)
        d = derive(t, contact, "closed-form", 360)
        other = "windward" if contact == "all-faces" else "all-faces"
        name = f"polar_{contact}.png"
        plot_derivation(d, folder / name, other=compute_reservoir(t, d.reservoir.psi, other))
        s = d.associativity
        out += [f"![{contact}]({name})", "",
                f"{contact}: admissible = {d.admissibility.admissible}, max |L - dT/dpsi| = "
                f"{s.max_deviation:.4f}, max |L| = {s.max_lateral:.4f}.", ""]
    return out


def _loading_section(folder: Path) -> list[str]:
    from .io import save_figure_atomic
    from .plotting import _plt
    from .springs import SpringModel, simulate_loading_curve
    from .texture import WedgeTexture
    t = WedgeTexture(5, 5, 0.1, 0.1, height=1e-6)
    m = SpringModel(k_n=1e3, k_f=1e7, preload=2e-3)
    c = simulate_loading_curve(t, 0.0, m)
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(c.displacement * 1e6, c.tangential_stress / c.normal_stress[-1], label="springs")
    x = c.displacement[c.displacement < 1.5 * c.mu_steady * c.normal_stress[-1] / c.k_t]
    ax.plot(x * 1e6, c.k_t * x / c.normal_stress[-1], "--", label="k_t u (stick)")
    ax.axhline(c.mu_steady, color="0.5", lw=0.8)
    ax.set_xlabel("displacement along t_a (um)")
    ax.set_ylabel("tangential / normal stress")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure_atomic(fig, folder / "loading_curve.png", dpi=110)
    plt.close(fig)
    return ["## 4. From stick to full sliding (finite k_f)", "",
            "![loading curve](loading_curve.png)", "",
            f"alpha = beta = 5 deg, mu = 0.1, k_f/k_n = 1e4: k_t = {c.k_t:.4e} Pa/m, "
            f"measured initial slope {c.k_t_measured:.4e} Pa/m, steady mu {c.mu_steady:.6f} "
            "(closed form 0.100773).", ""]


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
    return Path(__file__).resolve().parents[2] / "shared" / "data" / "surfaces"


def _surface_validation_section() -> list[str]:
    from .closed_form import compute_reservoir, directions
    from .surface import heightmap_facets, mesh_facets, wedge_heightmap, wedge_mesh
    from .texture import WedgeTexture
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

    from .closed_form import compute_reservoir
    from .derive import derive
    from .plotting import plot_derivation
    from .surface import load_surface
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
    from .errors import InputError
    from .gauges import fit_derivation
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


def _numbered(k: int, section: list[str]) -> list[str]:
    """A section's lines with its first level-2 heading numbered k."""
    out = list(section)
    for i, line in enumerate(out):
        if line.startswith("## "):
            out[i] = f"## {k}. " + line[3:]
            break
    return out


def run(folder: str | Path = "reports") -> Path:
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    lines = ["# asperity validation report", "",
             "Generated by `asperity report`; do not edit by hand.", ""]
    lines += _spec_section() + _springs_section() + _figures(folder) + _loading_section(folder)
    lines += _surface_validation_section() + _measured_section(folder)
    from .report_gauges import section as gauge_section
    from .report_microslip import section as microslip_section
    from .report_moreau import section as moreau_section
    lines += _numbered(7, gauge_section(folder)) + _numbered(8, moreau_section(folder))
    lines += _numbered(9, microslip_section(folder))
    path = folder / "REPORT.md"
    write_text_atomic(path, "\n".join(lines))
    return path
