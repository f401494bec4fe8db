"""MuJoCo, the peer of ``asperity bench --only body`` (issue 20), run in a child process
(``python benchmarks/body_peers.py --worker box|disc --spec JSON`` prints one JSON line):
the package never imports MuJoCo (PyPI ``mujoco``, Apache-2.0; a benchmark peer only).

* ``box``: a 1 kg box (0.1 x 0.1 x 0.02 m) sliding on a plane, elliptic friction cone
  (``cone="elliptic"``, condim 3, mu = 0.3), time step dt; steps per second of MuJoCo's own
  C loop (``mujoco.rollout``, no Python per step) and of a Python loop of ``mj_step``;
  the faster of the two is MuJoCo's figure.
  The box, settled on the plane, is launched at v0 and stepped for ``slide_time`` (it
  slides throughout), relaunched from the same state until ``seconds`` have passed.
* ``disc``: a cylinder (radius R, height R/5) lying flat, condim 6, sliding friction mu,
  torsional coefficient 2 mu R / 3 (the torque of a uniformly loaded disc spinning in
  place: integral of mu p r dA = mu N (2 R / 3)), rolling 0; launched with v0 and omega0;
  the times at which sliding (|v| < stop_speed) and spinning (R |omega| < stop_speed)
  stop and v / (R omega) as the motion ends (when v + R omega first falls below
  ``end_fraction`` of its start).  MuJoCo's torsional friction is a coefficient of its
  own, decoupled from sliding; the uniformly loaded disc's ratio tends to 0.653 (SPEC 8).
"""
from __future__ import annotations

import json
import math
import sys
import time

BOX_XML = """
<mujoco>
  <option timestep="{dt}" cone="elliptic" gravity="0 0 -{g}"/>
  <worldbody>
    <geom type="plane" size="1e6 1e6 0.1" friction="{mu} 0 0" condim="3"/>
    <body pos="0 0 0.01">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.01" mass="1" friction="{mu} 0 0" condim="3"
            margin="0.001" gap="0.001"/>
    </body>
  </worldbody>
</mujoco>
"""

#: v / (R omega) is also given when v + R omega first falls below these fractions of its start
FRACTIONS = (0.5, 0.2, 0.1, 0.05, 0.02)

DISC_XML = """
<mujoco>
  <option timestep="{dt}" cone="elliptic" gravity="0 0 -{g}"/>
  <worldbody>
    <geom type="plane" size="100 100 0.1" friction="{mu} {tors} 0" condim="6"/>
    <body pos="0 0 {half}">
      <freejoint/>
      <geom type="cylinder" size="{R} {half}" mass="1" friction="{mu} {tors} 0"
            condim="6"/>
    </body>
  </worldbody>
</mujoco>
"""


def box(spec: dict) -> dict:
    import mujoco
    import numpy as np
    dt, seconds = spec["dt"], spec["seconds"]
    m = mujoco.MjModel.from_xml_string(BOX_XML.format(dt=dt, g=spec["g"], mu=spec["mu"]))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    for _ in range(2000):                      # settle on the plane at rest, then launch
        mujoco.mj_step(m, d)
    d.qvel[:] = 0.0
    d.qvel[0] = spec["v0"]
    what = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state0 = np.empty(mujoco.mj_stateSize(m, what))
    mujoco.mj_getState(m, d, state0, what)
    nstep = max(1, int(round(spec["slide_time"] / dt)))     # one launch: sliding throughout
    ncon = 0
    for _ in range(nstep):
        mujoco.mj_step(m, d)
        ncon += int(d.ncon)
    out = {"version": mujoco.__version__, "mean_contacts": ncon / nstep, "dt": dt,
           "launch_steps": nstep, "v_end": float(d.qvel[0])}
    # a Python loop of mj_step, relaunched every nstep steps
    n, el = 0, 0.0
    t0, c0 = time.perf_counter(), time.process_time()
    while el < seconds:
        mujoco.mj_setState(m, d, state0, what)
        for _ in range(nstep):
            mujoco.mj_step(m, d)
        n += nstep
        el = time.perf_counter() - t0
    cpu = time.process_time() - c0
    out["python_loop_steps_per_second"] = n / el
    out["python_loop_cpu_steps_per_second"] = n / cpu if cpu > 0 else None
    # MuJoCo's own C loop (rollout): one call of nstep steps from the launch, repeated;
    # wall and CPU time (the machine may be shared)
    try:
        from mujoco import rollout
        rollout.rollout(m, d, state0[None, :], nstep=min(nstep, 100))    # warm up
        n, el = 0, 0.0
        t0, c0 = time.perf_counter(), time.process_time()
        while el < seconds:
            rollout.rollout(m, d, state0[None, :], nstep=nstep)
            n += nstep
            el = time.perf_counter() - t0
        cpu = time.process_time() - c0
        out["rollout_steps_per_second"] = n / el
        out["steps_per_second"] = n / el
        out["cpu_steps_per_second"] = n / cpu if cpu > 0 else None
        out["loop"] = "mujoco.rollout (C loop)"
        if out["python_loop_steps_per_second"] > n / el:       # the faster of the two counts
            out["steps_per_second"] = out["python_loop_steps_per_second"]
            out["cpu_steps_per_second"] = out["python_loop_cpu_steps_per_second"]
            out["loop"] = "Python mj_step loop (faster than rollout in this run)"
    except Exception as exc:                  # pragma: no cover - depends on the version
        out["steps_per_second"] = out["python_loop_steps_per_second"]
        out["cpu_steps_per_second"] = None
        out["loop"] = f"Python mj_step loop (rollout failed: {type(exc).__name__}: {exc})"
    out["steps"] = n
    return out


