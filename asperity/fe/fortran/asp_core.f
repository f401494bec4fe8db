C     asperity: the law-frame core of the generated friction routines.
C     ASPLAW (written with the law's table) calls ASPW; the explicit
C     wrappers call ASPFRC and ASPRAD. See asperity/fe/fortran_core.py.
      SUBROUTINE ASPW(IOP,PRESS,X,Y,OUT,NCLAMP,N,L,TPSI,TCS,TSN,
     1 TPX,TPY,TLAT,TPHI,TLNP,NB,NBK,TBLO,TBHI)
C     core of the generated friction routines (asperity): see ASPLAW
      IMPLICIT NONE
      INTEGER IOP,NCLAMP,N,L,NB,NBK
      DOUBLE PRECISION PRESS,X,Y,OUT(12),TPSI(N),TCS(N),TSN(N),
     1 TPX(N,L),TPY(N,L),TLAT(N,L),TPHI(N,L),TLNP(L),TBLO(NBK,L),
     2 TBHI(NBK,L)
      INTEGER K,K2,J,J1,I,IT,JB,IB,JS,JE,JL,IX
      DOUBLE PRECISION W,DWDP,PL,PI,TWOPI,BX,BY,BL,DX,DY,T,QX,QY,QN,
     1 PHQ,R,GA,GB,G,GT,TL,TH,TN,PS,PSA,DPS,C,S,PX,PY,DPX,DPY,
     2 XLAM,BEST,BT,BPS,BPX,BPY,BDPX,BDPY,BGT,WX,WY,DTP,
     3 GLO,AMUP,AMUM,DMUP,DMUM,EPS,SX0,SY0,XX,XY,D2,BD2,CPQ,SPQ,
     4 SPAN,SA,SB,CA,CB,SMN,SMX
      PARAMETER (PI=3.141592653589793D0,TWOPI=6.283185307179586D0)
      BX(J) = (1.0D0-W)*TPX(J,K) + W*TPX(J,K2)
      BY(J) = (1.0D0-W)*TPY(J,K) + W*TPY(J,K2)
      BL(J) = (1.0D0-W)*TLAT(J,K) + W*TLAT(J,K2)
      DX(J) = TPX(J,K2) - TPX(J,K)
      DY(J) = TPY(J,K2) - TPY(J,K)
C     the law at PRESS: levels K and K2 blended by W (linear in ln p)
      K = 1
      K2 = 1
      W = 0.0D0
      DWDP = 0.0D0
      NCLAMP = 0
      IF (L .GT. 1) THEN
        K2 = 2
        PL = LOG(MAX(PRESS,1.0D-300))
        IF (PL .LE. TLNP(1)) THEN
          IF (PL .LT. TLNP(1)-1.0D-12) NCLAMP = 1
        ELSE IF (PL .GE. TLNP(L)) THEN
          K = L - 1
          K2 = L
          W = 1.0D0
          IF (PL .GT. TLNP(L)+1.0D-12) NCLAMP = 1
        ELSE
   10     IF (PL .GE. TLNP(K+1)) THEN
            K = K + 1
            GO TO 10
          END IF
          K2 = K + 1
          W = (PL-TLNP(K))/(TLNP(K2)-TLNP(K))
          DWDP = 1.0D0/(PRESS*(TLNP(K2)-TLNP(K)))
        END IF
      END IF
      SX0 = OUT(1)
      SY0 = OUT(2)
      DO 20 I = 1, 12
        OUT(I) = 0.0D0
   20 CONTINUE
      IF (IOP .EQ. 1) THEN
        CALL ASPLOC(N,TPSI,X,J,T)
        J1 = MOD(J,N) + 1
        OUT(1) = BX(J) + T*(BX(J1)-BX(J))
        OUT(2) = BY(J) + T*(BY(J1)-BY(J))
        OUT(3) = DWDP*(DX(J) + T*(DX(J1)-DX(J)))
        OUT(4) = DWDP*(DY(J) + T*(DY(J1)-DY(J)))
        RETURN
      END IF
      IF (IOP .EQ. 2) THEN
        CALL ASPRD(N,L,TPX,TPY,TPHI,K,K2,W,X,OUT(1))
        RETURN
      END IF
      IF (IOP .EQ. 4) THEN
C       1D: the tangential force limits along +Y and -Y
        CALL ASPLOC(N,TPSI,Y,J,T)
        J1 = MOD(J,N) + 1
        C = COS(Y)
        S = SIN(Y)
        AMUP = C*(BX(J)+T*(BX(J1)-BX(J))) + S*(BY(J)+T*(BY(J1)-BY(J)))
        DMUP = DWDP*(C*(DX(J)+T*(DX(J1)-DX(J)))
     1       + S*(DY(J)+T*(DY(J1)-DY(J))))
        CALL ASPLOC(N,TPSI,Y+PI,J,T)
        J1 = MOD(J,N) + 1
        AMUM = -C*(BX(J)+T*(BX(J1)-BX(J))) - S*(BY(J)+T*(BY(J1)-BY(J)))
        DMUM = -DWDP*(C*(DX(J)+T*(DX(J1)-DX(J)))
     1       + S*(DY(J)+T*(DY(J1)-DY(J))))
        IF (X .GT. PRESS*AMUP) THEN
          OUT(1) = PRESS*AMUP
          OUT(3) = AMUP + PRESS*DMUP
          OUT(9) = 1.0D0
        ELSE IF (X .LT. -PRESS*AMUM) THEN
          OUT(1) = -PRESS*AMUM
          OUT(3) = -AMUM - PRESS*DMUM
          OUT(9) = 1.0D0
        ELSE
          OUT(1) = X
          OUT(2) = 1.0D0
        END IF
        RETURN
      END IF
C     IOP = 3: stick while q = trial/PRESS lies in C
      QX = X/PRESS
      QY = Y/PRESS
      QN = SQRT(QX*QX+QY*QY)
      PHQ = ATAN2(QY,QX)
      CALL ASPRD(N,L,TPX,TPY,TPHI,K,K2,W,PHQ,R)
      IF (QN .LE. R) THEN
        OUT(1) = X
        OUT(2) = Y
        OUT(3) = 1.0D0
        OUT(6) = 1.0D0
        OUT(11) = PHQ
        RETURN
      END IF
C     the roots of G(psi) = (cos psi, sin psi) x (q - P(psi)) =
C     |q| sin(phq - psi) - lateral(psi) at the nodes, by blocks of NB
C     nodes: a block whose bounds keep G of one sign, or where every
C     slip would run against q (lam < 0), holds no root
      CPQ = QX/QN
      SPQ = QY/QN
      BEST = 1.0D300
      BD2 = 1.0D300
      JB = 0
      IX = 0
      XX = 0.0D0
      XY = 0.0D0
      BT = 0.0D0
      BPS = PHQ
      BPX = 0.0D0
      BPY = 0.0D0
      BDPX = 0.0D0
      BDPY = 0.0D0
      BGT = 0.0D0
      EPS = 1.0D-15*(QN+1.0D0)
      DO 60 IB = 1, NBK
        JS = (IB-1)*NB + 1
        JE = MIN(IB*NB,N)
        JL = MOD(JE,N) + 1
        SA = SPQ*TCS(JS) - CPQ*TSN(JS)
        SB = SPQ*TCS(JL) - CPQ*TSN(JL)
        CA = CPQ*TCS(JS) + SPQ*TSN(JS)
        CB = CPQ*TCS(JL) + SPQ*TSN(JL)
        SMN = MIN(SA,SB)
        SMX = MAX(SA,SB)
C       a block turning by half a turn or more is always searched
        SPAN = TCS(JS)*TSN(JL) - TSN(JS)*TCS(JL)
        IF (SPAN .LE. 0.0D0) GO TO 48
C       does the block hold the directions phq -+ 90 deg, phq?
        IF (-TCS(JS)*CPQ-TSN(JS)*SPQ .GE. 0.0D0 .AND.
     1      SPQ*TSN(JL)+CPQ*TCS(JL) .GE. 0.0D0) SMX = 1.0D0
        IF (TCS(JS)*CPQ+TSN(JS)*SPQ .GE. 0.0D0 .AND.
     1      -SPQ*TSN(JL)-CPQ*TCS(JL) .GE. 0.0D0) SMN = -1.0D0
        IF (QN*SMN-MAX(TBHI(IB,K),TBHI(IB,K2)) .GT. EPS) GO TO 60
        IF (QN*SMX-MIN(TBLO(IB,K),TBLO(IB,K2)) .LT. -EPS) GO TO 60
C       both ends behind q and less than half a turn between them: the
C       block lies behind q, where lam < 0
        IF (CA .LT. 0.0D0 .AND. CB .LT. 0.0D0) GO TO 60
   48   CONTINUE
        DO 50 J = JS, JE
          J1 = MOD(J,N) + 1
          GA = TCS(J)*QY - TSN(J)*QX - BL(J)
          GB = TCS(J1)*QY - TSN(J1)*QX - BL(J1)
          IF (GA*GB .GT. 0.0D0) GO TO 50
          PSA = TPSI(J)
          DPS = TPSI(J1) - PSA
          IF (J1 .EQ. 1) DPS = DPS + TWOPI
          DPX = BX(J1) - BX(J)
          DPY = BY(J1) - BY(J)
          TL = 0.0D0
          TH = 1.0D0
          GLO = GA
          T = 0.5D0
          IF (GA .NE. GB) T = GA/(GA-GB)
          DO 40 IT = 1, 60
            PS = PSA + T*DPS
            C = COS(PS)
            S = SIN(PS)
            PX = BX(J) + T*DPX
            PY = BY(J) + T*DPY
            G = C*(QY-PY) - S*(QX-PX)
            XLAM = C*(QX-PX) + S*(QY-PY)
            GT = -DPS*XLAM - (C*DPY - S*DPX)
            IF (ABS(G) .LE. EPS .OR. TH-TL .LE. 1.0D-15) GO TO 45
            IF (G*GLO .GT. 0.0D0) THEN
              TL = T
              GLO = G
            ELSE
              TH = T
            END IF
            TN = 0.5D0*(TL+TH)
            IF (GT .NE. 0.0D0) TN = T - G/GT
            IF (TN .LE. TL .OR. TN .GE. TH) TN = 0.5D0*(TL+TH)
            IF (ABS(TN-T) .LE. 1.0D-13) GO TO 45
            T = TN
   40     CONTINUE
   45     IF (XLAM .LT. -EPS) GO TO 50
          IF (JB .NE. 0) THEN
C           several roots (a non-associated law): the one nearest XX, XY,
C           where the elastic path from the start stress leaves C (the
C           flow goes on from there: the start itself when it lies on
C           the boundary, so that steady sliding stays put)
            IF (IX .EQ. 0) THEN
              CALL ASPXP(N,L,TPX,TPY,TPHI,K,K2,W,SX0/PRESS,SY0/PRESS,
     1         QX,QY,XX,XY)
              IX = 1
              BD2 = (BPX-XX)**2 + (BPY-XY)**2
            END IF
            D2 = (PX-XX)**2 + (PY-XY)**2
            IF (D2 .GT. BD2) GO TO 50
            IF (D2 .EQ. BD2 .AND. XLAM .GE. BEST) GO TO 50
            BD2 = D2
          END IF
          IF (.TRUE.) THEN
            BEST = XLAM
            JB = J
            BT = T
            BPS = PS
            BPX = PX
            BPY = PY
            BDPX = DPX
            BDPY = DPY
            BGT = GT
          END IF
   50   CONTINUE
   60 CONTINUE
      IF (JB .EQ. 0) THEN
C       no root (cannot happen for a valid table): the force of the
C       trial direction
        CALL ASPLOC(N,TPSI,PHQ,J,T)
        J1 = MOD(J,N) + 1
        OUT(1) = PRESS*(BX(J) + T*(BX(J1)-BX(J)))
        OUT(2) = PRESS*(BY(J) + T*(BY(J1)-BY(J)))
        OUT(9) = 2.0D0
        OUT(11) = PHQ
        RETURN
      END IF
      J = JB
      J1 = MOD(J,N) + 1
      C = COS(BPS)
      S = SIN(BPS)
      OUT(1) = PRESS*BPX
      OUT(2) = PRESS*BPY
      IF (BGT .NE. 0.0D0) THEN
        OUT(3) = BDPX*S/BGT
        OUT(4) = BDPY*S/BGT
        OUT(5) = -BDPX*C/BGT
        OUT(6) = -BDPY*C/BGT
        WX = DX(J) + BT*(DX(J1)-DX(J))
        WY = DY(J) + BT*(DY(J1)-DY(J))
        DTP = -((S*QX-C*QY)/PRESS + (S*WX-C*WY)*DWDP)/BGT
        OUT(7) = BPX + PRESS*(BDPX*DTP + WX*DWDP)
        OUT(8) = BPY + PRESS*(BDPY*DTP + WY*DWDP)
      ELSE
        OUT(7) = BPX
        OUT(8) = BPY
      END IF
      OUT(9) = 1.0D0
      OUT(10) = BEST*PRESS
      OUT(11) = BPS
      RETURN
      END
C
      SUBROUTINE ASPFRC(PRESS,PSI,PX,PY,NCLAMP)
C     the force per unit normal load for sliding along PSI (law frame)
      IMPLICIT NONE
      INTEGER NCLAMP
      DOUBLE PRECISION PRESS,PSI,PX,PY,OUT(12)
      CALL ASPLAW(1,PRESS,PSI,0.0D0,OUT,NCLAMP)
      PX = OUT(1)
      PY = OUT(2)
      RETURN
      END
C
      SUBROUTINE ASPRAD(PRESS,PHI,R,NCLAMP)
C     the distance to the boundary of C along the ray PHI (law frame)
      IMPLICIT NONE
      INTEGER NCLAMP
      DOUBLE PRECISION PRESS,PHI,R,OUT(12)
      CALL ASPLAW(2,PRESS,PHI,0.0D0,OUT,NCLAMP)
      R = OUT(1)
      RETURN
      END
C
      SUBROUTINE ASPXP(N,L,TPX,TPY,TPHI,K,K2,W,AX,AY,QX,QY,XX,XY)
C     XX, XY: where the straight path from A (inside C, or on its
C     boundary: A itself) to Q (outside) leaves C
      IMPLICIT NONE
      INTEGER N,L,K,K2,IT
      DOUBLE PRECISION TPX(N,L),TPY(N,L),TPHI(N,L),W,AX,AY,QX,QY,XX,XY,
     1 AN,RA,SL,SH,SM,VX,VY
      AN = SQRT(AX*AX+AY*AY)
      RA = 1.0D0
      IF (AN .GT. 0.0D0) CALL ASPRD(N,L,TPX,TPY,TPHI,K,K2,W,
     1 ATAN2(AY,AX),RA)
      IF (AN .GE. (1.0D0-1.0D-6)*RA) THEN
        XX = AX
        XY = AY
        RETURN
      END IF
      SL = 0.0D0
      SH = 1.0D0
      DO 10 IT = 1, 30
        SM = 0.5D0*(SL+SH)
        VX = AX + SM*(QX-AX)
        VY = AY + SM*(QY-AY)
        CALL ASPRD(N,L,TPX,TPY,TPHI,K,K2,W,ATAN2(VY,VX),RA)
        IF (VX*VX+VY*VY .LE. RA*RA) THEN
          SL = SM
        ELSE
          SH = SM
        END IF
   10 CONTINUE
      XX = AX + SH*(QX-AX)
      XY = AY + SH*(QY-AY)
      RETURN
      END
C
      SUBROUTINE ASPLOC(N,TPSI,ANG,J,T)
C     the interval J (nodes J, J+1, the last wrapping to 1) holding the
C     direction ANG, and the fraction T of it
      IMPLICIT NONE
      INTEGER N,J,JA,JB,JM
      DOUBLE PRECISION TPSI(N),ANG,T,Q,TWOPI,V1
      PARAMETER (TWOPI=6.283185307179586D0)
      Q = MOD(ANG-TPSI(1),TWOPI)
      IF (Q .LT. 0.0D0) Q = Q + TWOPI
      IF (Q .GE. TWOPI) Q = 0.0D0
      JA = 1
      JB = N + 1
   10 IF (JB-JA .GT. 1) THEN
        JM = (JA+JB)/2
        IF (TPSI(JM)-TPSI(1) .LE. Q) THEN
          JA = JM
        ELSE
          JB = JM
        END IF
        GO TO 10
      END IF
      J = JA
      IF (J .LT. N) THEN
        V1 = TPSI(J+1) - TPSI(1)
      ELSE
        V1 = TWOPI
      END IF
      T = (Q-(TPSI(J)-TPSI(1)))/(V1-(TPSI(J)-TPSI(1)))
      RETURN
      END
C
      SUBROUTINE ASPRD(N,L,TPX,TPY,TPHI,K,K2,W,PHI,R)
C     distance from the origin to the boundary of C (the polygon of the
C     blended nodes) along the ray PHI
      IMPLICIT NONE
      INTEGER N,L,K,K2,J,J1,JA,JB,JM,ITRY,JT
      DOUBLE PRECISION TPX(N,L),TPY(N,L),TPHI(N,L),W,PHI,R,BX,BY,BF,
     1 F1,Q,TWOPI,UX,UY,AX,AY,DX,DY,DEN,RR,TT,DD,VM
      PARAMETER (TWOPI=6.283185307179586D0,VM=1.0D-9)
      BX(J) = (1.0D0-W)*TPX(J,K) + W*TPX(J,K2)
      BY(J) = (1.0D0-W)*TPY(J,K) + W*TPY(J,K2)
      BF(J) = (1.0D0-W)*TPHI(J,K) + W*TPHI(J,K2)
      F1 = BF(1)
      Q = MOD(PHI-F1,TWOPI)
      IF (Q .LT. 0.0D0) Q = Q + TWOPI
      Q = Q + F1
      JA = 1
      JB = N + 1
   10 IF (JB-JA .GT. 1) THEN
        JM = (JA+JB)/2
        IF (BF(JM) .LE. Q) THEN
          JA = JM
        ELSE
          JB = JM
        END IF
        GO TO 10
      END IF
      UX = COS(Q)
      UY = SIN(Q)
      R = -1.0D0
      DO 20 ITRY = 0, 2
        JT = JA
        IF (ITRY .EQ. 1) JT = MOD(JA-2+N,N) + 1
        IF (ITRY .EQ. 2) JT = MOD(JA,N) + 1
        J1 = MOD(JT,N) + 1
        AX = BX(JT)
        AY = BY(JT)
        DX = BX(J1) - AX
        DY = BY(J1) - AY
        DD = DX*DX + DY*DY
        IF (DD .LE. 1.0D-30*(AX*AX+AY*AY)) THEN
          RR = SQRT(AX*AX+AY*AY)
          TT = 0.0D0
        ELSE
          DEN = UX*DY - UY*DX
          IF (DEN .EQ. 0.0D0) GO TO 20
          RR = (AX*DY - AY*DX)/DEN
          TT = ((RR*UX-AX)*DX + (RR*UY-AY)*DY)/DD
        END IF
        IF (R .LT. 0.0D0) R = RR
        IF (TT .GE. -VM .AND. TT .LE. 1.0D0+VM .AND. RR .GT. 0.0D0) THEN
          R = RR
          RETURN
        END IF
   20 CONTINUE
      RETURN
      END
