"""Benchmark of bodies on a plane (``asperity bench --only body``, issue 20): Moreau steps
per second of asperity's point mass on the ellipse and on the star-shaped law against
MuJoCo's box on a plane (elliptic friction cone) measured in the same run, MuJoCo's disc
(condim 6, the torsional coefficient of a uniformly loaded disc) sliding and spinning to
rest, and the disc of asperity's body solver with 256 contact points.

MuJoCo (PyPI ``mujoco``) is not a dependency of the package: it runs in a child process
(``benchmarks/body_peers.py`` of the repository) and is installed into the running
interpreter's environment with pip when missing, unless ``install`` is False (then its
figures are left out and the output says so, with the one line that installs it).

The point mass and the box solve the same problem: 1 kg launched at V0 on a plane, time
step DT, stepped for SLIDE_TIME (sliding throughout: the costly phase), relaunched until
``seconds`` have passed; compilation and MuJoCo's model building are excluded.  The box
(0.1 x 0.1 x 0.02 m, Coulomb mu = 0.3) has four corner contacts; the point mass one, with
the law of the issue (ellipse or star-shaped, mu1 = 0.6, mu2 = 0.3).  Figures depend on
the machine and its load (reported); they are printed, never asserted in unit tests.
"""
from __future__ import annotations

import importlib.util
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PEERS_SCRIPT = ROOT / "benchmarks" / "body_peers.py"
INSTALL_LINE = f"{Path(sys.executable).name} -m pip install mujoco"
DT = 1e-4
V0 = 10.0
SLIDE_TIME = 1.0
G = 9.81
#: the disc: radius, sliding friction, launch (eps = v0 / (R omega0) = 1)
DISC = {"radius": 0.05, "mu": 0.3, "v0": 1.0, "omega0": 20.0, "dt": 1e-4, "g": G,
        "stop_speed": 1e-3, "end_fraction": 0.02, "t_max": 3.0}
#: v / (R omega) of a uniformly loaded disc as both stop (SPEC.md 8; Farkas et al. 2003)
DISC_TERMINAL_RATIO = 0.653
#: the issue's targets: star law at least 5x MuJoCo's box; the 256-point disc (steps/s)
TARGETS = {"star_vs_mujoco_box": 5.0, "disc_256_ellipse_steps_per_second": 2e4,
           "disc_256_star_steps_per_second": 1e4}


def _laws():
    from ..laws import planar as L
    return {"ellipse": L.ellipse_law(0.6, 0.3), "star": L.star_law(0.6, 0.3)}


def point_mass_rate(law, seconds: float) -> dict:
    """Steps per second of asperity's point mass on ``law`` (the box's problem)."""
    import numpy as np

    from .moreau import point_mass, simulate
    body = point_mass(law)
    n = int(round(SLIDE_TIME / DT))
    u = V0 * np.array([math.cos(math.radians(30)), math.sin(math.radians(30))])
    last = {}

    def run():
        last["r"] = simulate(body, u, dt=DT, t_end=SLIDE_TIME, record_every=n)
    run()                                                # compilation
    done, t0, c0 = 0, time.perf_counter(), time.process_time()
    while True:
        run()
        done += n
        el = time.perf_counter() - t0
        if el >= seconds:
            break
    cpu = time.process_time() - c0
    r = last["r"]
    return {"steps_per_second": done / el, "cpu_steps_per_second": done / cpu if cpu > 0
            else None, "steps": done, "mean_iterations": r.mean_iterations,
            "status": r.status, "sliding_at_end": bool(np.any(r.u_final != 0.0))}


def _best(a: dict, b: dict) -> dict:
    """The faster of two measurements of the same thing (wall time; the machine is shared)."""
    if "steps_per_second" not in b:
        return a
    if "steps_per_second" not in a or b["steps_per_second"] > a["steps_per_second"]:
        return b
    return a


