"""Processes die with their parent, locks are never stuck, local workers fit the machine,
and a scheduler that cannot be used is refused before anything is created (issue 18,
sections 3, 4 and the locks of section 10).

Every command here runs in a child process of the package under test (its folder first on
the path), in a session of its own whose processes are all killed when the test ends,
however it ends; the child itself gets SIGKILL if the test process dies (conftest.py).
A test that kills a parent collects the parent's process tree first (from /proc,
independently of asperity's own code) and asserts that every process of it is gone a few
seconds later.
"""
from __future__ import annotations

import contextlib
import json
import os
import signal
import socket
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from cli_run import run

import asperity

TESTS = Path(__file__).resolve().parent
PKG_ROOT = Path(asperity.__file__).resolve().parents[1]      # the package under test
SURF = TESTS.parent / "surfaces"
#: seconds the processes of a killed parent may take to go
GONE_WITHIN = 5.0

# ~3 ms a case (a star-law fit of 72 directions, then the strip's verdict)
SLOW = """
[study]
kind = "monte-carlo"
samples = {n}
seed = 3
stages = ["fit", "risk"]
texture = "{texture}"
assembly = "{assembly}"
[parameters]
"texture.alpha_deg" = {{ distribution = "normal", mean = 30.0, sd = 1.5 }}
"loading.dT_max" = {{ distribution = "uniform", low = 20.0, high = 140.0 }}
"""


def study_file(folder: Path, n: int, name: str = "s.toml", plain: bool = False) -> Path:
    """A study of ``n`` cases (``plain``: it names its texture and assembly by plain
    names, as the web page wants, and they are copied beside it)."""
    if plain:
        for f in ("wedge-asymmetric.toml", "bushing-strip.toml"):
            (folder / f).write_text((SURF / f).read_text())
    tex, asm = (("wedge-asymmetric.toml", "bushing-strip.toml") if plain else
                (SURF / "wedge-asymmetric.toml", SURF / "bushing-strip.toml"))
    p = folder / name
    p.write_text(SLOW.format(n=n, texture=tex, assembly=asm))
    return p


# ----------------------------------------------------------------------------- processes

class Proc:
    """``python -m asperity ARGV`` (or ``python -c CODE``) of the package under test, in a
    session of its own; ``close()`` kills whatever of that session is left."""

    def __init__(self, *argv, code: str | None = None, env=None, stdout=subprocess.DEVNULL):
        e = dict(os.environ, **(env or {}))
        e["PYTHONPATH"] = os.pathsep.join([str(PKG_ROOT), str(TESTS)])
        e.pop("ASPERITY_DEBUG", None)
        e.pop("ASPERITY_SCHEDULER", None)
        cmd = [sys.executable, "-c", code] if code else \
            [sys.executable, "-m", "asperity", *map(str, argv)]
        self.p = subprocess.Popen(cmd, cwd=str(PKG_ROOT), env=e, stdout=stdout,
                                  stderr=subprocess.PIPE, text=True, start_new_session=True)
        self.pid = self.p.pid
        self.err: list[str] = []
        self._t = threading.Thread(target=self._drain, daemon=True)
        self._t.start()

    def _drain(self):
        for line in self.p.stderr:
            self.err.append(line)

    def stderr(self) -> str:
        self._t.join(10)
        return "".join(self.err)

    def close(self):
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(self.pid, signal.SIGKILL)
        with contextlib.suppress(Exception):
            self.p.wait(10)


@contextlib.contextmanager
def started(*argv, **kw):
    p = Proc(*argv, **kw)
    try:
        yield p
    finally:
        p.close()


def first_line(proc: Proc, timeout: float = 60.0) -> str:
    """The first line ``proc`` prints on stdout ('' if none within ``timeout``)."""
    line = [""]
    t = threading.Thread(target=lambda: line.__setitem__(0, proc.p.stdout.readline()),
                         daemon=True)
    t.start()
    t.join(timeout)
    return line[0]


def _ppids() -> dict[int, int]:
    """pid -> parent pid of every live process (from /proc/PID/stat; zombies left out)."""
    out = {}
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat", encoding="ascii", errors="replace") as fh:
                rest = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if rest[0] != "Z":
            out[int(d)] = int(rest[1])
    return out


