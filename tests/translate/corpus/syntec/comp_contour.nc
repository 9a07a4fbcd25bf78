(a pocket wall cut with cutter radius compensation - D1 = 5 mm)
G90 G17 G71 G94 G54
T1 M06
S2000 M03
G00 X-20. Y-20. Z5.
G01 Z-3. F300.
G41 D1 G01 X0. Y-10. F500.
G01 Y40.
G02 X10. Y50. R10.
G01 X60.
G02 X70. Y40. I0. J-10.
G01 Y0.
X0.
G40 G01 X-20. Y-20.
G00 Z5.
M05
M30
