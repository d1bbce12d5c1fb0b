%
O2000 (FACE MILL 80 X 40, ZIG-ZAG)
(T2: D50 face mill; the part spans X25-X105, passes 10 mm apart in Y run 25 mm past each end)
(The bench ignores O, T, M6, S, M3, G43 H, G54, M8, M9, M5 and M30 with one warning.)
G90 G17 G21 G94
T2 M6
G54 S3000 M3
G0 X0 Y0
G43 H2 Z3 M8
G1 Z-0.5 F800
X130 F9000
Y10
X0
Y20
X130
Y30
X0
Y40
X130
G0 Z3 M9
M5
M30
%
