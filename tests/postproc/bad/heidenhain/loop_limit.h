; expect E3317 4:31 past the limit
0 BEGIN PGM T MM
1 LBL 1
2 FN 9: IF +0 EQU +0 GOTO LBL 1
