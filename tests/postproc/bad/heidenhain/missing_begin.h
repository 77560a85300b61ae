; expect E3305 2:3 starts with BEGIN PGM
1 L X+1 FMAX
