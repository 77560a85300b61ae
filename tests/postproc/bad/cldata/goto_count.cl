$$ expect: 2:1: error[E3104]: GOTO has 4 values; expected groups of 3 (x,y,z)
GOTO/1,2,3,4
FINI
