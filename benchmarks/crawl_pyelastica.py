"""PyElastica's continuum snake, the peer of ``asperity crawl`` (issue 26, item 6): its example
(``examples/ContinuumSnakeCase/continuum_snake.py``, the snake of Zhang et al., Nat. Comm.
2021) rebuilt here with the same parameters, run, timed, and its body's curvature fitted as a
Fourier gait that ``asperity crawl --gait`` reads, so the same case can be run with prescribed
kinematics.  The package never imports PyElastica (PyPI ``pyelastica``, MIT); this script
installs it with pip in a child process when it is missing (``--no-install`` refuses).

    python benchmarks/crawl_pyelastica.py --json --gait-out /tmp/pyelastica_gait.toml

The case.  A Cosserat rod of 50 elements, L = 0.35 m, radius 0.011 L, density 1000 kg/m^3,
E = 1 MPa, shear modulus E / 1.5, lying on a plane (gravity 9.80665 m/s^2 along -y; the Plane surface and its
RodPlaneContactWithAnisotropicFriction contact of PyElastica 1.0, surface_tol 1e-4 m), driven by
a muscle torque wave sin(2 pi t / T - 2 pi s / lambda) (T = 2 s, lambda = L) shaped by a beta
spline of the example's six coefficients, ramped up over the first period.  Friction of the
plane: kinetic coefficients forward (towards the rod's last node, the head), backward and
lateral mu : 1.5 mu : 2 mu with mu = L / (g T^2 Fr), Froude number Fr = 0.1; no static
friction; each component is the coefficient times the component of the unit slip direction
(the componentwise rule of Hu et al.), switched on between |u| = tol and 2 tol
(slip_velocity_tol = 1e-8 m/s: the regularisation); normal contact a spring k = 1 N/m with
damping nu = 1e-6 N s/m; linear damping 2e-3 /s of velocities; time step 1e-4 s, position
Verlet.  The snake crawls towards its last node (+z at the start).

The speed.  The plane is (X, Y) = (z, x) of PyElastica (right-handed about the up axis +y).
Per period: the centre-of-mass displacement over [i T, (i + 1) T] projected on the body's mean
heading over that period (mean tangent angle, head-ward), in body lengths: the definition of
``speed_body_lengths_per_period`` of ``asperity crawl``.  The reported speed averages the
periods after ``--transient`` (default 3: the torque ramps over the first, the speed settles
by the third).  PyElastica's own figure (mean velocity along the mean displacement, after two
periods, in m/s) is given beside it.

The gait.  The tangent angle of each element from the node positions, its difference between
neighbours over the mean of their lengths is kappa at the interior nodes (s from tail, rest
arc length); the last ``--fit-periods`` periods are fitted by least squares with
kappa L = sum cos * cos 2 pi (m s / L + n t / T) + sin * sin 2 pi (m s / L + n t / T), for
integer m = 0..``--modes`` and n = -``--harmonics``..``--harmonics`` (n >= 0 for m = 0), t from
the start of the run (the fitted window starts a whole number of periods in, so the phase is
PyElastica's).  The fit's relative RMS error is reported.  The body's curvature is 99.9 % the
first harmonic (kappa L ~ 7.0 cos 2 pi (s / L + t / T - 0.26), close to the stereotypical
snake the example was tuned to), but the odd harmonics 3..11 carry 0.6 % ... 0.06 % of its
amplitude, which the quasi-static speed weighs by n: the defaults (8, 13) are where the
reference speed stops changing (a single term (1, 1) gives +4 %, (3, 3) +1.6 %, (8, 7) -0.2 %).
The independent quasi-static reference of the tests (tests/crawl_reference.py, componentwise
rule, the same coefficient ratios) is run on the fitted gait: it has no inertia, no
elasticity and uniform weight, PyElastica has all three.
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import importlib.metadata
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

PYELASTICA = "pyelastica==1.0.0"
HERE = Path(__file__).resolve().parent
PARAMETERS = {
    "source": "PyElastica examples/ContinuumSnakeCase/continuum_snake.py (Zhang et al. 2021)",
    "n_elem": 50, "length_m": 0.35, "radius_m": 0.35 * 0.011, "density_kg_m3": 1000.0,
    "youngs_modulus_pa": 1e6, "poisson_ratio": 0.5, "period_s": 2.0,
    "gravity_m_s2": 9.80665, "froude": 0.1, "mu_ratios_forward_backward_lateral": [1.0, 1.5, 2.0],
    "static_mu": [0.0, 0.0, 0.0], "slip_velocity_tol_m_s": 1e-8,
    "contact_stiffness_n_m": 1.0, "contact_damping_n_s_m": 1e-6,
    "damping_constant_1_s": 2e-3, "time_step_s": 1e-4,
    "muscle_b_coeff": [3.4e-3, 3.3e-3, 4.2e-3, 2.6e-3, 3.6e-3, 3.5e-3],
    "muscle_wavelength_body_lengths": 1.0, "muscle_ramp_up_time_s": 2.0,
    "muscle_torque": "sin(2 pi t / T - 2 pi s / lambda), s from the head, beta spline",
    "friction_rule": "componentwise",
}
PARAMETERS["mu_forward"] = PARAMETERS["length_m"] / (
    PARAMETERS["period_s"] ** 2 * PARAMETERS["gravity_m_s2"] * PARAMETERS["froude"])


def ensure_pyelastica(install: bool = True):
    """Import elastica, installing PYELASTICA with pip in a child process if allowed."""
    try:
        return importlib.import_module("elastica")
    except ImportError:
        if not install:
            raise SystemExit("pyelastica is not installed (run without --no-install)") from None
    print(f"installing {PYELASTICA}", file=sys.stderr, flush=True)
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", PYELASTICA], check=True)
    importlib.invalidate_caches()
    return importlib.import_module("elastica")


def build_snake(ea, p: dict, samples: dict, every: int):
    """The example's simulator, recording node positions every ``every`` steps."""
    class Snake(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping,
                ea.CallBacks, ea.Contact):
        pass

    class Record(ea.CallBackBaseClass):
        def make_callback(self, system, time, current_step):
            if current_step % every == 0:
                samples["t"].append(time)
                samples["x"].append(system.position_collection[[2, 0]].copy())

    sim = Snake()
    normal = np.array([0.0, 1.0, 0.0])
    L, g, T = p["length_m"], p["gravity_m_s2"], p["period_s"]
    rod = ea.CosseratRod.straight_rod(
        p["n_elem"], np.zeros(3), np.array([0.0, 0.0, 1.0]), normal, L, p["radius_m"],
        p["density_kg_m3"], youngs_modulus=p["youngs_modulus_pa"],
        shear_modulus=p["youngs_modulus_pa"] / (p["poisson_ratio"] + 1.0))
    sim.append(rod)
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, -g, 0.0]))
    sim.add_forcing_to(rod).using(
        ea.MuscleTorques, base_length=L, b_coeff=np.array(p["muscle_b_coeff"]), period=T,
        wave_number=2.0 * np.pi / p["muscle_wavelength_body_lengths"], phase_shift=0.0,
        rest_lengths=rod.rest_lengths, ramp_up_time=p["muscle_ramp_up_time_s"],
        direction=normal, with_spline=True)
    mu = p["mu_forward"] * np.array(p["mu_ratios_forward_backward_lateral"])
    ground = ea.Plane(plane_origin=np.array([0.0, -p["radius_m"], 0.0]), plane_normal=normal)
    sim.append(ground)
    sim.detect_contact_between(rod, ground).using(
        ea.RodPlaneContactWithAnisotropicFriction, k=p["contact_stiffness_n_m"],
        nu=p["contact_damping_n_s_m"], slip_velocity_tol=p["slip_velocity_tol_m_s"],
        static_mu_array=np.array(p["static_mu"]), kinetic_mu_array=mu)
    sim.dampen(rod).using(ea.AnalyticalLinearDamper, damping_constant=p["damping_constant_1_s"],
                          time_step=p["time_step_s"])
    sim.collect_diagnostics(rod).using(Record)
    sim.finalize()
    return sim, rod


