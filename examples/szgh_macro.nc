(cncc: dialect=szgh) (SZGH-CNC990MDb: four holes on a line, spaced by a G65 macro call with arguments)
G90 G54 G00 X0 Y0 Z10.
S1500 M03
G65 P8000 A10. B4.
G00 Z10.
M05
M30
O8000
(A -> #0: spacing, B -> #1: number of holes)
N1 #2=0
N2 IF (#2 GE #1) GOTO 6
N3 G00 X[#2*#0] Y0
N4 G01 Z-3. F200
N5 G00 Z2.
#2=#2+1
GOTO 2
N6 M99
