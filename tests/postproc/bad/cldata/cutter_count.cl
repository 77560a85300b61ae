$$ expect: 2:1: error[E3104]: CUTTER needs 1 to 7 values, has 8
CUTTER/10,5,0,5,0,0,50,1
FINI