def run_pyelastica(periods: float = 11.0, samples_per_period: int = 100, install: bool = True,
                   transient: int = 3) -> dict:
    """Run the example for ``periods`` periods; node positions (in the plane) sampled
    ``samples_per_period`` times a period.  Returns times, positions (S, 2, n + 1), the centre
    path (S, 2), speeds per period (body lengths, on the mean heading), their mean after
    ``transient`` periods, and the wall time of the integration alone."""
    ea = ensure_pyelastica(install)
    p = PARAMETERS
    dt, T = p["time_step_s"], p["period_s"]
    steps_per_period = round(T / dt)
    every = steps_per_period // samples_per_period
    samples = {"t": [], "x": []}
    sim, rod = build_snake(ea, p, samples, every)
    total = round(periods * steps_per_period)
    start = time.perf_counter()
    with contextlib.redirect_stdout(sys.stderr):          # it prints the final time
        ea.integrate(ea.PositionVerlet(), sim, total * dt, total, progress_bar=False)
    wall = time.perf_counter() - start
    t = np.array(samples["t"])
    pos = np.array(samples["x"])                          # (S, 2, n + 1): X = z, Y = x
    mass = rod.mass / rod.mass.sum()
    com = np.einsum("sij,j->si", pos, mass)
    per = speeds_per_period(t, pos, com, T, p["length_m"])
    steady = per[transient:]
    return {"t": t, "positions": pos, "com": com, "speed_per_period": per,
            "speed_body_lengths_per_period": float(np.mean(steady)) if steady else math.nan,
            "speed_spread": float(np.ptp(steady)) if steady else math.nan,
            "transient_periods": transient, "wall_time_s": wall, "periods": periods,
            "rest_lengths": rod.rest_lengths.copy(),
            "own_speed_m_s": own_speed(t, com, T),
            "elastica_version": importlib.metadata.version("pyelastica")}