def tree(pid: int) -> set[int]:
    """The descendants of ``pid`` now."""
    ppids = _ppids()
    found, todo = set(), [pid]
    while todo:
        q = todo.pop()
        kids = [c for c, pp in ppids.items() if pp == q and c not in found]
        found.update(kids)
        todo += kids
    return found


def alive(pids) -> set[int]:
    live = _ppids()
    return {p for p in pids if p in live}


def wait_gone(pids, timeout: float = GONE_WITHIN) -> float:
    """Seconds until none of ``pids`` lives; AssertionError naming the survivors."""
    t0 = time.monotonic()
    while alive(pids):
        if time.monotonic() - t0 > timeout:
            left = alive(pids)
            names = {p: Path(f"/proc/{p}/cmdline").read_bytes()[:80] for p in left
                     if os.path.exists(f"/proc/{p}")}
            raise AssertionError(f"still alive {timeout} s after their parent died: {names}")
        time.sleep(0.02)
    return time.monotonic() - t0


def wait_for(cond, timeout: float = 120.0, proc: Proc | None = None):
    t0 = time.monotonic()
    while True:
        v = cond()
        if v:
            return v
        if proc is not None and proc.p.poll() is not None:
            raise AssertionError(f"exited with {proc.p.returncode}: {proc.stderr()}")
        if time.monotonic() - t0 > timeout:
            raise AssertionError("timed out")
        time.sleep(0.05)


def case_ids(folder: Path) -> list[int]:
    """The stored case ids, duplicates included (an independent read of the store)."""
    try:
        if not (folder / "study.sqlite").is_file():
            return []
        con = sqlite3.connect(folder / "study.sqlite", timeout=5)
        try:
            return [r[0] for r in con.execute("SELECT case_id FROM cases ORDER BY case_id")]
        finally:
            con.close()
    except sqlite3.Error:
        return []


def sigkill(proc: Proc) -> tuple[set[int], float]:
    """Kill ``proc`` with SIGKILL; (its descendants before the kill, seconds until the last
    of them was gone)."""
    family = tree(proc.pid)
    proc.p.send_signal(signal.SIGKILL)
    proc.p.wait(10)
    return family, wait_gone(family)


# ----------------------------------------------------------------------------- section 3

@pytest.mark.slow
def test_dask_workers_die_with_the_client_even_inside_a_kernel(tmp_path):
    """A study's LocalCluster workers busy in code that holds the interpreter lock (as the
    compiled kernels do) still die at once with the client killed by SIGKILL."""
    f = study_file(tmp_path, 8)
    marks = tmp_path / "marks"
    marks.mkdir()
    code = (f"from asperity.study.spec import load_study\n"
            f"from asperity.study.store import open_store\n"
            f"from asperity.study.engine import run_study\n"
            f"from gil_hog import hogging_batch\n"
            f"s = load_study({str(f)!r})\n"
            f"run_study(s, open_store({str(tmp_path / 'out')!r}, s), workers=2, "
            f"batch_size=1, task=hogging_batch)\n")
    with started(code=code, env={"ASPERITY_TEST_MARKS": str(marks)}) as p:
        wait_for(lambda: len(list(marks.iterdir())) >= 2, 120, p)
        hogs = {int(m.name) for m in marks.iterdir()}
        family, took = sigkill(p)
        assert hogs <= family and len(family) >= 3       # 2 workers + a resource tracker
    assert took < GONE_WITHIN


