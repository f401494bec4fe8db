"""Helpers of the hostile-input suites: run the real command in a child process and judge
how it failed (one line on stderr, the right exit status, no traceback, no NaN), interrupt
it, limit its memory, or run it as an unprivileged user."""
from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import asperity

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
NON_FINITE = re.compile(r"\b(NaN|-?Infinity|nan|-?inf)\b")
#: the folder holding the package under test (the one these tests imported: the working
#: tree's, or the mutated copy of benchmarks/mutants.py), not necessarily ROOT
PACKAGE_PARENT = Path(asperity.__file__).resolve().parents[1]


def package_env(env=None) -> dict:
    """The environment of a child ``python -m asperity``: the package under test first
    on its path (give the child a cwd that holds no other ``asperity/``)."""
    e = dict(os.environ, **(env or {}))
    e["PYTHONPATH"] = os.pathsep.join([str(PACKAGE_PARENT)] + [
        p for p in e.get("PYTHONPATH", "").split(os.pathsep) if p])
    return e


def cli(*argv, cwd=None, timeout=120, env=None, preexec_fn=None, stdin=None):
    """(exit status, stdout, stderr) of ``python -m asperity ARGV`` in a child process
    (the package under test, whatever the cwd)."""
    e = package_env(env)
    e.pop("ASPERITY_DEBUG", None)
    p = subprocess.run([sys.executable, "-m", "asperity", *map(str, argv)], cwd=cwd, check=False,
                       capture_output=True, text=True, timeout=timeout, env=e,
                       preexec_fn=preexec_fn, stdin=stdin)
    return p.returncode, p.stdout, p.stderr


def assert_refused(result, *, code=1, contains=None):
    """A clean refusal: exit ``code``, nothing on stdout, exactly one line on stderr that
    names ``contains`` (a string or a list of strings), no traceback."""
    status, out, err = result
    assert "Traceback" not in err, err
    assert status == code, f"exit {status}, expected {code}: {err}"
    assert out == "", f"stdout not empty: {out[:200]}"
    assert err.count("\n") == 1 and err.endswith("\n"), f"not one line: {err!r}"
    for c in ([contains] if isinstance(contains, str) else contains or []):
        assert c in err, f"{c!r} not in {err!r}"


def assert_finite_output(text: str):
    """No NaN or infinity printed (JSON or text)."""
    m = NON_FINITE.search(text)
    assert m is None, f"non-finite value in output: ...{text[max(0, m.start() - 60):m.end() + 20]}"


#: a progress line of a command whose stderr is no terminal (asperity.progress)
PROGRESS_LINE = re.compile(r"^asperity [a-z]+: .*\d % after \d")


