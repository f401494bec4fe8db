"""The gfortran/ctypes harness (asperity.fe.fortran_harness) passes each routine what
Abaqus passes: checked with echo routines that have the routines' exact argument lists and
write what they receive into their state (the array sizes, the slip, the loads, the
properties, the direction cosines, the names with their hidden lengths), and a routine that
writes past its state variables is caught.  A harness bug would be a bug of every FE test."""
from __future__ import annotations

import numpy as np
import pytest
from fe_builds import library, needs_gfortran
from fe_standin import FRIC_INTERFACE as FRIC_HEAD

from asperity.fe.abaqus_explicit import VFRIC_HEAD, VFRICTION_HEAD
from asperity.fe.fortran_harness import FortranError, call_fric, call_vfric, call_vfriction

pytestmark = needs_gfortran


#: STATEV(1..22) of the FRIC echo
FRIC_ECHO = FRIC_HEAD + """\
      NAMES = 0
      IF (CINAME(1:8) .EQ. 'TEXTURED' .AND. SLNAME(1:9) .EQ. 'SECONDARY'
     1 .AND. MSNAME(1:4) .EQ. 'MAIN' .AND. LEN(MSNAME) .EQ. 80
     2 .AND. CINAME(9:80) .EQ. ' ') NAMES = 1
      STATEV(1) = LM
      STATEV(2) = KSTEP
      STATEV(3) = KINC
      STATEV(4) = NFDIR
      STATEV(5) = MCRD
      STATEV(6) = NSTATV
      STATEV(7) = NPROPS
      STATEV(8) = PRESS
      STATEV(9) = DTIME
      STATEV(10) = NODE
      STATEV(11) = DGAM(1)
      STATEV(12) = DGAM(NFDIR)
      STATEV(13) = PROPS(1)
      STATEV(14) = PROPS(NPROPS)
      STATEV(15) = DROT(1,1)
      STATEV(16) = DROT(2,1)
      STATEV(17) = DROT(1,2)
      STATEV(18) = TAU(NFDIR)
      STATEV(19) = NAMES
      STATEV(20) = SLIP(1)
      STATEV(21) = NOEL
      STATEV(22) = SED
      LM = 0
      DO 10 I = 1, NFDIR
        TAU(I) = -DGAM(I)
        DSLIP(I) = 2.0D0*DGAM(I)
   10 CONTINUE
      IF (PROPS(1) .LT. 0.0D0) STATEV(NSTATV+1) = 1.0D0
      RETURN
      END
"""

VFRICTION_ECHO = VFRICTION_HEAD + """\
      do 10 k = 1, nBlock
         state(1,1,k) = dSlipFric(1,k)
         state(2,1,k) = dSlipFric(nDir,k)
         state(3,1,k) = fNormal(k)
         state(4,1,k) = fStickForce(k)
         state(5,1,k) = areaCont(k)
         state(6,1,k) = dircosSl(1,k)
         state(7,1,k) = dircosN(nDir,k)
         state(8,1,k) = nBlock
         state(9,1,k) = nDir
         state(10,1,k) = nFricDir
         state(11,1,k) = nStates
         state(12,1,k) = nProps
         state(13,1,k) = props(nProps)
         state(14,1,k) = jConSlvUid(1,k)
         state(15,1,k) = nNodState
         state(16,1,k) = 0
         if (surfInt(1:8) .eq. 'TEXTURED') state(16,1,k) = 1
         fTangential(1,k) = -fStickForce(k)
   10 continue
      if (props(1) .lt. 0) state(nStates,1,nBlock+1) = 1
      return
      end
"""

VFRIC_ECHO = VFRIC_HEAD + """\
      do 10 k = 1, nContact
         jn = jConSlvid(k)
         statev(1,jn) = dSlipFric(1,k)
         statev(2,jn) = dSlipFric(nDir,k)
         statev(3,jn) = fNormal(k)
         statev(4,jn) = fStickForce(k)
         statev(5,jn) = areaSlv(jn)
         statev(6,jn) = dirCosSl(1,k)
         statev(7,jn) = dirCosN(nDir,k)
         statev(8,jn) = nContact
         statev(9,jn) = nDir
         statev(10,jn) = nFricDir
         statev(11,jn) = nStateVar
         statev(12,jn) = nSlvNod
         statev(13,jn) = props(nProps)
         statev(14,jn) = k
         fTangential(1,k) = -fStickForce(k)
   10 continue
      return
      end
"""


