$$ expect: 3:6: error[E3119]: CSYS with a rotation or translation is not applied (the set-up frame differs from the CL points' frame); post each set-up from its own CL file
TRNTYP/WORLD,0,0,0
CSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0
GOTO/120.,24.9625,-30.35,1.,0,0
FINI
