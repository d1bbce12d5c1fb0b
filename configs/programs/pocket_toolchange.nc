%
O1000 (POCKET 60 X 40 WITH A TOOL-CHANGE HEADER)
(T1: D10 flat end mill; work zero G54 at the pocket's lower left corner, Z0 on top)
(The bench ignores O, T, M6, S, M3, G43 H, G54, M8, M9, M5 and M30 with one warning;)
(the tool-length and work offsets do not move the path. program_strict: true refuses them.)
N10 G90 G17 G21 G40 G49 G80 G94
N20 T1 M6
N30 G54
N40 S8000 M3
N50 G0 X10 Y10
N60 G43 H1 Z3 M8
N70 G1 Z-2 F1000
(Outer lap with R5 corners, climb milling)
N80 G1 X45 F6000
N90 G3 X50 Y15 R5
N100 G1 Y25
N110 G3 X45 Y30 R5
N120 G1 X15
N130 G3 X10 Y25 R5
N140 G1 Y15
N150 G3 X15 Y10 R5
(Inner lap)
N160 G1 X20 Y15
N170 X40
N180 Y25
N190 X20
N200 Y15
N210 G0 Z3 M9
N220 M5
N230 M30
%
