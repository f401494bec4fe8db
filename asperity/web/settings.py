"""The server's settings, checked before anything starts (each refusal is one line)."""
from __future__ import annotations

import ipaddress
import os
import secrets
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, check_int, check_range

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765
#: default upload limit, MB (a 4096^2 float32 .npy is 64 MB; x3p are zipped)
DEFAULT_MAX_UPLOAD_MB = 256.0
MAX_UPLOAD_MB = 1e5


def default_data_dir() -> Path:
    """``$XDG_DATA_HOME/asperity/web`` (default ``~/.local/share/asperity/web``)."""
    base = os.environ.get("XDG_DATA_HOME") or os.path.join(os.path.expanduser("~"), ".local",
                                                            "share")
    return Path(base) / "asperity" / "web"


def is_loopback(host: str) -> bool:
    """True for ``localhost`` and the loopback addresses (127.0.0.0/8, ::1)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


@dataclass(frozen=True)
class Settings:
    """host, port: where to listen; data_dir: uploads and jobs; token: the access token
    every request needs (None: a loopback server without one); max_upload: bytes of one
    request at most; workers: computations at once (worker processes, at most one per core
    and what the free memory holds: workers_note says why when fewer than asked)."""

    host: str = DEFAULT_HOST
    port: int = DEFAULT_PORT
    data_dir: Path = field(default_factory=default_data_dir)
    token: str | None = None
    max_upload: int = int(DEFAULT_MAX_UPLOAD_MB * 2**20)
    workers: int = 2
    quick_wait: float = 2.0      # s a form waits for its job before showing the progress
    workers_note: str | None = None   # why fewer workers than asked (printed at start)


def make_settings(host: str = DEFAULT_HOST, port=DEFAULT_PORT, data_dir=None,
                  allow_remote: bool = False, max_upload_mb=DEFAULT_MAX_UPLOAD_MB,
                  workers=None, token: str | None = None) -> Settings:
    """Settings from the command's flags, checked: a host other than a loopback address is
    refused without ``allow_remote``; with it, every request needs the access token
    (``token``, else a new random one)."""
    if not isinstance(host, str) or not host.strip():
        raise InputError("--host must be an address such as 127.0.0.1")
    host = host.strip()
    if not is_loopback(host) and not allow_remote:
        raise InputError(f"--host {host} is not a loopback address: the page would be "
                         f"reachable from other machines; add --allow-remote (every request "
                         f"then needs the access token printed at start)")
    port = check_int("--port", port, 0, 65535)
    mb = check_range("--max-upload", max_upload_mb, 0.001, MAX_UPLOAD_MB, unit="MB")
    if workers is not None:
        workers = check_int("--workers", workers, 1, 64)
    if data_dir is not None and not str(data_dir).strip():
        raise InputError("--data-dir is empty: give a folder name (or leave --data-dir out "
                         f"for the default, {default_data_dir()})")
    folder = Path(os.path.expanduser(str(data_dir))) if data_dir else default_data_dir()
    if allow_remote and token is None:
        token = secrets.token_urlsafe(24)
    from ..resources import WORKER_BYTES, local_workers
    workers, note = local_workers(workers, WORKER_BYTES, dask=False)
    return Settings(host=host, port=port, data_dir=folder, token=token if allow_remote else None,
                    max_upload=int(mb * 2**20), workers=workers, workers_note=note)


def prepare_data_dir(folder: Path) -> Path:
    """Create the data folder (and its uploads/ and jobs/); one line if it cannot be used."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"--data-dir {str(folder)!r} exists and is not a folder")
    try:
        for sub in ("", "uploads", "jobs"):
            (folder / sub).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--data-dir {str(folder)!r} cannot be created "
                         f"({exc.strerror})") from None
    if not os.access(folder, os.W_OK):
        raise InputError(f"--data-dir {str(folder)!r} is not writable")
    return folder.resolve()
