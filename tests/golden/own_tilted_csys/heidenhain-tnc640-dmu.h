0 BEGIN PGM 1000 MM
1 ; a side face drilled from +X after a tilted CSYS (SolidWorks CAM's form: points and axis in the base frame): written as each profile's output.tilted_plane says
2 TOOL CALL S6000
3 M3
4 L X+10 Y+10 Z+5 R0 F1000
5 PLANE SPATIAL SPA+90 SPB+0 SPC+90 STAY
6 L A+Q120 C+Q122 R0 FMAX
7 L X+20 Y-30 Z+120 R0 FMAX
8 L Z+90
9 L Z+120 R0 FMAX
10 PLANE RESET STAY
11 M30
12 END PGM 1000 MM
