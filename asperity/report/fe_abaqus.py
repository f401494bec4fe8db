"""Report section: the friction law inside Abaqus (issue 27).  The FRIC routine generated
from four laws (an asymmetric truncated ellipse and a star law fitted to a wedge texture,
the windward star law of that texture with set-valued directions, Hu et al.'s
componentwise law), compiled with gfortran and called through ctypes as Abaqus calls it:
the table against the law, steady sliding in 360 directions on both sides, the tangents
against central differences; and the force polar that FRIC keeps against the symmetric
ellipse of ``asperity law --abaqus`` (the built-in *FRICTION, ANISOTROPIC), which loses
the asymmetry.  Without gfortran the section says so and shows the tables only."""
from __future__ import annotations

import math
import time
from functools import cache
from pathlib import Path

import numpy as np

K, P = 1e10, 2e6                       # elastic slip stiffness (Pa/m), pressure (Pa)
LAWS = ("ellipse", "star", "windward", "componentwise")
WORDS = {"ellipse": "truncated ellipse, wedge 20/40 deg (all faces)",
         "star": "star law, wedge 20/40 deg (all faces)",
         "windward": "star law, wedge 20/40 deg (windward: flat edges of D)",
         "componentwise": "componentwise, mu_f 0.1, mu_b 0.15, mu_t 0.2"}


@cache
def law(name: str):
    """The four laws of the section (the FE tests use them too)."""
    from ..friction.derive import derive
    from ..laws.fitting import fit_derivation
    from ..texture.wedges import WedgeTexture
    if name == "componentwise":
        from ..laws.componentwise import componentwise_gauge
        return componentwise_gauge(mu_f=0.1, mu_b=0.15, mu_t=0.2)
    contact = "windward" if name == "windward" else "all-faces"
    kind = "truncated-ellipse" if name == "ellipse" else "star"
    return fit_derivation(derive(WedgeTexture(20, 40, 0.15, 0.1), contact, "closed-form", 72),
                          kind)


def rot(th: float) -> np.ndarray:
    """The rotation by th (rad)."""
    return np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])


def steady_tau(gl, phi: float, th: float, side: int, press: float) -> np.ndarray:
    """TAU of steady sliding along local angle phi (SPEC.md section 10): texture on the
    main surface PRESS R(th) p(phi - th), on the secondary -PRESS R(th) p(phi + 180 - th)."""
    psi = phi - th if side > 0 else phi + math.pi - th
    return (1.0 if side > 0 else -1.0) * press * rot(th) @ gl.force(np.array([psi])).p[0]


def steady_error(lib, gl, th_deg: float, side: int, n: int = 360) -> float:
    """Largest |TAU - TAU_law| / PRESS of FRIC holding steady sliding along n directions."""
    from ..fe.fortran_harness import call_fric
    th = math.radians(th_deg)
    worst = 0.0
    for phi in 2 * math.pi * (np.arange(n) + 0.5) / n:
        ref = steady_tau(gl, phi, th, side, P)
        u = np.array([math.cos(phi), math.sin(phi)])
        out = call_fric(lib, lm=0, tau=ref, statev=np.zeros(3), dgam=1e-6 * u, press=P,
                        props=np.array([K, th_deg, float(side)]))
        worst = max(worst, float(np.abs(out.tau - ref).max()) / P)
    return worst


def tangent_error(lib, samples: int = 20) -> float:
    """Largest relative difference of DDTDDG from central differences of FRIC itself."""
    from ..fe.fortran_harness import call_fric
    rng = np.random.default_rng(27)
    worst = 0.0
    for _ in range(samples):
        tau0, dg = 0.05 * P * rng.normal(size=2), 4e-5 * rng.normal(size=2)
        props = np.array([K, rng.uniform(-180, 180), rng.choice([-1.0, 1.0])])

        def tau(d, tau0=tau0, props=props):
            return call_fric(lib, lm=0, tau=tau0, statev=np.zeros(3), dgam=d, press=P,
                             props=props)
        out = tau(dg)
        h = 1e-6 * np.abs(dg).max()
        num = np.column_stack([(tau(dg + e).tau - tau(dg - e).tau) / (2 * h)
                               for e in h * np.eye(2)])
        worst = max(worst, float(np.abs(out.ddtddg - num).max()) / K)
    return worst


