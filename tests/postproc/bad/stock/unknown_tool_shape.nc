(expect W4730: --stock-box=-20,-20,-5,20,20,1 --tool T1=other --tool T2=ball:10)
G21 G90 G17
T1 M6
S3000 M3
G0 X0. Y0. Z5.
G1 Z0.5 F1000.
G1 X10.
G0 Z5.
T2 M6
S8000 M3
G0 X-10. Y0. Z5.
G1 Z0. F1000.
G1 X10.
M5
M30
