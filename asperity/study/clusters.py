"""Where Dask work runs: a local cluster sized to the machine, or an existing scheduler
checked before anything is created.

* Local: :func:`connect` starts a ``LocalCluster`` of single-threaded worker processes on
  127.0.0.1, as many as asked but at most what the cores and the free memory allow
  (:func:`asperity.resources.local_workers` decides, and says so in one line).  Every
  worker dies with the process that started it (:mod:`asperity.lifeline`).
* Existing: :func:`resolve_scheduler` turns ``--scheduler`` (or $ASPERITY_SCHEDULER) -- an
  address ``tcp://HOST:PORT`` or a scheduler file -- into an address, and refuses in one
  line naming it an address that is malformed, a port out of range, a file that is not a
  scheduler file, a host where nothing listens, or a service that does not greet as a Dask
  scheduler does (an HTTP server, say) -- before a store or an output is created.
"""
from __future__ import annotations

import contextlib
import logging
import os

from ..errors import AsperityError, InputError, check_int

#: environment variable naming a scheduler address (or scheduler file) for every study
SCHEDULER_ENV = "ASPERITY_SCHEDULER"
#: Dask's scheduler port when an address gives none
DEFAULT_PORT = 8786
#: seconds to reach a scheduler's port, then to receive its greeting
CONNECT_SECONDS = 5.0
GREETING_SECONDS = 5.0
#: a Dask scheduler's first message (its handshake) is far smaller than this
MAX_GREETING_BYTES = 1 << 20
EXAMPLE = "an address such as tcp://10.0.0.5:8786 or a scheduler file"
#: Dask settings of a local cluster's workers: no profiler (it samples the running task's
#: stack every 10 ms, a few % of a worker's CPU, for a dashboard a local cluster does not
#: have), and glibc's own malloc thresholds, as in a serial run (Dask's pre-spawn
#: MALLOC_TRIM_THRESHOLD_ fixes them, and every array over 128 kB is then mapped and
#: unmapped afresh: +70 % page faults in a derive of a 256 x 256 scan)
LOCAL_WORKER_CONFIG = {"distributed.worker.profile.enabled": False,
                       "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}


class EngineError(AsperityError):
    """The cluster cannot be reached or cannot run asperity's tasks."""


class _InterruptedSync(logging.Filter):
    """Drops tornado's report of a known race in ``distributed.utils.sync``: Ctrl-C (or
    SIGTERM) that arrives before the coroutine has started leaves the ``future`` its
    cancel callback reads unassigned, and tornado logs that NameError with a traceback
    (``contact --window ... --workers 2`` interrupted).  Nothing is lost: the command has
    stopped already and says so in its own line."""

    def filter(self, record: logging.LogRecord) -> bool:
        exc = record.exc_info[1] if record.exc_info else None
        return not (isinstance(exc, NameError) and "'future'" in str(exc)
                    and exc.__traceback__ is not None
                    and "distributed" in _last_file(exc.__traceback__))


def _last_file(tb) -> str:
    while tb.tb_next is not None:
        tb = tb.tb_next
    return tb.tb_frame.f_code.co_filename


def quiet_interrupted_sync() -> None:
    """Install :class:`_InterruptedSync` on tornado's callback logger (once)."""
    log = logging.getLogger("tornado.application")
    if not any(isinstance(f, _InterruptedSync) for f in log.filters):
        log.addFilter(_InterruptedSync())


class _held_signals:
    """Signals held while a local cluster starts: one that came in the middle of
    LocalCluster() left it half started (atexit's close_clusters then failed with
    'AssertionError: Status.init'), and a terminal's Ctrl-C, sent to the whole process
    group, reached the worker processes as they imported dask (their KeyboardInterrupt
    tracebacks, 'Nanny failed to start').  Within the block SIGINT is ignored: the workers
    start with it ignored (an exec keeps an ignored signal, and Python then leaves it
    so) and the command closes them itself; a Ctrl-C in the second or two the workers take
    to start is not seen (press it again).  SIGTERM is recorded and raised after the block
    (:meth:`replay`).  Outside the main thread a no-op."""

    def __enter__(self):
        import signal
        import threading
        self.got, self.old = None, {}
        if threading.current_thread() is threading.main_thread():
            self.old = {signal.SIGINT: signal.signal(signal.SIGINT, signal.SIG_IGN),
                        signal.SIGTERM: signal.signal(signal.SIGTERM, self._hold)}
        return self

    def _hold(self, signum, frame):
        self.got = signum

    def __exit__(self, *exc):
        import signal
        for s, handler in self.old.items():
            signal.signal(s, handler)
        return False

    def replay(self) -> None:
        """Raise the signal held (to the handler restored: Terminated)."""
        import signal
        if self.got:
            signal.raise_signal(self.got)


def resolve_scheduler(scheduler: str | None) -> str | None:
    """The scheduler to use, checked: the argument, else $ASPERITY_SCHEDULER, else None
    (a local cluster).  A scheduler file is read for its address."""
    flag = "--scheduler" if scheduler is not None else f"${SCHEDULER_ENV}"
    s = scheduler if scheduler is not None else os.environ.get(SCHEDULER_ENV) or None
    if s is None:
        return None
    if not isinstance(s, str) or not s.strip():
        raise InputError(f"{flag} must be {EXAMPLE}")
    return check_scheduler(s.strip(), flag)


def check_scheduler(s: str, flag: str = "--scheduler") -> str:
    """The address of scheduler ``s`` (an address or a scheduler file) once it answers as
    a Dask scheduler; else one line naming ``flag``, ``s`` and what is wrong."""
    where = f"{flag} {s!r}"
    address = s
    if "://" not in s:
        if os.path.isdir(s):
            raise EngineError(f"{where} is a folder, not {EXAMPLE}")
        if os.path.exists(s):
            address = _scheduler_file(s, where)
            where = f"{where} (scheduler at {address!r})"
        elif ":" in s and "/" not in s:
            address = f"tcp://{s}"
        else:
            raise EngineError(f"{where}: no such scheduler file, and not an address; give "
                              f"{EXAMPLE}")
    scheme = address.split("://", 1)[0].lower()
    if scheme in ("tcp", "tls"):
        host, port = _host_port(address, where)
        _probe(host, port, where, greeting=scheme == "tcp")
    return address


def _scheduler_file(path: str, where: str) -> str:
    from ..io import read_json
    try:
        data = read_json(path, "Dask scheduler file", EngineError)
    except EngineError as exc:
        raise EngineError(f"{where}: not a Dask scheduler file: {str(exc).split(': ', 1)[-1]}") \
            from None
    address = data.get("address") if isinstance(data, dict) else None
    if not isinstance(address, str) or "://" not in address:
        raise EngineError(f"{where}: not a Dask scheduler file (it holds no \"address\" such "
                          f"as tcp://10.0.0.5:8786)")
    return address


def _host_port(address: str, where: str) -> tuple[str, int]:
    rest = address.split("://", 1)[1]
    if "/" in rest or "?" in rest or "#" in rest:
        raise EngineError(f"{where}: not an address (tcp://HOST:PORT, nothing after the port)")
    if rest.startswith("["):
        end = rest.find("]")
        if end < 0:
            raise EngineError(f"{where}: not an address (a '[' without its ']'; an IPv6 host "
                              f"is written tcp://[::1]:8786)")
        host, tail = rest[1:end], rest[end + 1:]
        if tail and not tail.startswith(":"):
            raise EngineError(f"{where}: not an address (tcp://[HOST]:PORT)")
        port_text = tail[1:] if tail else ""
    else:
        host, _, port_text = rest.rpartition(":") if ":" in rest else (rest, "", "")
        if ":" in host:
            raise EngineError(f"{where}: not an address (an IPv6 host is written in "
                              f"brackets: tcp://[::1]:8786)")
    if not host:
        raise EngineError(f"{where}: not an address (no host; tcp://HOST:PORT)")
    if not port_text:
        return host, DEFAULT_PORT
    if not port_text.isdigit():
        raise EngineError(f"{where}: the port {port_text!r} is not a number (1 to 65535)")
    port = int(port_text)
    if not 1 <= port <= 65535:
        raise EngineError(f"{where}: the port {port} is out of range (1 to 65535)")
    return host, port


def _probe(host: str, port: int, where: str, greeting: bool) -> None:
    """Reach host:port, and with ``greeting`` read the first 8 bytes a Dask scheduler sends
    to a new connection (the length of its handshake): anything else is not Dask."""
    import socket
    try:
        sock = socket.create_connection((host, port), timeout=CONNECT_SECONDS)
    except socket.gaierror:
        raise EngineError(f"{where}: unknown host {host!r}") from None
    except ConnectionRefusedError:
        raise EngineError(f"{where}: nothing listens on {host}:{port} (connection refused); "
                          f"start the scheduler (`dask scheduler`) or check the address") \
            from None
    except TimeoutError:
        raise EngineError(f"{where}: no answer from {host}:{port} within {CONNECT_SECONDS:g} s "
                          f"(nothing listens, or a firewall); check the address") from None
    except OSError as exc:
        raise EngineError(f"{where}: cannot be reached ({exc.strerror or type(exc).__name__})") \
            from None
    with sock:
        if not greeting:
            return
        sock.settimeout(GREETING_SECONDS)
        head = b""
        try:
            while len(head) < 8:
                part = sock.recv(8 - len(head))
                if not part:
                    break
                head += part
        except TimeoutError:
            pass
        except OSError as exc:
            raise EngineError(f"{where}: the connection failed ({exc.strerror or exc})") \
                from None
    if not head:
        raise EngineError(f"{where}: not a Dask scheduler (it sent no greeting within "
                          f"{GREETING_SECONDS:g} s: an HTTP server or another service?)")
    size = int.from_bytes(head.ljust(8, b"\0"), "little")
    if len(head) < 8 or not 0 < size <= MAX_GREETING_BYTES:
        shown = head.decode("ascii", "replace").strip() or head.hex()
        raise EngineError(f"{where}: not a Dask scheduler (it answers in another protocol: "
                          f"{shown[:20]!r})")


def connect(scheduler: str | None, workers: int | None, per_worker: float | None = None):
    """(client, local cluster or None, description, number of workers).  ``scheduler``: a
    checked address (:func:`resolve_scheduler`) or None for a local cluster of ``workers``
    processes (None: one per core) of about ``per_worker`` bytes each."""
    import dask
    import distributed

    from .. import lifeline
    from ..resources import WORKER_BYTES, local_workers, note
    logging.getLogger("distributed").setLevel(logging.ERROR)
    quiet_interrupted_sync()
    if scheduler is None:
        nw, why = local_workers(workers, per_worker or WORKER_BYTES)
        if why:
            note(why)
        import warnings
        cluster = client = None
        hold = _held_signals()
        try:
            # one core per worker: the numba kernels must not start a thread per core in
            # every worker (oversubscription)
            with hold, warnings.catch_warnings(), dask.config.set(LOCAL_WORKER_CONFIG):
                warnings.simplefilter("ignore")     # e.g. a note on a busy port
                cluster = distributed.LocalCluster(
                    n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1",
                    dashboard_address=None, silence_logs=logging.ERROR,
                    preload=[lifeline.PRELOAD],
                    env={"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"})
                client = distributed.Client(cluster)
            hold.replay()
        except KeyboardInterrupt:
            if cluster is not None:
                close(client, cluster)
            raise
        except Exception as exc:
            hold.replay()           # the workers ended by the SIGTERM held: that, not this
            if isinstance(exc, OSError):
                raise EngineError(f"cannot start a local Dask cluster ({exc})") from None
            raise
        return client, cluster, f"LocalCluster ({nw} workers)", nw
    try:
        client = distributed.Client(scheduler, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise EngineError(f"cannot reach the Dask scheduler at {scheduler!r} "
                          f"({' '.join(str(exc).split())[:200]})") from None
    except MemoryError:
        raise EngineError(f"{scheduler!r} is not a Dask scheduler (its answer is not Dask's "
                          f"protocol)") from None
    try:
        client.wait_for_workers(1, timeout=60)
    except (TimeoutError, OSError):
        client.close()
        raise EngineError(f"the Dask scheduler at {scheduler!r} has no workers (waited 60 s); "
                          f"start some with: dask worker {scheduler}") from None
    nw = len(client.scheduler_info(n_workers=-1)["workers"])
    return client, None, scheduler, nw


def close(client, cluster) -> None:
    """Close the client and a local cluster.  Called while an exception propagates (Ctrl-C,
    SIGTERM, an error): the results still running are not wanted, so the local workers are
    killed rather than closed (a worker finishes its task first, seconds), and
    distributed's logs of the tasks so lost are silenced, and asyncio's of the futures a
    close that runs out of time leaves unread (seen once under load: "Future exception was
    never retrieved ... TimeoutError" after SIGTERM to the whole group)."""
    import sys
    if sys.exc_info()[0] is not None:
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        logging.getLogger("asyncio").setLevel(logging.CRITICAL)
        _kill_workers(cluster)
    with contextlib.suppress(Exception):
        client.close(timeout=5)
    if cluster is not None:
        with contextlib.suppress(Exception):
            cluster.close(timeout=5)


def _kill_workers(cluster) -> None:
    """SIGKILL the worker processes of a local cluster; their nannies (in this process)
    are told first that they are closing, else each would start a new worker."""
    import signal
    try:
        from distributed.core import Status
        nannies = list(getattr(cluster, "workers", {}).values()) if cluster is not None \
            else []
    except Exception:                     # noqa: BLE001 - then the graceful close only
        return
    for nanny in nannies:
        pid = getattr(getattr(getattr(nanny, "process", None), "process", None), "pid", None)
        if not (isinstance(pid, int) and pid > 0):
            continue
        try:
            nanny.status = Status.closing_gracefully
            os.kill(pid, signal.SIGKILL)
        except (OSError, TypeError, AttributeError):
            pass


class cluster:
    """A Dask client for other work than studies (e.g. the tiles of one huge scan): the
    same choice as a study -- ``scheduler`` (or $ASPERITY_SCHEDULER) an existing cluster,
    else a LocalCluster of ``workers`` single-threaded processes on 127.0.0.1 of about
    ``per_worker`` bytes each -- closed at the end.
    ``with cluster(None, 2) as (client, where, n_workers): ...``"""

    def __init__(self, scheduler: str | None = None, workers: int | None = None,
                 per_worker: float | None = None):
        self.scheduler = resolve_scheduler(scheduler)
        self.workers = None if workers is None else check_int("--workers", workers, 1, 4096)
        self.per_worker = per_worker

    def __enter__(self):
        self.client, self.local, where, nw = connect(self.scheduler, self.workers,
                                                     self.per_worker)
        return self.client, where, nw

    def __exit__(self, *exc):
        close(self.client, self.local)
        return False
