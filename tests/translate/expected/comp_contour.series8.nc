(a pocket wall cut with cutter radius compensation - D1 = 5 mm)
G17 G71 G90
T1
(change to tool T1)
S2000.
M03
G00 X-20. Y-20. Z5.
G01 Z-3. F300.
G01 X-5. Y-10. F500.
G01 Y40.
G02 X10. Y55. I15. J0.
G01 X60.
G02 X75. Y40. I0. J15.
G01 Y-5.
G01 X0.
G01 X-20. Y-20.
G00 Z5.
M05
M30
