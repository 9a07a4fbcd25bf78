G70 ; inch
G90 ; absolute positions
G00X0Y0 ; to the part corner
Z0.1 ; above the part
M03 S2800
F12 ; plunge feed
G01Z-0.05 ; into the part
F25 ; cutting feed
G01X3.Y0 ; first side
Y2. ; second side
X0 ; third side
Y0 ; back to the corner
G00Z1. ; clear
M05
M30
