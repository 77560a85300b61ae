$$ expect: 2:1: error[E3115]: SPINDL in surface speed needs a CUTTER/TLDATA diameter before it
SPINDL/SMM,200,CLW
FINI