def rows(folder: Path) -> tuple[list[str], dict]:
    from ..fe.abaqus_fric import routine_source
    from ..fe.fortran_harness import compile_source, gfortran
    from ..fe.table import law_table
    have = gfortran() is not None
    out, libs = [], {}
    for name in LAWS:
        gl = law(name)
        t0 = time.perf_counter()
        tab = law_table(gl)
        src = routine_source(gl, "fric", header=[WORDS[name]], table=tab)
        gen = time.perf_counter() - t0
        cells = [WORDS[name], str(tab.n), f"{tab.max_error:.2e}", f"{gen:.2f}"]
        if have:
            import ctypes
            import tempfile
            with tempfile.TemporaryDirectory() as tmp:
                libs[name] = ctypes.CDLL(str(compile_source(src, tmp)))
            steady = max(steady_error(libs[name], gl, th, side)
                         for th, side in ((0.0, 1), (30.0, 1), (0.0, -1)))
            cells += [f"{steady:.2e}", f"{tangent_error(libs[name]):.1e}"]
        else:
            cells += ["(no gfortran)", "(no gfortran)"]
        out.append("| " + " | ".join(cells) + " |")
    return out, libs


def polar_figure(folder: Path, lib) -> str:
    """The windward law's force polar: the law, FRIC's steady stress, the symmetric ellipse."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..fe.fortran_harness import call_fric
    from ..laws.export import orthotropic_approximation
    from ..laws.sets import TruncatedEllipse
    from ..laws.walker_leine import associated
    gl = law("windward")
    psi = np.linspace(0, 2 * math.pi, 1441)
    p = gl.force(psi).p
    approx = orthotropic_approximation(gl)
    th = math.radians(gl.principal_direction_deg)
    ell = associated(TruncatedEllipse(approx.mu_1, approx.mu_1, approx.mu_2, approx.mu_2,
                                      theta=th)).force(psi).p
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.5, 4.2))
    ax.plot(p[:, 0], p[:, 1], "k-", lw=1.2, label="law --psi: p(psi)")
    ax.plot(ell[:, 0], ell[:, 1], "C1--", lw=1.2,
            label="law --abaqus: symmetric ellipse (*FRICTION, ANISOTROPIC)")
    deg = np.degrees(psi)
    bx.plot(deg, np.einsum("ij,ij->i", p, np.column_stack([np.cos(psi), np.sin(psi)])), "k-",
            lw=1.2, label="law --psi")
    bx.plot(deg, np.einsum("ij,ij->i", ell, np.column_stack([np.cos(psi), np.sin(psi)])),
            "C1--", lw=1.2, label="symmetric ellipse")
    if lib is not None:
        pts, phis = [], np.radians(np.arange(0, 360, 5.0) + 2.5)
        for phi in phis:
            u = np.array([math.cos(phi), math.sin(phi)])
            ref = P * gl.force(np.array([phi])).p[0]
            tau = call_fric(lib, lm=0, tau=ref, statev=np.zeros(3), dgam=1e-6 * u, press=P,
                            props=np.array([K, 0.0, 1.0])).tau
            pts.append(tau / P)
        pts = np.array(pts)
        ax.plot(pts[:, 0], pts[:, 1], "C0o", ms=4, label="FRIC: steady TAU / PRESS")
        bx.plot(np.degrees(phis), pts[:, 0] * np.cos(phis) + pts[:, 1] * np.sin(phis), "C0o",
                ms=4, label="FRIC")
    ax.axhline(0, color="0.8", lw=0.6)
    ax.axvline(0, color="0.8", lw=0.6)
    ax.set_xlabel("p_x (per unit normal load)")
    ax.set_ylabel("p_y")
    ax.set_title("force for every sliding direction", fontsize=10)
    ax.legend(fontsize=7, loc="upper center")
    bx.set_xlabel("sliding direction psi (deg from t_a)")
    bx.set_ylabel("friction along the slip, p . s")
    bx.set_xticks(range(0, 361, 60))
    bx.set_title("mu_a+ at 0 deg, mu_a- at 180 deg", fontsize=10)
    bx.legend(fontsize=7)
    fig.suptitle("Windward wedge 20/40 deg: what FRIC keeps and the built-in ellipse loses",
                 fontsize=11)
    fig.tight_layout()
    name = "fe_fric_polar.png"
    fig.savefig(Path(folder) / name, dpi=120)
    plt.close(fig)
    return name


def two_node(lib) -> list[str]:
    """SPEC.md section 5's two-node bar with the componentwise law's FRIC (NFDIR = 1) at
    both nodes in the Abaqus-like implicit driver, against the closed form."""
    from functools import partial

    from ..fe.fortran_harness import call_fric
    from ..fe.implicit_driver import two_node_cycles
    from ..microslip.closed_forms import two_node_drift_per_cycle, two_node_dT_c
    a = {"k": 1e6, "l0": 0.1, "alpha_T": 1.2e-5, "k_t": 5e5, "N": 100.0}
    gl = law("componentwise")
    mu_plus, mu_minus = (abs(float(v)) for v in gl.force(np.array([0.0, math.pi])).p[:, 0])
    dTc = two_node_dT_c(a["k"], a["k_t"], a["N"], mu_plus, mu_minus, a["alpha_T"], a["l0"])
    lo, hi = 0.0, 3.0 * dTc
    fric = partial(call_fric, lib, props=np.array([a["k_t"], 0.0, 1.0]), nfdir=1)
    ends, iters = two_node_cycles(fric, **a, dT_min=lo, dT_max=hi)
    drift = float(np.diff(ends)[1:].mean())
    want = two_node_drift_per_cycle(a["k"], a["k_t"], a["N"], mu_plus, mu_minus,
                                    a["alpha_T"], a["l0"], lo, hi)
    scale = a["alpha_T"] * a["l0"] * (hi - lo)
    return ["### The two-node assembly through FRIC", "",
            (f"SPEC.md section 5's bar (k = 1e6 N/m, l0 = 0.1 m, k_t = 5e5 N/m, N = 100 N, "
             f"alpha_T = 1.2e-5 /K) on the componentwise law (mu+ = {mu_plus:g} along +x, "
             f"mu- = {mu_minus:g}), cycled over [0, 3 dT_c] with dT_c = {dTc:.4g} K, each "
             "node's friction the generated FRIC (NFDIR = 1, PROPS(1) = k_t) in an "
             "Abaqus-like implicit driver (every iteration re-passes the start-of-increment "
             f"TAU and STATEV): drift per cycle {drift:.6e} m, closed form {want:.6e} m, "
             f"difference {abs(drift - want) / scale:.1e} of alpha_T l0 dT; at most "
             f"{max(iters)} Newton iterations an increment."), ""]


def section(folder: Path) -> list[str]:
    folder = Path(folder)
    table, libs = rows(folder)
    fig = polar_figure(folder, libs.get("windward"))
    gl = law("windward")
    mp, mm = gl.force(np.array([0.0, math.pi])).tangential
    return ["## The law inside Abaqus: generated FRIC", "",
            ("`asperity law GAUGE.json --fric FILE.f` writes Abaqus/Standard's FRIC with the "
             "law baked in as a table (`--vfric`, `--vfriction` the Explicit routines). Each "
             "law below: its table (nodes, largest force error against `asperity law --psi` "
             "on 36 000 directions, seconds to generate), then the routine compiled with "
             "gfortran and called through ctypes with Abaqus's argument list: the largest "
             "error of TAU / PRESS held in steady sliding along 360 directions (texture on "
             "the main surface at 0 and 30 deg, on the secondary at 0 deg), and the largest "
             "difference of DDTDDG from central differences of the routine (relative to the "
             "elastic stiffness)."), "",
            ("| law | nodes | table error | generate (s) | steady-sliding error | "
             "DDTDDG error |"), "|---|---:|---:|---:|---:|---:|", *table, "",
            f"![force polar]({fig})", "",
            (f"The windward law slides at mu_a+ = {mp:.3f} along +t_a and mu_a- = {mm:.3f} "
             "along -t_a. The symmetric orthotropic ellipse Abaqus's built-in anisotropic "
             "friction accepts (dashed) has the same friction both ways: the asymmetry that "
             "drives cumulative microslip is lost. FRIC (dots) keeps the law's force in "
             "every direction."), ""] + (two_node(libs["componentwise"]) if libs else [])
