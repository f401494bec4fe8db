"""File input and output: TOML input files with one-line errors, and atomic output (an
interrupted run never leaves a half-written file).
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path


@contextlib.contextmanager
def atomic_path(path: str | Path):
    """Yield a temporary path beside ``path``; on success it replaces ``path`` at once.

    On an exception the temporary file is removed and ``path`` is left as it was.
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        from .errors import InputError
        raise InputError(f"output folder {str(folder)!r} does not exist")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=folder)
    os.close(fd)
    try:
        yield Path(tmp)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_text_atomic(path: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def save_figure_atomic(fig, path: str | Path, **kwargs) -> None:
    """Save a matplotlib figure to ``path`` atomically (format from the suffix)."""
    fmt = Path(path).suffix.lstrip(".") or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)


def read_toml(path: str | Path, what: str, allowed: set[str], error) -> dict:
    """The top-level table of a TOML input file.  ``what`` names the file kind in the
    messages ("texture file"); a missing or unreadable file, invalid TOML or a top-level
    key outside ``allowed`` raises ``error`` (an InputError subclass) with one line."""
    import tomllib
    p = Path(path)
    if not p.is_file():
        raise error(f"{what} {str(p)!r} does not exist")
    try:
        with p.open("rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{p}: not valid TOML ({exc})") from None
    except OSError as exc:
        raise error(f"{p}: cannot be read ({exc.strerror})") from None
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise error(f"{p}: unknown key {unknown[0]!r}; allowed top-level keys: "
                    f"{', '.join(sorted(allowed))}")
    return data


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
