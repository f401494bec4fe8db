"""Abaqus user routines run without Abaqus: gfortran builds them into a shared library and
ctypes calls them with the full argument lists Abaqus passes (used by the tests and the
benchmark; nothing here is imported by the command).

gfortran's calling convention (https://gcc.gnu.org/onlinedocs/gfortran/Argument-passing-conventions.html):
the symbol is the lower-case name with one trailing underscore (``fric_``), every argument
goes by reference, arrays are column-major, and each CHARACTER argument adds a hidden length
(``size_t``, gfortran >= 8) passed by value at the END of the list, in order: FRIC, VFRIC
and VFRICTION each have three (the interaction and the two surface names, CHARACTER*80).

The include files Abaqus provides are replaced by stand-ins written here (our own text):
``ABA_PARAM.INC`` / ``aba_param.inc`` (Standard, REAL*8) and ``vaba_param.inc`` (Explicit,
double or single precision: the same routine source must compile against both).
"""
from __future__ import annotations

import ctypes as C
import itertools
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: gfortran flags of every build: fixed form held to 72 columns (an overlong line is an
#: error, not silently cut), all warnings shown
FLAGS = ("-shared", "-fPIC", "-O2", "-ffixed-form", "-ffixed-line-length-72", "-Wall",
         "-Werror=line-truncation")
STANDARD_INC = ("      IMPLICIT REAL*8(A-H,O-Z)\n"
                "      PARAMETER (NPRECD=2)\n")
EXPLICIT_INC = {
    "double": ("      implicit real*8 (a-h,o-z)\n"
               "      parameter (j_sys_Dimension = 2)\n"
               "      parameter (n_vec_Length = 136)\n"
               "      parameter (maxblk = n_vec_Length)\n"),
    "single": ("      implicit real (a-h,o-z)\n"
               "      parameter (j_sys_Dimension = 1)\n"
               "      parameter (n_vec_Length = 136)\n"
               "      parameter (maxblk = n_vec_Length)\n"),
}
NAME_LENGTH = 80
_builds = itertools.count()


class FortranError(RuntimeError):
    """gfortran is missing or refused a routine (the message holds its diagnostics)."""


def gfortran() -> str | None:
    """Path of gfortran, or None (tests skip with the reason)."""
    return shutil.which(os.environ.get("ASPERITY_GFORTRAN", "gfortran"))


def write_includes(folder: str | Path, precision: str = "double") -> Path:
    """Write the include stand-ins into ``folder``: ABA_PARAM.INC and aba_param.inc (both
    spellings: the file system is case-sensitive) and vaba_param.inc in ``precision``
    ("double" or "single")."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name in ("ABA_PARAM.INC", "aba_param.inc"):
        (folder / name).write_text(STANDARD_INC)
    (folder / "vaba_param.inc").write_text(EXPLICIT_INC[precision])
    return folder


def compile_source(source: str, folder: str | Path, *, precision: str = "double",
                   program: bool = False, flags: tuple = ()) -> Path:
    """Compile Fortran ``source`` in ``folder`` (include stand-ins of ``precision`` beside
    it) into a new shared library, or an executable when ``program``; return its path.
    Every build gets a new file name: the dynamic loader caches libraries by path."""
    exe = gfortran()
    if exe is None:
        raise FortranError("gfortran not found (Debian: apt-get install gfortran)")
    n = next(_builds)
    work = Path(folder) / f"build{n:03d}_{precision}"
    write_includes(work, precision)
    src = work / "routine.f"
    src.write_text(source)
    out = work / ("a.out" if program else f"libroutine{n:03d}.so")
    cmd = [exe, *(f for f in FLAGS if not (program and f in ("-shared", "-fPIC"))), *flags,
           f"-I{work}", str(src), "-o", str(out)]
    done = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=300,
                          check=False)
    if done.returncode != 0:
        raise FortranError(f"gfortran failed ({' '.join(cmd)}):\n{done.stderr}")
    return out


def load(source: str, folder: str | Path | None = None, precision: str = "double") -> C.CDLL:
    """Compile ``source`` and load the library (in a new temporary folder by default)."""
    folder = folder or tempfile.mkdtemp(prefix="asperity-fortran-")
    return C.CDLL(str(compile_source(source, folder, precision=precision)))


def _i(v) -> C.c_int:
    return C.c_int(int(v))


def _f(a, dtype=np.float64) -> np.ndarray:
    """A Fortran-ordered, writable copy of ``a`` (the routine may write into it)."""
    return np.array(a, dtype=dtype, order="F", copy=True)


#: values after a state array: a routine that writes past its state variables changes them
GUARD = 64
GUARD_VALUE = -7.25


def _guarded(a, dtype):
    """(buffer, view): ``a`` copied, Fortran order, into the head of a buffer followed by
    GUARD sentinel values."""
    a = np.asarray(a, dtype=dtype)
    buf = np.full(a.size + GUARD, GUARD_VALUE, dtype=dtype)
    buf[:a.size] = a.ravel(order="F")
    return buf, buf[:a.size].reshape(a.shape, order="F")


def _check_guard(buf, n: int, what: str) -> None:
    if not (buf[n:] == GUARD_VALUE).all():
        raise FortranError(f"the routine wrote past the end of {what}")


def _names(*names) -> list:
    return [C.create_string_buffer(n.encode().ljust(NAME_LENGTH), NAME_LENGTH) for n in names]


def _ptr(a: np.ndarray):
    assert a.flags.f_contiguous and a.flags.writeable
    return a.ctypes.data_as(C.c_void_p)


# ----------------------------------------------------------------------------- FRIC

@dataclass
class FricOut:
    """What one FRIC call returned (arrays are the caller's copies, as written)."""

    lm: int
    tau: np.ndarray
    statev: np.ndarray
    ddtddg: np.ndarray
    ddtddp: np.ndarray
    dslip: np.ndarray
    sed: float
    sfd: float
    pnewdt: float


def call_fric(lib, *, lm: int, tau, statev, dgam, press: float, props, nfdir: int = 2,
              drot=None, kinc: int = 1, kstep: int = 1, dtime: float = 1.0, sed: float = 0.0,
              node: int = 1, slip=None, sentinel: float | None = None) -> FricOut:
    """One call of ``FRIC`` exactly as Abaqus/Standard makes it (the whole argument list,
    three hidden name lengths at the end). ``tau`` and ``statev`` are copied before the
    call, so the caller's start-of-increment values are never touched. With ``sentinel``
    the outputs (DDTDDG, DDTDDP, DSLIP, SFD) start filled with it, to see what the routine
    wrote."""
    fill = 0.0 if sentinel is None else sentinel
    nstatv = int(np.asarray(statev).size)                # DEPVAR (0: a dummy element)
    tau, dgam = _f(tau), _f(dgam)
    sbuf, statev = _guarded(np.ravel(statev) if nstatv else [], np.float64)
    props = _f(props)
    ddtddg = _f(np.full((nfdir, nfdir), fill))
    ddtddp, dslip = _f(np.full(nfdir, fill)), _f(np.full(nfdir, fill))
    ddtddt = _f(np.full((nfdir, 2), fill))
    taulm, slipa = _f(np.zeros(nfdir)), _f(np.zeros(nfdir) if slip is None else slip)
    time, coords, rcoord = _f([0.0, 0.0]), _f(np.zeros(3)), _f(np.zeros(3))
    drot = _f(np.eye(2) if drot is None else drot)
    temp, predef = _f(np.zeros(2)), _f(np.zeros((2, 1)))
    lm_c, sed_c, sfd_c, pnewdt = C.c_int(lm), C.c_double(sed), C.c_double(fill), C.c_double(1.0)
    names = _names("TEXTURED", "SECONDARY", "MAIN")
    lib.fric_.restype = None
    lib.fric_(C.byref(lm_c), _ptr(tau), _ptr(ddtddg), _ptr(ddtddp), _ptr(dslip),
              C.byref(sed_c), C.byref(sfd_c), _ptr(ddtddt), C.byref(pnewdt),
              sbuf.ctypes.data_as(C.c_void_p),
              _ptr(dgam), _ptr(taulm), C.byref(C.c_double(press)), C.byref(C.c_double(0.0)),
              C.byref(C.c_double(1e12)), _ptr(slipa),
              C.byref(_i(kstep)), C.byref(_i(kinc)), _ptr(time), C.byref(C.c_double(dtime)),
              C.byref(_i(0)), names[0], names[1], names[2], C.byref(_i(0)), C.byref(_i(node)),
              C.byref(_i(1)), _ptr(coords), _ptr(rcoord), _ptr(drot), _ptr(temp), _ptr(predef),
              C.byref(_i(nfdir)), C.byref(_i(3)), C.byref(_i(0)), C.byref(_i(nstatv)),
              C.byref(C.c_double(1.0)), _ptr(props), C.byref(_i(props.size)),
              C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH))
    _check_guard(sbuf, nstatv, "STATEV")
    return FricOut(lm_c.value, tau, statev, ddtddg, ddtddp, dslip, sed_c.value, sfd_c.value,
                   pnewdt.value)


# ----------------------------------------------------------------------------- VFRIC

def call_vfric(lib, *, fnormal, fstick, dircos_sl, dircos_n, props, statev, jconslvid,
               area, dslip=None, dtype=np.float64, sentinel: float = 0.0) -> dict:
    """One call of ``VFRIC`` (Abaqus/Explicit, contact pairs) on ``nContact`` contact points.

    fnormal, fstick : (nContact,) normal force and stick force
    dircos_sl, dircos_n : (nDir, nContact) direction cosines of t1 and of the main normal
    statev : (nStateVar, nSlvNod), indexed by SURFACE node; jconslvid (nContact,) 1-based
    area : (nSlvNod,) tributary areas of the secondary nodes
    Returns fTangential (nFricDir, nContact) and statev as the routine left them."""
    fnormal, fstick = _f(fnormal, dtype), _f(fstick, dtype)
    dsl, dn = _f(dircos_sl, dtype), _f(dircos_n, dtype)
    ndir, ncon = dsl.shape
    nfric = ndir - 1
    props, area = _f(props, dtype), _f(area, dtype)
    buf, statev = _guarded(statev, dtype)
    nsv, nslv = statev.shape
    jcon = _f(jconslvid, np.int32)
    ftan = _f(np.full((nfric, ncon), sentinel), dtype)
    nfac, nmst = 4, 4
    jslv = _f(np.arange(1, nslv + 1), np.int32)
    jmst = _f(np.arange(1, nmst + 1), np.int32)
    jconm = _f(np.ones((nfac, ncon)), np.int32)
    dslip = _f(np.zeros((ndir, ncon)) if dslip is None else dslip, dtype)
    ftprev, shape = _f(np.zeros((ndir, ncon)), dtype), _f(np.zeros((nfac, ncon)), dtype)
    cslv, cmst = _f(np.zeros((ndir, nslv)), dtype), _f(np.zeros((ndir, nmst)), dtype)
    tslv, pslv = _f(np.zeros(ncon), dtype), _f(np.zeros((ncon, 1)), dtype)
    tmst, pmst = _f(np.zeros(1), dtype), _f(np.zeros((1, 1)), dtype)
    real = C.c_double if dtype == np.float64 else C.c_float
    names = _names("TEXTURED", "SECONDARY", "MAIN")
    lib.vfric_.restype = None
    lib.vfric_(_ptr(ftan), buf.ctypes.data_as(C.c_void_p),
               *(C.byref(_i(v)) for v in (1, 1, ncon, nfac, nslv, nmst, nfric, ndir, nsv,
                                          props.size, 0, 1, 1)),
               _ptr(jslv), _ptr(jmst), _ptr(jcon), _ptr(jconm),
               C.byref(real(0.0)), C.byref(real(0.0)), C.byref(real(1e-6)),
               names[0], names[1], names[2], C.byref(_i(1)),
               _ptr(dslip), _ptr(fstick), _ptr(ftprev), _ptr(fnormal), C.byref(real(0.0)),
               _ptr(shape), _ptr(cslv), _ptr(cmst), _ptr(dsl), _ptr(dn), _ptr(props),
               _ptr(area), _ptr(tslv), _ptr(pslv), _ptr(tmst), _ptr(pmst),
               C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH))
    _check_guard(buf, statev.size, "statev")
    return {"fTangential": ftan, "statev": statev}


