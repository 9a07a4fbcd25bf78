; LightBurn-style fill, grbl 1.1 laser (M4 dynamic power)
; Cut settings: speed 3000 mm/min, power 40%
G00 G17 G40 G21 G54
G90
M4
G0 X0 Y0
G1 X20 S400 F3000
G0 Y0.5
G1 X0 S400
G0 Y1
G1 X20 S400
G0 Y1.5
G1 X0 S400
G0 Y2
G1 X20 S400
M5
G0 X0 Y0
M2
