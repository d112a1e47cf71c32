C   PRINTED CIRCUIT BOARD CONTACT SEPARATION ANALYSIS
C
C     TRANSCRIBED STATEMENT FOR STATEMENT FROM APPENDIX G OF THE THESIS
C     (SEE APPENDIX_G_AS_PRINTED.TXT BESIDE THIS FILE).  EVERY DEPARTURE
C     FROM THE PRINTED LISTING IS MARKED WITH A LINE 'C RESTORED: N'
C     AND LISTED UNDER THAT NUMBER IN FORTRAN/RESTORATION.MD.
      DIMENSION V(4),C(4),ALPHA(4),DOG(4),SINH(4),COSH(4),P(4),U(4),Q(4)
      DIMENSION R(4),D1(4),D2(4),D3(4),D4(4),D5(4),D6(4),D7(4),D8(4)
      DIMENSION AP(4),PE(4),A1(4),B1(4,6),APE(4)
      DIMENSION V2(4), C2(4), ALPH2(4), V3(4), C3(4), ALPH3(4)
      DIMENSION P2(4), P3(4), C2S(4), C3S(4)
C RESTORED: 1  MR1 AND MR3 ARE MASS RATIOS WRITTEN WITH F15.9; THE
C             IMPLICIT INTEGER TYPE IS REJECTED BY A MODERN RUNTIME.
      REAL MR1, MR3
10    FORMAT( 7F15.9)
15    FORMAT (E15.9,I2)
C RESTORED: 2  PRINTED '(15,I5,...)': OCR OF I5. FORMAT 20 IS UNUSED.
20    FORMAT (I5,I5,I5,I5,I5,I5,I5)
C RESTORED: 3  END= ADDED: THE NEXT DATA SET IS READ UNTIL END OF FILE.
5     READ(5,10,END=999) XL,B,H,RHO,YSTAT
      READ (5,10) XL2, B2, H2,RHO2
      READ (5,10)XL3,B3,H3,RHO3
      READ (5,10) DELT,ER,DELY
      READ (5,15) E,N
      READ (5,10) XL2C
      WRITE (6,10) XL2 ,B2, H2, RHO2
      DT = DELT
      RHOC = (RHO) / 1728.0
      RHO2C = RHO2 / 1728.0
      RHO3C = RHO3 / 1728.0
      A = B * H
      A2 = B2 *H2
      A3 = B3 * H3
      WM = (RHOC *A *XL )/386.4
      WM2 = ( RHO2C * A2*XL2) / 386.4
      WM3 = (RHO3C * A3 * XL3) / 386.4
      EYE = (B*(H **3)) / 12.0
      EYE2 = (B2*(H2**3)) / 12.0
      EYE3 = (B3*(H3**3)) / 12.0
      W=SQRT((E*(EYE*386.4))/(A*RHOC))
      W2 = SQRT((E*(EYE2 * 386.4)) / (A2* RHO2C ))
      W3 = SQRT((E* ( EYE3 * 386.4)) / (A3 * RHO3C))
30    DO 35 I = 1, N
      READ (5,10) V(I), C(I), ALPHA(I)
35    CONTINUE
36    DO 37 I = 1,N
      READ (5,10) V2(I), C2(I), ALPH2(I)
37    CONTINUE
38    DO 39 I = 1,N
      READ (5,10) V3(I), C3(I), ALPH3(I)
39    CONTINUE
60    DO 70 I=1,N
      DOG(I)=-V(I)
      SINH(I)=(EXP(V(I))-EXP(DOG(I)))/2.0
      COSH(I)=(EXP(V(I))+EXP(DOG(I)))/2.0
      P(I) = (W * (V(I) ** 2 )) / (XL **2 )
      U(I) = V(I) / XL
      Q(I)=2.0/(U(I)**3)
      R(I)=(XL**2)/U(I)
      D1(I)=(Q(I)-R(I))*COS(V(I))+((2.0*(XL*SIN(V(I))))/(U(I)**2))-Q(I)
      D2(I)=(((2.0*XL)*COS(V(I)))/(U(I)**2))+(R(I)-Q(I))*SIN(V(I))
      D3(I)=((3.0*D2(I))/U(I))-((XL**3)*COS(V(I)))/U(I)
      D4(I)=((XL**3)*SIN(V(I))/U(I))-3.0*D1(I)/U(I)
      D5(I)=(R(I)+Q(I))*COSH(I)-((2.0*XL)*SINH(I)/(U(I)**2))-Q(I)
      D6(I)=((R(I)+Q(I))*SINH(I))-((2.0*XL)*COSH(I)/(U(I)**2))
      D7(I)=((XL**3)*COSH(I)/U(I))-3.0*D6(I)/U(I)
      D8(I)=((XL**3)*SINH(I)/U(I))-3.0*D5(I)/U(I)
      AP(I)=((3.*YSTAT)/(XL**3))*((D6(I)-D2(I))-ALPHA(I)*(D5(I)-D1(I)))
      PE(I)=(YSTAT/(XL**4))*((D8(I)-D4(I))-ALPHA(I)*(D7(I)-D3(I)))
      APE(I)=(AP(I)-PE(I))/2.0
      WRITE (6,10) V(I),C(I),ALPHA(I), P(I), APE(I)
