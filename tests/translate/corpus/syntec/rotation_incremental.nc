(G68 with incremental angles: G91 G68 adds to the rotation in force about the current point)
G90 G17 G71 G94 G54
G00 X0. Y0. Z10.
G68 X0. Y0. R10.
G01 X20. Y0. F250.
G91 G68 R15.
G90 G01 X40. Y10.
G03 X30. Y20. I-10. J0.
G91 G68 R20.
G90 G01 X30. Y20.
G02 X20. Y10. I0. J-10.
G01 X0. Y0.
G69
G00 X0. Y0.
(incremental moves under a rotation: cncc applies it)
G68 X5. Y5. R45.
G91 G01 X10. Y0.
G03 X-10. Y10. I-10. J0.
G90 G69
G00 X0. Y0. Z10.
M30
