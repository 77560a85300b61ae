; expect E3303 3:5 needs a value
0 BEGIN PGM T MM
1 L X+ FMAX
