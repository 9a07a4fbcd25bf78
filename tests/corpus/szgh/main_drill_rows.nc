; SZGH drilling rows with a block loop, relative moves
N1 G90 G54 G00 X0 Y0 Z50.
N2 WAT+X12 ; part present
N3 M3 S1800
N4 G43 Z20. H2
N5 G99 G81 X10. Y10. Z-8. R2. F120
N6 G91 G22 L4
N7 X15.
N8 G800
N9 G90 G80
N10 G00 Z50. M5
N11 M30