70    CONTINUE
      T=0.0
80    TY=0.0
      TYDTL=0.0
      ACT = 0.0
      CT=0.0
      CT2 = 0.0
      CT3 = 0.0
90    DO 100 I=1,N
      Y=APE(I)*C(I)*COS(P(I)*T)
      TY=TY+Y
      YDTL=-P(I)*APE(I)*C(I)*SIN(P(I)*T)
      TYDTL=TYDTL+YDTL
      AC=-P(I)*APE(I)*C(I)
      ACT=ACT+AC
      C1 = C(I) **2
      CT = CT + C1
      C2S(I) = C2(I)**2
      CT2 = CT2 + C2S(I)
      C3S(I) = C3(I) **2
      CT3 = CT3 + C3S(I)
100   CONTINUE
      IF (TY-DELY)130,131,110
110   WRITE(6,10)T, TY, TYDTL
      IF (DELT-0.0005)120,115,115
115   NT=T/(0.01/100.)
      NTY=TY/(0.1/100.)
      M=3
120   IF (DELT-0.00000001)131,131,122
122   TT=T
125   T=T+DELT
      GO TO 80
130   T=TT
      DELT=(DELT)/2.0
      T=T+DELT
      GO TO 80
131   ED=9.999
      WRITE (6,10)ED
132   EY = ((1.0 +ER) * ACT) / ((CT/WM) + (CT2/WM2) + ( CT3/WM3 ))
      WRITE(6,10) T,EY,CT,CT2,CT3
      DO 133 I=1,N
      K=I+1
      X=N
      J=1
      A1(I) = APE(I) * COS( P(I) * T)
      B1(I,J)=-APE(I)*SIN(P(I)*T)
      WRITE (6,10) A1(I) ,B1(I,J)
133   CONTINUE
170   T=0.0
200   TY=0.0
      TYDTL=0.0
      ACT=0.0
240   DO 300 I=1,N
      Y=A1(I)*COS(P(I)*T)
      Y=(Y+(B1(I,J)-((EY*C(I))/(WM*P(I))))*SIN(P(I)*T))*C(I)
      TY=TY+Y
      YDTL=-A1(I)*(SIN(P(I)*T))
      YDTL=(YDTL+(B1(I,J)-((EY*C(I))/(WM*P(I))))*COS(P(I)*T))*C(I)*P(I)
      TYDTL=TYDTL+YDTL
      AC=P(I)*B1(I,J)*C(I)
      ACT=ACT+AC
300   CONTINUE
315   WRITE (6,10)T, TY, TYDTL ,ACT
350   TY2DT = 0.0
      WM2 = WM2 * ( XL2C / XL2 )
400   DO 410 I = 1,N
      P2(I) = (W2 * (V2(I) **2)) / ( XL2 **2)
      P3(I) = (W3 * (V3(I) **2 )) / ( XL3**2 )
      Y2DT = (EY/WM2 ) * C2S(I)
      TY2DT = TY2DT + Y2DT
410   CONTINUE
      WRITE(6,10) TY2DT
450   TY3 = 0.0
500   DO 510 I = 1,N
      Y3 = TY2DT * (C3S(I) * SIN(P3(I) *T)) / (XL3 *P3(I) )
      TY3 = TY3 + Y3
510   CONTINUE
      TAU = 0.060
      WRITE (6,10) T, TY3
      DELT = DT
      T = T + DELT
      IF ( T - TAU) 520, 600, 600
520   GO TO 450
600   DO 610 I = 1,N
      WRITE(6,10) V2(I),C2(I),ALPH2(I), P2(I)
610   CONTINUE
650   DO 660 I = 1,N
      WRITE (6,10) V3(I), C3(I), ALPH3(I), P3(I)
660   CONTINUE
      GR = H2 / XL2
      BETA = WM / (WM2 + WM3)
      MR1 = WM2 / WM
      MR3 = WM2 / WM3
      WRITE (6,10) WM, WM2, WM3 ,XL2C
      WRITE(6,10) GR, BETA, MR1 ,MR3
      GO TO 5
C RESTORED: 3  (CONTINUED) THE END= BRANCH OF STATEMENT 5 ENDS THE RUN.
999   STOP
      END
