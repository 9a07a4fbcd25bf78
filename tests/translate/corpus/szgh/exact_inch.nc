; SZGH inch program with exact stop (G60) and continuous mode (G64)
G20 G90 G17 G94
G00 X0 Y0 Z1
G60
G01 Z-0.1 F8
G01 X1.5 F15
G64
G02 X2.5 Y1 I0 J1
G01 Y2
G04 P500
G00 Z1
M30
