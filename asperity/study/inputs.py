"""Every file a study names, found in one place: the study reader, the study store's
fingerprint and the web page's Studies jobs all take them from :func:`study_files`.

A study file names ``study.assembly``, ``study.texture`` and ``study.files`` (a name or
a glob pattern, or a list of them); the assembly file names ``[friction]`` ``gauge`` or
``texture``.  A texture file (a wedge TOML or a surface file), a gauge file and a scan name
no other file.  Each name is turned into a path by :func:`asperity.paths.named_path` (and
the patterns into their matches by :func:`asperity.paths.matching_files`), here only: the
reader opens the paths found here, the workers resolve the assembly's names with the same
function relative to the same folder.

With a :class:`Confine` every name must resolve inside its ``root`` (the web page's job
folder), whatever its form -- absolute, ``..``, ``~``, a glob, a symbolic link pointing
out -- or it is refused, before anything is read or globbed, in one line naming the key
(``study.files = '/etc/host*': <outside>``); a name that resolves inside but to no file is
refused too (``<missing>``), so that a refusal never says whether a file outside exists.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError, check_text
from ..paths import check_inside, file_digest, inside_matches, matching_files, named_path

#: most files of a scan library
MAX_FILES = 1_000_000
#: top-level tables of the TOML files a study reads (assembly and texture files)
_TOML_TOP = {"name", "description", "assembly", "friction", "loading", "texture", "springs"}


@dataclass(frozen=True)
class Confine:
    """Keep the files a study names inside the folder ``root``; ``outside`` and ``missing``
    end the one-line refusals (the page's words)."""

    root: Path
    outside: str = "names a file outside the folder the study may read"
    missing: str = "no such file"


@dataclass(frozen=True)
class Named:
    """One file name written in the study or its assembly: where (``key``), as written
    (``value``), and the paths it resolves to (a pattern: its matches)."""

    key: str
    value: str
    paths: tuple[Path, ...]


@dataclass(frozen=True)
class StudyFiles:
    """The files a study names (:func:`study_files`), and its assembly file's tables (read
    once, here)."""

    named: tuple[Named, ...]
    assembly: dict | None = None

    def path(self, key: str) -> Path | None:
        """The path of the single name at ``key`` (None if the study has none there)."""
        for n in self.named:
            if n.key == key:
                return n.paths[0]
        return None

    @property
    def scans(self) -> tuple[str, ...]:
        """The files of a scan library (``study.files``), in order, each once."""
        seen, out = set(), []
        for n in self.named:
            if n.key.startswith("study.files"):
                for p in map(str, n.paths):
                    if p not in seen:
                        seen.add(p)
                        out.append(p)
        return tuple(out)

    @property
    def existing(self) -> tuple[str, ...]:
        """Every named file that exists (what the study may read), each once."""
        out = dict.fromkeys(str(p) for n in self.named for p in n.paths if p.is_file())
        return tuple(out)


def assembly_key(value: str, key: str) -> str:
    """How a name in the assembly file is called in messages: ``bushing.toml: friction.gauge``."""
    return f"{value}: friction.{key}"


def study_files(st: dict, folder, kind: str, confine: Confine | None = None) -> StudyFiles:
    """The files named by the ``[study]`` table ``st`` of a study file in ``folder`` (the
    assembly file is read to find the files it names); ``confine``: refuse any name that
    resolves outside its root.  One-line InputError."""
    folder = Path(folder)
    named: list[Named] = []

    def one(key: str, value, base: Path, what: str) -> Path:
        v = check_text(key, value, 4096)
        if not v:
            raise InputError(f"{key} must be a file name ({what})")
        p = named_path(v, base)
        if confine is not None:
            check_inside(key, v, base, confine.root, confine.outside)
            if not p.is_file():
                raise InputError(f"{key} = {v!r}: {confine.missing}")
        named.append(Named(key, v, (p,)))
        return p

    asm = None
    if "assembly" in st:
        asm_path = one("study.assembly", st["assembly"], folder, "an assembly TOML file")
        asm = read_input_toml(asm_path, "assembly file")
        fr = asm.get("friction")
        for k in ("gauge", "texture"):
            if isinstance(fr, dict) and isinstance(fr.get(k), str) and fr[k]:
                one(assembly_key(st["assembly"], k), fr[k], asm_path.parent,
                    "a gauge or texture file")
    if "texture" in st:
        one("study.texture", st["texture"], folder, "a texture TOML or surface file")
    if "files" in st:
        _patterns(st["files"], folder, kind, confine, named)
    return StudyFiles(tuple(named), asm)


def _patterns(pats, folder: Path, kind: str, confine, named: list) -> None:
    if isinstance(pats, str):
        items = [("study.files", pats)]
    elif isinstance(pats, list) and pats:
        items = [(f"study.files[{i}]", p) for i, p in enumerate(pats)]
    else:
        raise InputError("study.files must be a list of file names or patterns, e.g. "
                         "[\"scans/*.x3p\"] (relative to the study file)")
    for key, pat in items:
        check_text(key, pat, 4096)
        if confine is not None:
            check_inside(key, pat, folder, confine.root, confine.outside)
    if kind != "files":
        return                                 # refused by the reader: nothing to match
    total = 0
    for key, pat in items:
        hits = matching_files(pat, folder)
        if confine is not None:
            inside_matches(key, pat, hits, confine.root, confine.outside)
            if not hits:
                raise InputError(f"{key} = {pat!r}: {confine.missing}")
        if not hits:
            raise InputError(f"{key} {pat!r} matches no file (relative to {folder})")
        total += len(hits)
        if total > MAX_FILES:
            raise InputError(f"study.files: at most {MAX_FILES} files, got more")
        named.append(Named(key, pat, tuple(hits)))


def read_input_toml(path: Path, what: str) -> dict:
    """The tables of an assembly or texture file a study names."""
    from ..io import read_toml
    return read_toml(path, what, _TOML_TOP, InputError)


def digests(paths) -> dict[str, str]:
    """{path: SHA-256 of its content} of the files ``paths``."""
    return {p: file_digest(p) for p in paths}