@pytest.mark.slow
def test_serve_killed_mid_study_takes_its_workers_and_the_restart_finishes_it(tmp_path):
    """`asperity serve` killed with SIGKILL while a study runs on a local cluster of two
    workers in its worker process: every process of it goes, no row is written after, and
    the restarted server finishes the job with every case exactly once."""
    httpx = pytest.importorskip("httpx")
    n = 1200
    files = tmp_path / "files"
    files.mkdir()
    f = study_file(files, n, plain=True)
    data = tmp_path / "data"

    def serve():
        p = Proc("serve", "--port", "0", "--workers", "1", "--data-dir", data,
                 stdout=subprocess.PIPE, env={"PYTHONUNBUFFERED": "1"})
        line = first_line(p)
        if not line.startswith("asperity serve: http"):
            p.close()
            raise AssertionError(f"asperity serve did not start: {p.stderr()}")
        return p, line.split(": ", 1)[1].strip().rstrip("/")

    first, url = serve()
    try:
        up = [("study", (f.name, f.read_bytes()))] + [
            ("companions", (c, (files / c).read_bytes()))
            for c in ("wedge-asymmetric.toml", "bushing-strip.toml")]
        r = httpx.post(f"{url}/studies", files=up, data={"workers": "2"}, timeout=60)
        assert r.status_code == 303, r.text[:300]
        jid = r.headers["location"].rsplit("/", 1)[-1]
        store = data / "jobs" / jid / "study"
        wait_for(lambda: len(case_ids(store)) >= 150, 180, first)
        family, took = sigkill(first)
        assert len(family) >= 3                  # the worker, its 2 Dask workers, trackers
    finally:
        first.close()
    assert took < GONE_WITHIN
    after = len(case_ids(store))
    assert after < n
    time.sleep(1.0)
    assert len(case_ids(store)) == after         # nobody writes into the store any more
    second, url = serve()                        # the lock on the data folder is free
    try:
        t0 = time.monotonic()
        while httpx.get(f"{url}/api/jobs/{jid}", timeout=30).json()["status"] in (
                "queued", "running"):
            assert time.monotonic() - t0 < 300, "the re-queued job did not finish"
            time.sleep(0.2)
        assert httpx.get(f"{url}/api/jobs/{jid}", timeout=30).json()["status"] == "done", \
            second.stderr()
        workers = tree(second.pid)
        second.p.send_signal(signal.SIGINT)
        assert second.p.wait(30) == 0
        wait_gone(workers)
    finally:
        second.close()
    ids = case_ids(store)
    assert ids == list(range(n))                 # every case once: none twice, none missing
    rows = (data / "jobs" / jid / "cases.csv").read_text().splitlines()
    assert len(rows) == n + 1


@pytest.mark.slow
def test_a_tiled_derive_killed_takes_its_workers_and_runs_again(tmp_path):
    import numpy as np
    rng = np.random.default_rng(4)
    np.save(tmp_path / "big.npy", rng.normal(size=(800, 800)).astype(np.float32))
    argv = ["derive", tmp_path / "big.npy", "--unit", "um", "--pixel-size", "1",
            "--tile-rows", "50", "--workers", "2"]
    with started(*argv, "--directions", "20000") as p:
        def busy():                          # two worker processes at work on tiles
            kids = tree(p.pid)
            return len([k for k in kids if _cpu_seconds(k) > 1.5]) >= 2 and kids
        wait_for(busy, 180, p)
        family, took = sigkill(p)
    assert len(family) >= 3 and took < GONE_WITHIN
    with started(*argv, "--directions", "16", "--json", stdout=subprocess.PIPE) as p:
        o, _ = p.p.communicate(timeout=300)
        assert p.p.returncode == 0, p.stderr()
    assert json.loads(o)["tiling"]["workers"] == 2


def _cpu_seconds(pid: int) -> float:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as fh:
            f = fh.read().rsplit(")", 1)[1].split()
        return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return 0.0


# ----------------------------------------------------------------------------- locks

@pytest.mark.slow
def test_two_studies_on_one_folder_exclude_each_other_and_a_killed_one_frees_it(tmp_path):
    f = study_file(tmp_path, 20000)
    out = tmp_path / "out"
    with started("study", f, "-o", out, "--workers", "0") as first:
        wait_for(lambda: len(case_ids(out)) > 0, 120, first)
        with started("study", f, "-o", out, "--workers", "0") as second:
            assert second.p.wait(60) == 1
            err = second.stderr()
        assert err.count("\n") == 1 and "Traceback" not in err, err
        assert "another asperity study is running on this folder" in err
        assert f"(process {first.pid})" in err
        assert first.p.poll() is None                # the first goes on
        sigkill(first)
    n = len(case_ids(out))
    # the kernel freed the lock with the killed run: the next one takes it and resumes
    with started("study", f, "-o", out, "--workers", "0", "--json",
                 stdout=subprocess.PIPE) as third:
        wait_for(lambda: len(case_ids(out)) > n + 100, 120, third)
        third.p.send_signal(signal.SIGINT)
        assert third.p.wait(60) == 130, third.stderr()
    assert len(set(case_ids(out))) == len(case_ids(out))


