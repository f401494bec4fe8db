"""Fortran text of the Abaqus/Explicit wrappers VFRIC (contact pairs) and VFRICTION
(general contact) around the generated law-frame core (``ASPLAW``: IOP = 1 the force for
a sliding direction, IOP = 2 the radial function of C; :mod:`asperity.fe.fortran_core`).

Per contact point: the local frame is t1 = dirCosSl (the slip direction of this
increment), n = dirCosN (the main surface's normal), t2 = n x t1 (3D; nFricDir = 1 in 2D).
props(1:3) is the law's +x axis in global coordinates; its projection on the tangent plane
lies at the angle th = atan2(a.t2, a.t1) from t1, so t1 is the law angle -th. props(4) = +1
puts the texture on the main surface: the secondary node slides over it along t1 and the
force on it is -fNormal p(-th); -1 on the secondary surface: the main surface slides over
the texture along -t1 and the force on the secondary node is the reaction +fNormal
p(180 deg - th). The law holds the node when the stick force vector lies in fNormal C
(|fStickForce| at most fNormal R(angle of the slider's sliding direction)): then
fTangential = (-fStickForce, 0); otherwise the sliding force rotated into (t1, t2), its
first component clipped to [-fStickForce, 0] as Abaqus requires. Pressure (for law
families) = fNormal / area of the node (VFRIC: areaSlv of the surface node, VFRICTION:
areaCont).

The wrappers use the include file's implicit typing only (the same source compiles against
the double and the single precision vaba_param.inc); the core is double precision and is
called with DBLE arguments.
"""
from __future__ import annotations

from .fortran_core import comment_block

#: state variables of the explicit routines (1-based), written only when they exist
EXPLICIT_STATE = (
    ("clamped", ("increments at which the pressure lay outside the law family's "
                 "pressures (clamped to the nearest member)")),
    ("stick", "1 if the law held the node at the last increment, 0 if it slid"),
)

VFRIC_HEAD = """\
      subroutine vfric(
C Write only -
     1 fTangential,
C Read/Write -
     2 statev,
C Read only -
     3 kStep, kInc, nContact, nFacNod, nSlvNod, nMstNod,
     4 nFricDir, nDir, nStateVar, nProps, nTemp, nPred, numDefTfv,
     5 jSlvUid, jMstUid, jConSlvid, jConMstid, timStep, timGlb,
     6 dTimCur, surfInt, surfSlv, surfMst, lContType,
     7 dSlipFric, fStickForce, fTangPrev, fNormal, frictionWork,
     8 shape, coordSlv, coordMst, dirCosSl, dirCosN, props,
     9 areaSlv, tempSlv, preDefSlv, tempMst, preDefMst)
C
      include 'vaba_param.inc'
C
      character*80 surfInt, surfSlv, surfMst
C
      dimension props(nProps), statev(nStateVar,nSlvNod),
     1 dSlipFric(nDir,nContact), fTangential(nFricDir,nContact),
     2 fTangPrev(nDir,nContact), fStickForce(nContact),
     3 areaSlv(nSlvNod), fNormal(nContact), shape(nFacNod,nContact),
     4 coordSlv(nDir,nSlvNod), coordMst(nDir,nMstNod),
     5 dirCosSl(nDir,nContact), dirCosN(nDir,nContact),
     6 jSlvUid(nSlvNod), jMstUid(nMstNod), jConSlvid(nContact),
     7 jConMstid(nFacNod,nContact), tempSlv(nContact),
     8 preDefSlv(nContact,nPred), tempMst(numDefTfv),
     9 preDefMst(numDefTfv,nPred)
"""

VFRICTION_HEAD = """\
      subroutine vfriction(
C Write only -
     1 fTangential,
C Read/Write -
     2 state,
C Read only -
     3 nBlock, nBlockAnal, nBlockEdge,
     4 nNodState, nNodSlv, nNodMst,
     5 nFricDir, nDir,
     6 nStates, nProps, nTemp, nFields,
     7 jFlags, rData,
     8 surfInt, surfSlv, surfMst,
     9 jConSlvUid, jConMstUid, props,
     1 dSlipFric, fStickForce, fTangPrev, fNormal,
     2 areaCont, dircosN, dircosSl,
     3 shapeSlv, shapeMst,
     4 coordSlv, coordMst,
     5 velSlv, velMst,
     6 tempSlv, tempMst,
     7 fieldSlv, fieldMst)
C
      include 'vaba_param.inc'
C
      dimension fTangential(nFricDir,nBlock),
     1 state(nStates,nNodState,nBlock),
     2 jConSlvUid(nNodSlv,nBlock), jConMstUid(nNodMst,nBlockAnal),
     3 props(nProps), dSlipFric(nDir,nBlock), fStickForce(nBlock),
     4 fTangPrev(nDir,nBlock), fNormal(nBlock), areaCont(nBlock),
     5 dircosN(nDir,nBlock), dircosSl(nDir,nBlock),
     6 shapeSlv(nNodSlv,nBlockEdge), shapeMst(nNodMst,nBlockAnal),
     7 coordSlv(nDir,nNodSlv,nBlock), coordMst(nDir,nNodMst,nBlockAnal),
     8 velSlv(nDir,nNodSlv,nBlock), velMst(nDir,nNodMst,nBlockAnal),
     9 tempSlv(nBlock), tempMst(nBlockAnal),
     1 fieldSlv(nFields,nBlock), fieldMst(nFields,nBlockAnal)
C
      parameter (iKStep = 1, iKInc = 2, iLConType = 3, nFlags = 3)
      parameter (iTimStep = 1, iTimGlb = 2, iDTimCur = 3,
     1 iFrictionWork = 4, nData = 4)
      dimension jFlags(nFlags), rData(nData)
      character*80 surfInt, surfSlv, surfMst
"""

