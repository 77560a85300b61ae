$$ expect: 3:1: error[E3119]: CSYS mirrors or scales (its 3x3 part is not a rotation within 1e-6): the points it places are not a rigid set-up's
TRNTYP/WORLD,0,0,0
CSYS/-1.,0,0,0,0,1.,0,0,0,0,1.,0
GOTO/120.,24.9625,-30.35
FINI