def test_two_servers_on_one_data_folder_exclude_each_other(tmp_path):
    data = tmp_path / "data"

    def serve(*extra):
        return Proc("serve", "--port", "0", "--workers", "1", "--data-dir", data, *extra,
                    stdout=subprocess.PIPE)
    with contextlib.ExitStack() as stack:
        first = serve("--workers", "64")
        stack.callback(first.close)
        assert first_line(first).startswith("asperity serve: http"), first.stderr()
        cores = len(os.sched_getaffinity(0))
        if cores < 64:                               # said once, when the server starts
            wait_for(lambda: "64 workers asked (--workers)" in "".join(first.err), 30)
            assert f"64 workers asked (--workers), {cores} started: this machine has " \
                   f"{cores} core" in "".join(first.err)
        second = serve()
        stack.callback(second.close)
        assert second.p.wait(60) == 1
        err = second.stderr()
        assert err.count("\n") == 1 and "is in use by another asperity serve" in err, err
        assert f"(process {first.pid})" in err
        sigkill(first)
        third = serve()                              # free again at once
        stack.callback(third.close)
        assert first_line(third).startswith("asperity serve: http"), third.stderr()


HOLD = """
import os, sys, time
from asperity.locks import lock_file
fh = lock_file(sys.argv[1], RuntimeError("held"))
child = os.fork()
if child == 0:                        # a child inherits the locked descriptor
    time.sleep(120)
    os._exit(0)
print("locked", child, flush=True)
time.sleep(120 if sys.argv[2] == "stay" else 0)
"""


def test_a_lock_left_to_a_child_of_a_finished_holder_is_taken_over(tmp_path):
    from asperity.locks import lock_file
    lock = tmp_path / ".lock"
    code = HOLD.replace("sys.argv[1]", repr(str(lock)))
    with started(code=code.replace("sys.argv[2]", "'stay'"), stdout=subprocess.PIPE) as p:
        assert first_line(p).startswith("locked ")
        t0 = time.monotonic()
        with pytest.raises(RuntimeError, match=rf"^in use \(process {p.pid}\)$"):
            lock_file(lock, RuntimeError("in use"), wait=0.5)  # alive: refused after 0.5 s
        assert time.monotonic() - t0 >= 0.5
    with started(code=code.replace("sys.argv[2]", "'go'"), stdout=subprocess.PIPE) as p:
        child = int(first_line(p).split()[1])
        assert p.p.wait(30) == 0                     # the holder has ended, its child not
        import fcntl
        probe = open(lock)                           # the inherited descriptor still locks it
        with pytest.raises(OSError):
            fcntl.flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
        probe.close()
        fh = lock_file(lock, RuntimeError("in use"), wait=0.5)
        try:
            assert alive([child])                    # taken over, not given back
            assert lock.read_text().split()[0] == str(os.getpid())
            with pytest.raises(RuntimeError):        # and it is exclusive again
                lock_file(lock, RuntimeError("in use"), wait=0.2)
        finally:
            fh.close()


# ----------------------------------------------------------------------------- section 4

def test_local_workers_fit_the_cores_and_the_free_memory(monkeypatch):
    from asperity import resources as R
    monkeypatch.setattr(R, "cpu_cores", lambda: 8)
    gb = 1 << 30
    for free, asked, want in [(24 * gb, 1000, 8), (24 * gb, 3, 3), (24 * gb, None, 8),
                              (1 * gb, 1000, 5), (1 * gb, None, 5), (0, 4, 1)]:
        monkeypatch.setattr(R, "available_memory", lambda free=free: free)
        n, why = R.local_workers(asked, 150 << 20)
        assert n == want, (free, asked, n)
        fit = int(0.8 * free / (150 << 20))            # 80 % of the free memory
        assert n == max(1, min(8 if asked is None else asked, 8, fit))
        if n < (8 if asked is None else asked):
            assert why and f", {n} started:" in why and "\n" not in why
            assert ("8 cores" in why) == (n == 8)
        else:
            assert why is None


