%
O9100
// HOLES ON A CIRCLE: G65 P9100 X Y I(radius) J(start angle) K(count) Z F
// argument check: the radius and the count are required
IF[#4EQ#0]GOTO90;
IF[#6EQ#0]GOTO90;
#10=0;
WHILE[#10LT#6]DO1;
#11=#5+#10*360./#6;
G98 G81 X[#24+#4*COS[#11]] Y[#25+#4*SIN[#11]] Z#26 R2. F#9;
#10=#10+1;
END1;
G80;
GOTO99;
N90 #3000=1(RADIUS AND COUNT REQUIRED);
N99 M99;
%
