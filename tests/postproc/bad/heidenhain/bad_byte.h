; expect E3302 3:9 byte 0xE9
0 BEGIN PGM T MM
1 L X+1 é FMAX
