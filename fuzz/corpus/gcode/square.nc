%
(shapebench test data: read by tests/bench/program_reader_test.cc)
N10 G90 G17 G21
N20 G0 X0 Y0
N30 G1 X20 F3000
N40 G3 X30 Y10 R10
N50 G1 Y20
N60 G4 P200
N70 G91 X-30
%
