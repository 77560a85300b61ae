(dialect fanuc)
(expect E1404 3:1 G68 changes the motion in a way vcpost does not follow)
G68 X0 Y0 R30.
M30
