$$ expect: 3:1: error[E3111]: KNOT values must increase from 0
GOTO/0,0,0
NURBS/
KNOT/0.6,0.3,1.0
CNTRL/1,1,0
CNTRL/2,1,0
CNTRL/3,1,0
CNTRL/4,1,0
FINI
