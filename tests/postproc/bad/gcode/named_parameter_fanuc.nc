(dialect fanuc)
(expect E1206 4:5 not part of this dialect)
G21
G0 X#<depth>
M30
