"""Results made fit for a page and a JSON file: plain values, finite numbers, and the
names the user gave the files instead of where they are stored."""
from __future__ import annotations


def rename(x, names: dict):
    """``x`` with every stored path in its strings replaced by the file's shown name
    (``names``: path text -> shown name; the longest paths first)."""
    if isinstance(x, dict):
        return {k: rename(v, names) for k, v in x.items()}
    if isinstance(x, list):
        return [rename(v, names) for v in x]
    if isinstance(x, str):
        for path, shown in sorted(names.items(), key=lambda kv: -len(kv[0])):
            x = x.replace(path, shown)
    return x


def one_line(exc: BaseException, names: dict | None = None, limit: int = 400) -> str:
    """The message of ``exc`` in one line, stored paths replaced by shown names."""
    from ..errors import one_line as line
    return line(rename(" ".join(str(exc).split()), names or {}), limit)
