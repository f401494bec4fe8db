"""``asperity serve`` in a child process for the web tests: started on 127.0.0.1 with a
free port and a data folder of the test's, stopped at the end (shared by the browser and
HTTP tests)."""
from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: the folder holding the package under test (a mutant's copy in benchmarks/mutants.py):
#: the server starts there, so that ``-m asperity`` imports that package, not the tree's
PACKAGE_ROOT = Path(importlib.util.find_spec("asperity").origin).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "data" / "surfaces"
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]


class Server:
    """A running ``asperity serve``; ``url`` is its address (with the token if any)."""

    def __init__(self, data_dir, *args, timeout: float = 60.0):
        cmd = [sys.executable, "-m", "asperity", "serve", "--port", "0", "--data-dir",
               str(data_dir), *args]
        self.data_dir = Path(data_dir)
        env = {**os.environ, "PYTHONUNBUFFERED": "1"}
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, env=env, cwd=str(PACKAGE_ROOT))
        self.err: list[str] = []
        threading.Thread(target=self._drain, daemon=True).start()
        line = self._first_line(timeout)
        if not line.startswith("asperity serve: http"):
            self.stop()
            raise RuntimeError(f"asperity serve did not start: {line!r} {''.join(self.err)}")
        self.url = line.split(": ", 1)[1].strip()
        self.base = self.url.split("?", 1)[0].rstrip("/")

    def _drain(self):
        for line in self.proc.stderr:
            self.err.append(line)

    def _first_line(self, timeout: float) -> str:
        out = []
        t = threading.Thread(target=lambda: out.append(self.proc.stdout.readline()),
                             daemon=True)
        t.start()
        t.join(timeout)
        return out[0] if out else ""

    def alive(self) -> bool:
        return self.proc.poll() is None

    def stop(self, timeout: float = 20.0) -> int:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(5)
        return self.proc.returncode


def served(data_dir, *args):
    """A module fixture's body: a Server on ``data_dir``, stopped cleanly (exit 0) with no
    traceback on its stderr."""
    srv = Server(data_dir, *args)
    try:
        yield srv
    finally:
        assert srv.stop() == 0
    assert "Traceback" not in "".join(srv.err), "".join(srv.err)


def wait_for(pred, timeout: float = 60.0, step: float = 0.2):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        v = pred()
        if v:
            return v
        time.sleep(step)
    raise AssertionError("timed out")


def job_done(server, r, why=None, timeout: float = 180.0) -> str:
    """The id of the job a form's POST (``r``: 303 to the job's page) started, once it has
    finished as "done" (``why(r)``: what to show when the POST was refused instead)."""
    import time

    import httpx
    assert r.status_code == 303, (r.status_code, why(r) if why else r.text[-2000:])
    jid = r.headers["location"].rsplit("/", 1)[-1]
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        st = httpx.get(f"{server.base}/api/jobs/{jid}").json()
        if st["status"] not in ("queued", "running"):
            assert st["status"] == "done", st
            return jid
        time.sleep(0.1)
    raise AssertionError(f"job {jid} did not finish")
