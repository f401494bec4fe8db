"""The FE strip check of issue 27 (target: under 5 minutes on 2 cores) and the plan-view
drag check, timed.

    python benchmarks/bench_fe_getfem.py [--mesh 200] [--assembly surfaces/bushing-strip.toml]
                                         [--json]

The strip: by default the slender strip of tests/test_fe_getfem.py (h / l = 1/50), run as
``asperity risk --fe getfem`` runs it (GetFEM under /usr/bin/python3, Q1 plane stress,
``--mesh`` elements along l); with --assembly a strip assembly file instead.  Prints the
seconds, elements, increments and Newton iterations of the FE run, the chain's drift beside
the FE drift, and the 24-direction drag of the wedge's star law."""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SLENDER = {"assembly": {"model": "strip", "h": 2e-3, "E": 1e11, "p": 5e6, "l": 0.1,
                        "k_t": 1e12, "alpha_T": 1e-5, "n": 401, "nu": 0.3},
           "friction": {"mu_plus": 0.2, "mu_minus": 0.1},
           "loading": {"dT_min": 0.0, "dT_max": 30.0}}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", type=int, default=200, help="elements along l")
    ap.add_argument("--assembly", default=None, help="a strip assembly file")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    sys.path.insert(0, str(ROOT))
    from asperity import derive, fit_derivation
    from asperity.fe.checks import drag_check
    from asperity.fe.strip import run_strip_fe
    from asperity.microslip.assembly import assembly_from_dict, load_assembly
    from asperity.microslip.risk import assembly_friction
    from asperity.texture.wedges import WedgeTexture
    asm = (load_assembly(args.assembly) if args.assembly else
           assembly_from_dict(SLENDER, ROOT / "slender-strip.toml"))
    fr = assembly_friction(asm)
    t0 = time.perf_counter()
    fe = run_strip_fe(asm, fr.mu_plus, fr.mu_minus, mesh=args.mesh)
    wall = time.perf_counter() - t0
    fe.pop("_profile", None)
    gl = fit_derivation(derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360), "star")
    t1 = time.perf_counter()
    drag = drag_check(gl, 24)
    out = {"strip": {"assembly": asm.name, "seconds_wall": wall,
                     "seconds_getfem": fe["seconds"], "elements": fe["elements"],
                     "elements_along_l": fe["elements_along_l"],
                     "elements_through_h": fe["elements_through_h"],
                     "increments": fe["increments"],
                     "newton_iterations": fe["newton_iterations"],
                     "cycles_run": fe["cycles_run"],
                     "fe_drift_per_cycle_m": fe["drift_per_cycle_m"],
                     "chain_drift_per_cycle_m": fe["chain_drift_per_cycle_m"],
                     "relative_difference": fe["relative_difference"],
                     "target_seconds": 300.0},
           "drag": {"directions": 24, "seconds_wall": time.perf_counter() - t1,
                    "elements": drag["elements"], "max_relative_error":
                    drag["max_relative_error"]}}
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    s, d = out["strip"], out["drag"]
    print(f"FE strip check ({s['assembly']}): {s['seconds_wall']:.2f} s wall "
          f"({s['seconds_getfem']:.2f} s in GetFEM; target < 300 s), {s['elements']} elements "
          f"({s['elements_along_l']} x {s['elements_through_h']}), {s['increments']} "
          f"increments, {s['newton_iterations']} Newton iterations, {s['cycles_run']} cycles")
    print(f"  drift per cycle: FE {s['fe_drift_per_cycle_m']:+.6g} m, chain "
          f"{s['chain_drift_per_cycle_m']:+.6g} m ({100 * s['relative_difference']:.3g} % "
          "apart)")
    print(f"drag check: 24 directions in {d['seconds_wall']:.2f} s, {d['elements']} elements, "
          f"largest relative error {d['max_relative_error']:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
