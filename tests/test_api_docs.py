"""The API reference as the documentation site builds it: every name of ``asperity.__all__``
has a numpydoc docstring (a summary, every parameter, what it returns, an example), and every
example runs as written (a doctest, in a scratch folder where ``surfaces/`` is the shipped one).

The site's build (``docs/``) draws its API pages from these docstrings and fails on the same
numpydoc checks (``NUMPYDOC_CHECKS`` of the site's extension, ``docs/_ext/asperity_docs.py``)."""
from __future__ import annotations

import doctest
import sys
from pathlib import Path

import numpy as np
import pytest

import asperity

ROOT = Path(__file__).resolve().parents[1]
numpydoc_validate = pytest.importorskip("numpydoc.validate", reason="the docs extra")
pytest.importorskip("sphinx", reason="the docs extra")
sys.path.insert(0, str(ROOT / "docs" / "_ext"))
CHECKS = __import__("asperity_docs").NUMPYDOC_CHECKS      # the site's own list
PUBLIC = [name for name in asperity.__all__ if name != "__version__"]


@pytest.fixture
def in_project(tmp_path, monkeypatch):
    """A scratch working folder in which ``surfaces/`` is the shipped one."""
    (tmp_path / "surfaces").symlink_to(ROOT / "surfaces", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("name", PUBLIC)
def test_numpydoc_sections(name):
    result = numpydoc_validate.validate(f"asperity.{name}")
    errors = [f"{code} {message}" for code, message in result["errors"] if code in CHECKS]
    assert not errors, f"asperity.{name}: " + "; ".join(errors)


@pytest.mark.parametrize("name", PUBLIC)
def test_examples_run_as_written(name, in_project):
    obj = getattr(asperity, name)
    tests = [t for t in doctest.DocTestFinder(recurse=False).find(obj, f"asperity.{name}")
             if t.examples]
    assert tests, f"asperity.{name} has no example"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for test in tests:
        test.globs = {"asperity": asperity, "np": np}
        runner.run(test)
    summary = runner.summarize(verbose=False)
    assert summary.failed == 0, f"asperity.{name}: {summary.failed} example(s) failed (above)"
