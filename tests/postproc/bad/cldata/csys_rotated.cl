$$ expect: 3:1: error[E3119]: CSYS rotates about another axis than Z (or scales): only a translation and a rotation about Z are applied; post each set-up from its own CL file
TRNTYP/WORLD,0,0,0
CSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0
GOTO/120.,24.9625,-30.35,1.,0,0
FINI
