$$ expect: 2:1: error[E3117]: TRACUT transformations are not applied; write the CL file without TRACUT
TRACUT/1,0,0,10,0,1,0,0,0,0,1,0
GOTO/1,2,3
FINI
