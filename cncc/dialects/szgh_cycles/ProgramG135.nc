#700=-1
#701=#4003
#702=#4001
#703=#4010
#704=#5003
IF[[#4007 EQ 41] OR [#4007 EQ 42]] GOTO 9001
IF[[#12 NE 0] AND [[#12+0] EQ 0]] GOTO 9002
IF[[#20 NE 0] AND [[#20+0] EQ 0]] GOTO 9003
#708=#18+0
#709=#19+0
#710=#12
#711=#20
IF[#701 EQ 91] THEN #708=#5001+#708
IF[#701 EQ 91] THEN #709=#5002+#709
IF[#701 EQ 91] THEN #710=#704+#12
IF[#701 EQ 91] THEN #711=#710+#20
IF[[#18 NE 0] AND [[#18+0] EQ 0]] THEN #708=#5001
IF[[#19 NE 0] AND [[#19+0] EQ 0]] THEN #709=#5002
IF[#711 GE #710] GOTO 9004
#712=#710
IF[#703 EQ 98] THEN #712=#704
IF[ABS[#3] GT 32] GOTO 9005
#713=0
IF[ROUND[ABS[#3]] GE 1] THEN #713=ABS[#[1100+ROUND[ABS[#3]]]]/1000
#714=ABS[#5]
IF[#714 EQ 0] THEN #714=#4109
IF[#714 LE 0] GOTO 9006
#715=2.5+#700/2
#716=5-#715
G90
IF[#17 LE 0] GOTO 9007
#717=ABS[#11]
#718=ABS[#16]
#740=#710-#17
IF[#740 LT #711] THEN #740=#711
IF[[#740 GT #711] AND [#717 EQ 0]] GOTO 9008
#720=ABS[#7]/2-#713-ABS[#4]
#721=ABS[#8]/2-#713-ABS[#4]
IF[[#720 LT 0] OR [#721 LT 0]] GOTO 9041
#722=ABS[#9]
IF[#722 EQ 0] THEN #722=#713
IF[#722 LE 0] GOTO 9012
IF[[#713 GT 0] AND [#722 GT 2*#713]] GOTO 9013
#723=#722
IF[[#713 GT 0] AND [#723 GT 1.70710678*#713]] THEN #723=1.70710678*#713
#724=#720
IF[#721 LT #724] THEN #724=#721
#725=#722
IF[#725 GT #724] THEN #725=#724
IF[[#5001 NE #708] OR [#5002 NE #709]]
G00 X#708 Y#709
ENDIF
G00 Z#710
IF[#725 GT 0.0005]
G01 X[#708+#725] F#714
G#715 X[#708+#725] Y#709 Z#740 I[-#725] J0
G01 X#708
ELSE
G01 Z#740 F#714
ENDIF
#752=1
#753=#700
#757=0
N10 #750=0
#751=0
WHILE[#751 EQ 0] DO 1
IF[#750 GE #724-0.0005] THEN #751=1
IF[#751 EQ 1] THEN #750=#724
#755=#720-#724+#750
#756=#721-#724+#750
IF[[#755 GT 0.0005] OR [#756 GT 0.0005]]
G01 X[#708+#755] Y#709
#758=#756-#757
#759=#755-#757
IF[#758 GT 0.0005]
G01 X[#708+#752*#755] Y[#709+#753*#758]
ENDIF
IF[#757 GT 0]
G#715 X[#708+#752*#759] Y[#709+#753*#756] I[-#752*#757] J0
ENDIF
IF[#759 GT 0.0005]
G01 X[#708-#752*#759] Y[#709+#753*#756]
ENDIF
IF[#757 GT 0]
G#715 X[#708-#752*#755] Y[#709+#753*#758] I0 J[-#753*#757]
ENDIF
IF[#758 GT 0.0005]
G01 X[#708-#752*#755] Y[#709-#753*#758]
ENDIF
IF[#757 GT 0]
G#715 X[#708-#752*#759] Y[#709-#753*#756] I[#752*#757] J0
ENDIF
IF[#759 GT 0.0005]
G01 X[#708+#752*#759] Y[#709-#753*#756]
ENDIF
IF[#757 GT 0]
G#715 X[#708+#752*#755] Y[#709-#753*#758] I0 J[#753*#757]
ENDIF
IF[#758 GT 0.0005]
G01 X[#708+#752*#755] Y#709
ENDIF
ENDIF
#750=#750+#723
END 1
IF[#740 LE #711+0.0005] GOTO 90
#741=#740
#740=#740-#717
IF[#740 LT #711] THEN #740=#711
#751=#741+#718
IF[#751 GT #710] THEN #751=#710
G00 Z#710
G00 X#708 Y#709
G00 Z#751
G01 Z#740
GOTO 10
N90 G00 Z#712
G00 X#708 Y#709
G#702 G#701
M99
N9001 #3000=1 (cancel G41/G42 before a pocket or boss cycle)
N9002 #3000=2 (R, the R level, is missing)
N9003 #3000=3 (Z, the bottom, is missing)
N9004 #3000=4 (Z, the bottom, must lie below the R level)
N9005 #3000=5 (D, the tool radius number, is 0 to 32)
N9006 #3000=6 (F, the cutting feed, is missing)
N9007 #3000=7 (W, the first depth below R, must be greater than 0)
N9008 #3000=8 (Q, the depth per pass, is needed to reach Z)
N9012 #3000=12 (K, the step, is missing)
N9013 #3000=13 (K, the step, must not exceed the tool diameter)
N9041 #3000=41 (I and J must leave room for the tool diameter plus 2E)
; ProgramG135: SZGH user cycle G135, inner rectangular pocket roughing, clockwise.
; Format: G134/G135 X_ Y_ Z_ R_ I_ J_ K_ W_ Q_ V_ E_ D_ F_  (G65 argument map: A#0 B#1 C#2 D#3 E#4 F#5 I#7 J#8 K#9
;   Q#11 R#12 U#15 V#16 W#17 X#18 Y#19 Z#20).
; Shipped with cncc in cncc/dialects/szgh_cycles and called as the controller calls its
; ProgramG files.  ProgramG134 is the same program with the other direction (#700).
; The path is described in docs/cycles.md (SZGH macro cycles).  Nothing below M99 runs
; except the alarm blocks N90xx, reached by GOTO.  Scratch variables (overwritten):
;   #700  direction: 1 counter-clockwise, -1 clockwise
;   #701  the caller's G90 / G91
;   #702  the caller's motion mode, restored at the end
;   #703  G98 / G99
;   #704  the initial level
;   #708  X and Y: the cycle's centre
;   #710  R level
;   #711  bottom
;   #712  return level: R (G99) or the initial level (G98)
;   #713  tool radius (D in um)
;   #714  feed: F, or the modal F
;   #715  G03 counter-clockwise, G02 clockwise
;   #716  the opposite direction
;   #717  Q: depth of each further pass
;   #718  V: clearance above the uncut floor
;   #740  floor of the first pass
;   #720  tool-centre half widths of the last ring
;   #722  K: step (the tool radius when not given)
;   #723  step used: at most 1.707 x tool radius, so corners are cleared
;   #724  the smaller half width
;   #725  helix radius of the entry
;   #752  rings start on the +X side
;   #757  sharp corners
;   #750  rings from the centre slot outward, one step apart
;   #758  half lengths of the straight parts of the sides
;   #741  next pass: Q deeper