def test_study_with_1000_workers_starts_what_the_machine_allows(tmp_path, capsys,
                                                                   monkeypatch):
    from asperity import resources as R
    cores = len(os.sched_getaffinity(0))
    monkeypatch.setattr(R, "available_memory", lambda: int(3.5 * R.WORKER_BYTES / 0.8))
    f = study_file(tmp_path, 30)
    code, out, err = run(capsys, "study", f, "-o", tmp_path / "o", "--workers", "1000",
                         "--json")
    assert code == 0, err
    n = min(cores, 3)                      # memory for 3 workers of a parameter study
    assert json.loads(out)["run"]["where"] == f"LocalCluster ({n} workers)"
    why = f"this machine has {cores} core" if n == cores else "of memory is free"
    assert err.startswith(f"asperity study: 1000 workers asked (--workers), {n} started: ")
    assert why in err and err.endswith("; an existing cluster (--scheduler) has no such "
                                       "limit\n") and err.count("\n") == 1, err
    from asperity.web.settings import make_settings
    s = make_settings(workers=64)                # said when the server starts
    assert s.workers == n and s.workers_note.startswith(f"64 workers asked (--workers), {n} "
                                                        f"started: ")
    assert "--scheduler" not in s.workers_note and make_settings(workers=1).workers_note is None


class _Banner:
    """A TCP service on 127.0.0.1 that greets every connection with a line of text (as
    SSH or SMTP servers do), for the scheduler checks."""

    def __enter__(self):
        import socketserver

        class Greet(socketserver.BaseRequestHandler):
            def handle(self):
                self.request.sendall(b"SSH-2.0-OpenSSH_9.2\r\n")
        self.srv = socketserver.ThreadingTCPServer(("127.0.0.1", 0), Greet)
        self.srv.daemon_threads = True
        threading.Thread(target=self.srv.serve_forever, daemon=True).start()
        return f"tcp://127.0.0.1:{self.srv.server_address[1]}"

    def __exit__(self, *exc):
        self.srv.shutdown()
        self.srv.server_close()


