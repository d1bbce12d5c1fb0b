%
(A rectangular pocket finishing pass with rounded corners, G-code subset of shapebench)
(Tangent arcs of R5 join the sides, so the tool runs through without stopping; the arcs)
(are clamped to the square root of a times r; the speed changes are shaped by the pattern.)
N10 G90 G17 G21
N20 G0 X0 Y0
N30 G1 Y95 F30000
N40 G2 X5 Y100 R5
N50 G1 X195
N60 G2 X200 Y95 R5
N70 G1 Y5
N80 G2 X195 Y0 R5
N90 G1 X5
N100 G2 X0 Y5 R5
N110 G4 P100
%
