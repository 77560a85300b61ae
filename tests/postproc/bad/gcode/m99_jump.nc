(dialect fanuc)
(expect E1301 6:5 jump vcpost does not follow)
M98 P2000
M30
O2000
M99 P20
