; expect E3310 5:3 not on the circle
0 BEGIN PGM T MM
1 L X+10 Y+0 F100
2 CC X+0 Y+0
3 C X+0 Y+11 DR+
