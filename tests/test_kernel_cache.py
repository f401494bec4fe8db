"""numba's cache and kernels that call into other modules (asperity/kernel_cache.py): after a
callee changes, the caller's cached kernels are dropped, so no stale machine code runs (it
did: a git pull left the body solver's step running its old Newton iteration)."""
from __future__ import annotations

import ast
import os
from pathlib import Path

import pytest

from asperity import kernel_cache as KC

PKG = Path(KC.__file__).resolve().parent


def kernel_modules():
    return sorted(p.relative_to(PKG).as_posix() for p in PKG.rglob("_*kernels.py"))


def direct_calls(module: str) -> set[str]:
    """The kernel modules a kernel module imports (relative imports of *_kernels modules)."""
    path = PKG / module
    tree = ast.parse(path.read_text())
    out = set()
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and node.level and node.module \
                and node.module.split(".")[-1].endswith("kernels"):
            base = path.parent
            for _ in range(node.level - 1):
                base = base.parent
            target = base.joinpath(*node.module.split(".")).with_suffix(".py")
            out.add(target.relative_to(PKG).as_posix())
    return out


def test_calls_is_the_transitive_closure_of_the_kernel_modules_imports():
    direct = {m: direct_calls(m) for m in kernel_modules()}
    for m in direct:
        seen, todo = set(), list(direct[m])
        while todo:
            d = todo.pop()
            if d not in seen:
                seen.add(d)
                todo.extend(direct.get(d, ()))
        assert set(KC.CALLS.get(m, ())) == seen, \
            f"{m} calls into {sorted(seen)}; kernel_cache.CALLS says {KC.CALLS.get(m)}"
    assert set(KC.CALLS) <= set(direct), "CALLS names a module that is not a kernel module"


def test_every_caller_refreshes_its_cache_at_import_before_its_kernels():
    for m in KC.CALLS:
        tree = ast.parse((PKG / m).read_text())
        calls = [k for k, node in enumerate(tree.body)
                 if isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
                 and getattr(node.value.func, "id", "") == "refresh"
                 and [a.id for a in node.value.args if isinstance(a, ast.Name)] == ["__file__"]]
        defs = [k for k, node in enumerate(tree.body) if isinstance(node, ast.FunctionDef)]
        assert calls, f"{m} does not call refresh(__file__)"
        assert not defs or calls[0] < defs[0], f"{m} calls refresh after defining kernels"


def test_dependents_are_the_inverse_of_calls():
    for m in kernel_modules():
        for d in KC.dependents(m):
            assert m in KC.CALLS[d]
    assert "dynamics/_body_kernels.py" in KC.dependents("dynamics/_body_step_kernels.py")


@pytest.fixture
def tree(tmp_path, monkeypatch):
    """A package root holding the body kernels' three files (contents irrelevant)."""
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    d = tmp_path / "dynamics"
    d.mkdir()
    for name in ("_body_kernels.py", "_body_step_kernels.py", "_body_law_kernels.py"):
        (d / name).write_text("# kernel\n")
    return tmp_path


def caches(folder: Path, stem: str) -> list[str]:
    return sorted(p.name for p in folder.glob(f"{stem}.*.nb[ic]"))


def plant(folder: Path, stem: str):
    folder.mkdir(parents=True, exist_ok=True)
    for name in (f"{stem}.f-10.py311.nbi", f"{stem}.f-10.py311.1.nbc"):
        (folder / name).write_bytes(b"x")


def test_a_changed_callee_drops_the_callers_cache_and_nothing_else(tree):
    caller = tree / "dynamics" / "_body_kernels.py"
    callee = tree / "dynamics" / "_body_step_kernels.py"
    folder = KC.cache_dir(caller)
    assert folder == caller.parent / "__pycache__"
    plant(folder, "_body_kernels")
    plant(folder, "_body_step_kernels")
    # first import after the change of scheme: no mark yet, so the caches are dropped
    assert KC.refresh(str(caller), root=tree)
    assert caches(folder, "_body_kernels") == []
    assert caches(folder, "_body_step_kernels") != []          # the callee's own: numba's
    # numba caches again; nothing changed since: kept
    plant(folder, "_body_kernels")
    assert not KC.refresh(str(caller), root=tree)
    assert caches(folder, "_body_kernels") != []
    # the callee changes (a pull, an edit): dropped again
    st = callee.stat()
    os.utime(callee, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    assert KC.refresh(str(caller), root=tree)
    assert caches(folder, "_body_kernels") == []
    # so does a change of size at the same time stamp
    plant(folder, "_body_kernels")
    callee.write_text("# kernel, longer\n")
    os.utime(callee, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    assert KC.refresh(str(caller), root=tree)


def test_refresh_ignores_modules_that_call_nothing_and_files_outside_the_package(tree):
    assert not KC.refresh(str(tree / "dynamics" / "_body_law_kernels.py"), root=tree)
    assert not KC.refresh(str(tree.parent / "elsewhere.py"), root=tree)


def test_the_cache_folder_follows_numba_cache_dir(tree, monkeypatch):
    import numba.core.config as cfg
    monkeypatch.setattr(cfg, "CACHE_DIR", str(tree / "numba-cache"))
    caller = tree / "dynamics" / "_body_kernels.py"
    folder = KC.cache_dir(caller)
    assert str(folder).startswith(str(tree / "numba-cache"))
    plant(folder, "_body_kernels")
    assert KC.refresh(str(caller), root=tree)
    assert caches(folder, "_body_kernels") == []
