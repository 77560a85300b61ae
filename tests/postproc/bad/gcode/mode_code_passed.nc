(expect W1406 3:1 is a mode of the control) (dialect fanuc)
O1
G05.1 Q1
G1 X1 F100
M30
