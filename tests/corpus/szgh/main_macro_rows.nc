; SZGH: rows of holes from a G65 macro in the same file (arguments A -> #0, B -> #1)
G90 G54 G00 X0 Y0 Z20.
M3 S1200
G65 P9500 A12.5 B5.
G00 Y20.
G65 P9500 A12.5 B3.
G00 Z20.
M5
M30
O9500
; A: pitch, B: holes in the row
N1 #3=0
N2 IF (#3 GE #1) GOTO 9
N3 G00 X[#3*#0]
N4 G01 Z-4. F150
N5 G00 Z2.
N6 #3=#3+1
N7 GOTO 2
N9 M99
