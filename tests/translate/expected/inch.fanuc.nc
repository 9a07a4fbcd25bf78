(an inch program: G70, arcs by I/J and R, a dwell)
G17 G20 G90 G94;
S800.;
M03;
G00 X0. Y0. Z0.5;
G01 Z-0.125 F10.;
G01 X2.5 F20.;
G03 X3.5 Y1. I0. J1.;
G01 Y2.25;
G02 X2.25 Y3.5 I-1.25 J0.;
G01 X0.;
G01 Y0.;
G04 X1.5;
G00 Z0.5;
M05;
M30;
