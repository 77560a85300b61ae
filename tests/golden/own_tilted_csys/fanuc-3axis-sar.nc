%
O1000
N10 G21 G17 G40 G49 G80 G90 G94
N20 G54
N30 (a side face drilled from +X after a tilted CSYS [SolidWorks CAM's form: points and axis in the base frame]: written as each profile's output.tilted_plane says)
N40 S6000 M3
N50 G1 X10. Y10. Z5. F1000.
N60 M5
N70 (SET-UP 2: CLAMP THE PART WITH ITS DIRECTION [1, 0, 0] UP THE SPINDLE [+Z] AND ITS [0, 1, 0] ALONG +X, SET G55 ON ITS POINT [0, 0, 0], THEN CYCLE START)
N80 M0
N90 G55
N100 M3
N110 G0 X20. Y-30. Z120.
N120 G1 Z90.
N130 G0 Z120.
N140 M30
%
