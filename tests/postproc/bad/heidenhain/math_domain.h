; expect E3318 3:21 division by zero
0 BEGIN PGM T MM
1 FN 4: Q1 = +1 DIV +0
