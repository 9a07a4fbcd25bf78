; SERIES 8 mill, inch: plate with a slot and four holes
G70 ; inch
G90 ; absolute
G00XY ; to the part zero
Z0.1 ; clearance
M03 S2500
F20 ; feed 20 IPM
G01Z-0.05 ; plunge
X2.5 ; slot
G00Z0.1 ; retract
G81X0.5Y0.5Z-0.3R0.1 ; first hole
X2.
Y1.5
X0.5
G80 ; cancel
G00Z1. ; clear
M05
M30
