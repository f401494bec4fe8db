"""Compiled Abaqus routines for the FE tests: each source is built once per test process
(gfortran into a temporary folder removed at exit) and loaded through ctypes; tests skip
with the reason when gfortran is absent."""
from __future__ import annotations

import atexit
import ctypes
import shutil
import tempfile
from functools import cache

import pytest

from asperity.fe.fortran_harness import compile_source, gfortran

needs_gfortran = pytest.mark.skipif(
    gfortran() is None, reason="gfortran not installed (Debian package gfortran; .ci/run "
                               "installs it)")


@cache
def build_dir() -> str:
    path = tempfile.mkdtemp(prefix="asperity-fe-tests-")
    atexit.register(shutil.rmtree, path, True)
    return path


@cache
def library(source: str, precision: str = "double") -> ctypes.CDLL:
    """The routine ``source`` compiled against the ``precision`` include stand-ins."""
    return ctypes.CDLL(str(compile_source(source, build_dir(), precision=precision)))
