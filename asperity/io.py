"""File input and output that never loses a file.

Inputs: :func:`read_toml` and :func:`read_json` read text files of bounded size and turn
every way a file can be broken (missing, unreadable, not UTF-8, invalid syntax, nested too
deeply, integers too long) into one :class:`~asperity.errors.InputError` line.

Outputs are written atomically: a writer gets a temporary file beside the target
(:func:`atomic_path`) and the target is replaced only when the writer succeeded.  Inside
an :func:`output_transaction` (every command runs in one) the replacements wait until the
transaction ends without error, so the outputs of a command are committed together or not
at all, and an interrupted run leaves every existing file as it was.  A committed file
gets the mode of the file it replaces (else ``0o666`` less the umask); a symbolic link is
written through (its target is replaced, the link stays); ``-`` means standard output, and
a target that is not a regular file (``/dev/stdout``, a FIFO) is written in place.
:func:`check_output` refuses an unusable path before any work is done.
"""
from __future__ import annotations

import contextlib
import contextvars
import os
import shutil
import stat
import sys
import tempfile
from pathlib import Path

from .errors import InputError, OutputError

#: largest input text file read (TOML, JSON): far above any real one, far below memory
MAX_INPUT_BYTES = 64 << 20
#: figure formats matplotlib writes without extra packages (by file suffix)
FIGURE_FORMATS = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff",
                  "webp", "pgf", "raw", "rgba")
STDOUT = "-"

_pending: contextvars.ContextVar[list | None] = contextvars.ContextVar("_pending", default=None)


# ----------------------------------------------------------------------------- outputs

def _umask_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def _one_line_os(path, exc: OSError) -> OutputError:
    why = exc.strerror or type(exc).__name__
    return OutputError(f"cannot write {str(path)!r}: {why}")


def _resolve(path: str | Path) -> Path:
    """The file a write to ``path`` must replace: symbolic links followed."""
    return Path(os.path.realpath(path))


def _special(path: str | Path) -> bool:
    """An existing target that is not a regular file or folder (a device such as
    /dev/stdout or /dev/null, a FIFO): written in place, not replaced."""
    try:
        mode = os.stat(path).st_mode              # follows symbolic links
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def check_output(path: str | Path | None, what: str, *, figure: bool = False,
                 stdout_ok: bool = True) -> None:
    """Refuse, before any work, an output path that cannot be written.

    what   : the flag or field naming it in the message (``--plot``)
    figure : the suffix must name a figure format matplotlib writes
    """
    if path is None:
        return
    p = str(path)
    if p == STDOUT:
        if not stdout_ok:
            raise InputError(f"{what}: '-' (standard output) is not allowed here")
        return
    if not p.strip():
        raise InputError(f"{what}: empty file name")
    if _special(p):
        if not os.access(p, os.W_OK):
            raise InputError(f"{what}: {p!r} cannot be written (permission denied)")
    elif _resolve(p).is_dir():
        raise InputError(f"{what}: {p!r} is a folder, not a file")
    if figure:
        fmt = Path(p).suffix.lower().lstrip(".") or ("png" if _special(p) else "")
        if fmt not in FIGURE_FORMATS:
            raise InputError(f"{what}: unsupported figure format {Path(p).suffix or '(none)'!r}; "
                             f"use one of .{', .'.join(FIGURE_FORMATS[:6])} ...")
    if _special(p):
        return                                   # a device or FIFO: written in place
    target = _resolve(p)
    folder = target.parent
    if not folder.is_dir():
        raise InputError(f"{what}: output folder {str(Path(p).parent)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"{what}: output folder {str(Path(p).parent) or '.'!r} is not "
                         "writable (permission denied)")