def disc(spec: dict) -> dict:
    import mujoco
    dt, R, mu, g = spec["dt"], spec["radius"], spec["mu"], spec["g"]
    tors = 2.0 * mu * R / 3.0
    half = R / 10.0
    m = mujoco.MjModel.from_xml_string(DISC_XML.format(dt=dt, g=g, mu=mu, tors=tors, R=R,
                                                       half=half))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    for _ in range(200):                       # settle on the plane at rest
        mujoco.mj_step(m, d)
    d.qvel[:] = 0.0
    d.qvel[0] = spec["v0"]
    d.qvel[5] = spec["omega0"]
    stop_speed = spec["stop_speed"]
    start = spec["v0"] + R * abs(spec["omega0"])
    slide_stop = spin_stop = end_ratio = None
    end_t = None
    ncon = 0
    t0 = d.time
    rows = []
    ratios = {}
    steps = int(spec["t_max"] / dt)
    for k in range(steps):
        mujoco.mj_step(m, d)
        ncon = max(ncon, int(d.ncon))
        t = d.time - t0
        v = math.hypot(d.qvel[0], d.qvel[1])
        w = R * abs(d.qvel[5])
        if k % max(1, steps // 200) == 0:
            rows.append((t, v, w))
        if end_ratio is None and v + w < spec["end_fraction"] * start:
            end_ratio = v / w if w > 0 else math.inf
            end_t = t
        for f in FRACTIONS:
            if f not in ratios and v + w < f * start:
                ratios[f] = v / w if w > 0 else math.inf
        if slide_stop is None and v < stop_speed:
            slide_stop = t
        if spin_stop is None and w < stop_speed:
            spin_stop = t
        if slide_stop is not None and spin_stop is not None:
            break
    return {"version": mujoco.__version__, "contacts": ncon, "dt": dt, "radius": R, "mu": mu,
            "torsional": tors, "v0": spec["v0"], "omega0": spec["omega0"],
            "slide_stop_time": slide_stop, "spin_stop_time": spin_stop,
            "spin_stops_before_slide_by": (None if slide_stop is None or spin_stop is None
                                           else slide_stop - spin_stop),
            "terminal_ratio": end_ratio, "terminal_ratio_time": end_t,
            "ratio_when_below": {f"{f:g}": ratios.get(f) for f in FRACTIONS},
            "stop_speed": stop_speed, "end_fraction": spec["end_fraction"],
            "path": rows}


def main(argv) -> int:
    if "--worker" not in argv:
        print(__doc__)
        return 0
    try:
        from asperity.lifeline import die_with_parent
        die_with_parent()
    except Exception:                          # pragma: no cover - run outside the repo
        pass
    name = argv[argv.index("--worker") + 1]
    spec = json.loads(argv[argv.index("--spec") + 1])
    try:
        import mujoco  # noqa: F401
    except ImportError as exc:
        print(json.dumps({"error": f"mujoco cannot be imported ({exc})"}))
        return 0
    print(json.dumps({"box": box, "disc": disc}[name](spec)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
