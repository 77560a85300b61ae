(expect E4720: --stock-from-program)
G21 G90 G17
T1 M6
S8000 M3
G0 X0. Y0. Z5.
G1 Z0. F1000.
G1 X10.
M5
M30
