%
O1000
G21 G17 G40 G49 G80 G90 G94
G54
G61.1
(a side face drilled from +X after a tilted CSYS [SolidWorks CAM's form: points and axis in the base frame]: written as each profile's output.tilted_plane says)
S6000 M3
G1 X10. Y10. Z5. F1000.
M5
(SET-UP 2: CLAMP THE PART WITH ITS DIRECTION [1, 0, 0] UP THE SPINDLE [+Z] AND ITS [0, 1, 0] ALONG +X, SET G55 ON ITS POINT [0, 0, 0], THEN CYCLE START)
M0
G55
M3
G0 X20. Y-30. Z120.
G1 Z90.
G0 Z120.
G64
M30
%
