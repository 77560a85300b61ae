(expect E1404 3:1 G51 changes the motion)
(dialect fanuc)
G51 X0 Y0 P2000
M30
