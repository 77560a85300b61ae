$$ expect: 4:1: error[E3109]: arc end point is 5.5000 mm from the centre, its start 5.0000 mm (tolerance 0.0050 mm)
GOTO/5,0,0
CIRCLE/0,0,0,0,0,1,5
GOTO/0,5.5,0
FINI
