"""Report section: the measured surfaces of ``../shared/data/surfaces`` (when that folder is
present): principal direction, axis coefficients, anisotropy and fitted laws."""
from __future__ import annotations

from pathlib import Path

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


def section(folder: Path) -> list[str]:
    import time

    from ..friction.derive import derive
    from ..friction.faces import compute_reservoir
    from ..friction.plot import plot_derivation
    from ..surface.facets import load_surface
    root = shared_surfaces()
    out = ["## Measured surfaces", ""]
    if not root.is_dir():
        return out + [f"(skipped: {root} is absent)", ""]
    out += ["`asperity derive FILE` with mu = 0.1, plane removed, uniform preload, 360 "
            "directions. t_a: principal direction (the axis of the cos 2psi term of T, "
            "across the lay), degrees from +x; "
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