def mujoco_status(install: bool) -> tuple[bool, str]:
    """(available, what happened): MuJoCo importable here, installed now with pip, or not."""
    if importlib.util.find_spec("mujoco") is not None:
        return True, "installed"
    if not install:
        return False, f"mujoco is not installed (install it with: {INSTALL_LINE})"
    from ..lifeline import preexec
    r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "mujoco"],
                       capture_output=True, text=True, preexec_fn=preexec())
    importlib.invalidate_caches()
    if r.returncode == 0 and importlib.util.find_spec("mujoco") is not None:
        return True, "installed now with pip"
    lines = (r.stderr or r.stdout).strip().splitlines()
    return False, (f"pip could not install mujoco ({lines[-1] if lines else r.returncode}); "
                   f"install it with: {INSTALL_LINE}")


def _child(worker: str, spec: dict) -> dict:
    from ..lifeline import preexec
    if not PEERS_SCRIPT.is_file():
        return {"error": f"{PEERS_SCRIPT} not found (the peers run from a repository checkout)"}
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    r = subprocess.run([sys.executable, str(PEERS_SCRIPT), "--worker", worker, "--spec",
                        json.dumps(spec)], capture_output=True, text=True, env=env,
                       preexec_fn=preexec())
    if r.returncode != 0:
        lines = r.stderr.strip().splitlines()
        return {"error": lines[-1] if lines else f"exit status {r.returncode}"}
    return json.loads(r.stdout.strip().splitlines()[-1])


def body_solver_disc(law_name: str, seconds: float) -> dict:
    """The body solver's 256-point disc (:func:`asperity.dynamics.disc_bench.bench_disc`)."""
    from .disc_bench import bench_disc
    return dict(bench_disc(law_name, contact_points=256, seconds=seconds))


def bench_body(seconds: float = 1.0, install: bool = True) -> dict:
    """Every figure of the body benchmark and whether each target is met (None: not
    measured)."""
    out = {"load_average": list(os.getloadavg()), "dt": DT, "v0": V0, "targets": TARGETS}
    ok, note = mujoco_status(install)
    out["mujoco_status"] = note
    spec = {"dt": DT, "g": G, "mu": 0.3, "v0": V0, "slide_time": SLIDE_TIME,
            "seconds": seconds}
    # MuJoCo, asperity, MuJoCo, asperity: the best of two each (the machine is shared)
    box = [_child("box", spec) if ok else {"skipped": note}]
    laws = _laws()
    ours = [{name: point_mass_rate(law, seconds) for name, law in laws.items()}]
    if ok:
        box.append(_child("box", spec))
        ours.append({name: point_mass_rate(law, seconds) for name, law in laws.items()})
    out["mujoco_box"] = box[0] if len(box) == 1 else _best(*box)
    out["point_mass"] = {name: ours[0][name] if len(ours) == 1 else _best(ours[0][name],
                                                                           ours[1][name])
                         for name in laws}
    rate = out["mujoco_box"].get("steps_per_second")
    cpu = out["mujoco_box"].get("cpu_steps_per_second")
    for v in out["point_mass"].values():
        v["vs_mujoco_box"] = v["steps_per_second"] / rate if rate else None
        v["cpu_vs_mujoco_box"] = (v["cpu_steps_per_second"] / cpu
                                  if cpu and v["cpu_steps_per_second"] else None)
    out["mujoco_disc"] = _child("disc", DISC) if ok else {"skipped": note}
    out["mujoco_disc"].pop("path", None)
    out["disc_terminal_ratio_expected"] = DISC_TERMINAL_RATIO
    out["disc_256"] = {name: body_solver_disc(name, seconds) for name in ("ellipse", "star")}
    verdict = {}
    for key, what in (("star_vs_mujoco_box", "vs_mujoco_box"),
                      ("star_vs_mujoco_box_cpu_time", "cpu_vs_mujoco_box")):
        star = out["point_mass"]["star"][what]
        verdict[key] = {"value": star, "target": TARGETS["star_vs_mujoco_box"],
                        "met": None if star is None else star >= TARGETS["star_vs_mujoco_box"]}
    for name in ("ellipse", "star"):
        key = f"disc_256_{name}_steps_per_second"
        rate = out["disc_256"][name].get("steps_per_second")
        verdict[key] = {"value": rate, "target": TARGETS[key],
                        "met": None if rate is None else rate >= TARGETS[key]}
    out["verdict"] = verdict
    return out