def check_outputs(outputs: list[tuple[str, str | None, bool]], inputs=()) -> None:
    """Check several outputs of one command: each usable (:func:`check_output`), no two
    naming the same file or both standard output, none naming an input file.

    outputs : (what, path, figure) triples; inputs : paths the command reads
    """
    seen: dict = {}
    ins = {_resolve(p) for p in inputs if p not in (None, STDOUT)}
    for what, path, figure in outputs:
        if path is None:
            continue
        check_output(path, what, figure=figure)
        key = STDOUT if str(path) == STDOUT else (str(path) if _special(path)
                                                  else _resolve(path))
        if key in seen:
            raise InputError(f"{seen[key]} and {what} name the same output "
                             f"({'standard output' if key == STDOUT else str(path)!r})")
        seen[key] = what
        if key in ins:
            raise InputError(f"{what}: {str(path)!r} is also an input of this command; "
                             "write to another file")


@contextlib.contextmanager
def atomic_path(path: str | Path):
    """Yield a temporary path to write instead of ``path``; when the block succeeds the
    temporary file replaces ``path`` (at once, or when the enclosing
    :func:`output_transaction` ends).  On an error nothing is left behind and ``path`` is
    as it was.  Write errors (full disk, permissions) become one-line OutputErrors."""
    p = str(path)
    special = p == STDOUT or _special(p)
    target = None if special else _resolve(p)
    if target is not None:
        if target.is_dir():
            raise OutputError(f"cannot write {p!r}: it is a folder")
        folder = target.parent
        if not folder.is_dir():
            raise OutputError(f"cannot write {p!r}: folder {str(Path(p).parent)!r} does not exist")
    else:
        folder = Path(tempfile.gettempdir())
    name = "stdout" if target is None else target.name
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".part", dir=folder)
    except OSError as exc:
        raise _one_line_os(path, exc) from None
    os.close(fd)
    tmp = Path(tmp)
    try:
        try:
            yield tmp
        except OSError as exc:                     # full disk, quota, permissions
            raise _one_line_os(path, exc) from None
        pending = _pending.get()
        if pending is None:
            _commit(tmp, p)
        else:
            pending.append((tmp, p))
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


def _commit(tmp: Path, path: str) -> None:
    """Put the finished temporary file in place of ``path``."""
    try:
        if path == STDOUT:
            sys.stdout.flush()
            with tmp.open("rb") as src:
                shutil.copyfileobj(src, sys.stdout.buffer)
            sys.stdout.buffer.flush()
            tmp.unlink()
            return
        if _special(path):                                # device, FIFO: write in place
            with tmp.open("rb") as src, open(path, "wb") as dst:
                shutil.copyfileobj(src, dst)
            tmp.unlink()
            return
        target = _resolve(path)
        mode = stat.S_IMODE(target.stat().st_mode) if target.exists() else _umask_mode()
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except OSError as exc:
        with contextlib.suppress(OSError):
            tmp.unlink()
        if isinstance(exc, BrokenPipeError):
            raise                                      # the reader left: not an error
        raise _one_line_os(path, exc) from None


def on_commit(fn) -> None:
    """Run ``fn()`` once the enclosing :func:`output_transaction` has committed its files
    (at once when there is none): for messages such as "plot written to ..."."""
    pending = _pending.get()
    if pending is None:
        fn()
    else:
        pending.append((None, fn))


@contextlib.contextmanager
def output_transaction():
    """Hold back every :func:`atomic_path` replacement made inside the block and commit
    them together when it ends without an error; on an error (or Ctrl-C) discard them all."""
    if _pending.get() is not None:                 # nested: the outer one commits
        yield
        return
    pending: list = []
    token = _pending.set(pending)
    try:
        yield
    except BaseException:
        _pending.reset(token)
        for tmp, _ in pending:
            if tmp is not None:
                with contextlib.suppress(OSError):
                    tmp.unlink()
        raise
    _pending.reset(token)
    # devices and standard output first: they are written in place and may still fail
    # (a full device, a closed pipe); the renames of regular files come last
    files = sorted(((t, p) for t, p in pending if t is not None),
                   key=lambda tp: not (tp[1] == STDOUT or _special(tp[1])))
    for i, (tmp, path) in enumerate(files):
        try:
            _commit(tmp, path)
        except BaseException:
            for t, _ in files[i + 1:]:
                with contextlib.suppress(OSError):
                    t.unlink()
            raise
    for t, fn in pending:
        if t is None:
            fn()


