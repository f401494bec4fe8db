"""Abaqus/Standard FRIC generated from a gauge file, and the entry point of every generated
routine (:func:`routine_source`).

FRIC (Abaqus User Subroutines Reference, FRIC): called at a closed contact point in every
iteration with TAU and STATEV as they were at the start of the increment, DGAM the slip
increment of the whole increment so far and LM as the previous iteration left it; it returns
the frictional stress at the end of the increment (the sign of the slip), DDTDDG and DDTDDP,
and LM = 0 (slip or elastic stick).  The routine is therefore a pure function of its
start-of-increment values: iterations leave no trace.

Properties (``*FRICTION, USER, PROPERTIES=3``): PROPS(1) the elastic slip stiffness (shear
stress per unit slip, > 0), PROPS(2) the angle (deg) from local slip direction 1 to the law's
+x axis, PROPS(3) +1 when the texture is on the main (master) surface, -1 on the secondary
(slave) surface.  State variables (``DEPVAR``, each used only if present): STATEV(1) the
accumulated frictional slip (path length), STATEV(2) the increments whose pressure lay
outside a law family's pressures (the law clamped), STATEV(3) 1 if the point slipped in the
increment, 0 if it stuck.
"""
from __future__ import annotations

from .fortran_core import comment_block, law_source

ROUTINES = ("fric", "vfric", "vfriction")

