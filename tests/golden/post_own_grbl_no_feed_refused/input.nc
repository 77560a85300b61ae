%
(a cut before any feed rate: grbl and LinuxCNC refuse it)
G21 G90 G17
S10000 M3
G0 X0 Y0 Z5
G1 Z-1
G1 X10
M30
%
