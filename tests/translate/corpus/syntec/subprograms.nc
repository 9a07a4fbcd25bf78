(subprograms: an incremental pocket called at three places, an absolute finishing pass)
(called twice by L2, a nested call and a G65 macro whose body depends on its argument)
O0001
G90 G17 G71 G94 G54
T3 M06
S3000 M03
G00 X0. Y0. Z5.
M98 P1000
G00 X50. Y0.
M98 P1000
G00 X0. Y50.
M98 P1000
M98 P2000 L2
G65 P3000 A10.
G65 P3000 A20.
G00 Z20.
M05
M30
O1000 (incremental square pocket: position-independent)
G91 G01 Z-7. F120.
G01 X10. F300.
G02 X10. Y-10. R10.
M98 P1100
G01 Y10.
G90 G00 Z5.
M99
O1100 (nested: a short incremental step)
G91 G01 X-5.
G01 X-15.
M99
O2000 (absolute finishing pass: same blocks on every call)
G90 G00 X100. Y100.
G01 Z-2. F80.
G01 X120. F250.
G00 Z5.
M99
O3000 (macro: the body depends on #1)
G90 G00 X[#1] Y80.
G01 Z-1. F100.
G00 Z5.
M99
