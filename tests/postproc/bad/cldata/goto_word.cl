$$ expect: 2:8: error[E3104]: expected a number, found 'X'
GOTO/1,X,3
FINI
