"""Hand-written Fortran stand-ins for the harness tests (not generated from gauge files):

* :func:`coulomb_fric` -- a FRIC with an elastic predictor (PROPS(1) = k) and a return map
  onto mu+ / mu- along the single direction (NFDIR = 1) or onto an isotropic disc of
  radius mu+ (NFDIR = 2), with its consistent tangent;
* :func:`ellipse_core` -- ASPFRC / ASPRAD (the interface of the generated law-frame core)
  for an associated truncated ellipse, closed form, so the explicit wrappers can be tested
  against ``TruncatedEllipse.normal_point`` / ``.radial``.
"""
from __future__ import annotations


def _d(x: float) -> str:
    """A double-precision Fortran literal of ``x``, exact to the last bit."""
    return f"{float(x):.17E}".replace("E", "D")


#: FRIC's interface as the User Subroutines Reference gives it (written here, not taken from
#: the package, so that the stand-ins and the harness's echo check the package's own copy)
FRIC_INTERFACE = """      SUBROUTINE FRIC(LM,TAU,DDTDDG,DDTDDP,DSLIP,SED,SFD,
     1 DDTDDT,PNEWDT,STATEV,DGAM,TAULM,PRESS,DPRESS,DDPDDH,SLIP,
     2 KSTEP,KINC,TIME,DTIME,NOEL,CINAME,SLNAME,MSNAME,NPT,NODE,
     3 NPATCH,COORDS,RCOORD,DROT,TEMP,PREDEF,NFDIR,MCRD,NPRED,
     4 NSTATV,CHRLNGTH,PROPS,NPROPS)
C
      INCLUDE 'ABA_PARAM.INC'
C
      CHARACTER*80 CINAME,SLNAME,MSNAME
      DIMENSION TAU(NFDIR),DDTDDG(NFDIR,NFDIR),DDTDDP(NFDIR),
     1 DSLIP(NFDIR),DDTDDT(NFDIR,2),STATEV(*),DGAM(NFDIR),
     2 TAULM(NFDIR),SLIP(NFDIR),TIME(2),COORDS(MCRD),
     3 RCOORD(MCRD),DROT(2,2),TEMP(2),PREDEF(2,*),PROPS(NPROPS)
"""
HEAD = FRIC_INTERFACE + """      DIMENSION TTR(2)
"""


def coulomb_fric(mu_plus: float, mu_minus: float) -> str:
    """FRIC source of the asymmetric 1D / isotropic 2D Coulomb stand-in."""
    return HEAD + f"""      PARAMETER (XMUP={_d(mu_plus)})
      PARAMETER (XMUM={_d(mu_minus)})
      IF (LM .EQ. 2) RETURN
      LM = 0
      AK = PROPS(1)
      DO 10 I = 1, NFDIR
         TTR(I) = TAU(I) + AK*DGAM(I)
         DDTDDP(I) = 0.0D0
         DSLIP(I) = 0.0D0
         DO 5 J = 1, NFDIR
            DDTDDG(I,J) = 0.0D0
    5    CONTINUE
         DDTDDG(I,I) = AK
   10 CONTINUE
      STK = 1.0D0
      IF (NFDIR .EQ. 1) THEN
         IF (TTR(1) .GT. XMUP*PRESS) THEN
            TAU(1) = XMUP*PRESS
            DDTDDP(1) = XMUP
         ELSE IF (TTR(1) .LT. -XMUM*PRESS) THEN
            TAU(1) = -XMUM*PRESS
            DDTDDP(1) = -XMUM
         ELSE
            TAU(1) = TTR(1)
            GO TO 90
         END IF
         STK = 0.0D0
         DSLIP(1) = (TTR(1) - TAU(1))/AK
         DDTDDG(1,1) = 0.0D0
      ELSE
         TN = SQRT(TTR(1)**2 + TTR(2)**2)
         IF (TN .LE. XMUP*PRESS) THEN
            TAU(1) = TTR(1)
            TAU(2) = TTR(2)
            GO TO 90
         END IF
         STK = 0.0D0
         DO 30 I = 1, 2
            TAU(I) = XMUP*PRESS*TTR(I)/TN
            DSLIP(I) = (TTR(I) - TAU(I))/AK
            DDTDDP(I) = XMUP*TTR(I)/TN
            DO 20 J = 1, 2
               DDTDDG(I,J) = -XMUP*PRESS*AK*TTR(I)*TTR(J)/TN**3
   20       CONTINUE
            DDTDDG(I,I) = DDTDDG(I,I) + XMUP*PRESS*AK/TN
   30    CONTINUE
      END IF
   90 CONTINUE
      IF (NSTATV .GE. 1) STATEV(1) = STK
      RETURN
      END
"""


def ellipse_core(ap: float, am: float, bp: float, bm: float, theta: float = 0.0,
                 p_lo: float = 0.0, p_hi: float = 1e30) -> str:
    """ASPLAW(IOP, PRESS, X, Y, OUT, NCLAMP) for IOP = 1 (the force OUT(1:2) for sliding
    along X rad) and IOP = 2 (the radial function OUT(1) of C at X) of the associated
    truncated ellipse with semi-axes ap/am along +-t_a, bp/bm along +-t_b, t_a at
    ``theta`` rad in the law frame. NCLAMP = 1 when PRESS lies outside [p_lo, p_hi] (as
    a family's pressures would be)."""
    consts = "".join(f"      PARAMETER ({k}={_d(v)})\n" for k, v in
                     (("AP", ap), ("AM", am), ("BP", bp), ("BM", bm), ("TH", theta),
                      ("PLO", p_lo), ("PHI", p_hi)))
    return f"""      SUBROUTINE ASPLAW(IOP, PRESS, X, Y, OUT, NCLAMP)
      IMPLICIT NONE
      INTEGER IOP, NCLAMP
      DOUBLE PRECISION PRESS, X, Y, OUT(12), A, B, C, S, Q, XL, YL
      DOUBLE PRECISION AP, AM, BP, BM, TH, PLO, PHI
{consts}      NCLAMP = 0
      IF (PRESS .LT. PLO .OR. PRESS .GT. PHI) NCLAMP = 1
      C = COS(X - TH)
      S = SIN(X - TH)
      A = AP
      IF (C .LT. 0.0D0) A = AM
      B = BP
      IF (S .LT. 0.0D0) B = BM
      IF (IOP .EQ. 2) THEN
         OUT(1) = 1.0D0/SQRT((C/A)**2 + (S/B)**2)
         RETURN
      END IF
      Q = SQRT((A*C)**2 + (B*S)**2)
      XL = A*A*C/Q
      YL = B*B*S/Q
      OUT(1) = XL*COS(TH) - YL*SIN(TH)
      OUT(2) = XL*SIN(TH) + YL*COS(TH)
      RETURN
      END
"""
