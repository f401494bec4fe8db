"""The package layout: one room per pipeline stage, no import circles, the command line and
the report on top, small modules, and the public API unchanged.

The import graph is read from the source (every ``import`` statement, also those inside
functions, which are the lazy imports that keep ``import asperity`` fast), so a circle
that only closes when some function runs is caught too.
"""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import asperity

PACKAGE = Path(asperity.__file__).resolve().parent
ROOMS = ("texture", "surface", "friction", "laws", "dynamics", "microslip", "report", "cli",
         "web", "contact", "crawling", "fe")
#: lines of code (and comments) a module may have; its docstrings -- the API reference's
#: numpydoc sections and examples -- are not counted, but the whole file stays under
#: MAX_TOTAL_LINES
MAX_LINES = 400
MAX_TOTAL_LINES = 700

#: asperity.__all__ as the public API was fixed (issue 10): names may be added, never lost
PUBLIC_API = {
    "__version__", "WedgeTexture", "GaussianWedgeTexture", "load_texture", "compute_H",
    "compute_reservoir", "compute_axis_coefficients", "SpringModel", "simulate_sliding",
    "simulate_reservoir", "simulate_loading_curve", "load_surface", "FacetSurface",
    "read_surface", "compute_facet_reservoir", "fit_derivation", "WalkerLeineLaw",
    "TruncatedEllipse", "read_gauge", "write_gauge", "PlanarLaw", "coulomb_law",
    "ellipse_law", "truncated_ellipse_law", "collinear_law", "star_law",
    "windward_star_law", "law_from_gauge", "slide", "ratchet_drift_square",
    "deflection_deg", "simulate_microslip", "long_life", "assess", "two_node_chain",
    "strip_chain", "Loading", "load_assembly", "AsperityError", "InputError",
}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports_of(name: str) -> set[str]:
    """The asperity modules that ``name`` imports, anywhere in its source."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            # "from pkg import module" imports the module; "from mod import name" the module
            targets = [f"{mod}.{a.name}" if f"{mod}.{a.name}" in MODULES else mod
                       for a in node.names]
        else:
            continue
        out.update(t for t in targets if t in MODULES and t != name)
    return out


GRAPH = {name: imports_of(name) for name in MODULES}


def find_circle(graph: dict[str, set[str]]) -> list[str] | None:
    """A cycle of the directed graph as a list of nodes (first == last), or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in state:
                found = visit(m)
                if found:
                    return found
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state:
            found = visit(n)
            if found:
                return found
    return None


def test_the_circle_finder_finds_circles():
    assert find_circle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_circle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None


def test_no_import_circle():
    circle = find_circle(GRAPH)
    assert circle is None, "import circle: " + " -> ".join(circle)


def test_every_room_is_a_package_with_a_docstring():
    for room in ROOMS:
        init = PACKAGE / room / "__init__.py"
        assert init.is_file(), f"asperity/{room}/ is not a package"
        assert ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))), \
            f"asperity/{room}/__init__.py says nothing about the room"


def test_the_library_never_imports_the_command_line():
    bad = [(a, b) for a, deps in GRAPH.items() for b in deps
           if b.startswith("asperity.cli") and not a.startswith("asperity.cli")
           and a != "asperity.__main__"]
    assert not bad, f"library modules import the command line: {bad}"


def test_only_the_report_command_imports_the_report():
    bad = [(a, b) for a, deps in GRAPH.items() for b in deps
           if b.startswith("asperity.report") and not a.startswith("asperity.report")
           and a != "asperity.cli.report"]
    assert not bad, f"modules other than cli/report.py import the report: {bad}"


def test_only_the_serve_command_imports_the_web_page():
    """asperity/web/ sits on top like cli/ and report/: nothing but ``asperity serve``
    imports it, and it imports neither the command line nor the report."""
    bad = [(a, b) for a, deps in GRAPH.items() for b in deps
           if b.startswith("asperity.web") and not a.startswith("asperity.web")
           and a != "asperity.cli.serve"]
    assert not bad, f"modules other than cli/serve.py import the web page: {bad}"
    up = [(a, b) for a, deps in GRAPH.items() if a.startswith("asperity.web") for b in deps
          if b.startswith(("asperity.cli", "asperity.report"))]
    assert not up, f"the web page imports the command line or the report: {up}"


