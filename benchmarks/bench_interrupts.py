"""How soon each long command stops after Ctrl-C (SIGINT) or SIGTERM: seconds from the
signal to the exit of the process, with its status.

The tests (tests/test_cli_signals.py and the hostile suites) check what happens on a
signal -- one line, status 130 or 143, nothing written, no traceback, no worker left --
but no time: on a loaded machine any bound is flaky.  The times are here.  Each command
runs in a child process whose stderr is a pipe, is signalled once its long work has
printed a progress line and run ``--settle`` seconds more, and is timed to its exit.
The commands are those of the tests (``long_runs``): a run of minutes each.

    python benchmarks/bench_interrupts.py [--repeats 3] [--settle 1] [--only slide ...]

The README promises a stop within about a second (the kernels run in pieces of well under
a second; a run on a local Dask cluster kills its workers rather than waiting for their
tasks).  Measured with --repeats 2 on 2 cores shared with other work (load 2.3):

    command                            signal  status seconds to exit (min / median / max)
    derive                             SIGINT     130   0.48 /   0.49 /   0.49
    derive                             SIGTERM    143   0.47 /   0.56 /   0.65
    contact windows                    SIGINT     130   0.52 /   0.63 /   0.74
    contact windows                    SIGTERM    143   0.32 /   0.37 /   0.42
    slide                              SIGINT     130   0.31 /   0.35 /   0.38
    slide                              SIGTERM    143   0.31 /   0.34 /   0.37
    slide --body                       SIGINT     130   0.31 /   0.42 /   0.52
    slide --body                       SIGTERM    143   0.52 /   0.52 /   0.52
    risk                               SIGINT     130   0.32 /   0.34 /   0.37
    risk                               SIGTERM    143   0.42 /   0.44 /   0.47
    study                              SIGINT     130   0.47 /   0.52 /   0.57
    study                              SIGTERM    143   0.52 /   0.54 /   0.57
    contact windows --workers 2 (group) SIGINT     130   0.27 /   0.29 /   0.32
    contact windows --workers 2 (group) SIGTERM    143   0.26 /   0.29 /   0.32
    study --workers 2 (group)          SIGINT     130   0.52 /   0.52 /   0.52
    study --workers 2 (group)          SIGTERM    143   0.42 /   0.44 /   0.47

At load 6 to 10 the single-process commands took 0.3 to 3.2 s and the cluster runs 0.7 to
3.2 s; before the workers were killed on an early stop, a cluster run took 4.5 to 5.4 s
(16 s when a nanny restarted a worker the signal had reached).
"""
from __future__ import annotations

import argparse
import signal
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"


def measure(name: str, sig: int, settle: float, workers: int = 0) -> tuple[float, int]:
    """(seconds from ``sig`` to the exit, exit status) of one run of ``name``."""
    sys.path[:0] = [str(ROOT), str(TESTS)]      # this tree's package, in the children too
    from hostile import Running
    from test_cli_signals import long_runs
    with tempfile.TemporaryDirectory() as tmp:
        argv, _ = long_runs(Path(tmp))[name]
        argv = [str(a) for a in argv]
        if workers:
            argv = argv[:argv.index("--workers")] if "--workers" in argv else argv
            argv += ["--workers", str(workers)]
        run = Running(*argv, cwd=tmp, group=bool(workers))
        run.wait_progress(above=0.0 if name == "study" else None)
        time.sleep(settle)
        run.send(sig)
        status, err, _ = run.finish()
        if status not in (130, 143):
            raise SystemExit(f"{name}: exit {status}: {err.strip()}")
        return run.took, status


CASES = [("derive", 0), ("contact windows", 0), ("slide", 0), ("slide --body", 0),
         ("risk", 0), ("study", 0), ("contact windows", 2), ("study", 2)]


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=1, help="runs per command and signal")
    ap.add_argument("--settle", type=float, default=1.0,
                    help="seconds between the first progress line and the signal")
    ap.add_argument("--only", nargs="+", default=None, help="command names (see CASES)")
    a = ap.parse_args(argv)
    print(f"{'command':34s} {'signal':7s} {'status':6s} seconds to exit (min / median / max)")
    for name, workers in CASES:
        if a.only and name not in a.only:
            continue
        label = name + (f" --workers {workers} (group)" if workers else "")
        for sig in (signal.SIGINT, signal.SIGTERM):
            runs = [measure(name, sig, a.settle, workers) for _ in range(a.repeats)]
            t = [x for x, _ in runs]
            print(f"{label:34s} {sig.name:7s} {runs[0][1]:6d} {min(t):6.2f} / "
                  f"{statistics.median(t):6.2f} / {max(t):6.2f}", flush=True)


if __name__ == "__main__":
    main()
