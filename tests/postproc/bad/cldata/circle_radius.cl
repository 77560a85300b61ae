$$ expect: 3:1: error[E3109]: circle radius 4.0000 mm, but the arc starts 5.0000 mm from its centre
GOTO/5,0,0
CIRCLE/0,0,0,0,0,1,4
GOTO/0,5,0
FINI