def own_speed(t, com, T) -> float:
    """PyElastica's example's figure: the mean centre velocity after two periods along the
    mean displacement of a period (m/s), from the sampled centre path."""
    whole = math.floor(t[-1] / T + 1e-9)
    if whole < 4:
        return math.nan
    ends = [np.argmin(np.abs(t - i * T)) for i in range(1, whole)]
    direction = np.mean(np.diff(com[ends], axis=0), axis=0)
    direction /= np.linalg.norm(direction)
    i0 = np.argmin(np.abs(t - 2 * T))
    return float((com[-1] - com[i0]) @ direction / (t[-1] - t[i0]))


def tangent_angles(pos: np.ndarray) -> np.ndarray:
    """(S, n) unwrapped tangent angle of each element, tail to head."""
    d = np.diff(pos, axis=2)
    return np.unwrap(np.arctan2(d[:, 1], d[:, 0]), axis=1)


def speeds_per_period(t, pos, com, T, L) -> list:
    """Centre displacement over each whole period on the mean tangent angle, in L."""
    phi = np.mean(tangent_angles(pos), axis=1)
    phi = np.unwrap(phi)
    out = []
    for i in range(round(t[-1] / T + 1e-9)):
        sel = (t >= i * T - 1e-9) & (t <= (i + 1) * T + 1e-9)
        idx = np.flatnonzero(sel)
        if len(idx) < 3 or t[idx[-1]] < (i + 1) * T - 1e-9:
            break
        heading = np.mean(phi[idx[:-1]])
        d = com[idx[-1]] - com[idx[0]]
        out.append(float(d @ [math.cos(heading), math.sin(heading)]) / L)
    return out


def curvature_samples(run: dict):
    """kappa L at the interior nodes, their s / L (rest arc length from the tail), per sample."""
    pos = run["positions"]
    phi = tangent_angles(pos)
    seg = np.linalg.norm(np.diff(pos, axis=2), axis=1)   # (S, n) element lengths
    voronoi = 0.5 * (seg[:, 1:] + seg[:, :-1])
    L = PARAMETERS["length_m"]
    kappa_L = np.diff(phi, axis=1) / voronoi * L
    s = np.cumsum(run["rest_lengths"])[:-1] / L          # interior nodes
    return s, kappa_L


def fourier_basis(sigma, tau, modes: int, harmonics: int):
    """Columns (cos, sin) of 2 pi (m sigma + n tau), m = 0..modes, n = -harmonics..harmonics
    (n >= 0 for m = 0: the other half repeats), and their (m, n, kind) labels."""
    cols, labels = [], []
    for m in range(modes + 1):
        for n in range(-harmonics, harmonics + 1):
            if m == 0 and n < 0:
                continue
            arg = 2 * np.pi * (m * sigma + n * tau)
            cols.append(np.cos(arg))
            labels.append((m, n, "cos"))
            if not (m == 0 and n == 0):
                cols.append(np.sin(arg))
                labels.append((m, n, "sin"))
    return np.stack(cols, -1), labels


def fit_gait(run: dict, fit_periods: int, modes: int, harmonics: int) -> dict:
    """Least-squares Fourier fit of kappa L over the last ``fit_periods`` whole periods."""
    T = PARAMETERS["period_s"]
    s, kL = curvature_samples(run)
    t = run["t"]
    last = math.floor(t[-1] / T + 1e-9)
    sel = (t >= (last - fit_periods) * T - 1e-9) & (t < last * T - 1e-9)
    tau = (t[sel] / T)[:, None] * np.ones_like(s)[None, :]
    sigma = np.ones_like(tau) * s[None, :]
    A, labels = fourier_basis(sigma.ravel(), tau.ravel(), modes, harmonics)
    y = kL[sel].ravel()
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    err = float(np.sqrt(np.mean((A @ coef - y) ** 2)) / np.sqrt(np.mean(y ** 2)))
    terms = {}
    for c, (m, n, kind) in zip(coef, labels):
        terms.setdefault((m, n), {"m": m, "n": n, "cos": 0.0, "sin": 0.0})[kind] = float(c)
    return {"terms": list(terms.values()), "relative_rms_error": err,
            "window_periods": [last - fit_periods, last], "modes": modes,
            "harmonics": harmonics,
            "kappa_L_rms": float(np.sqrt(np.mean(y ** 2)))}


