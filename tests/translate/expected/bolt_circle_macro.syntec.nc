(bolt circle: 8 holes on R40 about X50 Y50, drilled by a macro B loop)
G17 G71 G90 G94;
T2;
M06;
S1200.;
M03;
(centre X)
(centre Y)
(radius)
(holes)
(start angle)
G00 X50. Y50. Z10.;
G99 G81 X86.955 Y65.307 Z-12. R2. F150.;
X65.307 Y86.955;
X34.693 Y86.955;
X13.045 Y65.307;
X13.045 Y34.693;
X34.693 Y13.045;
X65.307 Y13.045;
X86.955 Y34.693;
G80;
G00 Z10.;
M05;
M30;
