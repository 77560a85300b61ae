(expect W1306 3:1 not in this file) (dialect fanuc)
O1
G65 P9010 A1.
G0 X1.
M30
