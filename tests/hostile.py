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
    p = subprocess.run([sys.executable, "-m", "asperity", *map(str, argv)], cwd=cwd,
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


def interrupt(*argv, after=1.5, cwd=None, timeout=60):
    """Start ``asperity ARGV``, send SIGINT ``after`` seconds, and return (exit status,
    stderr, seconds from SIGINT to exit)."""
    p = subprocess.Popen([sys.executable, "-m", "asperity", *map(str, argv)], cwd=cwd,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=package_env())
    time.sleep(after)
    if p.poll() is not None:
        out, err = p.communicate()
        raise AssertionError(f"finished before the interrupt (exit {p.returncode}): {err}")
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("still running after SIGINT") from None
    return p.returncode, err, time.perf_counter() - t0


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
        r = subprocess.run(["chattr", "+i", str(self.folder)], capture_output=True, text=True)
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