class _Http:
    """An HTTP server on 127.0.0.1 (a free port) for the scheduler checks."""

    def __enter__(self):
        from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
        self.srv = ThreadingHTTPServer(("127.0.0.1", 0), BaseHTTPRequestHandler)
        threading.Thread(target=self.srv.serve_forever, daemon=True).start()
        return f"tcp://127.0.0.1:{self.srv.server_address[1]}"

    def __exit__(self, *exc):
        self.srv.shutdown()
        self.srv.server_close()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_bad_schedulers_are_refused_in_one_line_and_leave_nothing(tmp_path, capsys,
                                                                    monkeypatch):
    from asperity.study import clusters
    monkeypatch.setattr(clusters, "GREETING_SECONDS", 1.0)
    monkeypatch.chdir(tmp_path)
    f = study_file(tmp_path, 10)
    import numpy as np
    np.save(tmp_path / "scan.npy", np.random.default_rng(1).normal(size=(40, 40)))
    (tmp_path / "garbage.json").write_text("\x00garbage{")
    (tmp_path / "noaddr.json").write_text('{"type": "Scheduler"}')
    (tmp_path / "empty.json").write_text("")
    (tmp_path / "afolder").mkdir()
    free = _free_port()
    with _Http() as http, _Banner() as banner:
        cases = [("tcp://127.0.0.1:99999", "port 99999 is out of range"),
                 ("tcp://[::1", "without its ']'"),
                 ("tcp://127.0.0.1:x1", "port 'x1' is not a number"),
                 ("tcp://:8786", "no host"),
                 ("tcp://127.0.0.1:8786/path", "nothing after the port"),
                 (str(tmp_path / "garbage.json"), "not a Dask scheduler file"),
                 (str(tmp_path / "noaddr.json"), "holds no \"address\""),
                 (str(tmp_path / "empty.json"), "not a Dask scheduler file"),
                 (str(tmp_path / "afolder"), "is a folder"),
                 ("no-such-file.json", "no such scheduler file"),
                 (f"tcp://127.0.0.1:{free}", f"nothing listens on 127.0.0.1:{free}"),
                 (f"127.0.0.1:{free}", "connection refused"),
                 (http, "not a Dask scheduler (it sent no greeting"),
                 (banner, "not a Dask scheduler (it answers in another protocol: 'SSH-2.0-')")]
        before = sorted(p.name for p in tmp_path.iterdir())
        for address, msg in cases:
            for argv in (["study", f, "-o", tmp_path / "out"], ["study", f]):
                code, out, err = run(capsys, *argv, "--scheduler", address)
                assert code == 1 and out == "", (address, code, err)
                assert err.count("\n") == 1 and msg in err and repr(address) in err, err
                assert "internal error" not in err and "memory" not in err, err
            assert sorted(p.name for p in tmp_path.iterdir()) == before, address
        # the same check for the other commands that take --scheduler
        monkeypatch.setenv("ASPERITY_SCHEDULER", http)
        code, out, err = run(capsys, "study", f)
        assert code == 1 and "$ASPERITY_SCHEDULER" in err and "not a Dask scheduler" in err
        monkeypatch.delenv("ASPERITY_SCHEDULER")
        for argv in (["risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip-mild.toml",
                      "--map", "alpha=5:40:3", "beta=5:40:3"],
                     ["derive", tmp_path / "scan.npy", "--unit", "um", "--pixel-size", "1"]):
            code, out, err = run(capsys, *argv, "--scheduler", "tcp://127.0.0.1:99999")
            assert code == 1 and "port 99999 is out of range" in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_run_that_fails_before_its_first_case_leaves_the_folder_as_it_was(tmp_path,
                                                                             monkeypatch):
    from asperity.study import engine
    from asperity.study.run import run_study_file

    def refuse(*a, **k):
        raise engine.EngineError("no cluster today")
    monkeypatch.setattr(engine, "_connect", refuse)
    f = study_file(tmp_path, 10)
    with pytest.raises(engine.EngineError):
        run_study_file(f, tmp_path / "new" / "deep", workers=2)
    assert not (tmp_path / "new").exists()
    (tmp_path / "empty").mkdir()
    with pytest.raises(engine.EngineError):
        run_study_file(f, tmp_path / "empty", workers=2)
    assert list((tmp_path / "empty").iterdir()) == []
    run_study_file(f, tmp_path / "half", workers=0)   # a store with cases stays
    con = sqlite3.connect(tmp_path / "half" / "study.sqlite")
    with con:
        con.execute("DELETE FROM cases WHERE case_id >= 5")
    con.close()
    with pytest.raises(engine.EngineError):
        run_study_file(f, tmp_path / "half", workers=2)
    assert case_ids(tmp_path / "half") == [0, 1, 2, 3, 4]


def test_a_store_killed_before_its_tables_were_made_is_taken_as_new(tmp_path):
    """A kill between the creation of study.sqlite and its first transaction (or a reader
    that opened the file first) leaves a database without tables: the next run uses it."""
    from asperity.study.run import run_study_file
    f = study_file(tmp_path, 6)
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "study.sqlite").write_bytes(b"")
    (tmp_path / "header").mkdir()
    con = sqlite3.connect(tmp_path / "header" / "study.sqlite")
    con.execute("PRAGMA journal_mode=WAL")            # the header written, no table yet
    con.close()
    for folder in ("empty", "header"):
        s = run_study_file(f, tmp_path / folder, workers=0)
        assert s["run"]["ran"] == 6 and case_ids(tmp_path / folder) == list(range(6))


def test_folders_named_like_study_files_and_an_empty_data_folder_say_what_they_are(
        tmp_path, capsys):
    (tmp_path / "foo.toml").mkdir()
    (tmp_path / "empty").mkdir()
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "x.txt").write_text("x")
    for target, msg in [("foo.toml", "a folder named like a study file, not a study file"),
                        ("empty", "an empty folder, not a study folder"),
                        ("other", "a folder that holds no study")]:
        code, out, err = run(capsys, "study", tmp_path / target)
        assert code == 1 and err.count("\n") == 1 and msg in err, err
        assert "give a study file (.toml)" in err
    code, out, err = run(capsys, "serve", "--data-dir", "")
    assert code == 1 and err.count("\n") == 1 and "--data-dir is empty" in err, err
    code, out, err = run(capsys, "serve", "--data-dir", "  ")
    assert code == 1 and "--data-dir is empty" in err, err
