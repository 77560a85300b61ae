$$ expect: 3:1: error[E3111]: KNOT outside a NURBS/ block
GOTO/0,0,0
KNOT/0.5,1.0
FINI
