"""MuJoCo's disc beside ours in the report's section on bodies (:mod:`asperity.report.bodies`):
the figures of ``asperity bench --only body --json`` read from a committed JSON (MuJoCo is
never needed to build the report) and our disc run with the benchmark's criteria."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .bodies_runs import BENCH_COMMAND, BENCH_DISC, BENCH_JSON, FULL, MASS, G, Sizes


def bench_json(folder: Path):
    """(the benchmark's body part or None, where it was read): ``body-bench.json`` in the
    report folder, else in the repository's reports/."""
    from ..errors import InputError
    from ..io import read_json
    root = Path(__file__).resolve().parents[2] / "reports"
    for p in (Path(folder) / BENCH_JSON, root / BENCH_JSON):
        if p.is_file():
            try:
                data = read_json(p, "benchmark JSON")
            except InputError:
                continue
            if isinstance(data, dict):
                body = data.get("body", data)
                if isinstance(body, dict) and isinstance(body.get("mujoco_disc"), dict):
                    return body, p
    return None, None


def crossing_times(t, v, w, stop_speed: float, end_fraction: float):
    """The benchmark's criteria on a path: (slide stop: first v < stop_speed, spin stop:
    first R |omega| < stop_speed, v / (R omega) where v + R |omega| first falls below
    end_fraction of its start)."""
    def first(mask):
        k = np.flatnonzero(mask)
        return float(t[k[0]]) if k.size else None
    s = v + w
    k = np.flatnonzero(s < end_fraction * s[0])
    ratio = None
    if k.size:
        ratio = float(v[k[0]] / w[k[0]]) if w[k[0]] > 0 else math.inf
    return first(v < stop_speed), first(w < stop_speed), ratio


def our_bench_disc(spec: dict, sizes: Sizes = FULL) -> dict:
    """Our disc with the benchmark's numbers and criteria, and the reference ODE's."""
    from ..bodies.closed_forms import disc_reference
    from ..bodies.footprint import disc
    from ..dynamics.body import simulate_body
    from ..laws.planar import coulomb_law
    Rb = spec["radius"]
    fp = disc(Rb, contact_points=sizes.disc_points)
    r = simulate_body(fp.points, fp.weights, coulomb_law(spec["mu"]), mass=MASS,
                      inertia=MASS * fp.inertia_per_mass, u0=(spec["v0"], 0.0, spec["omega0"]),
                      dt=spec["dt"])
    v, w = np.hypot(r.u[:, 0], r.u[:, 1]), Rb * np.abs(r.u[:, 2])
    ours = crossing_times(r.t, v, w, spec["stop_speed"], spec["end_fraction"])
    ref = disc_reference(spec["v0"], spec["omega0"], spec["mu"], G, Rb, "disc")
    rw = Rb * ref.omega
    exact = crossing_times(ref.t, ref.v, rw, spec["stop_speed"], spec["end_fraction"])
    return {"result": r, "ref": ref, "ours": ours, "exact": exact, "points": fp.n}


def plot_bench(path, spec, mine, mujoco) -> None:
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.3))
    r, ref = mine["result"], mine["ref"]
    Rb = spec["radius"]
    ax.plot(r.t, np.hypot(r.u[:, 0], r.u[:, 1]), color="tab:blue", lw=2.2, alpha=0.5,
            label="asperity: v")
    ax.plot(r.t, Rb * np.abs(r.u[:, 2]), color="tab:red", lw=2.2, alpha=0.5,
            label="asperity: R omega")
    ax.plot(ref.t, ref.v, "k--", lw=0.8, label="closed forms (reference ODE)")
    ax.plot(ref.t, Rb * ref.omega, "k--", lw=0.8)
    if mujoco is not None:
        path_rows = mujoco.get("path")
        try:
            p = np.asarray(path_rows, dtype=float)
        except (TypeError, ValueError):
            p = np.empty((0, 0))
        if p.ndim == 2 and p.shape[0] > 1 and p.shape[1] == 3 and np.all(np.isfinite(p)):
            ax.plot(p[:, 0], p[:, 1], color="tab:blue", lw=1.0, ls=":", label="MuJoCo: v")
            ax.plot(p[:, 0], p[:, 2], color="tab:red", lw=1.0, ls=":",
                    label="MuJoCo: R omega")
        for key, c, what in (("slide_stop_time", "tab:blue", "slide"),
                             ("spin_stop_time", "tab:red", "spin")):
            t = _num(mujoco.get(key))
            if t is not None:
                ax.axvline(t, color=c, lw=0.9, ls="-.", label=f"MuJoCo {what} stops")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("m/s")
    ax.set_title(f"Disc R = {Rb:g} m, mu = {spec['mu']:g}, v0 = {spec['v0']:g} m/s, "
                 f"omega0 = {spec['omega0']:g} rad/s", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def bench_section(folder: Path, sizes: Sizes = FULL) -> list[str]:
    """The MuJoCo part: our disc with the benchmark's numbers, MuJoCo's from
    ``body-bench.json`` when present; writes bodies_mujoco.png."""
    folder = Path(folder)
    lines = []
    bench, where = bench_json(folder)
    mj = bench.get("mujoco_disc") if bench else None
    have = isinstance(mj, dict) and "slide_stop_time" in mj
    spec = dict(BENCH_DISC)
    if have:
        for k in spec:
            if _num(mj.get(k)) is not None and mj[k] > 0:
                spec[k] = float(mj[k])
    mine = our_bench_disc(spec, sizes)
    plot_bench(folder / "bodies_mujoco.png", spec, mine, mj if have else None)
    r = mine["result"]
    lines += ["### MuJoCo's disc beside ours", "",
              f"The disc of `asperity bench --only body`: R = {spec['radius']:g} m, mu = "
              f"{spec['mu']:g}, v0 = {spec['v0']:g} m/s, omega0 = {spec['omega0']:g} rad/s, "
              f"dt = {spec['dt']:g} s.  MuJoCo models it as a cylinder with condim 6 and the "
              "torsional coefficient of a uniformly loaded disc spinning in place (2 mu R / 3), "
              "decoupled from sliding; ours samples the footprint "
              f"({mine['points']} points).  Same criteria for all: sliding stops when v < "
              f"{spec['stop_speed']:g} m/s, spinning when R omega < {spec['stop_speed']:g} "
              f"m/s; v / (R omega) where v + R omega first falls below "
              f"{spec['end_fraction']:g} of its start.", "",
              "| model | slide stops (s) | spin stops (s) | spin before slide by (s) | "
              "v / (R omega) near the end |", "|---|---|---|---|---|"]

    def row(name, s, w, ratio):
        gap = "" if s is None or w is None else f"{s - w:+.4f}"
        rt = "n/a" if ratio is None else f"{ratio:.3g}"
        return f"| {name} | {_t(s)} | {_t(w)} | {gap} | {rt} |"
    lines.append(row("closed forms (reference ODE)", *mine["exact"]))
    lines.append(row(f"asperity body solver ({r.status})", *mine["ours"]))
    if have:
        lines.append(row(f"MuJoCo {mj.get('version', '?')} (condim 6)",
                         *(_num(mj.get(k)) for k in ("slide_stop_time", "spin_stop_time",
                                                     "terminal_ratio"))))
        la = bench.get("load_average")
        la = _num(la[0]) if isinstance(la, list) and la else None
        lines += ["", f"MuJoCo's figures from `{where.name}` (written by `{BENCH_COMMAND}`"
                  + ("" if la is None else f"; load average {la:.2f} then") + ")."]
    else:
        lines += ["", "MuJoCo's disc not measured here: the report does not need MuJoCo.  "
                  f"Run `{BENCH_COMMAND}` (installs MuJoCo with pip in a child process) and "
                  "regenerate the report to add its row."]
    lines += ["", "![MuJoCo's disc beside ours](bodies_mujoco.png)", ""]
    return lines


def _num(x) -> float | None:
    """A finite number of a JSON file, else None."""
    ok = isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
    return float(x) if ok else None


def _t(x) -> str:
    return "never" if x is None else f"{x:.4f}"