def gait_toml(fit: dict) -> str:
    p = PARAMETERS
    window = fit["window_periods"]
    lines = [f"# PyElastica continuum snake: its curvature fitted over periods {window[0]}..{window[1]}",
             f"# relative RMS error of the fit {fit['relative_rms_error']:.4f}",
             "# kappa L = sum cos*cos 2pi(m s/L + n t/T) + sin*sin(...), s from tail",
             "[gait]", 'kind = "fourier"', f"length = {p['length_m']!r}",
             f"period = {p['period_s']!r}", ""]
    for term in fit["terms"]:
        lines += ["[[gait.terms]]", f"m = {term['m']!r}", f"n = {term['n']!r}",
                  f"cos = {term['cos']!r}", f"sin = {term['sin']!r}", ""]
    return "\n".join(lines)


def write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def reference_on_fit(fit: dict, points: int, steps: int) -> dict:
    """The tests' quasi-static reference on the fitted gait (componentwise, same ratios)."""
    sys.path.insert(0, str(HERE.parent / "tests"))
    from crawl_reference import reference_speed
    terms = [[t["m"], t["n"], t["cos"], t["sin"]] for t in fit["terms"]]
    start = time.perf_counter()
    r = reference_speed(0.0, 0.0, *PARAMETERS["mu_ratios_forward_backward_lateral"],
                        "componentwise", points=points, steps=steps, terms=terms)
    r["wall_time_s"] = time.perf_counter() - start
    return r


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--periods", type=float, default=11.0, help="periods to run (default 11)")
    ap.add_argument("--transient", type=int, default=3, help="periods left out of the mean")
    ap.add_argument("--fit-periods", type=int, default=2, help="last periods fitted")
    ap.add_argument("--modes", type=int, default=8, help="largest m of the fit (default 8)")
    ap.add_argument("--harmonics", type=int, default=13, help="largest |n| of the fit (default 13)")
    ap.add_argument("--gait-out", type=Path, help="write the fitted gait (TOML) here")
    ap.add_argument("--reference-points", type=int, default=401)
    ap.add_argument("--reference-steps", type=int, default=200)
    ap.add_argument("--no-reference", action="store_true", help="skip the quasi-static reference")
    ap.add_argument("--no-install", action="store_true", help="do not pip install pyelastica")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    a = ap.parse_args(argv)
    if not (math.isfinite(a.periods) and a.periods <= 1000):
        ap.error(f"--periods must be finite and at most 1000, got {a.periods}")
    if not (a.periods >= a.transient + 1 and a.periods >= a.fit_periods + 1 and a.transient >= 0
            and a.fit_periods >= 1 and a.modes >= 1 and a.harmonics >= 1):
        ap.error("need periods >= transient + 1 and >= fit-periods + 1, fit-periods >= 1, "
                 "modes >= 1, harmonics >= 1")
    if a.reference_points < 3 or a.reference_steps < 4:
        ap.error("--reference-points must be >= 3 and --reference-steps >= 4")
    run = run_pyelastica(a.periods, install=not a.no_install, transient=a.transient)
    fit = fit_gait(run, a.fit_periods, a.modes, a.harmonics)
    out = {"pyelastica": {k: run[k] for k in ("speed_body_lengths_per_period",
                                             "speed_per_period", "transient_periods",
                                             "wall_time_s", "periods", "elastica_version",
                                             "speed_spread",
                                             "own_speed_m_s")},
           "parameters": PARAMETERS, "gait_fit": fit,
           "command": "python benchmarks/crawl_pyelastica.py " + " ".join(sys.argv[1:]
                                                                         if argv is None else argv),
           "load_average_after": list(os.getloadavg())}
    out["pyelastica"]["wall_time_per_period_s"] = run["wall_time_s"] / a.periods
    if a.gait_out:
        write_atomic(a.gait_out, gait_toml(fit))
        out["gait_file"] = str(a.gait_out)
    if not a.no_reference:
        ref = reference_on_fit(fit, a.reference_points, a.reference_steps)
        u_dyn = run["speed_body_lengths_per_period"]
        out["reference_quasi_static"] = ref
        out["reference_vs_pyelastica_relative"] = (ref["U"] - u_dyn) / u_dyn
    if a.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"PyElastica {a.periods:g} periods in {run['wall_time_s']:.1f} s: "
              f"{run['speed_body_lengths_per_period']:.4f} L per period "
              f"(after {a.transient} periods); fit error {fit['relative_rms_error']:.3f}")
        if "reference_quasi_static" in out:
            print(f"quasi-static reference on the fitted gait: {out['reference_quasi_static']['U']:.4f}"
                  f" L per period ({100 * out['reference_vs_pyelastica_relative']:+.1f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
