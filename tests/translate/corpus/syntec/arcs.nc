(arcs in every plane: full circles, R arcs over 180 degrees, a helix)
G90 G17 G71 G94
G00 X0. Y0. Z0.
G01 X10. F400.
G03 I-10. J0.
G02 X-10. Y0. R-10.
G02 X10. Y0. R10.
G03 X0. Y10. Z-5. I-10. J0. F300.
G18
G01 X0. Y10. Z0.
G02 X10. Z10. I10. K0.
G19
G03 Y20. Z20. J10. K0.
G17
G00 Z20.
M30