def _met(v) -> str:
    return "not measured" if v["met"] is None else ("target met" if v["met"] else
                                                    "target NOT met")


def format_body(out: dict) -> str:
    """Human-readable lines of :func:`bench_body`."""
    la = out["load_average"]
    lines = [f"body: load average {la[0]:.2f} {la[1]:.2f} {la[2]:.2f}; dt = {out['dt']:g} s, "
             f"launched at {out['v0']:g} m/s, sliding throughout; MuJoCo: "
             f"{out['mujoco_status']}"]
    box = out["mujoco_box"]
    if "steps_per_second" in box:
        lines.append(f"body, MuJoCo {box['version']} box on a plane (elliptic cone): "
                     f"{box['steps_per_second']:.3e} steps/s ({box['loop']}; rollout "
                     f"{box.get('rollout_steps_per_second', float('nan')):.3e}, Python loop "
                     f"{box['python_loop_steps_per_second']:.3e}), "
                     f"{box['mean_contacts']:.2f} contacts/step")
    else:
        lines.append(f"body, MuJoCo box: left out: {box.get('skipped') or box.get('error')}")
    for name, v in out["point_mass"].items():
        r, rc = v["vs_mujoco_box"], v["cpu_vs_mujoco_box"]
        lines.append(f"body, asperity point mass, {name:7s} law: {v['steps_per_second']:.3e} "
                     f"steps/s (mean {v['mean_iterations']:.2f} iterations/step)"
                     + ("" if r is None else f", {r:.2f}x MuJoCo's box")
                     + ("" if rc is None else f" ({rc:.2f}x in CPU time)"))
    for key, what in (("star_vs_mujoco_box", "wall time"),
                      ("star_vs_mujoco_box_cpu_time", "CPU time")):
        v = out["verdict"][key]
        lines.append(f"body, star law vs MuJoCo's box ({what}): target >= {v['target']:g}x: "
                     + ("" if v["value"] is None else f"{v['value']:.2f}x, ") + _met(v))
    d = out["mujoco_disc"]
    if "slide_stop_time" in d:
        def f(x):
            return "never" if x is None else f"{x:.4f} s"
        lines.append(
            f"body, MuJoCo disc (R = {d['radius']:g} m, mu = {d['mu']:g}, torsional "
            f"2 mu R / 3 = {d['torsional']:.4g} m, condim 6, {d['contacts']} contacts; v0 = "
            f"{d['v0']:g} m/s, omega0 = {d['omega0']:g} rad/s): sliding stops at "
            f"{f(d['slide_stop_time'])}, spinning at {f(d['spin_stop_time'])}"
            + ("" if d["spin_stops_before_slide_by"] is None else
               f" ({d['spin_stops_before_slide_by']:+.4f} s before sliding)"))
        tr = d["terminal_ratio"]
        lines.append(f"body, MuJoCo disc v / (R omega) as it ends (v + R omega below "
                     f"{d['end_fraction']:g} of the start): "
                     + ("n/a" if tr is None else f"{tr:.3g}")
                     + f"; a uniformly loaded disc: {out['disc_terminal_ratio_expected']:g}, "
                     "stopping together")
        rw = d.get("ratio_when_below") or {}
        if rw:
            lines.append("body, MuJoCo disc v / (R omega) when v + R omega falls below "
                         + ", ".join(f"{k} of its start: "
                                     + ("n/a" if x is None else f"{x:.3g}")
                                     for k, x in rw.items()))
    else:
        lines.append(f"body, MuJoCo disc: left out: {d.get('skipped') or d.get('error')}")
    for name, v in out["disc_256"].items():
        key = f"disc_256_{name}_steps_per_second"
        if "error" in v:
            lines.append(f"body, disc with 256 contact points, {name}: {v['error']}")
        else:
            lines.append(f"body, disc with 256 contact points, {name}: "
                         f"{v.get('steps_per_second', float('nan')):.3e} steps/s (target >= "
                         f"{TARGETS[key]:g}): {_met(out['verdict'][key])}")
    return "\n".join(lines)
