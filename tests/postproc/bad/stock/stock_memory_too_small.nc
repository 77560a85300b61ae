(expect E4724: --stock-box=-500,-500,-5,500,500,1 --stock-cell 0.01 --stock-memory 16)
G21 G90 G17
T1 M6
S8000 M3
G0 X0. Y0. Z5.
G1 Z0. F1000.
G1 X10.
M5
M30