FRIC = """\
      SUBROUTINE FRIC(LM,TAU,DDTDDG,DDTDDP,DSLIP,SED,SFD,
     1 DDTDDT,PNEWDT,STATEV,DGAM,TAULM,PRESS,DPRESS,DDPDDH,SLIP,
     2 KSTEP,KINC,TIME,DTIME,NOEL,CINAME,SLNAME,MSNAME,NPT,NODE,
     3 NPATCH,COORDS,RCOORD,DROT,TEMP,PREDEF,NFDIR,MCRD,NPRED,
     4 NSTATV,CHRLNGTH,PROPS,NPROPS)
C
      INCLUDE 'ABA_PARAM.INC'
C
      CHARACTER*80 CINAME,SLNAME,MSNAME
C
      DIMENSION TAU(NFDIR),DDTDDG(NFDIR,NFDIR),DDTDDP(NFDIR),
     1 DSLIP(NFDIR),DDTDDT(NFDIR,2),STATEV(*),DGAM(NFDIR),
     2 TAULM(NFDIR),SLIP(NFDIR),TIME(2),COORDS(MCRD),
     3 RCOORD(MCRD),DROT(2,2),TEMP(2),PREDEF(2,*),PROPS(NPROPS)
C
      DOUBLE PRECISION OUT(12),PD,AKD,XL,YL,S1,S2,CT,ST,THD,
     1 A11,A21,A12,A22,B11,B21,B12,B22,PID
      INTEGER NCL
      PARAMETER (PID=3.141592653589793D0)
C     an open point (LM = 2 on entry) stays frictionless
      IF (LM .EQ. 2) RETURN
      AKD = PROPS(1)
      IF (AKD .LE. 0.0D0) THEN
C       no elastic slip stiffness: rigid stick by Lagrange multipliers
        LM = 1
        RETURN
      END IF
      LM = 0
      PD = PRESS
      THD = PROPS(2)*PID/180.0D0
      IF (NPROPS .GE. 3) THEN
        IF (PROPS(3) .LT. 0.0D0) THEN
          THD = THD + PID
        END IF
      END IF
      CT = COS(THD)
      ST = SIN(THD)
      NCL = 0
      DO 10 I = 1, NFDIR
        DDTDDP(I) = 0.0D0
        DO 10 J = 1, NFDIR
          DDTDDG(I,J) = 0.0D0
   10 CONTINUE
      IF (PD .LE. 0.0D0) THEN
        DO 20 I = 1, NFDIR
          DSLIP(I) = TAU(I)/AKD + DGAM(I)
          TAU(I) = 0.0D0
   20   CONTINUE
        SFD = 0.0D0
        SED = 0.0D0
        RETURN
      END IF
      IF (NFDIR .EQ. 1) THEN
        S1 = TAU(1) + AKD*DGAM(1)
        CALL ASPLAW(4,PD,S1,-THD,OUT,NCL)
        TAU(1) = OUT(1)
        DDTDDG(1,1) = AKD*OUT(2)
        DDTDDP(1) = OUT(3)
        DSLIP(1) = (S1-OUT(1))/AKD
        SFD = TAU(1)*DSLIP(1)
        SED = TAU(1)*TAU(1)/(2.0D0*AKD)
      ELSE
        S1 = TAU(1) + AKD*DGAM(1)
        S2 = TAU(2) + AKD*DGAM(2)
        XL = CT*S1 + ST*S2
        YL = -ST*S1 + CT*S2
        OUT(1) = CT*TAU(1) + ST*TAU(2)
        OUT(2) = -ST*TAU(1) + CT*TAU(2)
        CALL ASPLAW(3,PD,XL,YL,OUT,NCL)
        TAU(1) = CT*OUT(1) - ST*OUT(2)
        TAU(2) = ST*OUT(1) + CT*OUT(2)
        A11 = OUT(3)
        A21 = OUT(4)
        A12 = OUT(5)
        A22 = OUT(6)
        B11 = CT*A11 - ST*A21
        B21 = ST*A11 + CT*A21
        B12 = CT*A12 - ST*A22
        B22 = ST*A12 + CT*A22
        DDTDDG(1,1) = AKD*(B11*CT - B12*ST)
        DDTDDG(1,2) = AKD*(B11*ST + B12*CT)
        DDTDDG(2,1) = AKD*(B21*CT - B22*ST)
        DDTDDG(2,2) = AKD*(B21*ST + B22*CT)
        DDTDDP(1) = CT*OUT(7) - ST*OUT(8)
        DDTDDP(2) = ST*OUT(7) + CT*OUT(8)
        DSLIP(1) = (S1-TAU(1))/AKD
        DSLIP(2) = (S2-TAU(2))/AKD
        SFD = TAU(1)*DSLIP(1) + TAU(2)*DSLIP(2)
        SED = (TAU(1)*TAU(1) + TAU(2)*TAU(2))/(2.0D0*AKD)
      END IF
      IF (NSTATV .GE. 1) STATEV(1) = STATEV(1)
     1  + SQRT(DSLIP(1)**2 + DSLIP(NFDIR)**2*(NFDIR-1))
      IF (NSTATV .GE. 2) STATEV(2) = STATEV(2) + NCL
      IF (NSTATV .GE. 3) THEN
        STATEV(3) = 0.0D0
        IF (OUT(9) .GT. 0.5D0) STATEV(3) = 1.0D0
      END IF
      RETURN
      END
C
"""


def law_table_of(gauge, tol: float = 1e-4):
    """LawTable of a GaugeLaw, FamilyTable of a GaugeFamily."""
    from ..laws.family import GaugeFamily
    from .table import family_table, law_table
    return family_table(gauge, tol) if isinstance(gauge, GaugeFamily) else law_table(gauge, tol)


def routine_source(gauge, routine: str = "fric", header=(), table=None) -> str:
    """The self-contained fixed-form Fortran of ``routine`` ("fric", "vfric" or
    "vfriction") for a GaugeLaw or GaugeFamily: the header comment lines ``header``, the
    routine, and the law's table and core."""
    from ..errors import check_choice
    routine = check_choice("routine", routine, ROUTINES)
    table = table if table is not None else law_table_of(gauge)
    if routine == "fric":
        return comment_block(header) + FRIC + law_source(table)
    from .abaqus_explicit import explicit_source
    return explicit_source(routine, law_source(table), header)