class Running:
    """``asperity ARGV`` in a child process whose stderr is a pipe, with a progress line
    every ``every`` seconds (``$ASPERITY_PROGRESS_EVERY``): :meth:`wait_progress` waits
    for the long work to be under way (an event, not a guess of how long start-up takes
    on a loaded machine), :meth:`send` signals it (``group``: its whole process group, as
    a terminal's Ctrl-C does), :meth:`finish` collects its exit status and stderr."""

    def __init__(self, *argv, cwd=None, every=0.2, group=False, env=None):
        import threading
        e = package_env({**(env or {}), "ASPERITY_PROGRESS_EVERY": str(every)})
        e.pop("ASPERITY_DEBUG", None)
        self.group = group
        self.p = subprocess.Popen([sys.executable, "-m", "asperity", *map(str, argv)],
                                  cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True, env=e, start_new_session=group)
        self.err: list[str] = []
        self.out: list[str] = []
        self.progress = threading.Event()
        self.sent_at = None
        self._readers = [threading.Thread(target=self._read, args=(s, k), daemon=True)
                         for s, k in ((self.p.stderr, self.err), (self.p.stdout, self.out))]
        for t in self._readers:
            t.start()

    def _read(self, stream, into):
        for line in stream:
            into.append(line)
            if into is self.err and PROGRESS_LINE.match(line):
                self.progress.set()
        if into is self.err:
            self.progress.set()                 # ended: wake a waiter

    def wait_progress(self, timeout=600, above=None):
        """Wait for the first progress line (with ``above``: the first past that percentage);
        the command must still be running."""
        t0 = time.monotonic()
        while not self._seen(above) and self.p.poll() is None:
            self.progress.clear()
            if self._seen(above):
                break
            if not self.progress.wait(max(0.0, timeout - (time.monotonic() - t0))):
                self.kill()
                raise AssertionError(f"no progress line within {timeout} s")
        if not self._seen(above) or self.p.poll() is not None:
            self.kill()
            raise AssertionError(f"ended before the progress line awaited (exit "
                                 f"{self.p.returncode}): {''.join(self.err)}")

    def _seen(self, above) -> bool:
        for x in list(self.err):
            if PROGRESS_LINE.match(x):
                m = re.search(r"(\d+(\.\d+)?) % after", x)
                if above is None or (m and float(m.group(1)) > above):
                    return True
        return False

    def send(self, sig, whole_group: bool | None = None):
        """Signal the command (its whole group: by default when started with ``group``)."""
        self.sent_at = time.perf_counter()
        if self.group if whole_group is None else whole_group:
            os.killpg(self.p.pid, sig)
        else:
            self.p.send_signal(sig)

    def group_gone(self, timeout=60.0) -> bool:
        """Whether every process of its group (Dask workers included) ends within
        ``timeout`` s (started with ``group``)."""
        t0 = time.monotonic()
        while time.monotonic() - t0 < timeout:
            if not group_members(self.p.pid):
                return True
            time.sleep(0.1)
        return False


    def finish(self, timeout=300):
        """(exit status, stderr without the progress lines, the progress lines); the
        seconds from the signal to the exit are in ``self.took``."""
        try:
            self.p.wait(timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(f"still running {timeout} s after the signal") from None
        self.took = None if self.sent_at is None else time.perf_counter() - self.sent_at
        for t in self._readers:
            t.join(30)
        lines = [x for x in self.err if not PROGRESS_LINE.match(x)]
        return self.p.returncode, "".join(lines), [x for x in self.err if x not in lines]

    def kill(self):
        if self.p.poll() is None:
            (os.killpg(self.p.pid, signal.SIGKILL) if self.group else self.p.kill())
            self.p.wait()


def group_members(pgid: int) -> list[int]:
    """The live (not zombie) processes of process group ``pgid`` (Linux /proc)."""
    out = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat", encoding="ascii", errors="replace") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if fields[0] != "Z" and int(fields[2]) == pgid:
            out.append(int(d))
    return out


def interrupt(*argv, sig=signal.SIGINT, cwd=None, group=False):
    """Start ``asperity ARGV``, wait for its first progress line (the long work is under
    way), send ``sig`` (Ctrl-C by default) and return (exit status, stderr without the
    progress lines).  Behaviour only: how soon it stops is measured by
    benchmarks/bench_interrupts.py, not asserted (a loaded machine makes any bound flaky)."""
    run = Running(*argv, cwd=cwd, group=group)
    run.wait_progress()
    run.send(sig)
    status, err, _ = run.finish()
    return status, err


def limit_memory(nbytes: int):
    """preexec_fn: the child may map at most ``nbytes`` of address space."""
    def apply():
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (nbytes, nbytes))
    return apply


def as_nobody():
    """preexec_fn: run the child as the unprivileged user nobody when we are root (so
    that permissions apply), else unchanged."""
    def apply():
        if os.geteuid() == 0:
            os.setgid(65534)
            os.setuid(65534)
    return apply


class read_only:
    """Make ``folder`` unwritable for the test's child processes, also when they run as
    root (for whom permission bits do not count): the immutable attribute (chattr +i) then,
    else the permission bits.  Restored on exit."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.how = None

    def __enter__(self):
        if os.geteuid() != 0:
            os.chmod(self.folder, 0o555)
            self.how = "chmod"
            return self
        r = subprocess.run(["chattr", "+i", str(self.folder)], capture_output=True, text=True,
                           check=False)
        if r.returncode != 0:
            raise RuntimeError(f"cannot make {self.folder} read-only as root: {r.stderr.strip()}")
        self.how = "chattr"
        return self

    def __exit__(self, *exc):
        if self.how == "chattr":
            subprocess.run(["chattr", "-i", str(self.folder)], check=True)
        elif self.how == "chmod":
            os.chmod(self.folder, 0o755)
        return False