def call_vfriction(lib, *, fnormal, fstick, dircos_sl, dircos_n, props, state, area,
                   dslip=None, dtype=np.float64, sentinel: float = 0.0) -> dict:
    """One call of ``VFRICTION`` (Abaqus/Explicit, general contact) on ``nBlock`` contact
    points of node-to-face contact (nNodState = nNodSlv = 1, facets of 4 main nodes).

    state : (nStates, 1, nBlock); area : (nBlock,) the contact areas (areaCont)."""
    fnormal, fstick = _f(fnormal, dtype), _f(fstick, dtype)
    dsl, dn = _f(dircos_sl, dtype), _f(dircos_n, dtype)
    ndir, nblock = dsl.shape
    nfric = ndir - 1
    props, area = _f(props, dtype), _f(area, dtype)
    buf, state = _guarded(state, dtype)
    nstates, nnodstate, _ = state.shape
    nslv, nmst, nfields = 1, 4, 1
    ftan = _f(np.full((nfric, nblock), sentinel), dtype)
    jflags = _f([1, 1, 1], np.int32)
    rdata = _f([0.0, 0.0, 1e-6, 0.0], dtype)
    jslv = _f(np.arange(1, nblock + 1).reshape(1, nblock), np.int32)
    jmst = _f(np.ones((nmst, nblock)), np.int32)
    dslip = _f(np.zeros((ndir, nblock)) if dslip is None else dslip, dtype)
    ftprev = _f(np.zeros((ndir, nblock)), dtype)
    shs, shm = _f(np.ones((nslv, 1)), dtype), _f(np.zeros((nmst, nblock)), dtype)
    cs, cm = _f(np.zeros((ndir, nslv, nblock)), dtype), _f(np.zeros((ndir, nmst, nblock)), dtype)
    vs, vm = _f(np.zeros((ndir, nslv, nblock)), dtype), _f(np.zeros((ndir, nmst, nblock)), dtype)
    ts, tm = _f(np.zeros(nblock), dtype), _f(np.zeros(nblock), dtype)
    fs, fm = _f(np.zeros((nfields, nblock)), dtype), _f(np.zeros((nfields, nblock)), dtype)
    names = _names("TEXTURED", "", "")
    lib.vfriction_.restype = None
    lib.vfriction_(_ptr(ftan), buf.ctypes.data_as(C.c_void_p),
                   *(C.byref(_i(v)) for v in (nblock, nblock, 1, nnodstate, nslv, nmst, nfric,
                                              ndir, nstates, props.size, 0, nfields)),
                   _ptr(jflags), _ptr(rdata), names[0], names[1], names[2],
                   _ptr(jslv), _ptr(jmst), _ptr(props), _ptr(dslip), _ptr(fstick),
                   _ptr(ftprev), _ptr(fnormal), _ptr(area), _ptr(dn), _ptr(dsl),
                   _ptr(shs), _ptr(shm), _ptr(cs), _ptr(cm), _ptr(vs), _ptr(vm),
                   _ptr(ts), _ptr(tm), _ptr(fs), _ptr(fm),
                   C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH), C.c_size_t(NAME_LENGTH))
    _check_guard(buf, state.size, "state")
    return {"fTangential": ftan, "state": state}
