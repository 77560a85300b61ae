; expect E3311 4:3 below half the chord
0 BEGIN PGM T MM
1 L X+0 Y+0 F100
2 CR X+30 Y+0 R+5 DR+
