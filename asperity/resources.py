"""What a request costs, checked before the work starts.

:func:`check_memory` refuses a computation whose estimated memory does not fit in what the
machine (or its container) has free, and :func:`check_work` one whose number of elementary
steps is beyond any useful run, each with one line that names the limit and the flag (or
file key) that lowers the cost.  Estimates are deliberately simple (bytes per element
times elements); they only have to catch what cannot possibly fit.
"""
from __future__ import annotations

import contextvars
import os

from .errors import ResourceError

#: share of the free memory a single computation may plan to use
MEMORY_SHARE = 0.8


#: seconds an answer of :func:`available_memory` is reused (it reads three files)
MEMORY_CACHE_SECONDS = 0.5
_cache: list = [-1.0, 0]


def available_memory() -> int:
    """Bytes of memory free for this process: MemAvailable of /proc/meminfo, bounded by a
    cgroup limit when one is set; the physical memory where /proc is missing.  Reused for
    :data:`MEMORY_CACHE_SECONDS` (studies check it for every small case)."""
    import time
    now = time.monotonic()
    if now - _cache[0] < MEMORY_CACHE_SECONDS:
        return _cache[1]
    free = _read_available_memory()
    _cache[0], _cache[1] = now, free
    return free


def _read_available_memory() -> int:
    free = None
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    free = int(line.split()[1]) * 1024
                    break
    except (OSError, ValueError, IndexError):
        pass
    if free is None:
        try:
            free = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
        except (ValueError, OSError, AttributeError):
            free = 8 << 30
    try:
        import resource
        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
        if soft != resource.RLIM_INFINITY and soft > 0:    # ulimit -v: what is left of it
            free = min(free, max(soft - _mapped_bytes(), 0))
    except (ImportError, OSError, ValueError):
        pass
    for path in ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"):
        try:
            with open(path, encoding="ascii") as fh:
                text = fh.read().strip()
            if text.isdigit():
                free = min(free, int(text))
        except OSError:
            continue
    return int(free)


def _mapped_bytes() -> int:
    """Address space this process maps now (VmSize), 0 where unknown."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def format_bytes(n: float) -> str:
    for unit, size in (("TB", 1 << 40), ("GB", 1 << 30), ("MB", 1 << 20), ("kB", 1 << 10)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.0f} bytes"


def check_memory(need_bytes: float, what: str, lower: str) -> None:
    """Refuse ``what`` if it needs more than :data:`MEMORY_SHARE` of the free memory.

    lower : how to lower the cost, e.g. "lower --directions" or "use fewer nodes (n)"
    """
    free = available_memory()
    if need_bytes > MEMORY_SHARE * free:
        raise ResourceError(f"{what} needs about {format_bytes(need_bytes)} of memory, more than "
                            f"the {format_bytes(MEMORY_SHARE * free)} this machine can give it; "
                            f"{lower}")


def check_work(steps: float, limit: float, what: str, lower: str) -> None:
    """Refuse ``what`` if it takes more than ``limit`` elementary steps."""
    if steps > limit:
        raise ResourceError(f"{what} takes {steps:.3g} steps, at most {limit:.3g}; {lower}")


# ----------------------------------------------------------------------------- local workers

#: memory of one warm local worker process (asperity, numba's kernels, Dask): measured
#: 92-130 MB of private memory and 134-172 MB proportional set size (RssAnon and Pss of a
#: LocalCluster worker after a study's cases); a case's own needs come on top
WORKER_BYTES = 150 << 20


def cpu_cores() -> int:
    """Cores this process may use: its CPU affinity, bounded by a cgroup CPU quota."""
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    try:
        with open("/sys/fs/cgroup/cpu.max", encoding="ascii") as fh:
            quota, period = fh.read().split()[:2]
        if quota != "max" and int(period) > 0:
            n = min(n, max(1, -(-int(quota) // int(period))))
    except (OSError, ValueError):
        pass
    return max(1, n)


def local_workers(asked: int | None, per_worker: float = WORKER_BYTES, *,
                  flag: str = "--workers", what: str = "workers",
                  dask: bool = True) -> tuple[int, str | None]:
    """How many local worker processes to start for ``asked`` (None: one per core): at most
    one per core and as many as :data:`MEMORY_SHARE` of the free memory holds at
    ``per_worker`` bytes each (at least one).  Returns (number, the one line that says why
    fewer were started, or None).  The one place that decides it for every command
    (``dask``: the workers of a local Dask cluster, which ``--scheduler`` replaces)."""
    cores = cpu_cores()
    free = available_memory()
    fit = int(MEMORY_SHARE * free // max(per_worker, 1.0))
    want = cores if asked is None else int(asked)
    n = max(1, min(want, cores, fit))
    if n >= want:
        return n, None
    why = (f"this machine has {cores} core{'s' * (cores != 1)}" if n == cores else
           f"{format_bytes(free)} of memory is free, about {format_bytes(per_worker)} a "
           f"worker")
    asked_text = f"{want} {what} asked ({flag})" if asked is not None else \
        f"{want} {what} (one per core) wanted"
    tail = "; an existing cluster (--scheduler) has no such limit" if dask else ""
    return n, f"{asked_text}, {n} started: {why}{tail}"


#: the program named in front of :func:`note` lines ("asperity study"; set by the command)
PROGRAM: contextvars.ContextVar[str] = contextvars.ContextVar("PROGRAM", default="asperity")


def note(line: str) -> None:
    """One line on stderr about how a request is carried out (not an error)."""
    import sys
    try:
        print(f"{PROGRAM.get()}: {line}", file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass
