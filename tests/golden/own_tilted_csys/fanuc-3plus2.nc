%
O1000
N10 G21 G17 G40 G49 G80 G90 G94
N20 G54
N30 (a side face drilled from +X after a tilted CSYS [SolidWorks CAM's form: points and axis in the base frame]: written as each profile's output.tilted_plane says)
N40 S6000 M3
N50 G1 X10. Y10. Z5. F1000.
N60 G68.2 X0. Y0. Z0. I90. J90. K0.
N70 G53.1
N80 G0 X20. Y-30. Z120.
N90 G1 Z90.
N100 G0 Z120.
N110 G69
N120 M30
%
