$$ expect: 3:1: error[E3110]: CIRCLE must be followed by GOTO, not GODLTA
GOTO/5,0,0
CIRCLE/0,0,0,0,0,1,5
GODLTA/0,0,1
FINI
