; expect E3313 3:3 a move must come first
0 BEGIN PGM T MM
1 CT X+10 Y+10 F100