@contextlib.contextmanager
def outside_transaction():
    """Files written atomically inside the block replace theirs at once, even within an
    :func:`output_transaction` (a working store's files, such as a study's summary, which
    must not wait for the command's other outputs)."""
    token = _pending.set(None)
    try:
        yield
    finally:
        _pending.reset(token)


def write_text_atomic(path: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def save_figure_atomic(fig, path: str | Path, **kwargs) -> None:
    """Save a matplotlib figure to ``path`` atomically (format from the suffix, else png)."""
    fmt = Path(str(path)).suffix.lower().lstrip(".") or "png"
    if fmt not in FIGURE_FORMATS:
        raise OutputError(f"cannot write {str(path)!r}: unsupported figure format {fmt!r}")
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend (imported on first use)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


# ----------------------------------------------------------------------------- inputs

def read_text_file(path: str | Path, what: str, error=InputError,
                   max_bytes: int = MAX_INPUT_BYTES) -> str:
    """The UTF-8 text of an input file, or ``error`` with one line saying why not."""
    p = Path(path)
    if not p.is_file():
        if p.is_dir():
            raise error(f"{what} {str(p)!r} is a folder, not a file")
        if p.exists():
            raise error(f"{what} {str(p)!r} is not a regular file (a device or a pipe)")
        raise error(f"{what} {str(p)!r} does not exist")
    try:
        size = p.stat().st_size
        if size > max_bytes:
            raise error(f"{p}: {size / 2**20:.0f} MB is too large for {_a(what)} "
                        f"(at most {max_bytes >> 20} MB)")
        data = p.read_bytes()
    except OSError as exc:
        raise error(f"{p}: cannot be read ({exc.strerror})") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{p}: not UTF-8 text (byte {exc.start}); {_a(what)} must be UTF-8") from None


def _a(noun: str) -> str:
    """'a gauge file', 'an assembly file'."""
    return f"{'an' if noun[:1].lower() in 'aeiou' else 'a'} {noun}"


def read_toml(path: str | Path, what: str, allowed: set[str], error) -> dict:
    """The top-level table of a TOML input file.  ``what`` names the file kind in the
    messages ("texture file"); a missing or unreadable file, invalid TOML or a top-level
    key outside ``allowed`` raises ``error`` (an InputError subclass) with one line."""
    p = Path(path)
    data = parse_toml(read_text_file(p, what, error), p, error)
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise error(f"{p}: unknown key {unknown[0]!r}; allowed top-level keys: "
                    f"{', '.join(sorted(allowed))}")
    return data


def parse_toml(text: str, path, error) -> dict:
    """The TOML document ``text`` of file ``path``, or ``error`` with one line."""
    import tomllib
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{path}: not valid TOML ({str(exc).splitlines()[0]})") from None
    except RecursionError:
        raise error(f"{path}: not a usable TOML file (arrays or tables nested too deeply)") \
            from None


def read_json(path: str | Path, what: str, error=InputError, parse_constant=None):
    """The JSON value of an input file, or ``error`` with one line (invalid JSON, nested
    too deeply, an integer too long to convert)."""
    import json
    p = Path(path)
    text = read_text_file(p, what, error)
    try:
        return json.loads(text, parse_constant=parse_constant)
    except json.JSONDecodeError as exc:
        raise error(f"{p}: not valid JSON ({exc.msg}, line {exc.lineno} column "
                    f"{exc.colno})") from None
    except RecursionError:
        raise error(f"{p}: not a usable {what} (nested too deeply)") from None
    except ValueError as exc:                       # e.g. an integer of thousands of digits
        raise error(f"{p}: not a usable {what} ({str(exc).splitlines()[0][:120]})") from None


def json_ready(x):
    """Plain JSON values: NumPy scalars and arrays as Python values, NaN and infinities as
    None (JSON has neither), keys as text, anything else as its text."""
    import math

    import numpy as np
    if isinstance(x, dict):
        return {str(k): json_ready(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [json_ready(v) for v in x]
    if isinstance(x, np.ndarray):
        return json_ready(x.tolist())
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if x is None or isinstance(x, str):
        return x
    return str(x)
