"""Speed of the generated Abaqus routines (issue 27): microseconds per FRIC call, timed
inside a Fortran driver PROGRAM (ctypes alone costs about a microsecond a call) making 1e6
calls in 3D (NFDIR = 2) with sticking, sliding and mixed slip increments; and the time to
generate each routine (the law's table included) from a gauge law. Targets: one call at
most 1 us, a routine generated in under 1 s.

Run:  python benchmarks/bench_fric.py [--calls N] [--repeats R] [--json]
(needs gfortran; the driver is compiled with the harness's flags, -O2).
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time

#: slip increments: |DGAM| x PROPS(1) against the law's force x PRESS (about 0.1 to 0.2)
STICK, SLIDE = 1e-8, 1e-4
DRIVER = """\
      PROGRAM BENCH
      IMPLICIT REAL*8(A-H,O-Z)
      CHARACTER*80 CINAME,SLNAME,MSNAME
      CHARACTER*16 ARG
      DIMENSION TAU(2),DDTDDG(2,2),DDTDDP(2),DSLIP(2),DDTDDT(2,2),
     1 STATEV(3),DGAM(2),TAULM(2),SLIP(2),TIME(2),COORDS(3),
     2 RCOORD(3),DROT(2,2),TEMP(2),PREDEF(2,1),PROPS(3),
     3 GX(1024),GY(1024),AMP(1024),T0X(1024),T0Y(1024)
      INTEGER*8 IC0,IC1,IRATE
C     arguments: the number of calls, the share of sliding calls, and
C     1 if a sliding call starts on the boundary (steady sliding: the
C     stress of the previous increment), 0 if from zero (slip onset)
      CALL GET_COMMAND_ARGUMENT(1,ARG)
      READ (ARG,*) NCALL
      CALL GET_COMMAND_ARGUMENT(2,ARG)
      READ (ARG,*) SHARE
      CALL GET_COMMAND_ARGUMENT(3,ARG)
      READ (ARG,*) LSTEADY
      DO 10 J = 1, 1024
        ANG = 2.399963229728653D0*J
        GX(J) = COS(ANG)
        GY(J) = SIN(ANG)
        AMP(J) = {stick}
        IF (MOD(J*0.618033988749895D0,1.0D0) .LT. SHARE)
     1    AMP(J) = {slide}
   10 CONTINUE
      PROPS(1) = 1.0D6
      PROPS(2) = 30.0D0
      PROPS(3) = 1.0D0
      PRESS = 1.0D0
      DPRESS = 0.0D0
      DDPDDH = 1.0D12
      DTIME = 1.0D0
      CHRLNGTH = 1.0D0
      CINAME = 'TEXTURED'
      SLNAME = 'SECONDARY'
      MSNAME = 'MAIN'
      DO 20 J = 1, 2
        TAULM(J) = 0.0D0
        SLIP(J) = 0.0D0
        TIME(J) = 0.0D0
        TEMP(J) = 0.0D0
        PREDEF(J,1) = 0.0D0
        DROT(J,1) = 0.0D0
        DROT(J,2) = 0.0D0
        DROT(J,J) = 1.0D0
   20 CONTINUE
      DO 25 J = 1, 3
        COORDS(J) = 0.0D0
        RCOORD(J) = 0.0D0
   25 CONTINUE
      DO 30 J = 1, 1024
        T0X(J) = 0.0D0
        T0Y(J) = 0.0D0
        IF (LSTEADY .EQ. 1 .AND. AMP(J) .GT. {stick}) THEN
          LM = 0
          TAU(1) = 0.0D0
          TAU(2) = 0.0D0
          DGAM(1) = AMP(J)*GX(J)
          DGAM(2) = AMP(J)*GY(J)
          CALL FRIC(LM,TAU,DDTDDG,DDTDDP,DSLIP,SED,SFD,
     1     DDTDDT,PNEWDT,STATEV,DGAM,TAULM,PRESS,DPRESS,DDPDDH,SLIP,
     2     1,1,TIME,DTIME,0,CINAME,SLNAME,MSNAME,0,1,
     3     1,COORDS,RCOORD,DROT,TEMP,PREDEF,2,3,0,
     4     3,CHRLNGTH,PROPS,3)
          T0X(J) = TAU(1)
          T0Y(J) = TAU(2)
        END IF
   30 CONTINUE
      S = 0.0D0
      CALL SYSTEM_CLOCK(IC0,IRATE)
      DO 100 I = 1, NCALL
        J = MOD(I,1024) + 1
        LM = 0
        TAU(1) = T0X(J)
        TAU(2) = T0Y(J)
        STATEV(1) = 0.0D0
        STATEV(2) = 0.0D0
        STATEV(3) = 0.0D0
        SED = 0.0D0
        PNEWDT = 1.0D0
        DGAM(1) = AMP(J)*GX(J)
        DGAM(2) = AMP(J)*GY(J)
        CALL FRIC(LM,TAU,DDTDDG,DDTDDP,DSLIP,SED,SFD,
     1   DDTDDT,PNEWDT,STATEV,DGAM,TAULM,PRESS,DPRESS,DDPDDH,SLIP,
     2   1,I,TIME,DTIME,0,CINAME,SLNAME,MSNAME,0,1,
     3   1,COORDS,RCOORD,DROT,TEMP,PREDEF,2,3,0,
     4   3,CHRLNGTH,PROPS,3)
        S = S + TAU(1) + DDTDDG(1,2) + STATEV(3)
  100 CONTINUE
      CALL SYSTEM_CLOCK(IC1)
      WRITE (*,'(2ES24.15)') DBLE(IC1-IC0)/DBLE(IRATE), S
      END
