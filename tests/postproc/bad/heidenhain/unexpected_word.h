; expect E3307 5:14 is no word of C blocks
0 BEGIN PGM T MM
1 L X+10 Y+0 F100
2 CC X+0 Y+0
3 C X+0 Y+10 PA+5 DR+
