; expect E3304 3:3 starts no Klartext block
0 BEGIN PGM T MM
1 G01 X1
