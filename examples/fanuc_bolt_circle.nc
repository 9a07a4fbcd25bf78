%
O1000 (Fanuc macro B: 6 holes on a 30 mm radius, drilled in a WHILE loop)
G90 G17 G21 G94 G54
T1 M06
S1200 M03
#1 = 50.      (centre X)
#2 = 40.      (centre Y)
#3 = 30.      (radius)
#4 = 6        (holes)
G00 X50. Y40. Z10.
G99 G81 Z-5. R2. F150. K0
#10 = 0
WHILE [#10 LT #4] DO1
#11 = #10 * 360. / #4
X[#1 + #3 * COS[#11]] Y[#2 + #3 * SIN[#11]]
#10 = #10 + 1
END1
G80
G00 Z10.
M05
M30
%
