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
#755=ABS[#7]/2-#713
#756=ABS[#8]/2-#713
IF[ABS[#8] LT 2*#713] GOTO 9061
IF[#755 LT 0] GOTO 9062
#757=0
IF[ABS[#15] GT 0] THEN #757=ABS[#15]-#713
IF[#757 LT 0] GOTO 9063
IF[[#757 GT #755] OR [#757 GT #756]] GOTO 9064
#720=ABS[#9]
IF[#720 LE #713] GOTO 9065
IF[#720 GT ABS[#7]-#713] GOTO 9066
#721=[#720-#713]/2
IF[#721 GT #756] GOTO 9067
#724=#708+ABS[#7]/2-#720
IF[[#5001 NE #724] OR [#5002 NE #709]]
G00 X#724 Y#709
ENDIF
G00 Z#710
G01 Z#711 F#714
G#715 X[#708+#755] Y#709 I#721 J0
#752=1
#753=#700
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
G#715 X#724 Y#709 I[-#721] J0
G00 Z#712
G#702 G#701
M99
N9001 #3000=1 (cancel G41/G42 before a pocket or boss cycle)
N9002 #3000=2 (R, the R level, is missing)
N9003 #3000=3 (Z, the bottom, is missing)
N9004 #3000=4 (Z, the bottom, must lie below the R level)
N9005 #3000=5 (D, the tool radius number, is 0 to 32)
N9006 #3000=6 (F, the cutting feed, is missing)
N9061 #3000=61 (J must be at least the tool diameter)
N9062 #3000=62 (I must be at least the tool diameter)
N9063 #3000=63 (U, the corner radius, is smaller than the tool radius)
N9064 #3000=64 (U, the corner radius, is larger than half the rectangle)
N9065 #3000=65 (K must exceed the tool radius)
N9066 #3000=66 (K puts the start point beyond the -X side)
N9067 #3000=67 (the lead-in half circle does not fit: K is too large for J)
; ProgramG137: SZGH user cycle G137, inner rectangle finishing, clockwise.
; Format: G136/G137 X_ Y_ Z_ R_ I_ J_ K_ U_ D_ F_  (G65 argument map: A#0 B#1 C#2 D#3 E#4 F#5 I#7 J#8 K#9
;   Q#11 R#12 U#15 V#16 W#17 X#18 Y#19 Z#20).
; Shipped with cncc in cncc/dialects/szgh_cycles and called as the controller calls its
; ProgramG files.  ProgramG136 is the same program with the other direction (#700).
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
;   #755  tool-centre half widths
;   #757  tool-centre corner radius: U - tool (sharp without U)
;   #720  K: start point, this far inside the +X side
;   #721  radius of the lead-in and lead-out half circles
;   #758  half lengths of the straight parts of the sides
