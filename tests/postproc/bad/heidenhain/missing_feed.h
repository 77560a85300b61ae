; expect E3325 3:3 before any feed rate
0 BEGIN PGM T MM
1 L X+1 Y+1
