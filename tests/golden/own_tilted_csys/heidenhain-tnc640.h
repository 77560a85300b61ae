0 BEGIN PGM 1000 MM
1 ; a side face drilled from +X after a tilted CSYS (SolidWorks CAM's form: points and axis in the base frame): written as each profile's output.tilted_plane says
2 TOOL CALL S6000
3 M3
4 L X+10 Y+10 Z+5 R0 F1000
5 M5
6 ; SET-UP 2: CLAMP THE PART WITH ITS DIRECTION (1, 0, 0) UP THE SPINDLE (+Z) AND ITS (0, 1, 0) ALONG +X, SET THE PRESET ON ITS POINT (0, 0, 0), THEN CYCLE START
7 M0
8 M3
9 L X+20 Y-30 Z+120 R0 FMAX
10 L Z+90
11 L Z+120 R0 FMAX
12 M30
13 END PGM 1000 MM
