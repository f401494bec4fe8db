"""File names written inside input files (a study's ``texture``, ``assembly`` and
``files``, an assembly's ``[friction]`` ``gauge`` and ``texture``): one rule that turns
them into paths, one check that keeps them inside a folder, one content digest.

The rule (:func:`named_path`): ``~`` and ``~user`` are expanded, an absolute name is
taken as it is, any other name is relative to the folder of the file that names it;
``study.files`` may hold glob patterns (:func:`matching_files`, ``**`` recursive).
Every reader of such a name calls these functions, so the path a check saw is the path
that is read: nothing expands a name a second, different way.

:func:`check_inside` confines a path to a folder (symbolic links followed: a link inside
the folder that points out of it is outside); the web page's study jobs use it, the
command line does not (a local user may name any file).
"""
from __future__ import annotations

import glob
import hashlib
import os
from pathlib import Path

from .errors import InputError

#: bytes read at a time when a file's content is hashed
_PIECE = 1 << 20


def named_path(value: str, folder) -> Path:
    """The path of file name ``value`` written in a file of ``folder``."""
    v = os.path.expanduser(value)
    return Path(v) if os.path.isabs(v) else Path(folder) / v


def matching_files(pattern: str, folder) -> list[Path]:
    """The regular files a name or glob pattern of a file in ``folder`` matches, sorted
    (a plain name: itself, if it is a file)."""
    full = str(named_path(pattern, folder))
    hits = sorted(glob.glob(full, recursive=True)) if glob.has_magic(full) else [full]
    return [Path(h) for h in hits if os.path.isfile(h)]


def is_inside(path, root) -> bool:
    """Whether ``path`` resolves (symbolic links followed, ``..`` applied) inside the
    folder ``root``."""
    real = os.path.realpath(path)
    top = os.path.realpath(root)
    return real == top or real.startswith(top.rstrip(os.sep) + os.sep)


def check_inside(key: str, value: str, folder, root, why: str) -> None:
    """InputError ``key = 'value': why`` unless the name (or, for a glob pattern, the
    folder part before its first wildcard, and the pattern itself read as a path) resolves
    inside ``root``.  The matches of a pattern are checked one by one too (see
    :func:`inside_matches`)."""
    full = str(named_path(value, folder))
    fixed = full
    if glob.has_magic(full):
        parts = Path(full).parts
        first = next(i for i, p in enumerate(parts) if glob.has_magic(p))
        fixed = str(Path(*parts[:first])) if first else "."
    if not (is_inside(fixed, root) and is_inside(os.path.normpath(full), root)):
        raise InputError(f"{key} = {value!r}: {why}")


def inside_matches(key: str, value: str, hits, root, why: str) -> None:
    """InputError naming the key if a match of ``value`` resolves outside ``root`` (a link
    among the files, or a ``..`` after a wildcard)."""
    for h in hits:
        if not is_inside(h, root):
            raise InputError(f"{key} = {value!r}: {why}")


def file_digest(path) -> str:
    """SHA-256 of a file's content (read in pieces), hex; InputError if unreadable."""
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            while piece := fh.read(_PIECE):
                h.update(piece)
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror or type(exc).__name__})") \
            from None
    return h.hexdigest()
