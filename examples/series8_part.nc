; cncc: dialect=series8 (a modeline: cncc reads this file as SERIES 8 without -x)
G00X0Y0 ;rapid to the part zero
F20 ;feed rate in inches per minute
G01X2.Y0 ;first side
Y1.5 ;second side
G03X1.Y2.5I1.J0 ;a quarter arc (counter-clockwise, I unsigned)
G01X0 ;back along the top
Y0 ;down to the start
M30
