; expect W3342 3:17 retracts to a safe height
0 BEGIN PGM T MM
1 L Z+0 R0 FMAX M92
2 END PGM T MM
