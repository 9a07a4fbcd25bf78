; SZGH tapping with pitch K, pecks with User P2 clearance
M3 S100 ;
G90 G00 X0 Y0 Z50 ;
G99 G84 X300 Y-250 Z-150 R-120 P0.3 K5 F500 ;
Y-550 K5 ;
G98 Y-750 K5 ;
G80 ;
M3 S2000 ;
G99 G83 X300. Y-250. Z-150. R-100. Q15. F120. ;
Y-550. ;
G98 Y-750. ;
G80 ;
M02 ;
