"""The study engine on real Dask clusters (issue 12), all on 127.0.0.1: the same results
in this process, on a LocalCluster of 2 workers and on an external cluster started with
`dask scheduler` / `dask worker`, for any batch size; a client killed with SIGKILL and
rerun, a worker killed mid-study, Ctrl-C; the store refusing another study; export."""
from __future__ import annotations

import contextlib
import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from cli_run import run
from hostile import assert_refused, cli, package_env

from asperity.study.run import run_study_file

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
FIELDS = "case_id, status, message, verdict, mu_plus, mu_minus, drift_per_cycle_m, " \
         "cycles_to_tolerance, \"texture.alpha_deg\", \"loading.dT_max\""

SMALL = """
[study]
kind = "latin-hypercube"
samples = 300
seed = 9
texture = "SURF/wedge-asymmetric.toml"
assembly = "SURF/bushing-strip.toml"
[parameters]
"texture.alpha_deg" = { distribution = "normal", mean = 30.0, sd = 1.5 }
"texture.mu_alpha" = { distribution = "uniform", low = 0.08, high = 0.12 }
"loading.dT_max" = { distribution = "uniform", low = 20.0, high = 140.0 }
"""
# ~3 ms a case (a star-law fit of 72 directions): long enough to be interrupted
SLOW = """
[study]
kind = "monte-carlo"
samples = N
seed = 3
stages = ["fit", "risk"]
texture = "SURF/wedge-asymmetric.toml"
assembly = "SURF/bushing-strip.toml"
[parameters]
"texture.alpha_deg" = { distribution = "normal", mean = 30.0, sd = 1.5 }
"loading.dT_max" = { distribution = "uniform", low = 20.0, high = 140.0 }
"""


def study_file(tmp_path: Path, body: str, name="s.toml", n=None) -> Path:
    p = tmp_path / name
    p.write_text(body.replace("SURF", str(SURF)).replace("samples = N", f"samples = {n}"))
    return p


def stored(folder: Path, fields: str = FIELDS) -> list[tuple]:
    con = sqlite3.connect(folder / "study.sqlite")
    try:
        return con.execute(f"SELECT {fields} FROM cases ORDER BY case_id").fetchall()
    finally:
        con.close()


def count(folder: Path) -> int:
    try:
        con = sqlite3.connect(folder / "study.sqlite", timeout=5)
        try:
            return con.execute("SELECT COUNT(*) FROM cases").fetchone()[0]
        finally:
            con.close()
    except sqlite3.Error:
        return 0


def wait_for(cond, timeout=120.0, every=0.05):
    t0 = time.monotonic()
    while not cond():
        if time.monotonic() - t0 > timeout:
            raise AssertionError("timed out")
        time.sleep(every)


def test_same_results_in_process_any_batch_size_and_on_two_local_workers(tmp_path):
    f = study_file(tmp_path, SMALL)
    ref = run_study_file(f, tmp_path / "a", workers=0, batch_size=1)
    run_study_file(f, tmp_path / "b", workers=0, batch_size=7)
    two = run_study_file(f, tmp_path / "c", workers=2)
    assert two["run"]["where"] == "LocalCluster (2 workers)" and two["run"]["ran"] == 300
    a, b, c = (stored(tmp_path / x) for x in "abc")
    assert len(a) == 300 and {r[1] for r in a} == {"ok"}
    assert a == b == c
    assert {k: v for k, v in ref.items() if k not in ("store", "run", "figures")} == \
        {k: v for k, v in two.items() if k not in ("store", "run", "figures")}
    assert set(ref["verdicts"]) >= {"ratchet", "alternating-slip"}


# ----------------------------------------------------------------------------- external cluster