def test_the_web_stack_loads_only_for_asperity_serve():
    """``import asperity`` and the command line's parser leave FastAPI, uvicorn, Jinja2
    and Starlette out (``asperity serve --help`` too)."""
    code = ("import sys, asperity\n"
            "from asperity.cli.main import build_parser\n"
            "build_parser()\n"
            "web = [m for m in ('fastapi', 'uvicorn', 'jinja2', 'starlette', 'plotly')\n"
            "       if m in sys.modules]\n"
            "print(web)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60)
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


def docstring_lines(text: str) -> int:
    """Lines taken by the module's, classes' and functions' docstrings."""
    n = 0
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) \
                and node.body and isinstance(node.body[0], ast.Expr) \
                and isinstance(node.body[0].value, ast.Constant) \
                and isinstance(node.body[0].value.value, str):
            n += node.body[0].end_lineno - node.body[0].lineno + 1
    return n


def test_modules_are_small():
    sizes = {name: (len(text.splitlines()), docstring_lines(text))
             for name, p in MODULES.items() for text in [p.read_text(encoding="utf-8")]}
    big = {name: total - docs for name, (total, docs) in sizes.items()
           if total - docs > MAX_LINES}
    assert not big, f"modules over {MAX_LINES} lines of code: {big}"
    long = {name: total for name, (total, _) in sizes.items() if total > MAX_TOTAL_LINES}
    assert not long, f"modules over {MAX_TOTAL_LINES} lines with their docstrings: {long}"


def test_docstring_lines_are_counted_apart():
    text = '"""Module\n\ntext."""\n\n\ndef f():\n    """One\n    two."""\n    return 1\n'
    assert docstring_lines(text) == 5 and len(text.splitlines()) == 9


def test_numba_kernels_live_in_kernel_modules():
    """Compiled loops sit in ``_*kernels`` modules (the kernel triad of STYLE.md), cached."""
    for name, path in MODULES.items():
        text = path.read_text(encoding="utf-8")
        if "@njit" in text or "@numba.njit" in text:
            assert name.rpartition(".")[2].endswith("_kernels"), f"{name} compiles numba code"
            assert "cache=True" in text and "cache=False" not in text, \
                f"{name}: numba kernels must be compiled with cache=True"


def test_every_module_imports_alone_in_a_fresh_interpreter():
    """Each module imported first, with no asperity module loaded before it: an import
    order that only works when something else was imported first fails here."""
    code = ("import importlib, sys\n"
            f"names = {sorted(n for n in MODULES if n != 'asperity.__main__')!r}\n"
            "bad = []\n"
            "for n in names:\n"
            "    for m in [m for m in sys.modules if m == 'asperity' or m.startswith('asperity.')]:\n"
            "        del sys.modules[m]\n"
            "    try:\n"
            "        importlib.import_module(n)\n"
            "    except Exception as exc:\n"
            "        bad.append(f'{n}: {type(exc).__name__}: {exc}')\n"
            "print('\\n'.join(bad))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "", out.stdout


def test_public_api_is_kept_and_resolves():
    assert PUBLIC_API <= set(asperity.__all__), PUBLIC_API - set(asperity.__all__)
    for name in asperity.__all__:
        assert getattr(asperity, name) is not None, name
    with pytest.raises(AttributeError):
        asperity.no_such_name  # noqa: B018


def test_import_asperity_stays_lazy():
    """``import asperity`` loads none of the rooms (numba, matplotlib, scipy stay out)."""
    code = ("import sys, asperity\n"
            "heavy = [m for m in ('numba', 'scipy', 'matplotlib', 'trimesh') if m in sys.modules]\n"
            "rooms = [m for m in sys.modules if m.startswith('asperity.')]\n"
            "print(heavy, rooms)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60)
    assert out.stdout.strip() == "[] []", out.stdout + out.stderr
