"""Binding the socket and running uvicorn: the body of ``asperity serve``."""
from __future__ import annotations

import socket
import sys

from ..errors import InputError


def lock_data_dir(folder):
    """An exclusive lock on the data folder: two servers on one folder would both run its
    queued jobs."""
    from ..locks import lock_file
    return lock_file(folder / ".serve.lock", InputError(
        f"--data-dir {str(folder)!r} is in use by another asperity serve; stop it or give "
        f"another --data-dir"))


def bind(host: str, port: int) -> socket.socket:
    """A listening socket on host:port (port 0: a free one), or one line saying why not."""
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except socket.gaierror as exc:
        raise InputError(f"--host {host}: not an address of this machine ({exc.strerror})") \
            from None
    family, _, _, _, addr = infos[0]
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind(addr)
    except OSError as exc:
        sock.close()
        if exc.errno in (98, 48):                  # EADDRINUSE (Linux, macOS)
            raise InputError(f"--port {port} is in use on {host} (another asperity serve?); "
                             f"pick another with --port") from None
        raise InputError(f"cannot listen on {host}:{port} ({exc.strerror})") from None
    sock.listen(128)
    sock.set_inheritable(True)
    return sock


def url_of(host: str, port: int, token: str | None) -> str:
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}/" + (f"?token={token}" if token else "")


def serve(settings) -> int:
    """Run the server until Ctrl-C (or SIGTERM); the workers stop with it."""
    import logging

    import uvicorn

    from ..io import outside_transaction
    from .app import create_app
    from .settings import prepare_data_dir
    folder = prepare_data_dir(settings.data_dir)
    from dataclasses import replace
    settings = replace(settings, data_dir=folder)
    lock = lock_data_dir(folder)
    sock = bind(settings.host, settings.port)
    port = sock.getsockname()[1]
    app = create_app(settings)
    logging.basicConfig(level=logging.WARNING, format="asperity serve: %(message)s")
    config = uvicorn.Config(app, log_level="warning", access_log=False, lifespan="on",
                            timeout_graceful_shutdown=3)
    server = uvicorn.Server(config)
    print(f"asperity serve: {url_of(settings.host, port, settings.token)}", flush=True)
    print(f"  data folder {folder}; {settings.workers} worker process(es); uploads up to "
          f"{settings.max_upload / 2**20:.4g} MB; Ctrl-C stops", file=sys.stderr, flush=True)
    if settings.workers_note:
        print(f"  {settings.workers_note}", file=sys.stderr, flush=True)
    if settings.token:
        print("  every request needs the token in this link (it sets a cookie); keep it "
              "private", file=sys.stderr, flush=True)
    try:
        with outside_transaction():            # job files are written as they come
            server.run(sockets=[sock])
    except KeyboardInterrupt:                  # uvicorn passes Ctrl-C on once it stopped
        pass
    finally:
        sock.close()
        lock.close()
    print("asperity serve: stopped", file=sys.stderr, flush=True)
    return 0