@pytest.mark.parametrize("nfdir", [1, 2])
def test_fric_receives_what_abaqus_passes(nfdir):
    lib = library(FRIC_ECHO)
    dgam = np.array([2.5e-6, -1.5e-6])[:nfdir]
    props = np.array([3e9, 30.0, -1.0])
    drot = np.array([[0.6, -0.8], [0.8, 0.6]])
    tau0 = np.array([7.0, -9.0])[:nfdir]
    out = call_fric(lib, lm=1, tau=tau0, statev=np.zeros(30), dgam=dgam, press=4.5e6,
                    props=props, nfdir=nfdir, drot=drot, kinc=7, kstep=3, dtime=0.25,
                    sed=1.25, node=42, slip=np.full(nfdir, 8e-6))
    sv = out.statev
    assert sv[:10].tolist() == [1, 3, 7, nfdir, 3, 30, 3, 4.5e6, 0.25, 42]
    assert sv[10:14].tolist() == [dgam[0], dgam[-1], 3e9, -1.0]
    assert sv[14:17].tolist() == [0.6, 0.8, -0.8]          # DROT column-major
    assert sv[17:22].tolist() == [tau0[-1], 1.0, 8e-6, 0.0, 1.25]
    assert sv[22:].tolist() == [0.0] * 8                    # nothing else touched
    assert out.lm == 0 and out.tau.tolist() == (-dgam).tolist()
    assert out.dslip.tolist() == (2 * dgam).tolist()
    assert tau0.tolist() == [7.0, -9.0][:nfdir]            # the caller's TAU is a copy


def test_a_routine_writing_past_its_state_is_caught():
    lib = library(FRIC_ECHO)
    with pytest.raises(FortranError, match="past the end of STATEV"):
        call_fric(lib, lm=0, tau=np.zeros(2), statev=np.zeros(22), dgam=np.zeros(2),
                  press=1.0, props=np.array([-1.0, 0.0, 1.0]))
    lib = library(VFRICTION_ECHO)
    with pytest.raises(FortranError, match="past the end of state"):
        call_vfriction(lib, fnormal=[1.0], fstick=[1.0], dircos_sl=[[1.0], [0.0], [0.0]],
                       dircos_n=[[0.0], [0.0], [1.0]], props=[-1.0, 0.0, 0.0, 1.0],
                       state=np.zeros((16, 1, 1)), area=[1.0])


def _explicit_inputs(nblock: int, ndir: int):
    rng = np.random.default_rng(5)
    sl = rng.normal(size=(ndir, nblock))
    n = rng.normal(size=(ndir, nblock))
    return {"fnormal": rng.uniform(1, 2, nblock), "fstick": rng.uniform(0.1, 1, nblock),
            "dircos_sl": sl / np.linalg.norm(sl, axis=0), "dircos_n": n / np.linalg.norm(n, axis=0),
            "props": np.array([1.0, 0.5, -0.25, -1.0]), "area": rng.uniform(1e-6, 2e-6, nblock),
            "dslip": rng.normal(scale=1e-6, size=(ndir, nblock))}


@pytest.mark.parametrize("precision", ["double", "single"])
@pytest.mark.parametrize("ndir", [2, 3])
def test_vfriction_receives_what_abaqus_passes(precision, ndir):
    dtype = np.float64 if precision == "double" else np.float32
    nblock = 5
    x = _explicit_inputs(nblock, ndir)
    out = call_vfriction(library(VFRICTION_ECHO, precision), state=np.zeros((16, 1, nblock)),
                         dtype=dtype, **x)
    got = out["state"][:, 0, :].astype(float)
    want = [x["dslip"][0], x["dslip"][-1], x["fnormal"], x["fstick"], x["area"],
            x["dircos_sl"][0], x["dircos_n"][-1]]
    rel = 1e-15 if precision == "double" else 1e-6
    for row, w in enumerate(want):
        assert got[row] == pytest.approx(w, rel=rel, abs=1e-30), row
    assert got[7:].T.tolist() == [[nblock, ndir, ndir - 1, 16, 4, -1.0, k + 1, 1, 1]
                                  for k in range(nblock)]
    assert out["fTangential"][0] == pytest.approx(-x["fstick"], rel=rel)
    no_slip = call_vfriction(library(VFRICTION_ECHO, precision),
                             state=np.zeros((16, 1, nblock)), dtype=dtype,
                             **{**x, "dslip": None})
    assert no_slip["state"][:2, 0, :].tolist() == [[0.0] * nblock] * 2


@pytest.mark.parametrize("ndir", [2, 3])
def test_vfric_receives_what_abaqus_passes_per_surface_node(ndir):
    """Contact points 1..3 on surface nodes 4, 1, 3 of 4: each point's values land in its
    node's column; node 2 (not in contact) is untouched."""
    x = _explicit_inputs(3, ndir)
    area = np.array([1.0, 2.0, 3.0, 4.0]) * 1e-6
    nodes = np.array([4, 1, 3])
    out = call_vfric(library(VFRIC_ECHO), statev=np.zeros((14, 4)), jconslvid=nodes,
                     **{**x, "area": area})
    sv = out["statev"]
    assert sv[:, 1].tolist() == [0.0] * 14
    for k, j in enumerate(nodes - 1):
        assert sv[:7, j].tolist() == [x["dslip"][0, k], x["dslip"][-1, k], x["fnormal"][k],
                                      x["fstick"][k], area[j], x["dircos_sl"][0, k],
                                      x["dircos_n"][-1, k]]
        assert sv[7:, j].tolist() == [3, ndir, ndir - 1, 14, 4, -1.0, k + 1]
    assert out["fTangential"][0].tolist() == (-x["fstick"]).tolist()