"""
#: name -> (share of sliding calls, 1 if they start on the boundary)
MIXES = {"stick": (0.0, 0), "slip onset": (1.0, 0), "steady slide": (1.0, 1),
         "mixed": (0.5, 1)}


def laws() -> dict:
    from asperity import derive, fit_derivation
    from asperity.laws.componentwise import componentwise_gauge
    from asperity.texture.wedges import WedgeTexture
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360)
    w = derive(WedgeTexture(30.0, 30.0, 0.3, 0.3), "windward", n_directions=360)
    return {"asymmetric ellipse": fit_derivation(d, "truncated-ellipse"),
            "star (all faces)": fit_derivation(d, "star"),
            "star (windward)": fit_derivation(w, "star"),
            "componentwise": componentwise_gauge(mu_f=0.2, mu_b=0.1, mu_t=0.15)}


def bench(calls: int = 1_000_000, repeats: int = 3) -> dict:
    from asperity.fe.abaqus_fric import law_table_of, routine_source
    from asperity.fe.fortran_harness import compile_source
    out = {"calls": calls, "repeats": repeats, "nfdir": 2,
           "note": "best of the repeats; the machine may be shared (timings are then upper "
                   "bounds)", "laws": {}}
    folder = tempfile.mkdtemp(prefix="asperity-bench-fric-")
    for name, gl in laws().items():
        gen = {}
        for routine in ("fric", "vfric", "vfriction"):
            best = float("inf")
            for _ in range(repeats):
                t0 = time.perf_counter()
                text = routine_source(gl, routine)
                best = min(best, time.perf_counter() - t0)
            gen[routine] = best
            if routine == "fric":
                fric = text
        table = law_table_of(gl)
        exe = compile_source(DRIVER.format(stick=f"{STICK:.1E}".replace("E", "D"),
                                           slide=f"{SLIDE:.1E}".replace("E", "D")) + fric,
                             folder, program=True)
        per_call = {}
        for mix, (share, steady) in MIXES.items():
            best = float("inf")
            for _ in range(repeats):
                done = subprocess.run([str(exe), str(calls), str(share), str(steady)],
                                      capture_output=True,
                                      text=True, timeout=600, check=True)
                best = min(best, float(done.stdout.split()[0]))
            per_call[mix] = best / calls * 1e6
        out["laws"][name] = {"table_nodes": table.n, "generation_seconds": gen,
                             "us_per_call": per_call}
    return out


def format_bench(out: dict) -> str:
    lines = [(f"FRIC calls from a Fortran driver: {out['calls']:.0e} per run, NFDIR = 2, best of "
             f"{out['repeats']} ({out['note']})"),
             "us per call: " + ", ".join(MIXES) + " (mixed: half stick, half steady); "
             "generation s: fric, vfric, vfriction"]
    for name, r in out["laws"].items():
        u, g = r["us_per_call"], r["generation_seconds"]
        lines.append(f"{name:20s} {r['table_nodes']:5d} nodes  us/call "
                     + " ".join(f"{u[m]:6.3f}" for m in MIXES)
                     + f"   gen s {g['fric']:.3f} {g['vfric']:.3f} {g['vfriction']:.3f}")
    worst = {m: max(r["us_per_call"][m] for r in out["laws"].values()) for m in MIXES}
    slowest = max(max(r["generation_seconds"].values()) for r in out["laws"].values())
    lines.append("worst us per call (target <= 1): " + ", ".join(
        f"{m} {v:.3f}" + ("" if v <= 1.0 else " OVER") for m, v in worst.items()))
    lines.append(f"slowest generation {slowest:.3f} s (target < 1)")
    return "\n".join(lines)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--calls", type=int, default=1_000_000)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    a = p.parse_args()
    if a.calls < 1 or a.repeats < 1:
        sys.exit("bench_fric: --calls and --repeats must be >= 1")
    res = bench(a.calls, a.repeats)
    print(json.dumps(res, indent=2) if a.json else format_bench(res))
