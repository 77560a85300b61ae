; expect E3314 4:3 between two straight lines
0 BEGIN PGM T MM
1 CC X+0 Y+0
2 RND R5