#: the loop over the contact points; {n}: their number, {jn}: where point k's state
#: lies, {area}: its area, {sv1}, {sv2}: its state variables, {sl}, {cn}: the
#: direction-cosine arrays of t1 and n
BODY = """\
C
      double precision dpr, dth, dphi, drad, dpx, dpy, dfx, dfy, da1,
     1 da2, dc, ds, dfs, dfn, df1, df2, dpi, dout(12), dzero
      integer nclamp, lstick
      parameter (dpi = 3.141592653589793238D0)
      dzero = 0.0D0
C
      do 100 k = 1, {n}
         fTangential(1,k) = 0
         if (nFricDir .ge. 2) fTangential(2,k) = 0
         dfn = dble(fNormal(k))
         if (dfn .le. 0.0D0) go to 100
         dfs = dble(fStickForce(k))
         jn = {jn}
         ar = {area}
         dpr = 0.0D0
         if (ar .gt. 0) dpr = dfn/dble(ar)
C        the law's +x axis (props(1:3)) seen from t1 (projected)
         da1 = dble(props(1))*dble({sl}(1,k))
     1       + dble(props(2))*dble({sl}(2,k))
         da2 = 0.0D0
         if (nDir .ge. 3) then
            da1 = da1 + dble(props(3))*dble({sl}(3,k))
            da2 = dble(props(1))*(dble({cn}(2,k))*dble({sl}(3,k))
     1          - dble({cn}(3,k))*dble({sl}(2,k)))
     2          + dble(props(2))*(dble({cn}(3,k))*dble({sl}(1,k))
     3          - dble({cn}(1,k))*dble({sl}(3,k)))
     4          + dble(props(3))*(dble({cn}(1,k))*dble({sl}(2,k))
     5          - dble({cn}(2,k))*dble({sl}(1,k)))
         end if
         dth = 0.0D0
         if (da1 .ne. 0.0D0 .or. da2 .ne. 0.0D0) dth = atan2(da2, da1)
C        the slider's sliding direction in the law frame: the secondary
C        node along t1 (texture on main), or the main surface along -t1
         side = 1
         if (nProps .ge. 4) side = props(4)
         dphi = -dth
         if (side .lt. 0) dphi = dpi - dth
         call asplaw(2, dpr, dphi, dzero, dout, nclamp)
         drad = dout(1)
         if (dfs .le. dfn*drad) then
            lstick = 1
            df1 = -dfs
            df2 = 0.0D0
         else
            lstick = 0
            call asplaw(1, dpr, dphi, dzero, dout, nclamp)
            dpx = dout(1)
            dpy = dout(2)
            dfx = -dfn*dpx
            dfy = -dfn*dpy
            if (side .lt. 0) then
               dfx = -dfx
               dfy = -dfy
            end if
            dc = cos(dth)
            ds = sin(dth)
            df1 = dc*dfx - ds*dfy
            df2 = ds*dfx + dc*dfy
            df1 = min(0.0D0, max(-dfs, df1))
         end if
         fTangential(1,k) = real(df1, kind(fTangential))
         if (nFricDir .ge. 2) then
            fTangential(2,k) = real(df2, kind(fTangential))
         end if
         if (nStates .ge. 1) {sv1} = {sv1} + nclamp
         if (nStates .ge. 2) {sv2} = lstick
  100 continue
      return
      end
"""


def source(routine: str) -> str:
    """The VFRIC (``routine`` = "vfric") or VFRICTION ("vfriction") subroutine text; the
    law's ASPLAW and core must follow it to make a self-contained file."""
    if routine == "vfric":
        body = BODY.format(n="nContact", jn="jConSlvid(k)", area="areaSlv(jn)",
                           sl="dirCosSl", cn="dirCosN", sv1="statev(1,jn)",
                           sv2="statev(2,jn)").replace("nStates", "nStateVar")
        return VFRIC_HEAD + body
    if routine == "vfriction":
        return VFRICTION_HEAD + BODY.format(n="nBlock", jn="k", area="areaCont(k)",
                                            sl="dircosSl", cn="dircosN", sv1="state(1,1,k)",
                                            sv2="state(2,1,k)")
    raise ValueError(f"routine must be vfric or vfriction, got {routine!r}")


def explicit_source(routine: str, core: str, header_lines=()) -> str:
    """A self-contained routine file: ``header_lines`` as comments, the wrapper, then the
    law's table and core ``core`` (the text of :func:`asperity.fe.fortran_core.law_source`)."""
    return comment_block(header_lines) + source(routine) + core
