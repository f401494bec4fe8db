"""Every process a test starts dies with the test process, however that ends (a test
that fails half-way, pytest stopped with Ctrl-C or killed with SIGKILL): each child that
``subprocess`` starts asks the kernel for SIGKILL when its parent dies (Linux
``PR_SET_PDEATHSIG``; a servers' own workers then die with it, see asperity.lifeline).
The signal follows the thread that started the child, so tests start long-lived children
from the test's own thread.

A suite started in the background of a non-interactive shell (``pytest ... &``) inherits
SIGINT ignored, which every child would keep through exec: the tests of what a command
does on Ctrl-C would see it run on as if nothing had been pressed. The suite then takes
Ctrl-C's usual handler back, as a foreground run has it (children started while the
package itself ignores SIGINT, such as a starting cluster's, still inherit that)."""
from __future__ import annotations

import ctypes
import os
import signal
import subprocess
import sys

PR_SET_PDEATHSIG = 1
# no periodic progress lines from the suite's commands (their stderr is no terminal): what
# a test reads on stderr must not depend on how long a run took on a loaded machine; the
# tests of those lines ask for them (tests/test_cli_signals.py)
os.environ["ASPERITY_PROGRESS_EVERY"] = "0"
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:       # started in the background
    signal.signal(signal.SIGINT, signal.default_int_handler)
_popen_init = subprocess.Popen.__init__


def _die_with_parent() -> None:
    try:
        ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass


def _init(self, *args, preexec_fn=None, **kwargs):
    user = preexec_fn

    def preexec():
        if user is not None:                 # e.g. a change of user, which would clear
            user()                           # the signal asked before it
        _die_with_parent()
    _popen_init(self, *args, preexec_fn=preexec, **kwargs)


if sys.platform.startswith("linux"):
    subprocess.Popen.__init__ = _init
