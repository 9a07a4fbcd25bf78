; SERIES 8 pocket with rounded corners, inch
G70 ; inch input
G90 ; absolute
G00XY ; home of the part
Z0.1 ; over the part
M03 S3000
F15 ; pocket feed
G01Z-0.1 ; depth
X2.
G03X2.25Y0.25I0J0.25 ; corner
G01Y1.25
G03X2.Y1.5I0.25J0 ; corner
G01X0.
G00Z1. ; clear
M05
M30
