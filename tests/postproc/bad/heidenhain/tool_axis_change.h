; expect E3321 3:15 only tool axis Z
0 BEGIN PGM T MM
1 TOOL CALL 1 X S1000
