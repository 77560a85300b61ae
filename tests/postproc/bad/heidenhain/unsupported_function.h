; expect E3319 3:3 FN 14 raises an error
0 BEGIN PGM T MM
1 FN 14: ERROR = 1000
