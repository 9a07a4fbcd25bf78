(grbl router job: two holes and a slot, mm)
$H
G21 G90 G17
G0 Z5.
M3 S12000
G0 X10. Y10.
G1 Z-2. F200
G1 X50. F800
G0 Z5.
G0 X10. Y30.
G1 Z-3. F200
G0 Z5.
G0 X50. Y30.
G1 Z-3. F200
G0 Z5.
M5
G0 X0 Y0
M2
