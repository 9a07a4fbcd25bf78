(bolt circle: 8 holes on R40 about X50 Y50, drilled by a macro B loop)
G90 G17 G71 G94 G54
T2 M06
S1200 M03
#1 = 50.      (centre X)
#2 = 50.      (centre Y)
#3 = 40.      (radius)
#4 = 8        (holes)
#5 = 22.5     (start angle)
G00 X50. Y50. Z10.
G99 G81 Z-12. R2. F150. K0
#10 = 0
WHILE [#10 LT #4] DO1
#11 = #5 + #10 * 360. / #4
X[#1 + #3 * COS[#11]] Y[#2 + #3 * SIN[#11]]
#10 = #10 + 1
END1
G80
G00 Z10.
M05
M30