@contextlib.contextmanager
def external_cluster(tmp_path: Path, n_workers: int = 2):
    """`dask scheduler` and ``n_workers`` `dask worker` processes on 127.0.0.1 (stopped at
    the end); yields (scheduler file, worker processes)."""
    sched = tmp_path / "scheduler.json"
    env = package_env({"DASK_LOGGING__DISTRIBUTED": "error"})
    procs = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1",
                               "--port", "0", "--no-dashboard", "--scheduler-file", str(sched)],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    workers = []
    try:
        wait_for(lambda: sched.exists() and sched.stat().st_size > 0, 60)
        for _ in range(n_workers):
            workers.append(subprocess.Popen(
                [sys.executable, "-m", "dask", "worker", "--scheduler-file", str(sched),
                 "--host", "127.0.0.1", "--nthreads", "1", "--no-dashboard"], env=env,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        procs += workers
        from distributed import Client
        with Client(scheduler_file=str(sched), timeout="20s") as c:
            c.wait_for_workers(n_workers, timeout=60)
            address = c.scheduler.address
        assert address.startswith("tcp://127.0.0.1:")
        yield sched, address, workers
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


@pytest.mark.slow
def test_external_cluster_through_scheduler_and_a_worker_killed_mid_study(tmp_path):
    f = study_file(tmp_path, SMALL)
    run_study_file(f, tmp_path / "ref", workers=0)
    slow = study_file(tmp_path, SLOW, "slow.toml", n=800)
    with external_cluster(tmp_path) as (sched_file, address, workers):
        # the same command as on a laptop, sent to the cluster by its address
        status, out, err = cli("study", f, "-o", tmp_path / "ext", "--scheduler", address,
                               "--json", timeout=300)
        assert status == 0, err
        s = json.loads(out)
        assert s["run"]["where"] == address and s["run"]["workers"] == 2
        assert stored(tmp_path / "ext") == stored(tmp_path / "ref")
        # a worker dies (SIGKILL to `dask worker` and its process): the study completes
        p = subprocess.Popen([sys.executable, "-m", "asperity", "study", str(slow), "-o",
                              str(tmp_path / "kill"), "--batch-size", "20", "--json"],
                             env=package_env({"ASPERITY_SCHEDULER": str(sched_file)}),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        wait_for(lambda: count(tmp_path / "kill") >= 150 or p.poll() is not None)
        assert p.poll() is None, p.communicate()
        workers[0].send_signal(signal.SIGKILL)
        out, err = p.communicate(timeout=300)
        assert p.returncode == 0, err
    s = json.loads(out)
    assert s["completed"] == 800 and s["stored"] == 800 and s["failed"] == 0
    rows = stored(tmp_path / "kill", "case_id")
    assert [r[0] for r in rows] == list(range(800))


@pytest.mark.slow
def test_client_killed_with_sigkill_then_rerun_gives_every_case_once(tmp_path):
    f = study_file(tmp_path, SLOW, n=1200)
    out = tmp_path / "out"
    argv = [sys.executable, "-m", "asperity", "study", str(f), "-o", str(out), "--workers",
            "2", "--batch-size", "10"]
    p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         env=package_env())
    wait_for(lambda: count(out) >= 150 or p.poll() is not None)
    assert p.poll() is None, p.communicate()
    family = _descendants(p.pid)
    assert len(family) >= 2                       # the LocalCluster's worker processes
    p.send_signal(signal.SIGKILL)
    p.wait()
    n_killed = count(out)
    assert 150 <= n_killed < 1200
    # the workers watch their parent (asperity.lifeline): gone within seconds, nothing
    # written after the kill
    wait_for(lambda: not any(os.path.exists(f"/proc/{c}") for c in family), 5)
    time.sleep(0.5)
    assert count(out) == n_killed
    status, o, err = cli("study", f, "-o", out, "--workers", "2", "--json", timeout=600)
    assert status == 0, err
    s = json.loads(o)
    assert s["run"]["ran"] == 1200 - n_killed and s["completed"] == 1200
    run_study_file(f, tmp_path / "ref", workers=0)
    assert stored(out) == stored(tmp_path / "ref")


def _descendants(pid: int) -> list[int]:
    out, todo = [], [pid]
    while todo:
        q = todo.pop()
        kids = []
        for task in Path(f"/proc/{q}/task").glob("*"):
            try:
                kids += [int(x) for x in (task / "children").read_text().split()]
            except OSError:
                pass
        out += kids
        todo += kids
    return out


@pytest.mark.slow
def test_ctrl_c_stops_a_study_in_one_line_and_the_rerun_resumes(tmp_path):
    f = study_file(tmp_path, SLOW, n=600)
    out = tmp_path / "out"
    p = subprocess.Popen([sys.executable, "-m", "asperity", "study", str(f), "-o", str(out),
                          "--workers", "0", "--batch-size", "20"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=package_env())
    wait_for(lambda: count(out) >= 100 or p.poll() is not None, timeout=600)
    p.send_signal(signal.SIGINT)
    o, err = p.communicate(timeout=300)    # how soon: benchmarks/bench_interrupts.py
    assert p.returncode == 130 and err.count("\n") == 1 and "Traceback" not in err, err
    assert "cases stored in" in err and "run the same command again to resume" in err, err
    n = count(out)
    assert 100 <= n < 600
    s = run_study_file(f, out, workers=0)
    assert s["run"]["ran"] == 600 - n and s["completed"] == 600


# ----------------------------------------------------------------------------- store, CLI

def test_store_refuses_another_study_and_summarises_and_exports(tmp_path, capsys):
    import pyarrow.parquet as pq
    f = study_file(tmp_path, SMALL)
    out = tmp_path / "out"
    code, o, err = run(capsys, "study", f, "-o", out, "--workers", "0", "--json")
    assert code == 0, err
    first = json.loads(o)
    assert first["cases"] == 300 and first["stored"] == 300 and first["missing"] == 0
    for k in ("cases", "completed", "failed", "verdicts", "p_ratchet", "drift_per_cycle_m",
              "store"):
        assert k in first
    assert set(first["p_ratchet"]) == {"estimate", "low", "high"}
    assert set(first["drift_per_cycle_m"]) == {"p05", "p50", "p95"}
    # rerun: nothing to run, same summary
    code, o, err = run(capsys, "study", f, "-o", out, "--workers", "0", "--json")
    again = json.loads(o)
    assert again["run"]["ran"] == 0 and again["verdicts"] == first["verdicts"]
    # the folder alone gives the summary and exports one row per case
    code, o, err = run(capsys, "study", out, "--export", tmp_path / "cases.parquet", "--json")
    assert code == 0, err
    t = pq.read_table(tmp_path / "cases.parquet")
    assert t.num_rows == 300 and t.column("case_id").to_pylist() == list(range(300))
    assert t.column("verdict").to_pylist() == [r[3] for r in stored(out)]
    code, o, err = run(capsys, "study", out, "--export", tmp_path / "cases.csv")
    lines = (tmp_path / "cases.csv").read_text().splitlines()
    assert lines[0].startswith("case_id,texture.alpha_deg,") and len(lines) == 301
    # a changed study on the same folder is refused in one line, the store untouched
    before = (out / "study.sqlite").read_bytes()
    f.write_text(f.read_text().replace("seed = 9", "seed = 10"))
    code, o, err = run(capsys, "study", f, "-o", out, "--workers", "0")
    assert code == 1 and "holds a different study" in err and err.count("\n") == 1
    assert (out / "study.sqlite").read_bytes() == before


BAD = [
    ("[study]\nkind = \"monte-carlo\"\nseed = 1\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"loading.dT_max\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "study.samples missing"),
    ("[study]\nkind = \"grdi\"\n", "study.kind must be one of"),
    ("[study]\nkind = \"sobol\"\nsamples = 1000\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"loading.dT_max\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n"
     "\"assembly.N\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "power of 2"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"loading.dT_mx\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "loading.dT_mx"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"loading.dT_max\" = { distribution = \"normal\", mean = 1.0, sd = -2.0 }\n",
     "parameters.loading.dT_max.sd must be in (0, "),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"loading.dT_max\" = { distribution = \"uniform\", low = \"1\", high = 2.0 }\n",
     "parameters.loading.dT_max.low must be a number"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nassembly = \"SURF/two-node-spec.toml\"\n"
     "[parameters]\n\"assembly.k\" = { distribution = \"uniform\", low = -5.0, high = -1.0 }\n",
     "assembly.k must be in"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nassembly = \"missing.toml\"\n"
     "[parameters]\n\"loading.dT_max\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "does not exist"),
    ("[study]\nkind = \"files\"\nfiles = [\"nothing-*.x3p\"]\n", "matches no file"),
    ("[study]\nkind = \"grid\"\nassembly = \"SURF/two-node-spec.toml\"\n[parameters]\n"
     "\"loading.dT_max\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "not a distribution"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nstages = [\"derive\"]\n"
     "assembly = \"SURF/two-node-spec.toml\"\n[parameters]\n"
     "\"loading.dT_max\" = { distribution = \"uniform\", low = 1.0, high = 2.0 }\n",
     "derive and fit need a texture"),
    ("[study]\nkind = \"monte-carlo\"\nsamples = 10\nbatch = 5\n", "unknown key study.batch"),
    ("[study\nkind = 1\n", "not valid TOML"),
    ("[study]\nkind = \"files\"\nfiles = [\"SURF/wedge-30-10.stl\"]\nunit = \"furlong\"\n",
     "study.unit must be one of"),
    ("[study]\nkind = \"files\"\nfiles = [\"SURF/wedge-30-10.stl\"]\nunit = \"um\"\n"
     "max_slope = 95\n", "study.max_slope must be in (0, 90)"),
    ("[study]\nkind = \"grid\"\nassembly = \"SURF/two-node-spec.toml\"\n[parameters]\n"
     "\"loading.dT_max\" = { low = 1.0, high = 2.0, n = 100000 }\n"
     "\"assembly.N\" = { low = 1.0, high = 2.0, n = 100000 }\n", "at most 1e+07"),
]


@pytest.mark.parametrize("body,msg", BAD, ids=[m for _, m in BAD])
def test_bad_study_files_are_refused_in_one_line(tmp_path, capsys, body, msg):
    f = study_file(tmp_path, body)
    code, out, err = run(capsys, "study", f, "-o", tmp_path / "out", "--workers", "0")
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err
    assert not (tmp_path / "out" / "study.sqlite").exists()


def test_bad_targets_and_flags_are_refused_in_one_line(tmp_path, capsys):
    f = study_file(tmp_path, SMALL)
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "notes.txt").write_text("mine")
    (tmp_path / "afile").write_text("x")
    cases = [
        (["study", f, "-o", tmp_path / "full", "--workers", "0"], "not empty and holds no study"),
        (["study", f, "-o", tmp_path / "afile", "--workers", "0"], "is not a folder"),
        (["study", tmp_path / "nothing-here"], "give a study file (.toml) or a study folder"),
        (["study", tmp_path / "full"], "holds no study"),
        (["study", f, "--workers", "-1"], "--workers must be a whole number in [0, 4096]"),
        (["study", f, "--batch-size", "0"], "--batch-size must be a whole number"),
        (["study", f, "-o", tmp_path / "o2", "--scheduler", "tcp://127.0.0.1:9"],
         "nothing listens on 127.0.0.1:9"),
        (["study", f, "-o", tmp_path / "o3", "--workers", "0", "--export", tmp_path / "x.xlsx"],
         "--export writes .parquet or .csv"),
    ]
    for argv, msg in cases:
        code, out, err = run(capsys, *argv)
        assert code == 1 and msg in err and err.count("\n") == 1, (argv, err)
    assert (tmp_path / "full" / "notes.txt").read_text() == "mine"
    assert not (tmp_path / "o2").exists()
    assert_refused(cli("study", f, "--workers", "2", "--scheduler", "tcp://127.0.0.1:9"),
                   code=2, contains="not allowed with argument")


def test_risk_map_on_two_workers_equals_the_in_process_map(capsys):
    argv = ["risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip-mild.toml", "--map",
            "alpha=5:40:3", "beta=5:40:3", "--json"]
    code, a, err = run(capsys, *argv)
    assert code == 0, err
    code, b, err = run(capsys, *argv, "--workers", "2")
    assert code == 0, err
    assert json.loads(a) == json.loads(b)


@pytest.mark.slow
def test_a_case_that_kills_its_workers_is_isolated_and_stored_as_failed(tmp_path):
    import dask
    from study_crash import CRASH_CASE, crashing_batch

    from asperity.study.engine import run_study
    from asperity.study.spec import load_study
    from asperity.study.store import open_store
    study = load_study(study_file(tmp_path, SMALL.replace("samples = 300", "samples = 40")))
    store = open_store(tmp_path / "out", study)
    try:
        with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
            rep = run_study(study, store, workers=2, batch_size=8, task=crashing_batch)
    finally:
        store.close()
    assert rep.ran == 40
    rows = stored(tmp_path / "out", "case_id, status, message")
    assert [r[0] for r in rows] == list(range(40))
    bad = [r for r in rows if r[1] != "ok"]
    assert [r[0] for r in bad] == [CRASH_CASE], bad
    assert "died, also when it ran alone" in bad[0][2]


# ----------------------------------------------------------------------------- scan libraries

SCANS = """
[study]
kind = "files"
files = ["scan*.npy"]
unit = "um"
pixel_size = 1.0
mu = 0.1
stages = ["derive"]
directions = 36
"""


def test_a_scan_library_on_two_local_workers_stores_what_this_process_stores(tmp_path):
    """The workers warm up on a synthetic scan (asperity.study.warm) and run without Dask's
    profiler and with glibc's own malloc thresholds: every stored output stays that of the
    in-process run, bit for bit."""
    import numpy as np
    rng = np.random.default_rng(5)
    for i in range(6):
        z = np.cumsum(rng.normal(size=(40, 56)), axis=1) * 0.03 * (1 + i)
        np.save(tmp_path / f"scan{i}.npy", (z + np.cumsum(rng.normal(size=(40, 56)), axis=0)
                                            * 0.01).astype(np.float32))
    f = study_file(tmp_path, SCANS)
    run_study_file(f, tmp_path / "a", workers=0)
    two = run_study_file(f, tmp_path / "b", workers=2)
    assert two["run"]["where"] == "LocalCluster (2 workers)" and two["run"]["ran"] == 6
    a, b = (cases_but_seconds(tmp_path / x) for x in "ab")
    assert len(a) == 6 and {r["status"] for r in a} == {"ok"}
    assert all(0 < r["mu_a_plus"] < 1 and r["anisotropy"] > 0 for r in a)
    assert a == b


def cases_but_seconds(folder: Path) -> list[dict]:
    con = sqlite3.connect(folder / "study.sqlite")
    con.row_factory = sqlite3.Row
    try:
        return [{k: r[k] for k in r.keys() if k != "seconds"}   # noqa: SIM118 (a Row)
                for r in con.execute("SELECT * FROM cases ORDER BY case_id")]
    finally:
        con.close()


def test_local_workers_run_without_the_profiler_and_with_glibcs_malloc_thresholds():
    from asperity.study.clusters import cluster
    with cluster(None, 1) as (client, _where, _n):
        got = client.run(lambda: (__import__("dask").config.get(
            "distributed.worker.profile.enabled"), os.environ.get("MALLOC_TRIM_THRESHOLD_"),
            os.environ.get("NUMBA_NUM_THREADS")))
    assert list(got.values()) == [(False, None, "1")]


def test_the_warm_up_scan_runs_the_study_options_and_a_failure_stays_a_status(tmp_path):
    from asperity.study.cases import run_case
    from asperity.study.spec import load_study
    from asperity.study.warm import synthetic_scan
    (tmp_path / "scan0.npy").write_bytes(b"")          # named only: the warm-up reads its own
    spec = load_study(study_file(tmp_path, SCANS)).spec

    def status(surface):
        with synthetic_scan({**spec, "surface": surface}) as (s, path):
            got = run_case(s, {}, path)
        assert not os.path.exists(path)
        return got[0], got[3]

    st, out = status(spec["surface"])
    assert st == "ok" and 0 < out["mu_a_plus"] < 1
    assert status({"mu": 0.1})[0] == "ok"              # e.g. an x3p library: um, 1 um pixels
    assert status({"max_slope": 1e-3})[0] == "failed"  # every facet dropped
