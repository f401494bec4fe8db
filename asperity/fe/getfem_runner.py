"""Run GetFEM jobs in the system Python: a JSON job on stdin of
``/usr/bin/python3 -I getfem_script.py``, the result as JSON on its stdout.

GetFEM's Debian package (``python3-getfem``) is built against the system numpy and does not
load in the project's interpreter, so it runs in a child process: isolated mode (``-I``: no
PYTHONPATH, no user site), a timeout, and the child dies with the process that started it
(:func:`asperity.lifeline.preexec`, and the script watches its parent too).
"""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

from ..errors import AsperityError, InputError

#: the interpreter that has GetFEM (override with ASPERITY_GETFEM_PYTHON)
SYSTEM_PYTHON = "/usr/bin/python3"
SCRIPT = Path(__file__).with_name("getfem_script.py")
INSTALL = ("GetFEM is not available to {py} ({why}); install it with: apt-get install "
           "python3-getfem (Debian/Ubuntu; it runs under the system Python)")
#: seconds a job may take unless told otherwise
TIMEOUT = 600.0


class GetfemUnavailable(InputError):
    """GetFEM cannot be imported by the system Python (one line: how to install it)."""


class GetfemFailed(AsperityError):
    """A GetFEM run failed (Newton did not converge, timeout, a crash): one line."""


def system_python() -> str:
    return os.environ.get("ASPERITY_GETFEM_PYTHON", SYSTEM_PYTHON)


def run_job(job: dict, timeout: float = TIMEOUT) -> dict:
    """The JSON object the script prints for ``job``; GetfemUnavailable when GetFEM cannot
    be imported, GetfemFailed when the run fails or exceeds ``timeout`` seconds."""
    from ..lifeline import preexec
    py = system_python()
    if not os.path.isfile(py) or not os.access(py, os.X_OK):
        raise GetfemUnavailable(INSTALL.format(py=py, why="no such interpreter"))
    try:
        r = subprocess.run([py, "-I", str(SCRIPT)], check=False, input=json.dumps(job),
                           capture_output=True, text=True, timeout=timeout,
                           preexec_fn=preexec())
    except subprocess.TimeoutExpired:
        raise GetfemFailed(f"the GetFEM run took more than {timeout:g} s and was stopped; "
                           "use a coarser mesh (--fe-mesh)") from None
    except OSError as exc:
        raise GetfemUnavailable(INSTALL.format(py=py, why=exc.strerror or exc)) from None
    lines = r.stdout.strip().splitlines()
    try:
        out = json.loads(lines[-1]) if lines else None
    except json.JSONDecodeError:
        out = None
    if r.returncode != 0 or not isinstance(out, dict):
        err = r.stderr.strip().splitlines()
        raise GetfemFailed(f"the GetFEM run failed (exit status {r.returncode}): "
                           f"{err[-1] if err else 'no output'}")
    if out.get("error") == "import":
        raise GetfemUnavailable(INSTALL.format(py=py, why=out.get("detail", "import failed")))
    if "error" in out:
        raise GetfemFailed(f"the GetFEM run failed: {out.get('detail', out['error'])}")
    return out


def getfem_status() -> tuple[bool, str]:
    """(available, GetFEM version or the one-line reason it is not)."""
    try:
        out = run_job({"task": "probe"}, timeout=60.0)
    except (GetfemUnavailable, GetfemFailed) as exc:
        return False, str(exc)
    return True, str(out.get("getfem", "?"))
