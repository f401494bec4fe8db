"""numba's cache knows only the file of the function it compiled.  A cached kernel that calls
into another module keeps the callee it was compiled with after that module changes: after a
``git pull`` on an editable install (the README's set-up), or an edit, such a kernel runs the
old code silently (seen: the body solver's step ran its old Newton iteration from the cache
of ``_body_kernels`` after ``_body_step_kernels`` changed).

:func:`refresh`, called at the top of every kernel module that calls into another, drops
that module's cached kernels when one of the modules it calls into has changed since they
were cached (numba's own stamp of a file: its modification time and size), so numba compiles
them again.  It costs a few ``stat`` calls at import.  ``CALLS`` is the one list of which
kernel module calls into which (transitively); ``tests/test_kernel_cache.py`` checks it
against the modules' imports, and the mutation scripts take their dependents from it.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent

#: kernel module -> the kernel modules its kernels call into, transitively (paths in the
#: package, "/"-separated)
CALLS = {
    "laws/_warm_kernels.py": ("laws/_set_kernels.py",),
    "laws/_law_kernels.py": ("laws/_set_kernels.py", "laws/_warm_kernels.py"),
    "dynamics/_moreau_kernels.py": ("laws/_law_kernels.py", "laws/_set_kernels.py",
                                    "laws/_warm_kernels.py"),
    "dynamics/_body_step_kernels.py": ("dynamics/_body_law_kernels.py",),
    "dynamics/_body_kernels.py": ("dynamics/_body_law_kernels.py",
                                  "dynamics/_body_step_kernels.py"),
    "crawling/_kernels.py": ("dynamics/_body_law_kernels.py", "dynamics/_body_step_kernels.py"),
    "texture/_spring_kernels.py": ("texture/_tip_kernels.py",),
    "microslip/_march_kernels.py": ("microslip/_chain_kernels.py",),
    "microslip/_batch_kernels.py": ("microslip/_chain_kernels.py",
                                    "microslip/_march_kernels.py"),
    "microslip/_dynamic_kernels.py": ("microslip/_chain_kernels.py",),
}


def dependents(module: str) -> tuple[str, ...]:
    """The kernel modules whose kernels call into ``module`` (package path)."""
    return tuple(sorted(m for m, deps in CALLS.items() if module in deps))


def stamp(module: str, root: Path = PACKAGE) -> str:
    """A digest of the stamps (modification time, size) of the modules ``module`` calls into."""
    h = hashlib.sha256()
    for dep in CALLS.get(module, ()):
        st = os.stat(root / dep)
        h.update(f"{dep}:{st.st_mtime_ns}:{st.st_size};".encode())
    return h.hexdigest()[:20]


def cache_dir(py_file: Path) -> Path:
    """The folder numba caches the kernels of ``py_file`` in (its first locator that
    applies: NUMBA_CACHE_DIR, the source tree's __pycache__, the user-wide cache)."""
    try:
        from numba.core.caching import CacheImpl
        for cls in CacheImpl._locator_classes:
            loc = cls.from_function(refresh, str(py_file))
            if loc is not None:
                return Path(loc.get_cache_path())
    except Exception:                  # numba's internals moved: the default place
        pass
    return py_file.parent / "__pycache__"


def refresh(module_file: str, root: Path = PACKAGE) -> bool:
    """Drop the cached kernels of the module at ``module_file`` if a module it calls into
    changed since they were cached; True if it dropped them.  Never raises: a cache that
    cannot be read or written is numba's business (it then compiles without caching)."""
    path = Path(module_file).resolve()
    try:
        module = path.relative_to(root).as_posix()
    except ValueError:
        return False
    if module not in CALLS:
        return False
    try:
        now = stamp(module, root)
        folder = cache_dir(path)
        mark = folder / f"{path.stem}.calls"
        if mark.is_file() and mark.read_text() == now:
            return False
        for f in folder.glob(f"{path.stem}.*.nb[ic]"):
            f.unlink(missing_ok=True)
        folder.mkdir(parents=True, exist_ok=True)
        tmp = folder / f".{path.stem}.calls.{os.getpid()}"
        tmp.write_text(now)
        os.replace(tmp, mark)
        return True
    except OSError:
        return False
