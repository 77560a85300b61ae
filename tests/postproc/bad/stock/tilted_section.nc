(expect W4731: --stock-box=-20,-20,-5,20,20,1 --machine fanuc-3plus2)
G21 G90 G17
T1 M6
S8000 M3
G68.2 X0. Y0. Z0. I0. J10. K0.
G53.1
G0 X-5. Y0. Z5.
G1 Z0. F1000.
G1 X5.
G69
M5
M30
